# Clumps: three rigid clumps of overlapping spheres (two 2-sphere clumps, one 3-sphere clump) and
# one loose sphere thrown onto a floor of two facets next to a fixed Box wall, then four small 2- and
# 3-sphere clumps rained into the corner of a second Box wall; gravity -9.81, damping 0.4, friction
# 30 deg, dt = 0.5*PWaveTimeStep(). The clumps land on the floor, the walls and each other, tumble
# and pile up.
# Exercises Clump::updateProperties (discretization 0, overlaps counted twice; clump ids after
# their members, mass/centroid/principal inertia and orientation from Eigen's SelfAdjointEigenSolver),
# NewtonIntegrator's clump branch (members' forces and torques summed about the centroid, the clump
# integrated with leapfrogAsphericalRotate from its angular momentum, torque damped with the
# 1st-order Cundall rule, members placed by Clump::moveMembers) and Collider::mayCollide (members of
# one clump never interact). One clump starts with an angular momentum (State.angMom): setting
# angVel on an aspherical clump has no effect in YADE.
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
mat = O.materials.append(FrictMat(young=1e6, poisson=0.3, density=2600, frictionAngle=math.radians(30)))
L = 0.2
O.bodies.append([
    utils.facet([(-L, -L, 0), (L, -L, 0), (L, L, 0.01)], material=mat),
    utils.facet([(-L, -L, 0), (L, L, 0.01), (-L, L, 0)], material=mat),
    utils.box((0.12, 0, 0.05), (0.01, L, 0.05), fixed=True, material=mat),
])
# clump A: two overlapping spheres, axis tilted, pushed towards the wall
a = O.bodies.appendClumped([
    utils.sphere((0.06, 0.0, 0.025), 0.02, material=mat),
    utils.sphere((0.082, 0.006, 0.037), 0.015, material=mat),
])
# clump B: three overlapping spheres in a bent triangle, dropped onto clump A
b = O.bodies.appendClumped([
    utils.sphere((0.065, 0.004, 0.066), 0.015, material=mat),
    utils.sphere((0.085, -0.008, 0.071), 0.014, material=mat),
    utils.sphere((0.075, 0.016, 0.081), 0.013, material=mat),
])
# clump C: built with O.bodies.clump from appended spheres of unequal size, with a spin
ids = O.bodies.append([
    utils.sphere((0.058, 0.045, 0.03), 0.018, material=mat),
    utils.sphere((0.078, 0.05, 0.042), 0.012, material=mat),
])
c = O.bodies.clump(ids)
s = O.bodies.append(utils.sphere((0.03, -0.03, 0.02), 0.016, material=mat))
O.bodies[a[0]].state.vel = (0.3, 0.05, -0.1)
O.bodies[b[0]].state.vel = (0.05, 0.0, -0.3)
O.bodies[c].state.vel = (0.1, -0.2, 0.0)
O.bodies[c].state.angMom = (2e-6, -1e-6, 3e-6)
O.bodies[s].state.vel = (0.3, 0.3, 0.0)
# a second wall and four small 2- and 3-sphere clumps dropped into the corner, to pile up
O.bodies.append(utils.box((0, 0.11, 0.05), (L, 0.01, 0.05), fixed=True, material=mat))
rain = []
for k in range(4):
    x0, y0, z0 = 0.095 - 0.028 * (k % 2), 0.085 - 0.027 * (k // 2), 0.03 + 0.025 * k
    ph = 0.9 * k
    d = (0.011 * math.cos(ph), 0.011 * math.sin(ph), 0.004 * (k % 2))
    sph = [utils.sphere((x0, y0, z0), 0.012, material=mat),
           utils.sphere((x0 + d[0], y0 + d[1], z0 + d[2]), 0.01, material=mat)]
    if k % 2 == 0:
        sph.append(utils.sphere((x0 - d[1], y0 + d[0], z0 + 0.006), 0.009, material=mat))
    rain.append(O.bodies.appendClumped(sph))
for k, (cid, mids) in enumerate(rain):
    O.bodies[cid].state.vel = (0.1 * math.sin(k), 0.1 * math.cos(k), -0.2)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb(), Bo1_Box_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=0.4, gravity=(0, 0, -9.81)),
]
O.dt = 0.5 * utils.PWaveTimeStep()
print('clump: clumps %d %d %d, aspherical %s, dt=%.17g' % (a[0], b[0], c, [O.bodies[i].aspherical for i in (a[0], b[0], c)], O.dt), flush=True)

ryade_record.record('clump', steps=1500)
ryade_record.finish()
