# The concrete particle model, public version (pkg/dem/ConcretePM.cpp): CpmMat, Ip2_CpmMat_CpmMat_CpmPhys
# (one material copied, two averaged, damLaw of the first), Ip2_FrictMat_CpmMat_FrictPhys (the FrictMat
# body first: the other order aborts Debian's YADE on InteractionLoop's assert(!swap)), Law2_ScGeom_CpmPhys_Cpm (first-step
# lengths for sphere-sphere and sphere-facet/wall, damage in tension with omegaThreshold 0.9 breaking
# contacts, shear plasticity, compressive softening with epsSoft < 0, isoPrestress, neverDamage,
# equivStrainShearContrib, contacts made after cohesiveThresholdIter non-cohesive).
# Scenes: a chain of four spheres with initial gaps inside interactionDetectionFactor 1.5, one end fixed,
# the other pulled and sheared until the links break; a pair of two materials pressed together; a
# never-damaging pair pulled apart (driven); a sphere falling onto a CpmMat facet and another sliding on a CpmMat
# wall; a FrictMat sphere hitting a CpmMat one; two spheres meeting after iteration 10.
# Run: yade -n -x yade_ref/micro/rs_cpm.py [OUTDIR]
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
A = O.materials.append(CpmMat(young=1e7, poisson=0.2, density=2000, frictionAngle=0.6, sigmaT=1e4, epsCrackOnset=1e-3,
                              relDuctility=5, equivStrainShearContrib=0.5, label='A'))
B = O.materials.append(CpmMat(young=2e7, poisson=0.25, density=2500, frictionAngle=0.5, sigmaT=2e4, epsCrackOnset=2e-3,
                              relDuctility=3, damLaw=0, isoPrestress=50, label='B'))
N = O.materials.append(CpmMat(young=1.5e7, poisson=0.3, density=2200, frictionAngle=0.4, sigmaT=1e4, epsCrackOnset=1e-3,
                              relDuctility=4, neverDamage=True, label='N'))
F = O.materials.append(FrictMat(young=5e6, poisson=0.3, density=2000, frictionAngle=0.4, label='F'))
r = 0.01
# chain: spheres 2.1 r apart (gap 0.1 r, inside the factor 1.5), the first fixed, the last driven (pulled, sheared)
chain = [O.bodies.append(sphere((i * 2.1 * r, 0, 0), r, material=A, fixed=(i in (0, 3)))) for i in range(4)]
O.bodies[chain[-1]].state.vel = (0.08, 0.03, -0.02)
O.bodies[chain[1]].state.angVel = (0, 0, 3.0)
# two materials pressed together (the second driven) (averaged physics, damLaw 0 from the first: B)
p1 = O.bodies.append(sphere((0, 0.1, 0), r, material=B))
p2 = O.bodies.append(sphere((1.95 * r, 0.1, 0.002), 1.2 * r, material=A, fixed=True))
O.bodies[p1].state.vel = (0.05, 0, 0)
O.bodies[p2].state.vel = (-0.02, 0.01, 0)
# never-damaging pair pulled apart (driven)
n1 = O.bodies.append(sphere((0, 0.2, 0), r, material=N, fixed=True))
n2 = O.bodies.append(sphere((2.05 * r, 0.2, 0), r, material=N, fixed=True))
O.bodies[n2].state.vel = (0.02, 0.01, 0)
# a sphere falling onto a CpmMat facet, another pressed and sliding on a CpmMat wall
fc = O.bodies.append(facet(((0.2, -0.1, -0.05), (0.4, -0.1, -0.05), (0.3, 0.1, -0.05)), material=A))
s1 = O.bodies.append(sphere((0.3, 0, -0.05 + 1.05 * r), r, material=A))
O.bodies[s1].state.vel = (0.01, 0, -0.1)
wl = O.bodies.append(wall((0, 0, -0.3), axis=2, material=B))
s2 = O.bodies.append(sphere((0.5, 0.3, -0.3 + 0.98 * r), r, material=B))
O.bodies[s2].state.vel = (0.05, 0.02, 0)
O.bodies[s2].state.angVel = (1, -2, 0.5)
# FrictMat against CpmMat (the FrictMat body first)
f1 = O.bodies.append(sphere((0, 0.4, 0), 1.3 * r, material=F))
c1 = O.bodies.append(sphere((2.4 * r, 0.4, 0.003), r, material=A))
O.bodies[f1].state.vel = (0.1, 0, 0)
# two spheres meeting after iteration 10 (non-cohesive contact: it breaks as soon as it opens)
l1 = O.bodies.append(sphere((0, 0.6, 0), r, material=A))
l2 = O.bodies.append(sphere((3.6 * r, 0.6, 0.001), r, material=A))
O.bodies[l1].state.vel = (0.3, 0, 0)
O.bodies[l2].state.vel = (-0.3, 0, 0)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(aabbEnlargeFactor=1.5), Bo1_Facet_Aabb(), Bo1_Wall_Aabb()]),
    InteractionLoop(
        [Ig2_Sphere_Sphere_ScGeom(interactionDetectionFactor=1.5), Ig2_Facet_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
        [Ip2_CpmMat_CpmMat_CpmPhys(), Ip2_FrictMat_CpmMat_FrictPhys(), Ip2_FrictMat_FrictMat_FrictPhys()],
        [Law2_ScGeom_CpmPhys_Cpm(omegaThreshold=0.9, epsSoft=-2e-3, relKnSoft=0.3), Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=0.0, gravity=(0, 0, -9.81)),
]
O.dt = 2e-5

# a digest scene (golden/FORMAT.md): every step's SHA-256 of all values, full rows around the events
ryade_record.record('rs_cpm', steps=3000, micro_digest=True,
                    keep_steps=[0, 1, 2, 10, 11, 12, 200, 209, 210, 556, 557, 1500, 2565, 2566, 2567, 2754, 3000])
ryade_record.finish()
