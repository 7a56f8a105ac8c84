# O.engines assigned again mid-run with the same engine objects, printed by YADE 2023.02a:
#   yade -n -x engines_reassigned.py [again]   (or: compat run engines_reassigned.py [again])
# 300 spheres (makeCloud, seed 1) settle on a wall; every 500 steps, with the argument `again`,
# `O.engines = O.engines`. YADE keeps the engine objects, so the collider keeps its sorted bounds and
# stride and does not run early: the run gives the same doubles with or without the reassignment.
from yade import pack, utils
import sys
O.reset()
mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=0.5))
sp = pack.SpherePack()
sp.makeCloud((0, 0, 0), (0.1, 0.1, 0.3), rMean=0.005, rRelFuzz=0.3, num=300, seed=1)
sp.toSimulation(material=mat)
O.bodies.append(utils.wall(0, axis=2, sense=1, material=mat))
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                             [Law2_ScGeom_FrictPhys_CundallStrack()]),
             NewtonIntegrator(damping=0.2, gravity=(0, 0, -9.81))]
O.dt = 0.5 * utils.PWaveTimeStep()
again = len(sys.argv) > 1 and sys.argv[1] == 'again'
for k in range(40):
    O.run(500, True)
    if again:
        O.engines = O.engines
print('R', repr(sum(b.state.pos[2] for b in O.bodies if isinstance(b.shape, Sphere))), O.interactions.countReal(),
      len(O.interactions), repr(O.bodies[17].state.vel[2]))
