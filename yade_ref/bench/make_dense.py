# Benchmark scene (a) of issue 6: a dense periodic packing of 8000 spheres (rRelFuzz 0.3, FrictMat
# E=1e8, friction 30 deg, Cundall-Strack, damping 0.2) compacted to 100 kPa mean stress, relaxed with the
# cell held fixed until it is static and still at ~100 kPa, then exported (17 digits) as a ryade scene
# file so that YADE and ryade time the very same loaded state.
#   yade -n -x yade_ref/bench/make_dense.py OUT.scene.json [NUM] [FROM.scene.json]
# With FROM, step 1 is skipped: the spheres, cell and engines are read from that scene file (a
# state exported after step 1, e.g. the earlier export of this script), then steps 2-3 run.
# Steps:
#  1. makeCloud at solid fraction ~0.24, PeriIsoCompressor to 100 kPa (keepProportions);
#  2. loop: cell frozen (velGrad = 0), velocities zeroed, 2,000 relaxation steps; the mean stress
#     (-trace(utils.getStress())/3) is measured; if it is off by more than 3 % the cell is strained
#     homogeneously (a short constant velGrad, particles follow affinely) by the amount a linear
#     stiffness estimate asks for, and the loop repeats;
#  3. the final state is checked by running the 2,000 timed steps on a copy (O.saveTmp/loadTmp) and
#     printing the mean stress before and after.
import os, sys, json, time
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import pack

out = sys.argv[1]
num = int(sys.argv[2]) if len(sys.argv) > 2 else 8000
target = 100e3
r = 0.01
O.periodic = True
mat = O.materials.append(FrictMat(young=1e8, poisson=0.25, frictionAngle=radians(30), density=2650))
L = (num * 4.18879 * r**3 / 0.24)**(1. / 3)   # cloud at solid fraction ~0.24 (makeCloud's limit)
src = sys.argv[3] if len(sys.argv) > 3 else None
if src is None:
    sp = pack.SpherePack()
    n = sp.makeCloud((0, 0, 0), (L, L, L), rMean=r, rRelFuzz=0.3, num=num, periodic=True, seed=1)
    sp.toSimulation(material=mat)
    O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 PeriIsoCompressor(charLen=2 * r, stresses=[-target], maxUnbalanced=1e-2, doneHook='O.pause()', globalUpdateInt=20,
                                   keepProportions=True, label='comp'),
                 NewtonIntegrator(damping=0.2)]
    O.dt = 0.5 * PWaveTimeStep()
else:
    d0 = json.load(open(src))
    h = d0['cell_hsize']
    O.cell.hSize = Matrix3(*[h[i][j] for i in range(3) for j in range(3)])
    for b in d0['bodies']:
        body = utils.sphere(Vector3(*b['pos']), b['shape']['radius'], material=mat)
        body.state.vel, body.state.angVel = Vector3(*b['vel']), Vector3(*b['angVel'])
        w, x, y, z = b['ori']
        body.state.ori = Quaternion(w, x, y, z)
        body.state.mass, body.state.inertia = b['mass'], Vector3(*b['inertia'])
        O.bodies.append(body)
    O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 NewtonIntegrator(damping=0.2)]
    O.dt = d0['dt']
    n = len(O.bodies)
    print('read %d spheres from %s, dt %g' % (n, src, O.dt))


def mean_stress():
    s = utils.getStress()
    return -(s[0, 0] + s[1, 1] + s[2, 2]) / 3.


t0 = time.time()
if src is None:
    O.run(200000, True)
print('compressor done: %d iterations, %.0f s, cell %s, porosity %.4f, mean stress %.4g, unbalanced %.3g'
      % (O.iter, time.time() - t0, O.cell.size, utils.porosity(), mean_stress(), unbalancedForce()))
sys.stdout.flush()
O.engines = [e for e in O.engines if not isinstance(e, PeriIsoCompressor)]


def freeze_relax(steps):
    O.cell.velGrad = Matrix3.Zero
    for b in O.bodies:
        b.state.vel = Vector3.Zero
        b.state.angVel = Vector3.Zero
    O.run(steps, True)


freeze_relax(2000)
K = None   # d(mean stress)/d(volumetric strain), estimated from the previous correction
for it in range(30):
    p = mean_stress()
    print('relax %d: iter %d, mean stress %.5g, unbalanced %.3g, contacts %d' % (it, O.iter, p, unbalancedForce(), O.interactions.countReal()))
    sys.stdout.flush()
    if abs(p - target) < 0.03 * target:
        break
    if K is None:
        K = 50 * target   # first guess of the bulk stiffness of the packing
    ev = -(target - p) / K   # volumetric strain to apply (negative = compress)
    nsteps = 500
    rate = ev / 3. / (nsteps * O.dt)
    O.cell.velGrad = Matrix3(rate, 0, 0, 0, rate, 0, 0, 0, rate)
    O.run(nsteps, True)
    freeze_relax(2000)
    p2 = mean_stress()
    if abs(ev) > 0 and (p2 - p) / -ev > 0:
        K = (p2 - p) / -ev
# one step clears prevVelGrad; the exported state is then the relaxed, loaded packing
O.cell.velGrad = Matrix3.Zero
O.step()
O.resetTime()
p0 = mean_stress()
d = ryade_record.scene_dict(2000, script='yade_ref/bench/make_dense.py')
d['source'] = 'yade 2023.02a (PeriIsoCompressor to 100 kPa, then relaxed with a fixed cell at %.4g Pa mean stress)' % p0
with open(out, 'w') as f:
    json.dump(d, f)
nc0 = O.interactions.countReal()
print('written %s: porosity %.4f, real contacts %d, coordination %.3f, mean stress %.5g' % (out, utils.porosity(), nc0, 2. * nc0 / len(O.bodies), p0))
O.run(2000, True)
nc1 = O.interactions.countReal()
print('after the 2000 timed steps: real contacts %d, coordination %.3f, mean stress %.5g, unbalanced %.3g'
      % (nc1, 2. * nc1 / len(O.bodies), mean_stress(), unbalancedForce()))
sys.stdout.flush()
