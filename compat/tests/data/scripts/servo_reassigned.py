# ServoPIDController + O.engines = O.engines every 250 steps (with the argument 'again'), printed by YADE 2023.02a:
#   yade -n -x servo_reassigned.py [again]   (or: compat run servo_reassigned.py [again])
# YADE keeps the servo object, so its integral term iTerm carries on: the same doubles either way.
import math, sys
O.reset()
mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=math.radians(30)))
O.bodies.append(utils.box((0, 0, -0.01), (0.1, 0.1, 0.01), fixed=True, material=mat))
for (x, y) in [(-0.0101, -0.0101), (0.0101, -0.0101), (-0.0101, 0.0101), (0.0101, 0.0101)]:
    O.bodies.append(utils.sphere((x, y, 0.01 - 2e-6), 0.01, material=mat))
zp = 0.02005
pis = [O.bodies.append(utils.facet([(-0.03, -0.03, zp), (0.03, -0.03, zp), (0.03, 0.03, zp)], material=mat)),
       O.bodies.append(utils.facet([(-0.03, -0.03, zp), (0.03, 0.03, zp), (-0.03, 0.03, zp)], material=mat))]
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb(), Bo1_Box_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=0.2, gravity=(0, 0, -9.81)),
    ServoPIDController(ids=pis, axis=(0, 0, 2), target=20.0, kP=2e-3, kI=2e-5, kD=4e-4, maxVelocity=0.05, iterPeriod=2)]
O.dt = 1e-5
for k in range(8):
    O.run(250, True)
    if len(sys.argv) > 1 and sys.argv[1] == "again":
        O.engines = O.engines
print('S', repr(O.bodies[5].state.pos[2]), repr(O.engines[4].iTerm))
