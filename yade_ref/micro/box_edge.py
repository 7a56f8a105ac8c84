# Box outside-contact branch: a fixed Box rotated about a skew axis; sphere 1 hits one of its
# corners, sphere 2 one of its edges, both from outside, with spin; no gravity, no damping.
# Exercises Ig2_Box_Sphere_ScGeom outside branch (closest point clamped in box-local
# coordinates), Bo1_Box_Aabb of a rotated box, a fixed aspherical body (utils.box sets
# aspherical=True and a non-zero mass/inertia) whose ori must stay untouched.
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=math.radians(30)))
q = Quaternion(Vector3(1, 2, 3).normalized(), 0.4)
ext = Vector3(0.05, 0.03, 0.02)
box = O.bodies.append(utils.box((0, 0, 0), ext, orientation=q, fixed=True, material=mat))   # id 0
R = 0.01
# corner (+,+,+): approach along the local (1,1,1) diagonal
corner = q * ext
dc = q * Vector3(1, 1, 1).normalized()
s1 = O.bodies.append(utils.sphere(corner + dc * (R + 3e-4), R, material=mat))             # id 1
O.bodies[s1].state.vel = dc * (-0.2) + q * Vector3(0.0, 0.03, 0.0)
O.bodies[s1].state.angVel = (4.0, -1.0, 2.0)
# edge (x = -hx, z = +hz, y free): approach along the local (-1,0,1) direction
edge = q * Vector3(-ext[0], 0.005, ext[2])
de = q * Vector3(-1, 0, 1).normalized()
s2 = O.bodies.append(utils.sphere(edge + de * (R + 2e-4), R, material=mat))               # id 2
O.bodies[s2].state.vel = de * (-0.15) + q * Vector3(0.0, 0.05, 0.0)
O.bodies[s2].state.angVel = (0.0, 3.0, -6.0)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=0.0, gravity=(0, 0, 0)),
]
O.dt = 1e-5

ryade_record.record('box_edge', steps=600)
ryade_record.finish()
