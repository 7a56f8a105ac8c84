# A yade-batch job: drop a sphere with the table's damping and write its final height
readParamsFromTable(damping=0.2, steps=100, noTableOk=True)
from yade.params import table
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                             [Law2_ScGeom_FrictPhys_CundallStrack()]),
             NewtonIntegrator(damping=table.damping, gravity=(0, 0, -9.81))]
O.bodies.append([box((0, 0, 0), (1, 1, .1), fixed=True), sphere((0, 0, .2), .1)])
O.dt = 0.5 * PWaveTimeStep()
O.run(table.steps, True)
with open('result.%s.txt' % O.tags['description'], 'w') as f:
    f.write('%r %r\n' % (table.damping, O.bodies[1].state.pos[2]))
