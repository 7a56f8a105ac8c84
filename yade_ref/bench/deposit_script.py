# An unchanged-YADE-style user script for the bench: gravity deposition of NUM spheres (makeCloud, seed 1)
# into an open facet box (geom.facetBox), FrictMat, default-style engines, damping 0.4. Times one
# O.run(STEPS, True) after WARMUP steps and prints a BENCH line like run_scene.py.
#   yade -n -x yade_ref/bench/deposit_script.py [NUM] [STEPS] [WARMUP]
#   compat run --fast yade_ref/bench/deposit_script.py [NUM] [STEPS] [WARMUP] [SEED] [roll]
# With 'roll' the spheres and facets are CohFrictMat with the study's rolling resistance (ScGeom6D,
# CohFrictPhys, CohesionMoment with the incremental form; facets through Cundall-Strack).
import sys, time
from yade import pack, geom

num = int(sys.argv[1]) if len(sys.argv) > 1 else 4000
steps = int(sys.argv[2]) if len(sys.argv) > 2 else 2000
warmup = int(sys.argv[3]) if len(sys.argv) > 3 else 8000   # the pile has formed by then
seed = int(sys.argv[4]) if len(sys.argv) > 4 else 1
roll = len(sys.argv) > 5 and sys.argv[5] == 'roll'   # the study's aggregate: rolling resistance (CohFrictMat)
r = 0.01
L = (num * 4.18879 * r**3 / 0.1 / 3)**(1. / 3)   # a cloud of solid fraction ~0.1, three times as high as wide
if roll:
    mat = O.materials.append(CohFrictMat(young=1e7, poisson=0.3, frictionAngle=radians(30), density=2600, isCohesive=False,
                                         momentRotationLaw=True, alphaKr=0.5, alphaKtw=0.5, etaRoll=0.5, etaTwist=0.5))
else:
    mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=radians(30), density=2600))
O.bodies.append(geom.facetBox((L / 2, L / 2, 1.5 * L), (L / 2, L / 2, 1.5 * L), wallMask=31, material=mat))   # no lid
sp = pack.SpherePack()
sp.makeCloud((0, 0, 0), (L, L, 3 * L), rMean=r, rRelFuzz=0.2, num=num, seed=seed)
sp.toSimulation(material=mat)
if roll:
    loop = InteractionLoop([Ig2_Sphere_Sphere_ScGeom6D(), Ig2_Facet_Sphere_ScGeom()],
                           [Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(), Ip2_FrictMat_FrictMat_FrictPhys()],
                           [Law2_ScGeom6D_CohFrictPhys_CohesionMoment(always_use_moment_law=True, useIncrementalForm=True),
                            Law2_ScGeom_FrictPhys_CundallStrack()])
else:
    loop = InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                           [Law2_ScGeom_FrictPhys_CundallStrack()])
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]), loop,
             NewtonIntegrator(damping=0.4, gravity=(0, 0, -9.81))]
O.dt = 0.5 * PWaveTimeStep()
if warmup:
    O.run(warmup, True)
t0 = time.time()
O.run(steps, True)
dt = time.time() - t0
nc = O.interactions.countReal()
print('BENCH steps=%d bodies=%d contacts=%d seconds=%.6f particle_steps_per_s=%.6g contact_updates_per_s=%.6g'
      % (steps, len(O.bodies), nc, dt, steps * len(O.bodies) / dt, steps * nc / dt))
zmax = max(b.state.pos[2] for b in O.bodies if isinstance(b.shape, Sphere))
ke = sum(0.5 * b.state.mass * b.state.vel.squaredNorm() for b in O.bodies)
weight = sum(b.state.mass for b in O.bodies if isinstance(b.shape, Sphere)) * 9.81
print('STATE iter=%d zmax=%.9g kinetic=%.9g facetFz=%.9g weight=%.9g' % (O.iter, zmax, ke, sum(O.forces.f(b.id)[2] for b in O.bodies if isinstance(b.shape, Facet)), weight))
