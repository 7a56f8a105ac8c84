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

# B: bodiesHandling (dimensions of spheres and facets, spheresModify in place and as copies)
from yade import bodiesHandling as bh
d = bh.spheresPackDimensions([s0, m1, m2, s3, w1])
print('B', sorted((k, tuple(v) if hasattr(v, '__len__') else v) for k, v in d.items()))
O.bodies[s3].mask = 6
try:
    bh.spheresPackDimensions(mask=4)
except RuntimeWarning as e:
    print('B', bh.spheresPackDimensions([O.bodies[s0], O.bodies[s3]], mask=2)['number'],
          bh.spheresPackDimensions(mask=1)['number'], e)
f1 = O.bodies.append(utils.facet([(0, 0, 0), (0.1, 0.02, 0.3), (-0.05, 0.2, 0.01)]))
f2 = O.bodies.append(utils.facet([(0.3, -0.1, 0), (0.1, 0.02, 0.3), (-0.05, 0.2, -0.21)]))
print('B', sorted((k, tuple(v) if hasattr(v, '__len__') else v) for k, v in bh.facetsDimensions([f1, f2]).items()))
cps = bh.spheresModify([s0, s3], shift=(0.01, 0.2, -0.3), scale=0.7, orientation=Quaternion((1, 2, 0.5), 0.6), copy=True)
for b in cps:
    print('B', tuple(b.state.pos), b.shape.radius, b.state.mass, tuple(b.state.inertia), b.mask, b.dynamic)
print('B', bh.spheresModify([s3], scale=1.3, orientation=Quaternion((0, 0, 1), 0.3), shift=(0, 0.001, 0)))
b = O.bodies[s3]
print('B', tuple(b.state.pos), b.shape.radius, b.state.mass, tuple(b.state.inertia))
print('B', len(O.bodies.append(cps)), bh.sphereDuplicate(f1))

# C: the solid predicates inEllipsoid, inHyperboloid, inParallelepiped, notInNotch (inside-bits on a grid, with pads)
import itertools
preds = [pack.inEllipsoid((0.1, -0.2, 0.05), (1.0, 0.7, 0.45)),
         pack.inHyperboloid((0, 0, -1), (0.2, 0.1, 1), 0.9, 0.5),
         pack.inParallelepiped((0, 0, 0), (1, 0.1, 0), (0.2, 0.9, 0.1), (0.1, -0.2, 0.8)),
         pack.notInNotch((0, 0, 0), (1, 0.2, 0), (0, 1, 0.3), 0.2)]
grid = [Vector3(-1.2 + 0.1 * i, -1.1 + 0.1 * j, -1.05 + 0.1 * k) for i, j, k in itertools.product(range(25), range(23), range(22))]
for p in preds:
    for pad in (0, 0.05, -0.03):
        print('C', type(p).__name__, pad, ''.join('1' if p(q, pad) else '0' for q in grid).count('1'),
              hash(tuple(p(q, pad) for q in grid)) & 0xffffffff)
    print('C', type(p).__name__, [tuple(x) for x in p.aabb()])
sp = pack.regularHexa(pack.inEllipsoid((0, 0, 0), (0.3, 0.2, 0.25)) - pack.inSphere((0.1, 0, 0), 0.1), 0.02, 0.001)
print('C', len(sp), tuple(sp[0].state.pos), tuple(sp[-1].state.pos))

# D: O.bodies.getRoundness, clumpTemplate
c2, _ = O.bodies.appendClumped([sphere((1, 1, 1), 0.1, material=mat), sphere((1.12, 1, 1.01), 0.05, material=mat),
                                sphere((1, 1.1, 0.95), 0.07, material=mat)])
print('D', O.bodies.getRoundness(), O.bodies.getRoundness([c]), O.bodies.getRoundness([s0, s3, c2]))
t = clumpTemplate(relRadii=[1, .5], relPositions=[[0, 0, 0], [.7, 0, 0]])
print('D', t.numCM, t.relRadii, t.relPositions)
for args in (([1], [[0, 0, 0]]), ([1, 2], [[0, 0, 0], [0, 0, 0]]), ([1, 2], [[0, 0], [1, 0, 0]]), ([1, 2, 3], [[0, 0, 0]])):
    try:
        clumpTemplate(*args)
    except ValueError as e:
        print('D', e)

# E: gts surfaces (sweptPolylines2gtsSurface, cleanup, volume, area) and inGtsSurface
import gts
loop = lambda z, r: [(r * cos(2 * pi * k / 7), r * sin(2 * pi * k / 7), z) for k in range(8)]
surf = pack.sweptPolylines2gtsSurface([loop(0, 1), loop(0.5, 1.3), loop(1.2, 0.8)], threshold=1e-6, capStart=True, capEnd=True)
# area and volume to 12 digits: GTS sums the faces in an order that changes from run to run
print('E', surf.Nfaces, surf.Nvertices, surf.Nedges, surf.is_closed(), '%.12g %.12g' % (surf.area(), surf.volume()))
pred = pack.inGtsSurface(surf)
print('E', [tuple(x) for x in pred.aabb()])
# points off the surface's symmetry planes: a ray through an edge or a vertex is a tie GTS breaks by memory addresses
grid = [Vector3(-1.4 + 0.14 * i + 0.00731, -1.4 + 0.14 * j + 0.00419, -0.1 + 0.1 * k + 0.0013)
        for i, j, k in itertools.product(range(21), range(21), range(15))]
for pad in (0, 0.1):
    print('E', pad, sum(1 for q in grid if pred(q, pad)), hash(tuple(pred(q, pad) for q in grid)) & 0xffffffff)
print('E', len(pack.regularHexa(pred, 0.1, 0.0)), pack.inGtsSurface(surf, noPad=True)((0, 0, 0.6), 5))
s2 = pack.sweptPolylines2gtsSurface([loop(0, 1), loop(1, 1)])
try:
    pack.inGtsSurface(s2)
except ValueError as e:
    print('E', s2.is_closed(), e)

# F: pack.hexaNet (every startAtCorner / isSymmetric / row-parity case)
for corner, sym, ly in itertools.product((True, False), (True, False), (0.15, 0.2)):
    net, lx, lyr = pack.hexaNet(0.01, cornerCoord=[0.1, -0.2, 0.3], xLength=0.23, yLength=ly, mos=0.08, a=0.04, b=0.035,
                                startAtCorner=corner, isSymmetric=sym, fixed=True)
    print('F', corner, sym, len(net), lx, lyr, [tuple(s.state.pos) for s in net[:3]], tuple(net[-1].state.pos))

# E: gts.read of YADE's example surface (examples/gts-horse/horse.coarse.gts), translate/scale, inGtsSurface, write
horse = gts.read(open(os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'gts', 'horse.coarse.gts')))
print('E', horse.Nvertices, horse.Nedges, horse.Nfaces, horse.is_closed(), '%.12g %.12g' % (horse.area(), horse.volume()))
horse.translate(0.01, -0.02, 0.1)
horse.scale(2, 1.5, 1)
horse.rotate(0.3, 0.1, 1, 0.4)
hp = pack.inGtsSurface(horse)
lo, hi = hp.aabb()
print('E', tuple(lo), tuple(hi))
hgrid = [lo + Vector3((hi[0] - lo[0]) * (i + 0.0731) / 13., (hi[1] - lo[1]) * (j + 0.0419) / 11., (hi[2] - lo[2]) * (k + 0.013) / 9.)
         for i, j, k in itertools.product(range(14), range(12), range(10))]
print('E', sum(1 for q in hgrid if hp(q, 0)), sum(1 for q in hgrid if hp(q, 0.003)), hash(tuple(hp(q, 0) for q in hgrid)) & 0xffffffff)
out = os.path.join(sys.argv[1] if len(sys.argv) > 1 else '.', 'horse2.gts')
with open(out, 'w') as f:
    horse.write(f)
with open(out) as f:  # (YADE's PyGTS cannot read back what it wrote here: only the header is compared)
    print('E', f.readline().split())
