# gridpfacet.cylinder and cylinderConnection: nodes and connections appended to O.bodies in YADE's order,
# with their masses and inertias; a free chain falls onto a fixed cylinder, the bodies after 300 steps.
from yade.gridpfacet import *
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_GridConnection_Aabb()]),
             InteractionLoop([Ig2_GridNode_GridNode_GridNodeGeom6D(), Ig2_GridConnection_GridConnection_GridCoGridCoGeom()],
                             [Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow=True, setCohesionOnNewContacts=False),
                              Ip2_FrictMat_FrictMat_FrictPhys()],
                             [Law2_ScGeom6D_CohFrictPhys_CohesionMoment(), Law2_GridCoGridCoGeom_FrictPhys_CundallStrack()]),
             NewtonIntegrator(gravity=(0, 0, -10), damping=0.3)]
O.materials.append(CohFrictMat(young=1e6, poisson=0.3, density=1000, frictionAngle=0.5, normalCohesion=1e10,
                               shearCohesion=1e10, momentRotationLaw=True, label='cMat'))
O.materials.append(FrictMat(young=1e6, poisson=0.3, density=1000, frictionAngle=0.5, label='fMat'))
nodes, cyls = [], []
cylinder((0, 0, 0), (1, 0, 0), radius=0.1, nodesIds=nodes, cylIds=cyls, fixed=True, intMaterial='cMat', extMaterial='fMat')
cylinderConnection([(0.3, 0.6, 0.205), (0.25, 0.1, 0.21), (0.3, -0.4, 0.22), (0.2, -0.8, 0.3)], radius=0.1,
                   nodesIds=nodes, cylIds=cyls, intMaterial='cMat', extMaterial='fMat')
print('G %r %r' % (nodes, cyls))
O.dt = 1e-5
O.step()
for b in O.bodies:
    print('G %d %s %r %r %r' % (b.id, type(b.shape).__name__, list(b.state.pos), b.state.mass, list(b.state.inertia)))
O.run(300, True)
for b in O.bodies:
    print('G %d %r %r' % (b.id, list(b.state.pos), list(b.state.angVel)))
