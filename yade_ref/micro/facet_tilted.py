# Case B2: a facet tilted by 20 deg about x (created first, so it is id 0), a spinning sphere
# dropped 1 um above it, gravity, damping 0.2.
# Exercises damped free fall (dampGravity), contact creation after a few steps, the face branch
# with a non-axis-aligned normal, sliding/rolling down the slope with spin (twist term).
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=math.radians(30)))
th = math.radians(20)
def tilt(x, y):
    return (x, y * math.cos(th), y * math.sin(th))
f = O.bodies.append(utils.facet([tilt(-0.2, -0.2), tilt(0.2, -0.2), tilt(0, 0.2)], material=mat))  # id 0
R = 0.01
n = (0.0, -math.sin(th), math.cos(th))          # upward facet normal
c = tilt(0.0, 0.02)                              # point on the facet
d = R + 1e-6
s = O.bodies.append(utils.sphere((c[0] + d * n[0], c[1] + d * n[1], c[2] + d * n[2]), R, material=mat))  # id 1
O.bodies[s].state.vel = (0.05, 0.0, 0.0)
O.bodies[s].state.angVel = (3.0, 1.0, 20.0)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=0.2, gravity=(0, 0, -9.81)),
]
O.dt = 1e-5

ryade_record.record('facet_tilted', steps=3000)
ryade_record.finish()
