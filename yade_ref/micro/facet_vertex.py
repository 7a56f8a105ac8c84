# Case B4: a spinning sphere hits vertex 1 (0.05,-0.05,0) of a horizontal facet from outside
# the corner, no gravity, no damping.
# Exercises the Ig2_Facet_Sphere_ScGeom vertex branch (contact point at the vertex).
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=math.radians(30)))
f = O.bodies.append(utils.facet([(-0.05, -0.05, 0), (0.05, -0.05, 0), (0, 0.05, 0)], material=mat))  # id 0
s = O.bodies.append(utils.sphere((0.05 + 0.006, -0.05 - 0.006, 0.006), 0.01, material=mat))       # id 1
O.bodies[s].state.vel = (-0.15, 0.16, -0.14)
O.bodies[s].state.angVel = (-4.0, 1.0, 6.0)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=0.0, gravity=(0, 0, 0)),
]
O.dt = 1e-5

ryade_record.record('facet_vertex', steps=600)
ryade_record.finish()
