# Grid case G2: a small square net (3 x 3 GridNodes, spacing 6 cm, r = 2 mm; connections made by
# node distance as in YADE's examples/grids/Simple_Grid_Falling.py) tilted 30 deg about x, hanging from
# one fixed corner node and thrown down at 1 m/s under gravity (no damping).
# Exercises junction nodes with 2-4 bonds (node masses = sum of half-rib masses), large bond
# rotations (twist and bending in 3-D), connectionBody position sync, and the collider making
# (non-real) GridConnection-GridConnection pairs that Ig2_GridConnection_GridConnection rejects.
# Run: yade -n -x yade_ref/micro_grid/net.py [OUTDIR]
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *
from yade.gridpfacet import *

NX, NY = 3, 3
A = 0.06        # spacing
R = 0.002       # node / connection radius
TILT = math.radians(30)
STEPS = 1500

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
c, s = math.cos(TILT), math.sin(TILT)
nodes = []
for i in range(NX):
    for j in range(NY):
        x, y = i * A, j * A
        nodes.append(O.bodies.append(gridNode((x, y * c, y * s), R, material=nodeMat)))
conns = []
for i in range(len(nodes)):
    for j in range(i + 1, len(nodes)):
        dist = (O.bodies[nodes[i]].state.pos - O.bodies[nodes[j]].state.pos).norm()
        if dist <= A * 1.01:
            conns.append(O.bodies.append(gridConnection(nodes[i], nodes[j], R, material=ribMat)))
for n in nodes[1:]:
    O.bodies[n].state.vel = (0, 0, -1.0)
O.bodies[nodes[0]].dynamic = False      # fixed corner (after the masses were accumulated)
O.dt = 2e-5

rho = 950.0
Vh = 0.5 * A * math.pi * R ** 2
for n in nodes:
    b = O.bodies[n]
    k = len(b.shape.getConnections())
    print('[net] node %d: %d connections, mass %.17g (k * V/2 * rho = %.17g)' % (n, k, b.state.mass, k * Vh * rho))
print('[net] %d nodes, %d connections, bonds in container order:' % (len(nodes), len(conns)),
      [(i.id1, i.id2) for i in O.interactions.all(False)])


def final():
    real = [i for i in O.interactions if i.isReal]
    kinds = set(type(i.geom).__name__ for i in real)
    mb = max(i.phys.moment_bending.norm() for i in real)
    mt = max(i.phys.moment_twist.norm() for i in real)
    pot = len([i for i in O.interactions.all(False) if not i.isReal])
    print('[net] end: real %d (%s), potential %d, max |Mb| %g, max |Mt| %g, far corner %s'
          % (len(real), kinds, pot, mb, mt, O.bodies[nodes[-1]].state.pos))
    if len(real) != len(conns) or kinds != {'GridNodeGeom6D'}:
        return 'bonds broke or unexpected real interactions'
    if not (mb > 0 and mt > 0):
        return 'no bending/twist'
    return None


ryade_record.record('net', steps=STEPS, default_sub='golden/micro_grid', grid=True, final_check=final)
ryade_record.finish()
