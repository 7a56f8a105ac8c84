# Export files written by YADE's yade.export (text, VTKExporter) after a short run; ryade's compat
# layer must write the same bytes.   yade -n -x yade_ref/export/export_ref.py OUTDIR
import os, sys
from yade import export, pack
out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(sys.argv[0])))), 'golden', 'export')
os.makedirs(out, exist_ok=True)
O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=0.5))
sp = pack.SpherePack()
sp.makeCloud((0, 0, 0.05), (0.2, 0.2, 0.3), rMean=0.01, rRelFuzz=0.2, seed=3)
sp.toSimulation()
O.bodies.append(geom.facetBox((0.1, 0.1, 0.15), (0.1, 0.1, 0.15), wallMask=31))
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                             [Law2_ScGeom_FrictPhys_CundallStrack()]),
             NewtonIntegrator(damping=0.3, gravity=(0, 0, -9.81))]
O.dt = 0.5 * PWaveTimeStep()
O.run(400, True)
vtk = export.VTKExporter(os.path.join(out, 'snap'))
vtk.exportSpheres(what={'vel': 'b.state.vel', 'mass': 'b.state.mass'}, comment='spheres')
vtk.exportFacets(comment='facets')
vtk.exportSpheres(ids=[0, 1, 2], comment='three')
n = export.text(os.path.join(out, 'spheres.txt'))
print('exported', n, 'spheres at iter', O.iter)
sys.stdout.flush()
