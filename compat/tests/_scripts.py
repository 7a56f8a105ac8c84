"""Running the scripts of data/scripts in ryade (`compat run`) and in YADE (`yade -n -x`), for tests that
compare the lines both print."""
import os
import shutil
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
COMPAT = os.environ.get('COMPAT', os.path.join(ROOT, 'target', 'release', 'compat'))
SCRIPTS = os.path.join(HERE, 'data', 'scripts')

needs_compat = pytest.mark.skipif(not os.path.exists(COMPAT), reason='build the compat binary first (cargo build --release)')
needs_yade = pytest.mark.skipif(not shutil.which('yade'), reason='YADE not installed (CI installs it)')


def tagged_lines(engine, script, args=(), tags='ABCDEFRS'):
    """Run data/scripts/SCRIPT in `engine` ('ryade' or 'yade') and return its output lines that start
    with one of `tags` and a space."""
    path = os.path.join(SCRIPTS, script)
    cmd = [COMPAT, 'run', path] if engine == 'ryade' else ['yade', '-n', '-x', path]
    p = subprocess.run(cmd + list(args), capture_output=True, text=True, timeout=300,
                       env=dict(os.environ, RYADE_PYTHON=sys.executable, OMP_NUM_THREADS='1'))
    assert p.returncode == 0, p.stderr
    return [ln for ln in p.stdout.splitlines() if len(ln) > 1 and ln[0] in tags and ln[1] == ' ']


def tagged_lines_both(script, tmp_path, tags):
    """(ryade's, YADE's) tagged lines of data/scripts/SCRIPT, each run given its own empty folder (under
    `tmp_path`) as its first argument."""
    out = []
    for engine in ('ryade', 'yade'):
        d = tmp_path / engine
        d.mkdir()
        out.append(tagged_lines(engine, script, args=[str(d)], tags=tags))
    return tuple(out)
