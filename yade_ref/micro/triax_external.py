# TriaxialStressController moving its walls (pkg/dem/TriaxialStressController.cpp, controlExternalStress and
# the strain-rate branch): 60 spheres in a box of six aabbWalls (thickness 0.002); stress control on x and z
# (-5 kPa, servo on the walls' contact stiffness, clamped to max_vel, stressDamping), strain rate -0.5 on y
# (strainDamping), the back wall not activated (held). Friction 30 deg, GlobalStiffnessTimeStepper, damping 0.2.
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
young = 5e6
O.materials.append(FrictMat(young=young, poisson=0.5, frictionAngle=math.radians(30), density=2600, label='spheres'))
O.materials.append(FrictMat(young=young, poisson=0.5, frictionAngle=0, density=0, label='walls'))
mn, mx = Vector3(0, 0, 0), Vector3(0.1, 0.1, 0.1)
O.bodies.append(utils.aabbWalls([mn, mx], thickness=0.002, material='walls'))
sp = pack.SpherePack()
sp.makeCloud(mn, mx, 0.0125, 0.2, 60, False, 0.95, seed=11)
O.bodies.append([utils.sphere(c, r, material='spheres') for c, r in sp])
triax = TriaxialStressController(thickness=0.002, stressMask=5, internalCompaction=False, goal1=-5000, goal2=-0.5,
                                 goal3=-5000, max_vel=0.5, wall_back_activated=False)
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

ryade_record.record('triax_external', steps=3000)
ryade_record.finish()
