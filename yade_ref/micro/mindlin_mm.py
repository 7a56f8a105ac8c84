# Hertz-Mindlin with MatchMakers and a Hertzian facet (pkg/dem/HertzMindlin.cpp, pkg/common/MatchMaker.cpp,
# Ig2_Facet_Sphere_ScGeom::hertzian): en and frictAngle matched per pair of three materials (as the DEM2020
# mixer benchmark, examples/DEM2020Benchmark/original/mixer.py), frictAngle's unmatched pairs by 'min' of the
# materials' angles; the facets' equivalent radius 1e8 times the sphere's. Spheres of two materials dropped on
# a tilted facet floor and on each other. Gravity, no damping.
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
steel = O.materials.append(FrictMat(young=2e9, poisson=0.2, density=7200, frictionAngle=0.3))
m1 = O.materials.append(FrictMat(young=1e8, poisson=0.2, density=2500, frictionAngle=0.5))
m2 = O.materials.append(FrictMat(young=5e7, poisson=0.25, density=2000, frictionAngle=0.4))
O.bodies.append([utils.facet([(-0.1, -0.1, 0), (0.1, -0.1, 0.01), (0.1, 0.1, 0.01)], material=steel),
                 utils.facet([(-0.1, -0.1, 0), (0.1, 0.1, 0.01), (-0.1, 0.1, 0)], material=steel)])
specs = [((0, 0, 0.012), 0.01, m1), ((0.021, 0.002, 0.015), 0.008, m2), ((-0.02, 0.01, 0.011), 0.01, m2),
         ((0.001, 0.002, 0.033), 0.009, m1), ((0.02, -0.02, 0.03), 0.007, m2), ((-0.021, -0.019, 0.02), 0.009, m1)]
for i, (c, r, m) in enumerate(specs):
    b = O.bodies.append(utils.sphere(c, r, material=m))
    O.bodies[b].state.vel = (0.03 * (i % 3 - 1), 0.01 * (i % 2), -0.1)
    O.bodies[b].state.angVel = (2.0 * (i % 2), 0, -1.0)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom(hertzian=True)],
                    [Ip2_FrictMat_FrictMat_MindlinPhys(
                        frictAngle=MatchMaker(matches=((m1, m1, 0.3), (steel, m1, 0.2), (m1, m2, 0.25)), algo='min'),
                        en=MatchMaker(matches=((m1, m1, 0.5), (steel, m1, 0.4), (steel, m2, 0.4), (m1, m2, 0.45),
                                               (m2, m2, 0.4))))],
                    [Law2_ScGeom_MindlinPhys_Mindlin()]),
    NewtonIntegrator(damping=0.0, gravity=(0, 0, -9.81)),
]
O.dt = 1e-5

ryade_record.record('mindlin_mm', steps=3000)
ryade_record.finish()
