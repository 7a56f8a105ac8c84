# BubbleMat (pkg/dem/BubbleMat.cpp): Ip2_BubbleMat_BubbleMat_BubblePhys and Law2_ScGeom_BubblePhys_Bubble (Chan
# et al. 2011: Newton-Raphson on the force-separation law above the threshold Dmax, an exponential below it).
# Bubbles rising (gravity up, as examples/bouncingbubble.py) against a fixed one, one starting overlapped deep
# enough for the exponential branch, one pair glancing. Damping 0.1.
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
rad = 2.5e-3
O.materials.append(BubbleMat(density=1000, surfaceTension=71.97e-3))
O.bodies.append([utils.sphere((0, 0, 0), rad, fixed=True), utils.sphere((0, 0, -2 * rad * 0.999), rad),
                 utils.sphere((0.02, 0, 0), rad, fixed=True), utils.sphere((0.02, 0, -2 * rad * 0.7), rad),
                 utils.sphere((0.04, 0, 0), rad, fixed=True), utils.sphere((0.04 + 0.3 * rad, 0.2 * rad, -1.95 * rad), rad)])
O.bodies[5].state.vel = (0.01, 0, 0.02)
O.dt = 1e-6
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_BubbleMat_BubbleMat_BubblePhys()], [Law2_ScGeom_BubblePhys_Bubble()]),
    NewtonIntegrator(damping=0.1, gravity=(0, 0, 9.81)),
]

ryade_record.record('bubble', steps=3000)
ryade_record.finish()
