# Hertz-Mindlin with DMT adhesion (pkg/dem/HertzMindlin.cpp): Ip2_FrictMat_FrictMat_MindlinPhys with surface energy
# gamma and restitution coefficients en, es (Thornton 2013 damping ratios), Law2_ScGeom_MindlinPhys_Mindlin with
# includeAdhesion (adhesive Coulomb cap, viscous force limited by the adhesion). The scene of micro/mindlin.py:
# eight spheres dropped, spinning, onto a fixed box and a fixed sphere,
# without moments.
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
m1 = O.materials.append(FrictMat(young=5e7, poisson=0.3, density=2600, frictionAngle=math.radians(25)))
m2 = O.materials.append(FrictMat(young=2e7, poisson=0.25, density=1800, frictionAngle=math.radians(35)))
O.bodies.append(utils.box((0, 0, -0.005), (0.06, 0.06, 0.005), fixed=True, material=m1))
O.bodies.append(utils.sphere((0.035, 0.0, 0.008), 0.008, fixed=True, material=m2))
specs = [((0, 0, 0.0102), 0.01, m1), ((0.0195, 0.002, 0.0101), 0.009, m2), ((-0.019, -0.003, 0.0105), 0.01, m1),
         ((0.002, 0.0195, 0.0103), 0.008, m2), ((0.001, 0.001, 0.0295), 0.009, m1), ((0.036, 0.001, 0.0245), 0.0085, m2),
         ((-0.018, 0.018, 0.0299), 0.01, m2), ((0.019, -0.018, 0.0102), 0.0095, m1)]
for i, (c, r, m) in enumerate(specs):
    b = O.bodies.append(utils.sphere(c, r, material=m))
    O.bodies[b].state.vel = (0.02 * (i % 3 - 1), -0.015 * (i % 2), -0.05)
    O.bodies[b].state.angVel = (3.0 * (i % 2), -2.0 * (i % 3 - 1), 1.5)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_MindlinPhys(gamma=0.8, en=0.6, es=0.75)],
                    [Law2_ScGeom_MindlinPhys_Mindlin(includeAdhesion=True)]),
    NewtonIntegrator(damping=0.0, gravity=(0, 0, -9.81)),
]
O.dt = 2e-5

ryade_record.record('mindlin_adh', steps=3000)
ryade_record.finish()
