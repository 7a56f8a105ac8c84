# RyadePistonController (a ryade extension) on a small scene: a box "piston" comes down on a sphere
# resting on a plate, stops at the seating pressure, seats, cycles, and stops at the rut limit. Run
# twice: alone (O.run stays in Rust) and beside a PyRunner (O.run loops in Python); the lines printed
# must be the same. Usage: compat run piston_native.py
import sys


def scene(with_pyrunner):
    O.reset()
    plate = O.bodies.append(utils.box((0, 0, -0.01), (1, 1, 0.01), fixed=True))
    O.bodies.append(utils.sphere((0, 0, 0.05), 0.05))
    piston = O.bodies.append(utils.box((0, 0, 0.16), (0.2, 0.2, 0.05), fixed=True))
    pc = RyadePistonController(ids=[piston], area=0.16, alpha=0.1, Kp=1e-5, Ki=1e-3, vmax=1.0, dt=1e-5, pSeat=2000.0,
                               pPeak=20000.0, freq=50.0, pistonOff=-0.05, Z0=0.0, stepsEvery=50, phase='approach',
                               label='pc')
    engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb()]),
               InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                               [Law2_ScGeom_FrictPhys_CundallStrack()]),
               NewtonIntegrator(gravity=(0, 0, -9.81), damping=0.2), pc]
    if with_pyrunner:
        engines.append(PyRunner(command='pass', iterPeriod=10**6))
    O.engines = engines
    O.dt = 1e-5
    return pc


def run(tag, with_pyrunner):
    pc = scene(with_pyrunner)
    O.run(100000, True)  # ends at the approach's contact
    O.stopAtIter = 0
    rows = pc.takeSteps()
    print(tag, 'approach', O.iter, pc.phase, repr(pc.p), repr(pc.pf), len(rows), rows[0][:2], repr(rows[-1][-1]))
    pc.iterSeatEnd, pc.phase = O.iter + 200, 'seat'
    O.run(200, True)
    pc.zRef = O.bodies[pc.ids[0]].state.pos[2] + pc.pistonOff
    pc.resetCycle()
    pc.phase = 'cycle'
    O.run(1000, True)
    print(tag, 'cycle', O.iter, pc.n, repr(pc.peak), repr(pc.peakRaw), repr(pc.se), repr(pc.seRaw), repr(pc.maxRut),
          repr(pc.I), repr(O.bodies[pc.ids[0]].state.vel[2]), pc.stopped)
    pc.resetCycle()
    pc.stopRut = 0.5 * pc.maxRut
    O.run(1000, True)
    O.stopAtIter = 0
    print(tag, 'stop', O.iter, pc.n, pc.stopped, pc.phase, len(pc.takeSteps()), pc.takeSteps())


run('R', False)
run('P', True)
