"""PeriTriaxController and the moving periodic cell in the compat layer.

data/scripts/peri_triax_api.py drives the controller through YADE's Python API (live vector attributes
changed inside the doneHook, O.pause() from the hook during a background O.run() + O.wait() and during a
blocking O.run(n, True), the engine list reassigned with the same controller, the cell matrices with
velGrad applied through nextVelGrad, utils.getStress, the velGradWork energy). Every 'P ' line it prints
must equal YADE 2023.02a's (data/peri_triax_api.yade.txt, from `yade -n -x`; with `yade` installed YADE is
run live as well)."""
import math
import os

import pytest

from _scripts import HERE, needs_compat, needs_yade, tagged_lines
from yade import wrapper

EXPECTED = os.path.join(HERE, 'data', 'peri_triax_api.yade.txt')


def _expected():
    with open(EXPECTED) as f:
        return f.read().splitlines()


@needs_compat
def test_api_script_prints_yades_lines():
    got = tagged_lines('ryade', 'peri_triax_api.py', tags='P')
    exp = _expected()
    assert [ln for ln in exp if ln.startswith('P hook')] == [ln for ln in got if ln.startswith('P hook')], \
        'the doneHook fired at other iterations or states than in YADE'
    assert got == exp


@needs_yade
def test_api_reference_is_what_yade_prints():
    assert tagged_lines('yade', 'peri_triax_api.py', tags='P') == _expected()


def test_defaults_and_live_vectors_without_a_scene():
    t = wrapper.PeriTriaxController()
    assert (t.stressMask, t.globUpdate, t.growDamping, t.maxUnbalanced) == (0, 5, 0.25, 1e-4)
    assert math.isnan(t.mass) and math.isnan(t.currUnbalanced) and t.doneHook == ''
    g = t.goal
    g[2] = -0.1            # YADE returns a reference: the engine's goal changes
    assert tuple(t.goal) == (0.0, 0.0, -0.1)
    t.maxStrainRate = (1, 2, 3)
    assert tuple(t.maxStrainRate) == (1.0, 2.0, 3.0)
    with pytest.raises(TypeError):
        t.doneHook = 3
