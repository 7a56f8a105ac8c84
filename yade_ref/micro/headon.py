# Case A: two equal spheres, head-on normal contact (no gravity, no damping).
# Exercises Ig2_Sphere_Sphere_ScGeom, Ip2 kn=E*R, Law2 normal force, contact erase on separation.
# Run: yade -n -x yade_ref/micro/headon.py [OUTDIR]
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=math.radians(30)))
s0 = O.bodies.append(utils.sphere((0, 0, 0), 0.01, material=mat))
s1 = O.bodies.append(utils.sphere((0.0199, 0, 0), 0.01, material=mat))
O.bodies[s0].state.vel = (0.05, 0, 0)
O.bodies[s1].state.vel = (-0.05, 0, 0)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=0.0, gravity=(0, 0, 0)),
]
O.dt = 1e-5

ryade_record.record('headon', steps=300)
ryade_record.finish()
