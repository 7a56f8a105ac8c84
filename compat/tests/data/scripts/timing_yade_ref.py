# The timing statements of compat/tests/test_timing.py, printed by YADE 2023.02a:
#   yade -n -x timing_yade_ref.py   (or: compat run timing_yade_ref.py)
# Counts are deterministic (which engine ran how often); times are not, so only their sums are checked.
from yade import utils, timing
O.reset()
O.timingEnabled = True
mat = O.materials.append(FrictMat(young=1e8, poisson=0.25, density=2650, frictionAngle=0.5))
O.bodies.append(utils.wall(0, axis=2, sense=1, material=mat))
for k in range(20):
    O.bodies.append(utils.sphere((0.03 * (k % 5), 0.03 * (k // 5), 0.011 + 0.002 * k), 0.01, material=mat))
calls = []
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()], label='collider'),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                             [Law2_ScGeom_FrictPhys_CundallStrack()]),
             NewtonIntegrator(damping=0.2, gravity=(0, 0, -9.81)),
             PyRunner(command='calls.append(O.iter)', iterPeriod=7)]
O.dt = 1e-4
O.run(300, True)
names = [e.label or type(e).__name__ for e in O.engines]
print('A', [(n, e.execCount) for n, e in zip(names, O.engines)], len(calls))
ok = all(e.execTime > 0 for e in O.engines) and timing.runtime() == sum(e.execTime for e in O.engines)
print('B', ok, type(O.engines[0].execTime).__name__)
# timing.reset() zeroes; a new engine list keeps each engine object's own counts
timing.reset()
print('C', [e.execCount for e in O.engines], timing.runtime())
O.run(10, True)
eng = O.engines
O.engines = eng[:4]
O.run(5, True)
print('D', [e.execCount for e in eng])
O.timingEnabled = False
O.run(5, True)
print('E', [e.execCount for e in eng], O.timingEnabled)
O.engines[0].execCount = 3
print('F', O.engines[0].execCount, O.engines[0].timingDeltas)
