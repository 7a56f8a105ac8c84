# LudingMat (pkg/dem/LudingPM.cpp): Ip2_LudingMat_LudingMat_LudingPhys (slopes in series, plastic overlap
# limits from the radii) and Law2_ScGeom_LudingPhys_Basic (hysteretic normal spring: plastic loading k1,
# elastic un/reloading k2 growing with the largest overlap up to kp, adhesive branch kc; viscous G0; shear
# spring ks capped by Coulomb friction). Four pairs as examples/LudingPM/LudingPM_1.py (impact velocities
# for four plasticity regimes, here with ks and G0 given), a glancing pair, and a sphere of another
# LudingMat resting under gravity on a fixed one. dt 2e-3 (two collision times in 3000 steps).
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
rho, r = 2000, 0.2
k1 = 105.0
kp, kc = 5.0 * k1, k1
dpmax = 0.031
phif = dpmax * (kp - k1) * (2 * r) / (kp * 2 * r * r)
mass = 4.0 / 3.0 * math.pi * r ** 3 * rho
mats = [O.materials.append(LudingMat(frictionAngle=0.5, density=rho, k1=k1, kp=kp, kc=kc, ks=0.5 * k1, PhiF=phif, G0=0.05)),
        O.materials.append(LudingMat(frictionAngle=0.3, density=rho, k1=2 * k1, kp=8 * k1, kc=0.5 * k1, ks=k1, PhiF=0.8 * phif,
                                     G0=0.1))]
for i, chi in enumerate([0.34, 0.69, 1.1, 1.39]):
    O.bodies.append(utils.sphere((0, 3 * r * i, 0), r, material=mats[0], fixed=True))
    b = O.bodies.append(utils.sphere((0, 3 * r * i, 2 * r), r, material=mats[0]))
    O.bodies[b].state.vel = (0, 0, -math.sqrt(k1 / mass) * dpmax * chi)
O.bodies.append(utils.sphere((2, 0, 0), r, material=mats[0], fixed=True))
g = O.bodies.append(utils.sphere((2.1, 0.02, 2 * r - 0.01), r, material=mats[0]))
O.bodies[g].state.vel = (-0.05, 0.02, -0.1)
O.bodies[g].state.angVel = (0.1, 0, 0.3)
O.bodies.append(utils.sphere((4, 0, 0), r, material=mats[0], fixed=True))
O.bodies.append(utils.sphere((4, 0, 2 * r + 0.001), 0.8 * r, material=mats[1]))
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_LudingMat_LudingMat_LudingPhys()], [Law2_ScGeom_LudingPhys_Basic()]),
    NewtonIntegrator(damping=0, gravity=(0, 0, -9.81)),
]
O.dt = 2e-3

ryade_record.record('luding', steps=3000)
ryade_record.finish()
