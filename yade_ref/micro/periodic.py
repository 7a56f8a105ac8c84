# Case C: periodic cell 0.1^3, two spheres in contact across the x boundary (the pair is
# found through the image cellDist=(+-1,0,0)); they move out of the primary cell (positions
# are never wrapped), spin, damping 0.1, no gravity.
# Exercises the periodic InsertionSortCollider, shift2 = hSize*cellDist in Ig2/Law2, damping.
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
O.periodic = True
O.cell.setBox(0.1, 0.1, 0.1)
mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=math.radians(30)))
s0 = O.bodies.append(utils.sphere((0.005, 0.05, 0.05), 0.01, material=mat))
s1 = O.bodies.append(utils.sphere((0.0853, 0.0512, 0.0495), 0.01, material=mat))
O.bodies[s0].state.vel = (-0.05, 0.01, 0.0)
O.bodies[s0].state.angVel = (0.0, 2.0, -4.0)
O.bodies[s1].state.vel = (0.05, 0.0, 0.02)
O.bodies[s1].state.angVel = (5.0, 0.0, 1.0)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=0.1, gravity=(0, 0, 0)),
]
O.dt = 1e-5

ryade_record.record('periodic', steps=400)
ryade_record.finish()
