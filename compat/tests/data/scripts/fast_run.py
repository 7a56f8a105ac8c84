# compat run --fast: an unchanged YADE script (no ryade attribute in it). A periodic 3-sphere scene runs
# 60 steps; with 'facet' a fixed facet is added first, with 'rotfacet' a spinning one (outside the fast
# path); with 'pyrunner' a PyRunner runs every step. Prints the state after the run (17 digits) and the number of real contacts.
import math, sys
mode = sys.argv[1] if len(sys.argv) > 1 else ''
O.periodic = True
O.cell.setBox(0.1, 0.1, 0.1)
mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=math.radians(30)))
for p in [(0.0, 0.05, 0.05), (0.0195, 0.05, 0.05), (0.0385, 0.051, 0.05)]:
    O.bodies.append(utils.sphere(p, 0.01, material=mat))
if mode in ('facet', 'rotfacet'):
    O.bodies.append(utils.facet([(0.05, 0.0, 0.0), (0.06, 0.0, 0.0), (0.05, 0.01, 0.0)], material=mat))
    if mode == 'rotfacet':
        O.bodies[len(O.bodies) - 1].state.angVel = (0, 0, 1.0)
O.bodies[0].state.vel = (0.01, 0, 0)
O.bodies[1].state.angVel = (0, 0, 3.0)
ticks = []
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                             [Law2_ScGeom_FrictPhys_CundallStrack()]),
             NewtonIntegrator(damping=0.1)]
if mode == 'pyrunner':
    O.engines = O.engines + [PyRunner(command='ticks.append(1)', iterPeriod=1)]
O.dt = 1e-5
O.run(60, True)
for b in O.bodies:
    if isinstance(b.shape, Sphere):
        print('S %d %s' % (b.id, ' '.join('%.17g' % x for x in tuple(b.state.pos) + tuple(b.state.vel))))
print('C %d' % O.interactions.countReal())
