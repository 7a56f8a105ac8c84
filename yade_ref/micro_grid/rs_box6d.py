# Ig2_Box_Sphere_ScGeom6D (pkg/dem/Ig2_Box_Sphere_ScGeom.cpp): the box-sphere ScGeom made a ScGeom6D,
# its rotations precomputed every step (no creep). A fixed, tilted CohFrictMat box; sphere A rests on it
# spinning about two axes (bending and twist about the contact normal), sphere B falls on it off-centre
# with a spin and then rolls; sphere C rests on one of its edges.
# Ip2_CohFrictMat_CohFrictMat_CohFrictPhys + Law2_ScGeom6D_CohFrictPhys_CohesionMoment
# (always_use_moment_law=True): rolling and twisting resistance on the 6-D box contacts; gravity,
# damping 0.1. Run: yade -n -x yade_ref/micro_grid/rs_box6d.py [OUTDIR]
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
mat = O.materials.append(CohFrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=math.radians(30),
                                     isCohesive=False, momentRotationLaw=True, alphaKr=0.3, alphaKtw=0.2,
                                     etaRoll=0.2, etaTwist=0.1, label='m'))
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb()]),
    InteractionLoop(
        [Ig2_Sphere_Sphere_ScGeom6D(), Ig2_Box_Sphere_ScGeom6D()],
        [Ip2_CohFrictMat_CohFrictMat_CohFrictPhys()],
        [Law2_ScGeom6D_CohFrictPhys_CohesionMoment(always_use_moment_law=True)]),
    NewtonIntegrator(damping=0.1, gravity=(0, 0, -9.81)),
]
q = Quaternion((1, 0.3, 0), 0.1)
floor = O.bodies.append(utils.box((0, 0, 0), (0.5, 0.4, 0.05), fixed=True, material=mat))
O.bodies[floor].state.ori = q
n = q * Vector3(0, 0, 1)


def on_top(x, y, r, gap):
    """Centre of a sphere of radius r over point (x, y) of the box top, `gap` from touching (< 0: overlap)."""
    return q * Vector3(x, y, 0.05) + n * (r + gap)


# A: at its static overlap (kn = E r), spinning about two axes
a = O.bodies.append(utils.sphere(on_top(0.0, 0.0, 0.1, -1.07e-4), 0.1, material=mat))
O.bodies[a].state.angVel = (2.0, -1.0, 5.0)
# B: falls from 2 cm with a spin, then rolls down the tilt
b = O.bodies.append(utils.sphere(on_top(0.25, 0.1, 0.08, 0.02), 0.08, material=mat))
O.bodies[b].state.vel = (-0.3, 0.1, -0.2)
O.bodies[b].state.angVel = (0, 4.0, -3.0)
# C: over the box's edge (the contact point on the edge, the outside branch), sliding along it
c = O.bodies.append(utils.sphere(q * Vector3(-0.5, -0.2, 0.05) + (q * Vector3(-1, 0, 1)).normalized() * 0.0499, 0.05,
                                 material=mat))
O.bodies[c].state.vel = (0.0, 0.2, 0)
O.dt = 2e-5

ryade_record.record('rs_box6d', steps=3000, default_sub='golden/micro_grid', grid=True)
ryade_record.finish()
