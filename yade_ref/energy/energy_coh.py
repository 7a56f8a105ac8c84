# O.energy under O.trackEnergy recorded by YADE every step; ryade's `compat run` must write the same bytes
# (yade_ref/check_compat.sh; compat/tests/test_energy.py).   yade -n -x energy_coh.py OUTDIR
# A chain of cohesive spheres with rolling and twisting resistance, set spinning and falling:
# CohesionMoment's shearDissip, bendingDissip, twistDissip next to Newton's terms.
import os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
from energy_record import out_dir, record
from yade import utils
O.materials.append(CohFrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600, isCohesive=True, normalCohesion=1e3,
                               shearCohesion=1e3, momentRotationLaw=True, etaRoll=0.1, etaTwist=0.1, label='c'))
for k in range(6):
    O.bodies.append(utils.sphere((0.19 * k, 0.01 * k, 0.1 + 0.05 * (k % 2)), 0.1, material='c'))
O.bodies[2].state.angVel = Vector3(10, 30, 20)
O.bodies[4].state.vel = Vector3(1.5, 0, -2)
O.bodies[0].state.vel = Vector3(0, 1, 0)
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom6D()],
                             [Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow=True)],
                             [Law2_ScGeom6D_CohFrictPhys_CohesionMoment(useIncrementalForm=True, always_use_moment_law=True)]),
             NewtonIntegrator(damping=0.2, gravity=(0, 0, -9.81))]
O.dt = 0.5 * utils.PWaveTimeStep()
record(O, os.path.join(out_dir(), 'energy_coh.csv'), 1500)

