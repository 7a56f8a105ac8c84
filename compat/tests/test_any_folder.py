"""The user commands work from any folder without the checkout (issue 18): `RYADE_ROOT=builtin` makes
`compat` use the copies of the scripts and scenes built into it, as it does when the checkout it was
built from has been moved or deleted. Run from an empty temporary folder: `compat study`, `compat run`,
`compat gap --observed F --library L` (the committed example report is reproduced) and a bench scene
named by its name; `compat diff micro` without goldens says in one line how to point it at a checkout."""
import os
import shutil
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
COMPAT = os.environ.get('COMPAT', os.path.join(ROOT, 'target', 'release', 'compat'))

pytestmark = pytest.mark.skipif(not os.path.exists(COMPAT), reason='build the compat binary first (cargo build --release)')


def run(args, cwd, **env):
    e = dict(os.environ, RYADE_PYTHON=sys.executable, RYADE_ROOT='builtin', RYADE_CACHE=str(cwd / '.cache'))
    e.update(env)
    return subprocess.run([COMPAT] + args, cwd=cwd, env=e, capture_output=True, text=True, timeout=600)


def test_study_from_another_folder_with_the_builtin_scripts(tmp_path):
    p = run(['study', '--size', 'tiny', '--ratios', 'r07', '--cases', 'N', '--cycles', '1', '-j', '1', '--out', 'st'], tmp_path)
    assert p.returncode == 0, p.stderr
    h = (tmp_path / 'st' / 'r07_N_tiny_s1' / 'ryade' / 'history.csv').read_text().splitlines()
    assert h[0].startswith('cycle') and len(h) == 3  # cycle 0 and cycle 1
    assert (tmp_path / 'st' / 'fig_rutting.png').stat().st_size > 10000
    # the built-in copy of study.py is the checkout's
    cache = tmp_path / '.cache'
    copies = list(cache.glob('assets-*/yade_ref/study/study.py'))
    assert len(copies) == 1
    assert copies[0].read_bytes() == open(os.path.join(ROOT, 'yade_ref', 'study', 'study.py'), 'rb').read()


def test_run_and_gap_from_another_folder(tmp_path):
    (tmp_path / 's.py').write_text("O.bodies.append(sphere((0, 0, 0), 1))\nprint('bodies', len(O.bodies))\n")
    p = run(['run', 's.py'], tmp_path)
    assert p.returncode == 0 and 'bodies 1' in p.stdout, p.stderr
    shutil.copytree(os.path.join(ROOT, 'results', 'gap', 'library_r07_G_medium_c6'), tmp_path / 'L')
    shutil.copy(os.path.join(ROOT, 'results', 'gap', 'blind2028_r07_G_medium_c6', 'cases', 'case04', 'observed.csv'),
                tmp_path / 'F.csv')
    p = run(['gap', '--observed', 'F.csv', '--library', 'L', '--out', 'rep'], tmp_path)
    assert p.returncode == 0, p.stderr
    got = (tmp_path / 'rep' / 'report.md').read_text().splitlines()[1:]
    want = open(os.path.join(ROOT, 'results', 'gap', 'example_2028_case04', 'report.md')).read().splitlines()[1:]
    assert got == want


def test_bench_scene_by_name_and_diff_without_goldens(tmp_path):
    p = run(['bench', 'nosuchscene', '--no-yade'], tmp_path)
    assert p.returncode != 0 and 'built in: ' in p.stderr and 'dense8000.scene.json' in p.stderr, p.stderr
    p = run(['bench', 'dense8000', '--no-yade', '--steps', '5', '--warmup', '1', '--reps', '1', '--path', 'yade',
             '--threads', '1'], tmp_path)
    assert p.returncode == 0, p.stderr
    p = run(['diff', 'micro'], tmp_path, RYADE_ROOT='/nonexistent/checkout')
    assert p.returncode != 0
    msg = p.stderr.strip().splitlines()
    assert len(msg) == 1 and 'golden/micro not found' in msg[0] and 'RYADE_ROOT=' in msg[0] and '--golden' in msg[0], msg


def test_setup_sh_shows_cargo_and_builds_each_crate_once():
    """setup.sh (the README's first command) used to hide cargo's output for minutes and build the crate
    twice (cargo build, then cargo install)."""
    lines = [l.strip() for l in open(os.path.join(ROOT, 'setup.sh')) if l.strip() and not l.strip().startswith('#')]
    builds = [l for l in lines if l.startswith(('cargo build', 'cargo install', 'python3 -m maturin build'))
              or ('pip install' in l and './compat' in l)]
    assert len(builds) == 2 and builds[0].startswith('cargo install') and './compat' in builds[1], builds
    assert ' -v ' in builds[1]  # pip shows maturin's cargo output only with -v
    for l in lines:
        if l.startswith(('cargo', 'python3 -m pip install')):
            assert '/dev/null' not in l and '--quiet' not in l and ' -q' not in l, l
