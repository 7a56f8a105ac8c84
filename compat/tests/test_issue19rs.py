"""What issue 19's helper-B session added, against the lines Debian's YADE 2023.02a printed for
data/scripts/issue19rs_features.py (`yade -n -x`; run live too when YADE is installed): the concrete model
(CpmMat, Ip2_CpmMat_CpmMat_CpmPhys, Law2_ScGeom_CpmPhys_Cpm) on a link pulled into damage after its
interaction radius was reset (live functor attributes), labels that do not shadow a script's own module,
State.displ() as a method, SumIntrForcesCb's stderr output; refusals of what ryade lacks."""
import os
import subprocess
import sys

from _scripts import COMPAT, SCRIPTS, needs_compat, needs_yade, tagged_lines, tagged_lines_both

YADE_LINES = [
    'A 0.5898243829864078 0.0019625030865563975 8049.7091441934945 0.0019971767050945546 0.8191931872973319 '
    '5.087574407239664e-05',
    'B (-1.1399737903043167e-05, 0.0007409829636985974, 0.0) (-2.528591487201676, -0.038901407495410364, -0.0)',
    'C module CpmPhys',
    'D (4.0500000000040504e-05, 1.6200000000000394e-05, 0.0)',
]
#: what YADE's SumIntrForcesCb writes to stderr during the three steps (cerr, no newline)
YADE_CB = '(0,0)(2.51632,1)(2.5038,1)'


def _run(script_text, tmp_path):
    path = tmp_path / 'script.py'
    path.write_text(script_text)
    return subprocess.run([COMPAT, 'run', str(path)], capture_output=True, text=True, timeout=300,
                          env=dict(os.environ, RYADE_PYTHON=sys.executable, OMP_NUM_THREADS='1'))


@needs_compat
def test_issue19rs_features_equal_yade(tmp_path):
    assert tagged_lines('ryade', 'issue19rs_features.py', [str(tmp_path)], tags='ABCD') == YADE_LINES


@needs_compat
def test_sum_intr_forces_cb_prints_as_yade(tmp_path):
    p = subprocess.run([COMPAT, 'run', os.path.join(SCRIPTS, 'issue19rs_features.py')], capture_output=True, text=True,
                       timeout=300, env=dict(os.environ, RYADE_PYTHON=sys.executable, OMP_NUM_THREADS='1'))
    assert p.returncode == 0, p.stderr
    assert YADE_CB in p.stderr


@needs_compat
@needs_yade
def test_issue19rs_features_live_yade(tmp_path):
    ryade, yade = tagged_lines_both('issue19rs_features.py', tmp_path, 'ABCD')
    assert ryade == yade


@needs_compat
def test_unsupported_parts_say_so(tmp_path):
    """HydroForceEngine's fluid resolution and a CpmState value are refused with the name, not a bare error."""
    p = _run('h = HydroForceEngine(nCell=10, deltaZ=0.1)\nh.initialization()\nh.fluidResolution(1.0, 0.1)\n', tmp_path)
    assert p.returncode != 0 and 'HydroForceEngine.fluidResolution' in p.stderr, p.stderr
    p = _run("m = O.materials.append(CpmMat(sigmaT=1e6, epsCrackOnset=1e-4, relDuctility=30))\n"
             "b = O.bodies.append(sphere((0, 0, 0), 1, material=m))\nprint(O.bodies[b].state.normDmg)\n", tmp_path)
    assert p.returncode != 0 and 'CpmState.normDmg' in p.stderr, p.stderr
