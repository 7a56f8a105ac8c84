# O.energy under O.trackEnergy recorded by YADE every step; ryade's `compat run` must write the same bytes
# (yade_ref/check_compat.sh; compat/tests/test_energy.py).   yade -n -x energy_facet.py OUTDIR
# Spheres on facets under gravity with damping 0.3: NewtonIntegrator's nonviscDamp, kinetic, gravWork and
# Cundall-Strack's elastPotential, plastDissip, with a clump (aspherical kinetic energy), a sphere with
# blocked DOFs and a fixed body moved by its velocity (Newton counts its work, as YADE does).
import os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
from energy_record import out_dir, record
from yade import utils
O.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.4, density=2600, label='m'))
O.bodies.append(utils.facet([(-1, -1, 0), (1, -1, 0), (0, 1, 0)], material='m'))
O.bodies.append(utils.facet([(-1, -1, 0), (0, 1, 0), (-1, 1, 0.3)], material='m'))
O.bodies.append(utils.sphere((0, 0, 0.105), 0.1, material='m'))
O.bodies.append(utils.sphere((0.05, 0.02, 0.35), 0.1, material='m'))
O.bodies.append(utils.sphere((0.3, -0.3, 0.2), 0.08, material='m'))
O.bodies[4].state.blockedDOFs = 'xY'
O.bodies[3].state.vel = Vector3(0.3, -0.1, 0)
O.bodies[2].state.angVel = Vector3(0, 2.0, 0)
O.bodies.appendClumped([utils.sphere((-0.4, 0.2, 0.3), 0.07, material='m'), utils.sphere((-0.33, 0.24, 0.33), 0.06, material='m')])
piston = utils.sphere((0.4, 0.4, 0.5), 0.05, material='m', fixed=True)
O.bodies.append(piston)
piston.state.vel = Vector3(0, 0, -0.2)
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                             [Law2_ScGeom_FrictPhys_CundallStrack()]),
             NewtonIntegrator(damping=0.3, gravity=(0, 0, -9.81))]
O.dt = 0.5 * utils.PWaveTimeStep()
record(O, os.path.join(out_dir(), 'energy_facet.csv'), 1500)

