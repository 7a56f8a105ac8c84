# PeriTriaxController (pkg/dem/PeriIsoCompressor.cpp) on 48 spheres in a periodic cell: the cell's
# velocity gradient is the controller's output, so this scene checks the moving cell bit for bit
# (Cell::integrateAndUpdate, NewtonIntegrator's homothetic terms, the periodic collider on a shrinking
# cell, shiftVel in the contact kinematics) together with the controller.
#
# Preparation (not recorded): makeCloud(seed=3) in a 0.035 m cell, compressed by a PeriTriaxController
# to about 0.43 porosity; the positions, velocities and cell are then put into a fresh scene (no
# contacts yet), which is what ryade starts from. Recorded (1250 steps):
#   stage 1  isotropic stress goal -20 kPa (stressMask 7), stiffness servo (dynCell False);
#   doneHook stage2(): axial strain goal 0.5 % beyond the current z strain, lateral stress kept
#            (stressMask 3), hook -> stage3();
#   doneHook stage3(): cell inertia servo (dynCell True, mass from the bodies) back to -20 kPa on all axes.
# Both hooks must fire inside the window (final_check). Digest scene (FORMAT.md): every step is hashed,
# full body and contact rows at 6 steps, the cell and controller every step in peri_triax.peri.csv.gz.
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *
from yade import pack

STEPS = 1250


def frict():
    return FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=math.radians(30))


O.reset()
O.periodic = True
mat = O.materials.append(frict())
sp = pack.SpherePack()
sp.makeCloud((0, 0, 0), (0.035, 0.035, 0.035), rMean=0.004, rRelFuzz=0.2, num=48, periodic=True, seed=3)
sp.toSimulation(material=mat)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    PeriTriaxController(goal=(-2e4, -2e4, -2e4), stressMask=7, maxStrainRate=(5, 5, 5), globUpdate=5),
    NewtonIntegrator(damping=0.4),
]
O.dt = 0.5 * utils.PWaveTimeStep()
O.run(6000, True)
state = [(tuple(b.state.pos), b.shape.radius, tuple(b.state.vel), tuple(b.state.angVel)) for b in O.bodies]
hsize = Matrix3(O.cell.hSize)

O.reset()
O.periodic = True
O.cell.hSize = hsize
mat = O.materials.append(frict())
for pos, r, vel, angVel in state:
    b = O.bodies[O.bodies.append(utils.sphere(pos, r, material=mat))]
    b.state.vel = vel
    b.state.angVel = angVel

fired = []


def stage2():
    fired.append(('stage2', O.iter))
    triax.goal = (-2e4, -2e4, triax.strain[2] - 0.005)
    triax.stressMask = 3
    triax.doneHook = 'stage3()'


def stage3():
    fired.append(('stage3', O.iter))
    triax.dynCell = True
    triax.goal = (-2e4, -2e4, -2e4)
    triax.stressMask = 7
    triax.doneHook = ''


O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()], verletDist=-0.2),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    PeriTriaxController(label='triax', goal=(-2e4, -2e4, -2e4), stressMask=7, maxStrainRate=(1, 1, 1),
                        maxUnbalanced=0.3, relStressTol=0.1, absStressTol=1e4, globUpdate=5, doneHook='stage2()'),
    NewtonIntegrator(damping=0.4),
]
O.dt = 0.5 * utils.PWaveTimeStep()


def final_check():
    names = [f[0] for f in fired]
    if names != ['stage2', 'stage3']:
        return 'doneHooks fired %r, expected stage2 then stage3' % (fired,)
    if fired[1][1] > STEPS - 200:
        return 'stage3 fired at %d: fewer than 200 dynCell steps recorded' % fired[1][1]
    return None


# full rows: the first steps, the steps right after each doneHook (they fire at 690 and 955), the last
ryade_record.record('peri_triax', steps=STEPS, micro_digest=True, keep_steps=[0, 1, 2, 691, 956, STEPS],
                    final_check=final_check)
print('doneHooks fired:', fired)
ryade_record.finish()
