# Benchmark scene (a) of issue 6: a dense periodic packing of 8000 spheres (rRelFuzz 0.3, FrictMat
# E=1e8, friction 30 deg, Cundall-Strack, damping 0.2) compacted to 100 kPa with PeriIsoCompressor, then
# exported (17 digits) as a ryade scene file so that YADE and ryade time the very same state.
#   yade -n -x yade_ref/bench/make_dense.py OUT.scene.json [NUM]
import os, sys, json, time
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import pack

out = sys.argv[1]
num = int(sys.argv[2]) if len(sys.argv) > 2 else 8000
r = 0.01
O.periodic = True
mat = O.materials.append(FrictMat(young=1e8, poisson=0.25, frictionAngle=radians(30), density=2650))
L = (num * 4.18879 * r**3 / 0.24)**(1. / 3)   # cloud at solid fraction ~0.24 (makeCloud's limit)
sp = pack.SpherePack()
n = sp.makeCloud((0, 0, 0), (L, L, L), rMean=r, rRelFuzz=0.3, num=num, periodic=True, seed=1)
sp.toSimulation(material=mat)
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
             PeriIsoCompressor(charLen=2 * r, stresses=[-100e3], maxUnbalanced=5e-2, doneHook='O.pause()', globalUpdateInt=20,
                               keepProportions=True, label='comp'),
             NewtonIntegrator(damping=0.2)]
O.dt = 0.5 * PWaveTimeStep()
t0 = time.time()
O.run(60000, True)
print('compacted: %d spheres, %d iterations, %.0f s, cell %s, porosity %.4f' % (n, O.iter, time.time() - t0, O.cell.size, utils.porosity()))
# freeze the cell and drop the compressor, then let one step clear prevVelGrad
O.cell.velGrad = Matrix3.Zero
O.engines = [e for e in O.engines if not isinstance(e, PeriIsoCompressor)]
O.step()
O.resetTime()
d = ryade_record.scene_dict(2000, script='yade_ref/bench/make_dense.py')
d['source'] = 'yade 2023.02a (PeriIsoCompressor to 100 kPa)'
with open(out, 'w') as f:
    json.dump(d, f)
print('written', out, 'real contacts', O.interactions.countReal())
sys.stdout.flush()
