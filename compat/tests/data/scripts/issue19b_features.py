# What issue 19 (second session) added, printed as tagged lines to compare with YADE 2023.02a:
# A: the `+` of kinematic engines; B: SpherePack.psd; C: yade.math, opts; D: attributes of a script's own,
# dispMatrix; E: a TriaxialStressController run; F: a Hertz-Mindlin contact; R: TriaxialStateRecorder file.
from yade import pack, math as ymath
c = TranslationEngine(ids=[3, 4], velocity=1) + RotationEngine(angularVelocity=2)
c2 = c + HelixEngine(linearVelocity=0.5)
print('A', type(c).__name__, c2 is c, len(c.comb), list(c.ids), [type(e).__name__ for e in c.comb])
sp = pack.SpherePack()
sp.makeCloud((0, 0, 0), (1, 1, 1), rMean=0.05, rRelFuzz=0.5, seed=2)
e, cu = sp.psd(bins=7)
e2, cu2 = sp.psd(bins=5, mass=False)
print('B', len(sp), repr(e[3]), repr(cu[4]), repr(cu2[2]), len(e), len(cu))
print('C', repr(ymath.toHP1('0.1')), repr(ymath.radiansHP1(20)), repr(ymath.degreesHP1(0.5)), opts.nogui)
m = FrictMat(young=1e7)
m.myNote = 'kept'
il = InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                     [Law2_ScGeom_FrictPhys_CundallStrack()])
print('D', m.myNote, sorted(il.geomDispatcher.dispMatrix().items()), il.lawDispatcher.dispMatrix())
O.materials.append(FrictMat(young=5e6, poisson=0.5, frictionAngle=0.5, density=2600, label='s'))
O.materials.append(FrictMat(young=5e6, poisson=0.5, frictionAngle=0, density=0, label='w'))
O.bodies.append(aabbWalls([(0, 0, 0), (0.1, 0.1, 0.1)], thickness=0, material='w'))
sp = pack.SpherePack()
sp.makeCloud((0, 0, 0), (0.1, 0.1, 0.1), -1, 0.3333, 40, False, 0.95, seed=5)
O.bodies.append([sphere(cc, r, material='s') for cc, r in sp])
triax = TriaxialStressController(maxMultiplier=1.02, finalMaxMultiplier=1.002, thickness=0, goal1=-1000,
                                 goal2=-1000, goal3=-1000)
import sys, os
out = sys.argv[1] if len(sys.argv) > 1 else '.'
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                             [Law2_ScGeom_FrictPhys_CundallStrack()]),
             GlobalStiffnessTimeStepper(timeStepUpdateInterval=50), triax,
             TriaxialStateRecorder(iterPeriod=150, file=os.path.join(out, 'triax.txt')), NewtonIntegrator(damping=0.2)]
O.run(600, True)
print('E', repr(triax.meanStress), repr(triax.porosity), repr(triax.stress(3)[1]), repr(triax.strain[0]),
      repr(O.bodies[10].shape.radius), repr(triax.maxMultiplier))
for ln in open(os.path.join(out, 'triax.txt')).read().splitlines():
    print('R', ln)
O.reset()
O.materials.append(FrictMat(young=6e8, poisson=0.3, density=2600, frictionAngle=0.4))
O.bodies.append([sphere((0, 0, 0), 0.01, fixed=True), sphere((0.0199, 0.001, 0), 0.01)])
O.bodies[1].state.vel = (-0.05, 0.02, 0)
ip2 = Ip2_FrictMat_FrictMat_MindlinPhys(label='mip2')
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [ip2], [Law2_ScGeom_MindlinPhys_Mindlin()]),
             NewtonIntegrator(damping=0)]
mip2.betan = 0.2
O.dt = 1e-7
O.run(50, True)
i = O.interactions[0, 1]
print('F', i.phys.__class__.__name__, repr(i.phys.kn), repr(i.phys.normalForce[0]), repr(i.phys.shearForce[1]),
      repr(i.phys.betan), repr(i.phys.kno), repr(O.bodies[1].state.vel[0]))
