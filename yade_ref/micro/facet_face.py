# Case B: sphere sliding then rolling on a horizontal facet, gravity, no damping.
# Exercises Ig2_Facet_Sphere_ScGeom face branch (facet stored as id1 after the functor swap),
# facet refR1=2R stiffness (kn=4/3 E R), Coulomb sliding -> sticking/rolling, the facet torque
# with the sphericalBodies arm.
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=math.radians(30)))
s = O.bodies.append(utils.sphere((0, -0.3, 0.01 - 8e-7), 0.01, material=mat))     # id 0
f = O.bodies.append(utils.facet([(-1, -1, 0), (1, -1, 0), (0, 1, 0)], material=mat))  # id 1
O.bodies[s].state.vel = (0.5, 0, 0)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=0.0, gravity=(0, 0, -9.81)),
]
O.dt = 1e-5

ryade_record.record('facet_face', steps=4000)
ryade_record.finish()
