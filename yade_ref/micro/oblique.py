# Case A2: oblique sphere-sphere impact, unequal radii and two materials (harmonic kn/ks
# averages: kn=120948.6..., ks=30297.0...), both spheres spinning, Coulomb slip at 2 deg
# (min of the two friction angles). No gravity, no damping.
# Exercises ScGeom::precompute rotation/twist terms, avoidGranularRatcheting alpha with r1 != r2,
# the Coulomb cap, torques with different arms, and contact erase on separation.
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
m1 = O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=math.radians(2)))
m2 = O.materials.append(FrictMat(young=1.8e7, poisson=0.2, density=2000, frictionAngle=math.radians(30)))
s0 = O.bodies.append(utils.sphere((0, 0, 0), 0.01, material=m1))
s1 = O.bodies.append(utils.sphere((0.01814, 0.00408, 0.00204), 0.0085, material=m2))
O.bodies[s0].state.vel = (0.10, 0.02, -0.01)
O.bodies[s0].state.angVel = (1.0, -2.0, 8.0)
O.bodies[s1].state.vel = (-0.12, -0.05, 0.03)
O.bodies[s1].state.angVel = (3.0, -2.0, 1.0)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=0.0, gravity=(0, 0, 0)),
]
O.dt = 1e-5

ryade_record.record('oblique', steps=400)
ryade_record.finish()
