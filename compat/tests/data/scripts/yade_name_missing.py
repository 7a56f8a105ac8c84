from yade.gridpfacet import *
print('before')
gmshPFacet('mesh.geo')
print('never printed')
