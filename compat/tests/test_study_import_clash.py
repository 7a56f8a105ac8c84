"""study.py --import-specimen with a specimen parameter the specimen contradicts (compat diff
--ryade-arg=--friction=20 on YADE's specimens used to run unchanged: the import silently overrode it)
stops with the options named, in ryade and in YADE; the same parameter at the specimen's value runs."""
import os
import subprocess
import sys

from _scripts import COMPAT, ROOT, needs_compat, needs_yade

STUDY = os.path.join(ROOT, 'yade_ref', 'study', 'study.py')
SPEC = os.path.join(ROOT, 'golden', 'study', 'r05_N_tiny_s1', 'specimen.json')
ARGS = ['--import-specimen', SPEC, '--ratio', '0.5', '--case', 'N', '--size', 'tiny', '--seed', '1', '--cycles', '1']


def run(cmd, tmp_path, extra):
    return subprocess.run(cmd + [STUDY] + ARGS + ['--out', str(tmp_path)] + extra, capture_output=True, text=True,
                          timeout=300, cwd=tmp_path, env=dict(os.environ, RYADE_PYTHON=sys.executable, OMP_NUM_THREADS='1'))


@needs_compat
def test_contradicted_specimen_option_is_refused(tmp_path):
    p = run([COMPAT, 'run'], tmp_path, ['--friction', '20'])
    assert p.returncode != 0
    assert '--friction 20.0 (the specimen has 30)' in p.stderr, p.stderr
    p = run([COMPAT, 'run'], tmp_path, ['--friction', '30'])
    assert p.returncode == 0, p.stderr


@needs_yade
def test_contradicted_specimen_option_is_refused_in_yade(tmp_path):
    p = run(['yade', '-n', '-x'], tmp_path, ['--friction', '20'])
    assert '--friction 20.0 (the specimen has 30)' in p.stderr + p.stdout
