# Grid case G3: two spheres (FrictMat, r = 1.5 cm) rolling along a rope of 4 GridNodes (r = 2 mm,
# spacing 6 cm, end nodes fixed, interior nodes with blockedDOFs='z'), under gravity, no damping.
# Sphere A starts on connection 0-1 moving +x and crosses junction node 1 onto connection 1-2; sphere B
# starts on connection 2-3 moving -x and crosses junction node 2 onto connection 1-2 from its node2 end.
# Exercises Ig2_Sphere_GridConnection_ScGridCoGeom (projection, duplicate / hand-over logic in both
# branches: relPos <= 0.5 imports from the node1 neighbour, relPos > 0.5 from the node2 neighbour; the
# new interaction takes over the old one's geometry and physics objects, the old one is erased a step
# later), Ip2_FrictMat_FrictMat_FrictPhys between sphere and rib material, and
# Law2_ScGridCoGeom_FrictPhys_CundallStrack (force split (1-relPos, relPos) onto the two nodes, torques),
# with the node-node bonds carrying the load to the fixed ends.
# Why the interior nodes are blocked in z: with free nodes (mass ~1e-3 kg, transverse bond stiffness
# ~50 N/m) under a 37 g sphere, the contact rattles (erased and re-created every ~10 steps, no contact
# damping in YADE), so no contact survives a junction crossing and the hand-over is never exercised.
# Run: yade -n -x yade_ref/micro_grid/sphere_rope.py [OUTDIR]
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *
from yade.gridpfacet import *

NN = 4
A = 0.06        # node spacing
R = 0.002       # node / connection radius
RS = 0.015      # sphere radius
STEPS = 2000

O.reset()
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
nodes = [O.bodies.append(gridNode((i * A, 0, 0), R, material=nodeMat)) for i in range(NN)]
conns = [O.bodies.append(gridConnection(nodes[i], nodes[i + 1], R, material=ribMat)) for i in range(NN - 1)]
for n in (nodes[0], nodes[-1]):
    O.bodies[n].dynamic = False
for n in nodes[1:-1]:
    O.bodies[n].state.blockedDOFs = 'z'
sphA = O.bodies.append(utils.sphere((0.040, 0, RS + R - 1e-6), RS, material=sphMat))
O.bodies[sphA].state.vel = (1.0, 0, 0)
sphB = O.bodies.append(utils.sphere((0.136, 0, RS + R - 1e-6), RS, material=sphMat))
O.bodies[sphB].state.vel = (-0.8, 0, 0)
O.dt = 2e-5

# per sphere: (step, [(conn id, isDuplicate, trueInt)], [relPos]) whenever the set of real sphere-GC
# interactions or their duplicate flags change
history = {sphA: [], sphB: []}
shared = []         # steps at which two real interactions share one geometry object
fsum = [0.0]        # max |sum of O.forces.f over all bodies| (closed system: must vanish up to rounding)


def hook(step):
    tot = Vector3(0, 0, 0)
    for b in O.bodies:
        tot += O.forces.f(b.id)
    fsum[0] = max(fsum[0], tot.norm())
    for sph, hist in history.items():
        row = []
        for c in conns:
            i = O.interactions[sph, c] if O.interactions.has(sph, c) else None
            if i is not None and i.isReal:
                row.append((c, i.geom.isDuplicate, i.geom.trueInt, i.geom.relPos, i))
        key = [r[:3] for r in row]
        if len(row) == 2 and row[0][4].geom.penetrationDepth == row[1][4].geom.penetrationDepth \
                and row[0][4].phys.normalForce == row[1][4].phys.normalForce:
            shared.append((step, sph))
        if not hist or hist[-1][1] != key:
            hist.append((step, key, [r[3] for r in row]))


def final():
    msg = None
    for sph, hist in history.items():
        for h in hist:
            print('[sphere_rope] sphere %d from step %d: sphere-GC (conn, isDuplicate, trueInt): %s  relPos %s'
                  % (sph, h[0], h[1], ['%.6g' % x for x in h[2]]))
        print('[sphere_rope] sphere %d end pos %s vel %s' % (sph, O.bodies[sph].state.pos, O.bodies[sph].state.vel))
        first = conns[0] if sph == sphA else conns[2]
        if len(hist) != 4 or hist[1][1] != [(first, 0, -1)] or (conns[1], 2, conns[1]) not in hist[2][1] \
                or hist[3][1] != [(conns[1], 0, -1)]:
            msg = 'sphere %d: no clean hand-over from connection %d onto %d' % (sph, first, conns[1])
    print('[sphere_rope] steps with two real interactions sharing geom+phys (step, sphere):', shared)
    print('[sphere_rope] max |sum of all contact forces|: %g' % fsum[0])
    if fsum[0] > 1e-12:
        msg = 'contact forces do not sum to zero'
    return msg


ryade_record.record('sphere_rope', steps=STEPS, default_sub='golden/micro_grid', grid=True,
                    step_hook=hook, final_check=final)
ryade_record.finish()
