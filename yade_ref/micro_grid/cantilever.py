# Grid case G1: straight cantilever of 6 GridNodes along x (r = 2 mm, spacing 3 cm), node 0 fixed,
# bending under its own weight (gravity -9.81 z, no damping); the tip node also starts with a spin
# about x (twist) and a small sideways velocity (bending about z). dt = 2e-5 (3e-5 is unstable).
# Exercises gridNode/gridConnection (node masses, unp, kn = E pi r^2 / L, ks = 12 E I / L^3,
# kr = E I / L, ktw = 2 I G / L), Ig2_GridNode_GridNode_GridNodeGeom6D (rotations, connectionBody
# sync), Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow) and
# Law2_ScGeom6D_CohFrictPhys_CohesionMoment (total-form bending/twist moments, no limits).
# Run: yade -n -x yade_ref/micro_grid/cantilever.py [OUTDIR]
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *
from yade.gridpfacet import *

NN = 6          # nodes
R = 0.002       # node / connection radius
L = 0.03        # spacing
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
nodes = [O.bodies.append(gridNode((i * L, 0, 0), R, fixed=(i == 0), material=nodeMat)) for i in range(NN)]
conns = [O.bodies.append(gridConnection(nodes[i], nodes[i + 1], R, material=ribMat)) for i in range(NN - 1)]
# the tip node starts spinning about the chain axis and moving sideways: twist and 3-D bending
O.bodies[nodes[-1]].state.angVel = (20.0, 0, 0)
O.bodies[nodes[-1]].state.vel = (0, 0.01, 0)
O.dt = 2e-5

# ---- facts checked before the run (YADE values against closed forms)
E, nu, rho = 1e9, 0.3, 950.0
I_ = math.pi * (2 * R) ** 4 / 64
G = E / (2 * (1 + nu))
for k in range(NN - 1):
    i = O.interactions[nodes[k], nodes[k + 1]]
    ph = i.phys
    Lk = (O.bodies[nodes[k + 1]].state.pos - O.bodies[nodes[k]].state.pos).norm()
    assert ph.kn == E * math.pi * R ** 2 / Lk, (ph.kn, E * math.pi * R ** 2 / Lk)
    assert ph.ks == 12. * E * I_ / Lk ** 3 and ph.kr == E * I_ / Lk and ph.ktw == 2. * I_ * G / Lk
    assert ph.unp == -Lk + R + R and not ph.cohesionBroken
    assert i.geom.connectionBody.id == conns[k]
Vh = 0.5 * L * math.pi * R ** 2
print('[cantilever] kn=%.17g ks=%.17g kr=%.17g ktw=%.17g unp=%.17g' % (ph.kn, ph.ks, ph.kr, ph.ktw, ph.unp))
print('[cantilever] node masses', [O.bodies[n].state.mass for n in nodes], 'half-rib V*rho', Vh * rho)
print('[cantilever] intrs', [(i.id1, i.id2, i.isReal, i.iterMadeReal) for i in O.interactions.all(False)])

ip2 = O.engines[2].physDispatcher.functors[0]
flags = {}


def hook(step):
    if step in (0, 1, 2):
        flags[step] = ip2.setCohesionNow


def final():
    tip = O.bodies[nodes[-1]].state.pos
    mb = max(O.interactions[nodes[k], nodes[k + 1]].phys.moment_bending.norm() for k in range(NN - 1))
    mt = max(O.interactions[nodes[k], nodes[k + 1]].phys.moment_twist.norm() for k in range(NN - 1))
    print('[cantilever] setCohesionNow after steps 0,1,2:', flags)
    print('[cantilever] tip pos', tip, 'max |moment_bending|', mb, 'max |moment_twist|', mt)
    if flags != {0: True, 1: True, 2: False}:
        return 'unexpected setCohesionNow history %r' % flags
    if not (mb > 0 and mt > 0 and tip[2] < -1e-5):
        return 'cantilever did not bend (tip z %g, max Mb %g)' % (tip[2], mb)
    if len([i for i in O.interactions if i.isReal]) != NN - 1:
        return 'a bond broke'
    return None


ryade_record.record('cantilever', steps=STEPS, default_sub='golden/micro_grid', grid=True,
                    step_hook=hook, final_check=final)
ryade_record.finish()
