"""YADE's per-engine timing (`O.timingEnabled`, `Engine.execTime`/`execCount`, `yade.timing`).

`data/scripts/timing_yade_ref.py` prints run counts (deterministic: which engine ran how often, the
collider only when activated, a PyRunner every 7th step), `timing.reset()`, counts kept by an engine
object across a new `O.engines` list, and `O.timingEnabled = False`. The expected lines are what YADE
2023.02a printed for it (`yade -n -x`); when `yade` is installed the test runs it live as well.
(The engine-list bug these counts uncovered has its own file: test_engines_reassigned.py.)"""
import pytest

from _scripts import needs_compat, needs_yade, tagged_lines

from yade import O, timing, utils, FrictMat, ForceResetter, InsertionSortCollider, InteractionLoop, NewtonIntegrator, \
    PyRunner, Bo1_Sphere_Aabb, Ig2_Sphere_Sphere_ScGeom, Ip2_FrictMat_FrictMat_FrictPhys, \
    Law2_ScGeom_FrictPhys_CundallStrack


# yade -n -x data/scripts/timing_yade_ref.py (YADE 2023.02a, Debian)
YADE_TIMING = [
    "A [('ForceResetter', 300), ('collider', 1), ('InteractionLoop', 300), ('NewtonIntegrator', 300), ('PyRunner', 42)] 42",
    'B True int',
    'C [0, 0, 0, 0, 0] 0',
    'D [15, 0, 15, 15, 2]',
    'E [15, 0, 15, 15, 2] False',
    'F 3 None',
]


@needs_compat
def test_counts_match_what_yade_printed():
    assert tagged_lines('ryade', 'timing_yade_ref.py') == YADE_TIMING


@needs_yade
def test_yade_still_prints_the_recorded_counts():
    assert tagged_lines('yade', 'timing_yade_ref.py') == YADE_TIMING


def _small_scene(pyrunner=True):
    O.reset()
    mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=0.5))
    for k in range(4):
        O.bodies.append(utils.sphere((0.02 * k, 0, 0), 0.011, material=mat))
    engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
               InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                               [Law2_ScGeom_FrictPhys_CundallStrack()]),
               NewtonIntegrator(damping=0.2)]
    if pyrunner:
        engines.append(PyRunner(command='pass', iterPeriod=1, label='ctl'))
    O.engines = engines
    O.dt = 1e-5


def test_stats_prints_yades_table(capsys):
    _small_scene()
    O.timingEnabled = True
    try:
        O.run(20, True)
        timing.stats()
    finally:
        O.timingEnabled = False
    out = capsys.readouterr().out.splitlines()
    # YADE's layout: a 40-wide name column, three 20-wide columns padded for functor levels, a rule
    # of 103 dashes, a quoted label for labelled engines, a TOTAL row without count, an empty line
    assert out[0] == 'Name'.ljust(40) + ' ' + 'Count'.rjust(20) + ' ' + 'Time'.rjust(20) + ' ' + 'Rel. time'.rjust(20)
    assert out[1] == '-' * 103 and out[-1] == ''
    # NewtonIntegrator's checkpoints indented under it, as Debian's YADE prints them
    names = [ln[:40].rstrip() for ln in out[2:-1]]
    assert names == ['ForceResetter', 'InsertionSortCollider', 'InteractionLoop', 'NewtonIntegrator', '  forces sync',
                     '  motion integration', '  sync max vel', '  terminate', '  TOTAL', '"ctl"', 'TOTAL']
    counts = [ln[41:61].strip() for ln in out[2:-1]]
    # a PyRunner's first activation test only starts its period (YADE: 99 runs in 100 steps)
    assert counts == ['20', '1', '20', '20', '20', '20', '20', '20', '80', '19', '']
    total = out[-2]
    assert total[62:82].strip().endswith('us') and total[83:].strip() == '100.00%'
    top = [ln for ln in out[2:-2] if not ln.startswith(' ')]
    assert sum(float(ln[83:].strip().rstrip('%')) for ln in top) == pytest.approx(100.0, abs=0.05)
    newton = O.engines[3]
    assert sum(d[1] for d in newton.timingDeltas.data) <= newton.execTime
    timing.reset()
    assert timing.runtime() == 0 and [d[1:] for d in newton.timingDeltas.data] == [(0, 0)] * 4


def test_times_are_nanoseconds_that_add_up_and_cost_nothing_when_off():
    _small_scene()
    O.run(10, True)
    assert [e.execCount for e in O.engines] == [0] * 5 and timing.runtime() == 0
    O.timingEnabled = True
    try:
        O.run(50, True)
    finally:
        O.timingEnabled = False
    ns = [e.execTime for e in O.engines]
    # the collider ran at step 0 only, before timing was on
    assert [e.execCount for e in O.engines] == [50, 0, 50, 50, 50] and ns[1] == 0
    assert all(isinstance(t, int) and t > 0 for k, t in enumerate(ns) if k != 1)
    assert timing.runtime() == sum(ns) and sum(ns) < 5e9  # 50 steps of 4 spheres: well under 5 s
    # the flag survives O.reset(), as YADE's static TimingInfo::enabled does
    O.timingEnabled = True
    O.reset()
    assert O.timingEnabled
    O.timingEnabled = False


def test_rust_only_runs_are_timed_too():
    """Without Python engines O.run stays in Rust (`run_steps`); its engines are timed there."""
    _small_scene(pyrunner=False)
    O.timingEnabled = True
    try:
        O.run(30, True)
    finally:
        O.timingEnabled = False
    assert [e.execCount for e in O.engines] == [30, 1, 30, 30]
