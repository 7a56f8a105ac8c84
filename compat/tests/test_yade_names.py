"""Names YADE defines: `execfile` works as in YADE, and a YADE name ryade lacks stops a run with the
compat layer's 'does not support' message (never a bare NameError), also when the script is exec'd by
a wrapper (yade_ref/examples/run_example.py, as the example survey runs it)."""
import os
import subprocess
import sys

from _scripts import COMPAT, ROOT, SCRIPTS, needs_compat, needs_yade, tagged_lines


def run(*args, cwd=None):
    return subprocess.run([COMPAT] + list(args), capture_output=True, text=True, cwd=cwd, timeout=300,
                          env=dict(os.environ, RYADE_PYTHON=sys.executable))


@needs_compat
def test_execfile_runs_in_the_callers_namespace():
    lines = tagged_lines('ryade', 'execfile_main.py', tags='AB')
    # two spheres from the file, the second at z = 3 r; its volume sum 4/3 pi (r^3 + (r/2)^3); q = 3 * 14
    assert lines == ['A 2 0.75 %r' % (4 / 3. * 3.141592653589793 * (0.25 ** 3 + 0.125 ** 3)), 'B 42 False']


@needs_compat
@needs_yade
def test_execfile_as_yade():
    assert tagged_lines('ryade', 'execfile_main.py', tags='AB') == tagged_lines('yade', 'execfile_main.py', tags='AB')


@needs_compat
def test_missing_yade_name_says_does_not_support(tmp_path):
    script = os.path.join(SCRIPTS, 'yade_name_missing.py')
    want = 'ryade does not support yade.gridpfacet.gmshPFacet yet (%s, line 3)' % script
    p = run('run', '--no-check', script, cwd=tmp_path)
    assert p.returncode == 1 and 'before' in p.stdout and 'never printed' not in p.stdout
    assert want in p.stderr and 'NameError' not in p.stderr, p.stderr
    # exec'd by the examples' wrapper: the same message, at the example's line
    wrapper = os.path.join(ROOT, 'yade_ref', 'examples', 'run_example.py')
    p = run('run', wrapper, script, str(tmp_path / 'out.json'), '10', '5', cwd=tmp_path)
    assert p.returncode == 1 and want in p.stderr and 'NameError' not in p.stderr, p.stderr
    # the check before the run names it too
    p = run('run', script, cwd=tmp_path)
    assert p.returncode == 1 and 'before' not in p.stdout
    assert "gmshPFacet" in p.stderr and 'yade_name_missing.py, line 3' in p.stderr


@needs_compat
def test_name_yade_lacks_too_stays_a_name_error(tmp_path):
    p = run('run', os.path.join(SCRIPTS, 'plain_name_error.py'), cwd=tmp_path)
    assert p.returncode == 1 and 'before' in p.stdout
    assert "NameError: name 'notAYadeNameAtAll' is not defined" in p.stderr
    assert 'does not support' not in p.stderr


@needs_compat
def test_default_engines_have_yades_labels():
    lines = tagged_lines('ryade', 'default_labels.py', tags='L')
    assert lines == ["L -0.5 0.2 ['', 'collider', 'interactionLoop', 'timeStepper', 'newton']", 'L 0.25 0.1 True']


@needs_compat
@needs_yade
def test_default_engines_labels_as_yade():
    assert tagged_lines('ryade', 'default_labels.py', tags='L') == tagged_lines('yade', 'default_labels.py', tags='L')


@needs_compat
def test_missing_container_member_says_does_not_support(tmp_path):
    """A member of YADE's O.bodies / O.interactions ryade lacks (mpi/ompPerf.py's O.bodies.insertAtId) stops
    a run with the message and the line even past the check before the run; a member YADE lacks too stays
    an AttributeError."""
    script = tmp_path / 's.py'
    script.write_text("x = 1\nO.bodies.insertAtId(sphere((0, 0, 0), 1), 3)\n")
    p = run('run', '--no-check', str(script), cwd=tmp_path)
    assert p.returncode == 1 and 'AttributeError' not in p.stderr, p.stderr
    assert 'ryade does not support O.bodies.insertAtId yet (%s, line 2)' % script in p.stderr, p.stderr
    script.write_text("O.bodies.notAYadeMember\n")
    p = run('run', '--no-check', str(script), cwd=tmp_path)
    assert "AttributeError: 'BodyContainer' object has no attribute 'notAYadeMember'" in p.stderr, p.stderr
