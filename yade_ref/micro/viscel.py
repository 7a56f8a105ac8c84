# ViscElMat (pkg/dem/ViscoelasticPM.cpp): Ip2_ViscElMat_ViscElMat_ViscElPhys and Law2_ScGeom_ViscElPhys_Basic.
# Three groups of bodies that never meet, one per way the Ip2 gets a contact's constants, gravity, no damping:
#  A  contact time and restitutions (tc, en, et; Pournin): a fixed facet (massless: the sphere's mass stands
#     in) and two spinning spheres, the second dropped onto the first one's shoulder;
#  B  young, poisson and the normal restitution en (cn solved by Newton iteration, no shear damping), rolling
#     resistance mRtype 2: a wall floor and two spinning spheres thrown obliquely into it and into each other;
#  C  explicit kn, ks, cn, cs, rolling resistance mRtype 1: two spinning spheres colliding high above the floor.
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
mA = O.materials.append(ViscElMat(tc=0.002, en=0.6, et=0.8, frictionAngle=math.radians(25), density=2600))
mB = O.materials.append(ViscElMat(young=1e7, poisson=0.25, en=0.5, mR=0.05, mRtype=2,
                                  frictionAngle=math.radians(20), density=2600))
mC = O.materials.append(ViscElMat(kn=2e5, ks=6e4, cn=4.0, cs=1.0, mR=0.1, mRtype=1,
                                  frictionAngle=math.radians(30), density=2600))
r = 0.01
O.bodies.append(utils.wall(0.0, axis=2, material=mB))                                                 # 0
O.bodies.append(utils.facet([(-0.2, -0.2, 0.05), (0.2, -0.2, 0.05), (0.0, 0.25, 0.05)], material=mA))   # 1
a1 = O.bodies.append(utils.sphere((0.0, 0.0, 0.05 + r + 1e-6), r, material=mA))                        # 2
a2 = O.bodies.append(utils.sphere((0.012, 0.003, 0.05 + r + 0.0172), r, material=mA))                  # 3
b1 = O.bodies.append(utils.sphere((0.5, 0.0, r + 1e-6), r, material=mB))                               # 4
b2 = O.bodies.append(utils.sphere((0.521, 0.002, r + 2e-4), r, material=mB))                           # 5
c1 = O.bodies.append(utils.sphere((-0.5, 0.0, 1.0), r, material=mC))                                   # 6
c2 = O.bodies.append(utils.sphere((-0.48, 0.003, 1.0), r, material=mC))                               # 7
for i, v, w in [(a1, (0.1, 0, 0), (0, 0, 10)), (a2, (0, 0, -0.3), (4, -6, 0)), (b1, (0.2, 0.1, -0.1), (0, 8, 0)),
                (b2, (-0.1, 0, -0.2), (3, 0, 5)), (c1, (0.5, 0, 0), (0, 0, 20)), (c2, (-0.3, 0.05, 0), (5, 0, -10))]:
    O.bodies[i].state.vel = v
    O.bodies[i].state.angVel = w
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb(), Bo1_Wall_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                    [Ip2_ViscElMat_ViscElMat_ViscElPhys()],
                    [Law2_ScGeom_ViscElPhys_Basic()]),
    NewtonIntegrator(damping=0.0, gravity=(0, 0, -9.81)),
]
O.dt = 1e-5

ryade_record.record('viscel', steps=2000)
ryade_record.finish()
