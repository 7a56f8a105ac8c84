# A long YADE run whose last line ryade lacks (O.addScene): `compat run` must refuse it before step 1.
from yade import utils
O.materials.append(FrictMat(young=1e7, density=2600))
O.bodies.append(utils.sphere((0, 0, 1), 0.1))
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
             NewtonIntegrator(gravity=(0, 0, -9.81)),
             PyRunner(command='report()', iterPeriod=5000)]
O.dt = 1e-5


def report():
    print('step', O.iter, flush=True)


print('started', flush=True)
O.run(20000, True)
O.addScene()
