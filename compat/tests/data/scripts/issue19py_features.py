# Lines tagged A..F for compat/tests/test_issue19py.py: the same script under `yade -n -x` and `compat run`.
# A: bf.stressTensor / checkFailure (standalone sphere and clump member, stress correction on and off)
import sys
from bf import checkFailure, stressTensor
from yade import utils

mat = FrictMat(young=1e7, frictionAngle=0.5, density=2600)
O.materials.append(mat)
s0 = O.bodies.append(sphere((0, 0, 0.0098), 0.01, material=mat))
c, (m1, m2) = O.bodies.appendClumped([sphere((0.0005, 0.0003, 0.028), 0.009, material=mat),
                                      sphere((0.001, 0.0, 0.043), 0.007, material=mat)])
s3 = O.bodies.append(sphere((0.0125, 0.002, 0.012), 0.004, material=mat))
w1, w2 = O.bodies.append([utils.wall(0, axis=2, sense=1, material=mat), utils.wall(0.0498, axis=2, sense=-1, material=mat)])
O.bodies[w2].state.vel = (0, 0, -0.05)
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                             [Law2_ScGeom_FrictPhys_CundallStrack()]),
             NewtonIntegrator(damping=0.2, gravity=(0.3, -0.2, -9.81))]
O.dt = 0.5 * PWaveTimeStep()
O.run(120, True)
for b in (s0, m1, m2):
    print('A', b, [i.id2 if i.id1 == b else i.id1 for i in O.bodies[b].intrs()],
          [float(x) for x in stressTensor(O.bodies[b]).flatten()],
          [float(x) for x in stressTensor(O.bodies[b], stress_correction=False).flatten()])
    print('A', b, float(checkFailure(O.bodies[b], 1e3, 5e3, wei_V0=5e-7)),
          float(checkFailure(O.bodies[b], 1e4, 5e3, weibull=False)), float(checkFailure(O.bodies[b], 1e9, 5e9)))
