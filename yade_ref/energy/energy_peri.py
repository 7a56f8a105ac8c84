# O.energy under O.trackEnergy recorded by YADE every 5 steps; ryade's `compat run` must write the same
# bytes (yade_ref/check_compat.sh; compat/tests/test_energy.py).   yade -n -x energy_peri.py OUTDIR
# A periodic packing compressed by PeriTriaxController: its velGradWork next to Newton's and the law's terms.
import os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
from energy_record import out_dir, record
from yade import pack, utils
O.periodic = True
O.cell.setBox(0.6, 0.6, 0.6)
O.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.5, density=2600))
sp = pack.SpherePack()
sp.makeCloud((0, 0, 0), (0.6, 0.6, 0.6), rMean=0.05, rRelFuzz=0.2, periodic=True, seed=7)
sp.toSimulation()
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
             PeriTriaxController(goal=(-2e4, -2e4, -2e4), stressMask=7, maxUnbalanced=1e-3, maxStrainRate=(0.5, 0.5, 0.5), dynCell=False),
             NewtonIntegrator(damping=0.2)]
O.dt = 0.5 * utils.PWaveTimeStep()
record(O, os.path.join(out_dir(), 'energy_peri.csv'), 1500, every=5)
