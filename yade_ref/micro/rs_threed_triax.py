# ThreeDTriaxialEngine (pkg/dem/ThreeDTriaxialEngine.cpp): the TriaxialStressController with per-axis stress
# or strain control. 21 spheres (makeCloud of 60 at porosity 0.95 fits 21, seed 5) in six aabbWalls; x and z stress-controlled to -5 kPa
# (max_vel_i computed, then overwritten by the controller as in YADE), y strain-controlled (strainRate2 0.4,
# the current rate converging with the engine's own strainDamping 0.995); updateFrictionAngle with
# frictionAngleDegree 25 re-assigns the friction on the first run (setContactProperties, clumps not skipped).
# Run: yade -n -x yade_ref/micro/rs_threed_triax.py [OUTDIR]
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
young = 5e6
O.materials.append(FrictMat(young=young, poisson=0.5, frictionAngle=math.radians(30), density=2600, label='spheres'))
O.materials.append(FrictMat(young=young, poisson=0.5, frictionAngle=0, density=0, label='walls'))
mn, mx = Vector3(0, 0, 0), Vector3(0.1, 0.1, 0.1)
walls = O.bodies.append(utils.aabbWalls([mn, mx], thickness=0.002, material='walls'))
sp = pack.SpherePack()
sp.makeCloud(mn, mx, 0.0125, 0.2, 60, False, 0.95, seed=5)
O.bodies.append([utils.sphere(c, r, material='spheres') for c, r in sp])
triax = ThreeDTriaxialEngine(thickness=0.002, internalCompaction=False, goal1=-5000, goal2=-5000, goal3=-5000,
                             max_vel=0.5, stressControl_1=True, stressControl_2=False, stressControl_3=True,
                             strainRate2=0.4, strainDamping=0.995, updateFrictionAngle=True, frictionAngleDegree=25)
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

# a digest scene (golden/FORMAT.md): every step's SHA-256 of all values, full rows at a few steps
ryade_record.record('rs_threed_triax', steps=3000, micro_digest=True, keep_steps=[0, 1, 2, 100, 1500, 3000])
ryade_record.finish()
