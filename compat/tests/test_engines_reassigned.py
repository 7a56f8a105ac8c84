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
import pytest

from _scripts import needs_compat, needs_yade, tagged_lines


# yade -n -x data/scripts/engines_reassigned.py [again]: the same line with and without `again`
YADE_REASSIGNED = 'R 2.1354913934987185 309 648 0.005802433387350811'
# yade -n -x data/scripts/servo_reassigned.py [again]: the same line with and without `again`
YADE_SERVO_REASSIGNED = 'S 0.019920964660045493 -0.0003674124344628188'


@needs_compat
@pytest.mark.parametrize('again', [[], ['again']])
def test_reassigning_the_same_engines_keeps_their_state(again):
    """Regression: `O.engines = O.engines` mid-run rebuilt every Rust engine from its attributes, so the
    collider forgot its sorted bounds and stride and ran a full pass on the next step. YADE keeps the
    engine objects: its collider runs only when its Verlet bound says so, new pairs enter the container
    in the order of its later incremental passes, and the forces sum in that order. After 40
    reassignments ryade had 344 contacts where YADE has 309 (sum of heights 2.13623 vs 2.13549)."""
    assert tagged_lines('ryade', 'engines_reassigned.py', again) == [YADE_REASSIGNED]


@needs_compat
@pytest.mark.parametrize('again', [[], ['again']])
def test_a_reassigned_servo_keeps_its_integral(again):
    """Regression, same bug: the ServoPIDController rebuilt from its attributes restarted with iTerm 0
    (its constructor value), so the piston moved differently (z 0.0199219317 instead of YADE's
    0.0199209647 after 8 reassignments)."""
    assert tagged_lines('ryade', 'servo_reassigned.py', again) == [YADE_SERVO_REASSIGNED]


@needs_yade
def test_yade_reassignment_reference():
    assert tagged_lines('yade', 'servo_reassigned.py', ['again']) == [YADE_SERVO_REASSIGNED]
    assert tagged_lines('yade', 'engines_reassigned.py', ['again']) == [YADE_REASSIGNED]
