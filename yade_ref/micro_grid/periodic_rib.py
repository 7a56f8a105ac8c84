# Grid case G4: periodic cell 0.18 x 0.10 x 0.20 with an endless rope along x made of 3 GridNodes
# (x = 0.03, 0.09, 0.15; r = 2 mm, spacing 6 cm) and 3 GridConnections, the third one (node 2 -> node 0)
# crossing the cell boundary x = 0.18 (gridConnection(..., cellDist=Vector3i(1, 0, 0)); YADE keeps one
# interaction per body pair, so a periodic chain needs >= 3 nodes per period). Node 1 is fixed, nodes 0
# and 2 have blockedDOFs='z' (see sphere_rope.py for why). A sphere (FrictMat, r = 1.5 cm) starts at
# x = 0.002 resting on the boundary-crossing rib (whose image spans x = 0.15 .. 0.21) and rolls in -x
# across the cell boundary x = 0 (its position is never wrapped), which is also relPos = 0.5 of the rib;
# gravity, no damping, 1000 steps.
# Exercises periodic GridConnection (getSegment with hSize*cellDist, Bo1_GridConnection_Aabb periodic
# bound, node-node bond with cellDist: unp = r1 + r2 - |x2 + hSize*cellDist - x1|), the sphere-rib contact
# with a non-zero interaction cellDist (shift2), and the force split onto the two nodes of the crossing rib.
# Run: yade -n -x yade_ref/micro_grid/periodic_rib.py [OUTDIR]
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *
from yade.gridpfacet import *
from yade.minieigenHP import Vector3i

A = 0.06        # node spacing
R = 0.002       # node / connection radius
RS = 0.015      # sphere radius
Z0 = 0.05       # rope height
STEPS = 1000

O.reset()
O.periodic = True
O.cell.setBox(3 * A, 0.10, 0.20)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_GridConnection_Aabb()]),
    InteractionLoop(
        [Ig2_Sphere_Sphere_ScGeom(), Ig2_GridNode_GridNode_GridNodeGeom6D(),
         Ig2_Sphere_GridConnection_ScGridCoGeom(), Ig2_GridConnection_GridConnection_GridCoGridCoGeom()],
        [Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow=True, setCohesionOnNewContacts=False),
         Ip2_FrictMat_FrictMat_FrictPhys()],
        [Law2_ScGeom6D_CohFrictPhys_CohesionMoment(), Law2_ScGeom_FrictPhys_CundallStrack(),
         Law2_ScGridCoGeom_FrictPhys_CundallStrack(), Law2_GridCoGridCoGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=0.0, gravity=(0, 0, -9.81)),
]
nodeMat = O.materials.append(CohFrictMat(young=1e9, poisson=0.3, density=950, frictionAngle=math.radians(30),
                                         normalCohesion=1e100, shearCohesion=1e100, momentRotationLaw=True,
                                         label='node'))
ribMat = O.materials.append(FrictMat(young=1e8, poisson=0.25, density=950, frictionAngle=math.radians(30),
                                     label='rib'))
sphMat = O.materials.append(FrictMat(young=1e8, poisson=0.25, density=2650, frictionAngle=math.radians(30),
                                     label='sphere'))
nodes = [O.bodies.append(gridNode((0.5 * A + i * A, 0.05, Z0), R, material=nodeMat)) for i in range(3)]
conns = [O.bodies.append(gridConnection(nodes[0], nodes[1], R, material=ribMat)),
         O.bodies.append(gridConnection(nodes[1], nodes[2], R, material=ribMat)),
         O.bodies.append(gridConnection(nodes[2], nodes[0], R, material=ribMat, cellDist=Vector3i(1, 0, 0)))]
O.bodies[nodes[1]].dynamic = False
for n in (nodes[0], nodes[2]):
    O.bodies[n].state.blockedDOFs = 'z'
sph = O.bodies.append(utils.sphere((0.002, 0.05, Z0 + RS + R - 1e-6), RS, material=sphMat))
O.bodies[sph].state.vel = (-0.5, 0, 0)
O.dt = 2e-5

cross = O.interactions[nodes[2], nodes[0]]
print('[periodic_rib] crossing bond: id1 %d id2 %d cellDist %s unp %.17g kn %.17g (E pi r^2 / L = %.17g)'
      % (cross.id1, cross.id2, cross.cellDist, cross.phys.unp, cross.phys.kn, 1e9 * math.pi * R ** 2 / A))
print('[periodic_rib] crossing rib shape: periodic %s cellDist %s' % (O.bodies[conns[2]].shape.periodic,
                                                                     O.bodies[conns[2]].shape.cellDist))
hist = []
fsum = [0.0]


def hook(step):
    row = []
    for c in conns:
        if O.interactions.has(sph, c) and O.interactions[sph, c].isReal:
            i = O.interactions[sph, c]
            row.append((c, tuple(i.cellDist), i.geom.isDuplicate, i.geom.relPos))
    key = [r[:3] for r in row]
    if not hist or hist[-1][1] != key:
        hist.append((step, key, row))
    if row:
        # closed system: contact forces sum to zero over all bodies
        s = Vector3(0, 0, 0)
        for b in O.bodies:
            s += O.forces.f(b.id)
        fsum[0] = max(fsum[0], s.norm())


def final():
    for h in hist:
        print('[periodic_rib] from step %d: sphere-GC (conn, cellDist, isDuplicate): %s relPos %s'
              % (h[0], h[1], ['%.6g' % r[3] for r in h[2]]))
    print('[periodic_rib] sphere end pos', O.bodies[sph].state.pos, 'max |sum of all forces|', fsum[0])
    if len(hist) != 2 or hist[1][1][0][0] != conns[2] or hist[1][1][0][1] == (0, 0, 0):
        return 'expected one persistent contact with the crossing rib, with a non-zero cellDist'
    if O.bodies[sph].state.pos[0] >= 0:
        return 'the sphere did not cross the cell boundary'
    if fsum[0] > 1e-12:
        return 'forces do not sum to zero'
    return None


ryade_record.record('periodic_rib', steps=STEPS, default_sub='golden/micro_grid', grid=True,
                    step_hook=hook, final_check=final)
ryade_record.finish()
