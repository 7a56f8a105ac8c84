# Case E variant: a fixed facet "piston" (normal down) driven by a prescribed velocity
# (0.002, 0, -0.05) presses a sphere onto a fixed Box floor; gravity, damping 0.1.
# Exercises moving fixed bodies (pos += vel*dt for blockedDOFs=xyzXYZ), facet velocity in the
# relative velocity, Ig2_Box_Sphere_ScGeom (centre above the top face: outside branch, face region; kn=E*R), two contacts on one
# sphere.
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=math.radians(30)))
floor = O.bodies.append(utils.box((0, 0, -0.01), (0.1, 0.1, 0.01), fixed=True, material=mat))   # id 0, top at z=0
s = O.bodies.append(utils.sphere((0.0, 0.0, 0.01 - 1e-6), 0.01, material=mat))                 # id 1
zp = 0.0202
piston = O.bodies.append(utils.facet([(-0.03, -0.03, zp), (0.0, 0.03, zp), (0.03, -0.03, zp)], material=mat))  # id 2
O.bodies[piston].state.vel = (0.002, 0.0, -0.05)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb(), Bo1_Box_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=0.1, gravity=(0, 0, -9.81)),
]
O.dt = 1e-5

ryade_record.record('piston', steps=1500)
ryade_record.finish()
