"""Regression: `O.engines` assigned again with the same engine objects must keep their state.

YADE keeps engine objects across a new engine list, so a script that does `O.engines = O.engines` (or
`O.engines = O.engines[:4] + [...]` to start a new phase) goes on with the same collider, integrator
and controllers. ryade rebuilt every Rust engine from its Python attributes:
* the InsertionSortCollider forgot its sorted bounds and its Verlet stride and ran a full pass on the
  next step; pairs then entered the interaction container in another order than YADE's later
  incremental passes give, the force sums changed order, and the run left YADE's bits (after 40
  reassignments of a settling 300-sphere cloud: 344 contacts where YADE has 309);
* a ServoPIDController restarted with its constructor's iTerm = 0, so the integral action was lost
  and the piston moved differently.
The expected lines are what YADE 2023.02a printed (`yade -n -x`, the same with or without `again`);
with `yade` installed, YADE is run live too. Found while checking `execCount` against YADE (the
collider's count after a new list was 1 in ryade, 0 in YADE: test_timing.py)."""
import os
import shutil
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
COMPAT = os.environ.get('COMPAT', os.path.join(ROOT, 'target', 'release', 'compat'))
SCRIPTS = os.path.join(HERE, 'data', 'scripts')

# yade -n -x data/scripts/engines_reassigned.py [again]: the same line with and without `again`
YADE_REASSIGNED = 'R 2.1354913934987185 309 648 0.005802433387350811'
# yade -n -x data/scripts/servo_reassigned.py [again]: the same line with and without `again`
YADE_SERVO_REASSIGNED = 'S 0.019920964660045493 -0.0003674124344628188'


def _lines(cmd, tag):
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=300,
                       env=dict(os.environ, RYADE_PYTHON=sys.executable, OMP_NUM_THREADS='1'))
    assert p.returncode == 0, p.stderr
    return [ln for ln in p.stdout.splitlines() if len(ln) > 1 and ln[0] in tag and ln[1] == ' ']


needs_compat = pytest.mark.skipif(not os.path.exists(COMPAT), reason='build the compat binary first (cargo build --release)')
needs_yade = pytest.mark.skipif(not shutil.which('yade'), reason='YADE not installed (CI installs it)')


@needs_compat
@pytest.mark.parametrize('again', [[], ['again']])
def test_reassigning_the_same_engines_keeps_their_state(again):
    """Regression: `O.engines = O.engines` mid-run rebuilt every Rust engine from its attributes, so the
    collider forgot its sorted bounds and stride and ran a full pass on the next step. YADE keeps the
    engine objects: its collider runs only when its Verlet bound says so, new pairs enter the container
    in the order of its later incremental passes, and the forces sum in that order. After 40
    reassignments ryade had 344 contacts where YADE has 309 (sum of heights 2.13623 vs 2.13549)."""
    assert _lines([COMPAT, 'run', os.path.join(SCRIPTS, 'engines_reassigned.py')] + again, 'R') == [YADE_REASSIGNED]


@needs_compat
@pytest.mark.parametrize('again', [[], ['again']])
def test_a_reassigned_servo_keeps_its_integral(again):
    """Regression, same bug: the ServoPIDController rebuilt from its attributes restarted with iTerm 0
    (its constructor value), so the piston moved differently (z 0.0199219317 instead of YADE's
    0.0199209647 after 8 reassignments)."""
    assert _lines([COMPAT, 'run', os.path.join(SCRIPTS, 'servo_reassigned.py')] + again, 'S') == [YADE_SERVO_REASSIGNED]


@needs_yade
def test_yade_reassignment_reference():
    assert _lines(['yade', '-n', '-x', os.path.join(SCRIPTS, 'servo_reassigned.py'), 'again'], 'S') == [YADE_SERVO_REASSIGNED]
    assert _lines(['yade', '-n', '-x', os.path.join(SCRIPTS, 'engines_reassigned.py'), 'again'], 'R') == [YADE_REASSIGNED]
