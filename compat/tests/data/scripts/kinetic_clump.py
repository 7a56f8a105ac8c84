# utils.kineticEnergy() on a clump, a sphere and a facet (YADE 2023.02a's values in test_energy.py)
from yade import utils
O.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.4, density=2600))
O.bodies.append(utils.facet([(-1, -1, 0), (1, -1, 0), (0, 1, 0)]))
O.bodies.appendClumped([utils.sphere((-0.1, 0.2, 0.3), 0.07), utils.sphere((-0.03, 0.24, 0.33), 0.06)])
O.bodies.append(utils.sphere((0.2, 0, 0.2), 0.05))
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
             NewtonIntegrator(damping=0.1, gravity=(0, 0, -9.81))]
O.dt = 0.5 * utils.PWaveTimeStep()
for k in range(6):
    O.run(150, True)
    print("K", O.iter, repr(utils.kineticEnergy()))
