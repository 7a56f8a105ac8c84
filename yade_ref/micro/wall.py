# Case D: a spinning sphere thrown obliquely onto a Wall floor (z=0), gravity, damping 0.3.
# Exercises Bo1_Wall_Aabb (infinite bound), Ig2_Wall_Sphere_ScGeom (noRatch, refR1=R, kn=E*R),
# bouncing (erase and re-creation of the contact), sliding and rolling with spin.
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=math.radians(30)))
w = O.bodies.append(utils.wall(0.0, axis=2, material=mat))                        # id 0
s = O.bodies.append(utils.sphere((0.0, 0.0, 0.01002), 0.01, material=mat))        # id 1
O.bodies[s].state.vel = (0.3, 0.1, -0.05)
O.bodies[s].state.angVel = (0.0, 5.0, -3.0)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=0.3, gravity=(0, 0, -9.81)),
]
O.dt = 1e-5

ryade_record.record('wall', steps=1500)
ryade_record.finish()
