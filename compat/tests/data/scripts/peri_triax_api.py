# PeriTriaxController and the moving periodic cell through YADE's Python API (test_peri_triax.py runs this
# in ryade and YADE and compares the 'P ' lines): defaults, live vector attributes (triax.goal[2] = ...
# inside the doneHook), O.pause() from the hook during a background O.run() + O.wait(), the cell matrices
# (trsf, velGrad as a copy, nextVelGrad live, prevVelGrad, velGradChanged), refSize/size/volume,
# utils.getStress, porosity, the velGradWork energy, a velGrad assigned by hand after the controller
# is killed, and an engine list reassigned with the same controller object.
from yade import pack, utils


def g(x):
    return '%.17g' % x


def vec(v):
    return ' '.join(g(x) for x in v)


def mat(m):
    return ' '.join(g(m[i, j]) for i in range(3) for j in range(3))


t0 = PeriTriaxController()
print('P defaults', vec(t0.goal), t0.stressMask, vec(t0.maxStrainRate), g(t0.maxUnbalanced), g(t0.absStressTol),
      g(t0.relStressTol), g(t0.growDamping), t0.globUpdate, repr(t0.doneHook), t0.dynCell, g(t0.mass),
      g(t0.currUnbalanced), g(t0.externalWork), mat(t0.stressTensor))
gl = t0.goal
gl[1] = 5.0
t0.maxStrainRate[2] = 3.0
print('P live', vec(t0.goal), vec(t0.maxStrainRate))

O.periodic = True
O.cell.setBox(0.032, 0.032, 0.032)
sp = pack.SpherePack()
sp.makeCloud((0, 0, 0), (0.032, 0.032, 0.032), rMean=0.004, rRelFuzz=0.2, num=40, periodic=True, seed=5)
sp.toSimulation()
phase = [0]


def hook():
    print('P hook', O.iter, phase[0], vec(triax.stress), vec(triax.strain), g(triax.currUnbalanced))
    if phase[0] == 0:
        triax.goal[2] = triax.strain[2] - 0.01  # a live view: changes the engine's goal
        triax.stressMask = 3
        phase[0] = 1
    else:
        O.pause()


O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    PeriTriaxController(label='triax', goal=(-1e4, -1e4, -1e4), stressMask=7, maxStrainRate=(2, 2, 2),
                        maxUnbalanced=1e9, relStressTol=1e9, absStressTol=1e9, doneHook='hook()'),
    NewtonIntegrator(damping=0.3),
]
O.dt = 0.5 * utils.PWaveTimeStep()
O.trackEnergy = True


def state(tag):
    c = O.cell
    print('P %s iter' % tag, O.iter, g(O.time))
    print('P %s cell' % tag, mat(c.hSize), mat(c.trsf), mat(c.velGrad), mat(c.prevVelGrad))
    print('P %s sizes' % tag, vec(c.size), vec(c.refSize), g(c.volume), g(utils.porosity()))
    print('P %s triax' % tag, vec(triax.stress), vec(triax.strain), vec(triax.strainRate), vec(triax.stiff),
          vec(triax.prevGrow), vec(triax.goal), triax.stressMask, g(triax.currUnbalanced), g(triax.externalWork),
          vec(triax.maxBodySpan))
    print('P %s tensor' % tag, mat(triax.stressTensor), mat(utils.getStress()))
    print('P %s energy' % tag, g(O.energy['velGradWork']), g(utils.unbalancedForce()))
    s = sum(b.state.pos[0] + b.state.vel[1] for b in O.bodies)
    print('P %s bodies' % tag, g(s), O.interactions.countReal())


O.run(300, True)
state('a')
O.run(6000)  # in the background; the second doneHook pauses it
O.wait()
state('b')

# the same controller object in a new engine list keeps its state, as in YADE
O.engines = O.engines
O.run(20, True)
state('c')

# kill the controller and drive the cell by hand: velGrad is applied by NewtonIntegrator (nextVelGrad)
triax.dead = True
O.cell.velGrad = Matrix3(-0.5, 0, 0, 0, 0.2, 0, 0, 0, 0.3)
print('P assigned', mat(O.cell.velGrad), mat(O.cell.nextVelGrad), O.cell.velGradChanged)
O.step()
print('P stepped', mat(O.cell.velGrad), mat(O.cell.nextVelGrad), O.cell.velGradChanged)
O.cell.nextVelGrad[1, 1] = -0.1
O.run(30, True)
state('d')
