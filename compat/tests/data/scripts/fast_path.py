# O.ryadeFastPath: the same periodic 3-sphere scene run on the YADE-order path and on the fast path
# (2 threads, split in two runs); prints the largest position difference as JSON.
import json, math, sys
O.periodic = True
O.cell.setBox(0.1, 0.1, 0.1)
mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=math.radians(30)))
for p in [(0.0, 0.05, 0.05), (0.0195, 0.05, 0.05), (0.0385, 0.051, 0.05)]:
    O.bodies.append(utils.sphere(p, 0.01, material=mat))
O.bodies[0].state.vel = (0.01, 0, 0)
O.bodies[1].state.angVel = (0, 0, 3.0)
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
             NewtonIntegrator(damping=0.1)]
O.dt = 1e-5
O.saveTmp()
O.run(60, True)
ref = [tuple(b.state.pos) for b in O.bodies]
refv = [tuple(b.state.vel) + tuple(b.state.angVel) for b in O.bodies]
nref = O.interactions.countReal()
O.loadTmp()
O.ryadeFastPath = True
O.ryadeFastThreads = 2
O.run(30, True)
O.run(30, True)
got = [tuple(b.state.pos) for b in O.bodies]
gotv = [tuple(b.state.vel) + tuple(b.state.angVel) for b in O.bodies]
out = {'iter': O.iter, 'real_ref': nref, 'real_fast': O.interactions.countReal(),
       'max_dpos': max(abs(a - b) for r, g in zip(ref, got) for a, b in zip(r, g)),
       'max_dvel': max(abs(a - b) for r, g in zip(refv, gotv) for a, b in zip(r, g))}
fid = O.bodies.append(utils.facet([(-1, -1, 0), (1, -1, 0), (0, 1, 0)], material=mat))
O.bodies[fid].state.angVel = (0, 0, 1.0)   # a spinning facet: outside the fast path
try:
    O.run(1, True)
except RuntimeError as e:
    out['refused'] = str(e)
json.dump(out, open(sys.argv[1], 'w'))
