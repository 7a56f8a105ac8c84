# Grid case G5 (rolling resistance, total form): two CohFrictMat spheres (r = 1.5 cm, isCohesive=False,
# momentRotationLaw=True, alphaKr = alphaKtw = 0.5, etaRoll = etaTwist = 0.5): sphere A rests on a fixed
# Box floor (FrictMat), sphere B sits on top of A (1 mm off-axis) and starts spinning with
# angVel (0, 15, 10) rad/s (bending about y, twist about the vertical contact normal); gravity, no damping.
# Ig2_Sphere_Sphere_ScGeom6D + Ip2_CohFrictMat_CohFrictMat_CohFrictPhys +
# Law2_ScGeom6D_CohFrictPhys_CohesionMoment(always_use_moment_law=True, useIncrementalForm=False):
# moment_bending = kr * bending and moment_twist = ktw * twist * n from the total relative rotation,
# scaled down to maxRollPl |Fn| and maxTwistPl |Fn| (maxRollPl = maxTwistPl = 0.5 * 0.015); the law logs
# a warning on every call because the limits are active with the total form (expected, harmless).
# Sphere A - floor: Ig2_Box_Sphere_ScGeom + Ip2_FrictMat_FrictMat_FrictPhys (FrictMat vs CohFrictMat
# falls back to the FrictMat functor) + Law2_ScGeom_FrictPhys_CundallStrack.
# Run: yade -n -x yade_ref/micro_grid/rolling.py [OUTDIR]
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

# rolling_inc.py runs this same script with RYADE_ROLLING_INCREMENTAL = True (incremental moment form)
INCREMENTAL = globals().get('RYADE_ROLLING_INCREMENTAL', False)
NAME = 'rolling_inc' if INCREMENTAL else 'rolling'
RS = 0.015
STEPS = 1500

O.reset()
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb()]),
    InteractionLoop(
        [Ig2_Sphere_Sphere_ScGeom6D(), Ig2_Box_Sphere_ScGeom()],
        [Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(), Ip2_FrictMat_FrictMat_FrictPhys()],
        [Law2_ScGeom6D_CohFrictPhys_CohesionMoment(always_use_moment_law=True, useIncrementalForm=INCREMENTAL),
         Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=0.0, gravity=(0, 0, -9.81)),
]
floorMat = O.materials.append(FrictMat(young=1e8, poisson=0.25, density=2650, frictionAngle=math.radians(30),
                                       label='floor'))
sphMat = O.materials.append(CohFrictMat(young=1e8, poisson=0.25, density=2650, frictionAngle=math.radians(30),
                                        isCohesive=False, momentRotationLaw=True, alphaKr=0.5, alphaKtw=0.5,
                                        etaRoll=0.5, etaTwist=0.5, label='rolling'))
floor = O.bodies.append(utils.box((0, 0, -0.01), (0.2, 0.2, 0.01), fixed=True, material=floorMat))
# start at the static overlaps (kn = E r = 1.5e6 N/m for sphere-box and sphere-sphere), so that B does
# not bounce on A (there is no contact damping)
W = 2650 * 4. / 3 * math.pi * RS ** 3 * 9.81
KN = 1e8 * RS
sA = O.bodies.append(utils.sphere((0, 0, RS - 2 * W / KN), RS, material=sphMat))
sB = O.bodies.append(utils.sphere((0.001, 0, RS - 2 * W / KN + math.sqrt((2 * RS - W / KN) ** 2 - 0.001 ** 2)), RS,
                                  material=sphMat))
O.bodies[sB].state.angVel = (0, 15.0, 10.0)
O.dt = 2e-5

stat = {'limited_b': 0, 'limited_t': 0, 'contact_steps': 0, 'max_mb': 0.0, 'max_mt': 0.0}


def hook(step):
    if not O.interactions.has(sA, sB) or not O.interactions[sA, sB].isReal:
        return
    i = O.interactions[sA, sB]
    ph = i.phys
    fn = ph.normalForce.norm()
    mb, mt = ph.moment_bending.norm(), ph.moment_twist.norm()
    stat['contact_steps'] += 1
    stat['max_mb'] = max(stat['max_mb'], mb)
    stat['max_mt'] = max(stat['max_mt'], mt)
    # at the limit: |M| == maxPl * |Fn| up to rounding
    if step > 0 and abs(mb - ph.maxRollPl * fn) <= 1e-12 * mb:
        stat['limited_b'] += 1
    if step > 0 and abs(mt - ph.maxTwistPl * fn) <= 1e-12 * max(mt, 1e-300):
        stat['limited_t'] += 1


def final():
    i = O.interactions[sA, sB] if O.interactions.has(sA, sB) else None
    print('[%s] kn %.17g ks %.17g kr %.17g ktw %.17g maxRollPl %.17g maxTwistPl %.17g cohesionBroken %s'
          % (NAME, i.phys.kn, i.phys.ks, i.phys.kr, i.phys.ktw, i.phys.maxRollPl, i.phys.maxTwistPl,
             i.phys.cohesionBroken))
    print('[%s] contact steps %d, bending moment at the limit in %d steps, twist in %d; max |Mb| %g, max |Mt| %g'
          % (NAME, stat['contact_steps'], stat['limited_b'], stat['limited_t'], stat['max_mb'], stat['max_mt']))
    print('[%s] end: A pos %s angVel %s; B pos %s angVel %s' % (NAME, O.bodies[sA].state.pos, O.bodies[sA].state.angVel,
                                                              O.bodies[sB].state.pos, O.bodies[sB].state.angVel))
    if i is None or not i.isReal or stat['contact_steps'] != STEPS:
        return 'the sphere-sphere contact was lost'
    if stat['limited_b'] < 100 or stat['limited_t'] < 100:
        return 'the rolling/twist limits were hardly active'
    return None


ryade_record.record(NAME, steps=STEPS, default_sub='golden/micro_grid', grid=True, step_hook=hook, final_check=final)
ryade_record.finish()
