"""BoundDispatcher on its own in O.engines (test/pack-cloud.py, issue 19): the script runs steps; a sweep
of its own (which only a collider sets in YADE) is refused with the attribute named."""
import os
import subprocess
import sys

from _scripts import COMPAT, needs_compat

SCRIPT = '''
O.bodies.append([sphere((0, 0, 0), 0.5), sphere((2, 0, 0), 0.5)])
O.engines = [BoundDispatcher([Bo1_Sphere_Aabb()]%s)]
O.run(10, True)
print('ITER', O.iter)
'''


def _run(tmp_path, extra):
    path = tmp_path / 'script.py'
    path.write_text(SCRIPT % extra)
    return subprocess.run([COMPAT, 'run', str(path)], capture_output=True, text=True, timeout=300,
                          env=dict(os.environ, RYADE_PYTHON=sys.executable, OMP_NUM_THREADS='1'))


@needs_compat
def test_bound_dispatcher_alone_runs(tmp_path):
    p = _run(tmp_path, '')
    assert p.returncode == 0, p.stderr
    assert 'ITER 10' in p.stdout


@needs_compat
def test_bound_dispatcher_sweep_is_refused(tmp_path):
    p = _run(tmp_path, ', sweepDist=0.1')
    assert p.returncode != 0
    assert 'BoundDispatcher.sweepDist' in p.stderr
