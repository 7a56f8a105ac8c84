# CombinedKinematicEngine (`+` on kinematic engines) and HelixEngine (pkg/common/KinematicEngines.cpp): a
# closed box of 12 facets moved by TranslationEngine + RotationEngine (about a point off its centre) +
# HelixEngine + a dead RotationEngine (skipped), with loose spheres tumbling inside; a fixed sphere screwed
# along a skew axis by a HelixEngine alone, that a falling sphere lands on. Gravity, damping 0.2.
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
comb = (TranslationEngine(ids=box, translationAxis=(1, 0.5, 0), velocity=0.05)
        + RotationEngine(rotationAxis=(0, 0, 1), angularVelocity=3.0, rotateAroundZero=True, zeroPoint=(0.01, 0, 0.05))
        + HelixEngine(rotationAxis=(1, 1, 1), angularVelocity=-2.0, linearVelocity=0.03, zeroPoint=(0, 0.01, 0.05))
        + RotationEngine(rotationAxis=(1, 0, 0), angularVelocity=50.0, dead=True))
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    comb,
    HelixEngine(ids=[hub], rotationAxis=(0, 0.6, 0.8), angularVelocity=-30.0, linearVelocity=0.02, zeroPoint=(0.3, 0.001, 0.05)),
    NewtonIntegrator(damping=0.2, gravity=(0, 0, -9.81)),
]
O.dt = 1e-5

ryade_record.record('combined', steps=3000)
ryade_record.finish()
