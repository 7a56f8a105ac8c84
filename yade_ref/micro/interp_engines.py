# InterpolatingHelixEngine, BicyclePedalEngine (pkg/common/KinematicEngines.cpp) and
# InterpolatingDirectedForceEngine (pkg/common/ForceEngine.cpp): a box of facets carried on a pedal circle
# about a skew axis (1, 2, 2) (a quaternion from z to the axis), with spheres inside; a fixed sphere screwed
# by an interpolating helix (angular velocity interpolated in time, wrapped) that a falling sphere lands on;
# a sphere pushed by a force interpolated in time (wrapped) along an unnormalised direction into a fixed
# one. Gravity, damping 0.2.
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=math.radians(30)))
box = O.bodies.append(geom.facetBox((0, 0, 0.05), (0.04, 0.04, 0.04), material=mat))
balls = [O.bodies.append(utils.sphere(c, 0.008, material=mat)) for c in
         [(-0.02, -0.02, 0.0183), (0.0, 0.005, 0.0185), (0.021, -0.01, 0.0184), (0.028, 0.027, 0.02)]]
hub = O.bodies.append(utils.sphere((0.3, 0, 0.05), 0.01, material=mat, fixed=True))
drop = O.bodies.append(utils.sphere((0.3015, 0.001, 0.07002), 0.01, material=mat))
anvil = O.bodies.append(utils.sphere((0.6, 0, 0.05), 0.01, material=mat, fixed=True))
ram = O.bodies.append(utils.sphere((0.6, 0, 0.0702), 0.01, material=mat))
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    BicyclePedalEngine(ids=box, rotationAxis=(1, 2, 2), radius=0.01, angularVelocity=6.0, fi=0.3),
    InterpolatingHelixEngine(ids=[hub], times=[0, 0.005, 0.012, 0.02], angularVelocities=[0, 20, -10, 5],
                             rotationAxis=(0, 0.6, 0.8), zeroPoint=(0.3, 0.001, 0.05), wrap=True, slope=0.002),
    InterpolatingDirectedForceEngine(ids=[ram], times=[0.001, 0.004, 0.009], magnitudes=[0.0, 0.4, 0.1],
                                     direction=(0.1, 0.2, -2.0), wrap=True),
    NewtonIntegrator(damping=0.2, gravity=(0, 0, -9.81)),
]
O.dt = 1e-5

ryade_record.record('interp_engines', steps=3000)
ryade_record.finish()
