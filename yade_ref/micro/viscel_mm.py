# Ip2_ViscElMat_ViscElMat_ViscElPhys with MatchMakers (pkg/common/MatchMaker.cpp): en, et and frictAngle per pair
# of materials (matches given in either order), tc by the 'val' fallback (a number given where a MatchMaker is
# taken), the others of unmatched pairs by 'avg' of the materials' values would be refused (NaN values), so
# every pair used is matched. Three ViscElMat, spheres falling pairwise on fixed ones and on each other, as
# examples/ViscElMatchMaker.py, plus a sliding pair. Gravity, no damping.
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
r = 0.002381
mats = [O.materials.append(ViscElMat(frictionAngle=0.5, tc=0.001, en=0.5, et=0.5, density=2000)) for _ in range(3)]
specs = [((0, 0, 0), 0, True), ((0, 0, 2 * r), 1, False), ((3 * r, 0, 0), 0, True), ((3 * r, 0, 2 * r), 2, False),
         ((6 * r, 0, 0), 1, True), ((6 * r + 0.0005, 0, 2 * r), 2, False), ((9 * r, 0, 0), 2, True),
         ((9 * r + 0.001, 0.0003, 2 * r - 1e-5), 2, False)]
for c, m, fixed in specs:
    O.bodies.append(utils.sphere(c, r, material=mats[m], fixed=fixed))
for b in O.bodies:
    if not b.state.blockedDOFs:
        b.state.vel = (0.02, 0, -0.5)
mm = lambda a, b, c: MatchMaker(matches=((mats[0], mats[1], a), (mats[2], mats[0], b), (mats[1], mats[2], c),
                                         (mats[2], mats[2], 0.7)))
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()], verletDist=2 * r),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom()],
                    [Ip2_ViscElMat_ViscElMat_ViscElPhys(tc=0.0012, en=mm(.9, .5, .1), et=mm(.8, .4, .3),
                                                        frictAngle=mm(.1, .2, .3))],
                    [Law2_ScGeom_ViscElPhys_Basic()]),
    NewtonIntegrator(damping=0, gravity=(0, 0, -9.81)),
]
O.dt = 2e-6

ryade_record.record('viscel_mm', steps=3000)
ryade_record.finish()
