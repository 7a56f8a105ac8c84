# ServoPIDController (pkg/common/KinematicEngines.cpp) pressing a two-facet square piston onto four
# spheres resting on a Box floor, placed after NewtonIntegrator as in YADE's examples/PIDController.py;
# P, I and D terms all non-zero, iterPeriod 2 (the velocity is held between updates), maxVelocity
# clamps the approach. A TranslationEngine pushes a fifth (fixed) sphere sideways along (1, 1, 0)
# into one of them. Gravity, damping 0.2.
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=math.radians(30)))
O.bodies.append(utils.box((0, 0, -0.01), (0.1, 0.1, 0.01), fixed=True, material=mat))                  # id 0
for (x, y) in [(-0.0101, -0.0101), (0.0101, -0.0101), (-0.0101, 0.0101), (0.0101, 0.0101)]:      # ids 1-4
    O.bodies.append(utils.sphere((x, y, 0.01 - 2e-6), 0.01, material=mat))
zp = 0.02005
pis = [O.bodies.append(utils.facet([(-0.03, -0.03, zp), (0.03, -0.03, zp), (0.03, 0.03, zp)], material=mat)),
       O.bodies.append(utils.facet([(-0.03, -0.03, zp), (0.03, 0.03, zp), (-0.03, 0.03, zp)], material=mat))]  # 5, 6
pusher = O.bodies.append(utils.sphere((-0.045, -0.045, 0.01), 0.008, fixed=True, material=mat))    # id 7
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb(), Bo1_Box_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=0.2, gravity=(0, 0, -9.81)),
    ServoPIDController(ids=pis, axis=(0, 0, 2), target=20.0, kP=2e-3, kI=2e-5, kD=4e-4, maxVelocity=0.05, iterPeriod=2),
    TranslationEngine(ids=[pusher], velocity=0.02, translationAxis=(1, 1, 0)),
]
O.dt = 1e-5

ryade_record.record("servo", steps=4000)
ryade_record.finish()
