# Case B3: a spinning sphere hits the edge of a horizontal facet from outside (its projection
# falls outside the triangle, within R of edge 0), no gravity, no damping.
# Exercises the Ig2_Facet_Sphere_ScGeom edge branch (normal from the closest edge point),
# creation (pen > 0), the non-ratcheting lever arms and erase on separation.
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=math.radians(30)))
s = O.bodies.append(utils.sphere((0.0, -0.05 - 0.0075, 0.0075), 0.01, material=mat))            # id 0
f = O.bodies.append(utils.facet([(-0.05, -0.05, 0), (0.05, -0.05, 0), (0, 0.05, 0)], material=mat))  # id 1
O.bodies[s].state.vel = (0.05, 0.2, -0.2)
O.bodies[s].state.angVel = (2.0, -5.0, 3.0)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=0.0, gravity=(0, 0, 0)),
]
O.dt = 1e-5

ryade_record.record('facet_edge', steps=600)
ryade_record.finish()
