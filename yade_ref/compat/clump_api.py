# Clump API reference values for compat/tests/test_clump.py: run `yade -n -x yade_ref/compat/clump_api.py`
# (YADE 2023.02a, one thread) and copy the printed numbers into the test.
from yade import *
import math
O.reset()
mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=0.5))
f = O.bodies.append(utils.facet([(0,0,0),(1,0,0),(0,1,0)], material=mat))
r = O.bodies.appendClumped([utils.sphere((0,0,0.1), 0.02, material=mat), utils.sphere((0.025,0.01,0.11), 0.015, material=mat)])
print('ret', repr(r), type(r).__name__, type(r[1]).__name__)
c = O.bodies[r[0]]
for b in O.bodies:
    print(b.id, b.isClump, b.isClumpMember, b.isStandalone, b.clumpId, b.bounded, b.aspherical)
print('mass %r' % c.state.mass)
print('pos %r %r %r' % tuple(c.state.pos))
print('inertia %r %r %r' % tuple(c.state.inertia))
q = c.state.ori
print('ori %r %r %r %r' % (q[3], q[0], q[1], q[2]))
print('members', sorted(c.shape.members.keys()), type(c.shape).__name__)
for k, (p, o) in sorted(c.shape.members.items()):
    print('rel', k, '%r %r %r' % tuple(p), '%r %r %r %r' % (o[3], o[0], o[1], o[2]))
print('material', c.material)
ids = O.bodies.append([utils.sphere((1,1,1), 0.01, material=mat), utils.sphere((1.01,1,1), 0.01, material=mat), utils.sphere((1.5,1,1), 0.01, material=mat)])
cid = O.bodies.clump(ids[:2])
print('clump ret', cid, O.bodies[cid].state.mass, tuple(O.bodies[cid].state.pos), O.bodies[cid].aspherical)
for bad in ([], ):
    try:
        O.bodies.clump(bad); print('no error')
    except Exception as e:
        print('err', type(e).__name__, e)
try:
    O.bodies.clump([ids[2], ids[2]]); print('dup no error')
except Exception as e:
    print('dup err', type(e).__name__, e)
print('n bodies', len(O.bodies))
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=0.2, gravity=(0,0,-9.81))]
O.dt = 1e-5
O.run(100, True)
print('after100 pos %r %r %r' % tuple(c.state.pos), 'vel %r %r %r' % tuple(c.state.vel))
print('member pos %r %r %r' % tuple(O.bodies[r[1][1]].state.pos))
print('intrs', [(i.id1, i.id2) for i in O.interactions])
