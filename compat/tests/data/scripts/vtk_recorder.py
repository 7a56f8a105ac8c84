# VTKRecorder with spheres, facets, velocity and colors every 50 steps for 120 steps; argv[1]: output folder
import sys
from yade import utils
out = sys.argv[1]
O.materials.append(FrictMat(young=1e7, density=2600))
O.bodies.append([utils.sphere((0, 0, 0.1), 0.1, color=(0.1, 0.2, 0.3)), utils.sphere((0.3, 0, 0.2), 0.05, color=(1, 0.5, 0.25)),
                 utils.facet([(-1,-1,0),(1,-1,0),(0,1,0)], color=(0.7, 0.6, 0.5))])
O.bodies[0].state.angVel = Vector3(1, 2, 3)
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
             NewtonIntegrator(gravity=(0, 0, -9.81)),
             VTKRecorder(fileName=out + '/r-', recorders=['spheres', 'facets', 'velocity', 'colors'], iterPeriod=50, ascii=True)]
O.dt = 1e-4
O.run(120, True)
