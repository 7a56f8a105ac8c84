# Issue 19, helper B's session: a CpmMat link pulled apart after the interaction-radius idiom of the Cpm
# scripts (functor attributes changed after O.engines), its CpmPhys and elasticEnergy; a PyRunner labelled
# like the script's own `plot` module; State.displ() as a method; SumIntrForcesCb's stderr lines.
# Run: yade -n -x issue19rs_features.py / compat run issue19rs_features.py (lines A-D on stdout).
import sys
from yade import plot
m = O.materials.append(CpmMat(young=1e7, poisson=0.2, density=2000, frictionAngle=0.6, sigmaT=1e4, epsCrackOnset=1e-3,
                              relDuctility=5, equivStrainShearContrib=0.5))
a = O.bodies.append(sphere((0, 0, 0), 0.01, material=m, fixed=True))
b = O.bodies.append(sphere((0.0205, 0.0003, 0), 0.01, material=m, fixed=True))
O.bodies[b].state.vel = (0.05, 0.02, 0)
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(aabbEnlargeFactor=1.5, label='bo')]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(interactionDetectionFactor=1.5, label='ig')],
                             [Ip2_CpmMat_CpmMat_CpmPhys()], [Law2_ScGeom_CpmPhys_Cpm(label='cpm')]),
             NewtonIntegrator(damping=0), PyRunner(iterPeriod=1, command='pass', label='plot')]
O.dt = 1e-5
O.step()
bo.aabbEnlargeFactor = ig.interactionDetectionFactor = 1.0
O.run(80, True)
i = O.interactions[a, b]
print('A %r %r %r %r %r %r' % (i.phys.omega, i.phys.epsN, i.phys.sigmaN, i.phys.kappaD, i.phys.relResidualStrength,
                               cpm.elasticEnergy()))
print('B %r %r' % (tuple(i.phys.epsT), tuple(i.phys.normalForce)))
print('C', type(plot).__name__, i.phys.__class__.__name__)
print('D %r' % (tuple(O.bodies[b].state.displ()),))
il = typedEngine('InteractionLoop')
il.callbacks = [SumIntrForcesCb()]
sys.stderr.flush()
O.run(3, True)
sys.stderr.flush()
