# TriaxialStressController with internalCompaction (pkg/dem/TriaxialStressController.cpp, Shop::growParticles):
# 60 spheres in a box of six aabbWalls (thickness 0), held walls, the spheres grown every 10 steps by the
# multiplier that drives the mean wall stress to -2 kPa (maxMultiplier, then finalMaxMultiplier once reached);
# wall stiffness and stresses from the contacts; GlobalStiffnessTimeStepper sets dt. As the triax tutorial's
# first script (examples/triax-tutorial/script-session1.py), scaled down.
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
young = 5e6
O.materials.append(FrictMat(young=young, poisson=0.5, frictionAngle=math.radians(30), density=2600, label='spheres'))
O.materials.append(FrictMat(young=young, poisson=0.5, frictionAngle=0, density=0, label='walls'))
mn, mx = Vector3(0, 0, 0), Vector3(0.1, 0.1, 0.1)
O.bodies.append(utils.aabbWalls([mn, mx], thickness=0, material='walls'))
sp = pack.SpherePack()
sp.makeCloud(mn, mx, -1, 0.3333, 60, False, 0.95, seed=7)
O.bodies.append([utils.sphere(c, r, material='spheres') for c, r in sp])
triax = TriaxialStressController(maxMultiplier=1. + 2e4 / young, finalMaxMultiplier=1. + 2e3 / young, thickness=0,
                                 stressMask=7, internalCompaction=True, goal1=-2000, goal2=-2000, goal3=-2000)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    GlobalStiffnessTimeStepper(active=1, timeStepUpdateInterval=100, timestepSafetyCoefficient=0.8),
    triax,
    NewtonIntegrator(damping=0.2),
]

ryade_record.record('triax_internal', steps=3000)
ryade_record.finish()
