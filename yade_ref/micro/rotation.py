# RotationEngine (pkg/common/KinematicEngines.cpp): a closed box of 12 facets turning about a skew axis
# (1, 1, 0) through its centre (rotateAroundZero: each facet gets the velocity that carries it to its rotated
# place in one step), with loose spheres tumbling inside, and a fixed sphere spun in place (angVel only) that
# a falling sphere lands on. Gravity, damping 0.2.
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=math.radians(30)))
box = O.bodies.append(geom.facetBox((0, 0, 0.05), (0.04, 0.04, 0.04), material=mat))
balls = [O.bodies.append(utils.sphere(c, 0.008, material=mat)) for c in
         [(-0.02, -0.02, 0.0183), (0.0, 0.005, 0.0185), (0.021, -0.01, 0.0184), (-0.015, 0.02, 0.0186), (0.028, 0.027, 0.02)]]
for i, b in enumerate(balls):
    O.bodies[b].state.vel = (0.05 * (i - 2), 0.1 - 0.04 * i, -0.1)
hub = O.bodies.append(utils.sphere((0.3, 0, 0.05), 0.01, material=mat, fixed=True))
drop = O.bodies.append(utils.sphere((0.3015, 0.001, 0.07002), 0.01, material=mat))
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    RotationEngine(ids=box, rotationAxis=(1, 1, 0), angularVelocity=4.0, rotateAroundZero=True, zeroPoint=(0, 0, 0.05)),
    RotationEngine(ids=[hub], rotationAxis=(0, 0.6, 0.8), angularVelocity=-30.0),
    NewtonIntegrator(damping=0.2, gravity=(0, 0, -9.81)),
]
O.dt = 1e-5

ryade_record.record('rotation', steps=3000)
ryade_record.finish()
