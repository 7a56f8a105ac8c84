"""The command line explains itself and refuses what would write nothing useful (issue 18): help text for
`compat run` and for the options that had none (--seeds, --first-seed, gap -j); `--cycles 0` refused."""
import os
import re
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
COMPAT = os.environ.get('COMPAT', os.path.join(ROOT, 'target', 'release', 'compat'))

pytestmark = pytest.mark.skipif(not os.path.exists(COMPAT), reason='build the compat binary first (cargo build --release)')


def run(*args, cwd=None):
    return subprocess.run([COMPAT] + list(args), capture_output=True, text=True, timeout=120, cwd=cwd,
                          env=dict(os.environ, RYADE_PYTHON=sys.executable))


def option_help(text, opt):
    """The help text clap prints under `opt` (empty if none)."""
    m = re.search(r'^\s*(?:-\w, )?%s(?![\w-])(?: <\w+>)?([^\n]*)\n((?:\s{10,}\S[^\n]*\n)*)' % re.escape(opt), text, re.M)
    return (m.group(1) + ' ' + m.group(2)).strip() if m else ''


def test_help_texts():
    p = run('run', '--help')
    assert p.returncode == 0
    assert 'Run an unmodified YADE script' in p.stdout and '--no-check' in p.stdout and '--check' in p.stdout
    assert option_help(p.stdout, '<SCRIPT>')
    study = run('study', '--help').stdout
    assert 'Seeds per ratio and case' in option_help(study, '--seeds')
    assert 'First seed' in option_help(study, '--first-seed')
    gap = run('gap', '--help').stdout
    assert 'at the same time' in option_help(gap, '--jobs')
    for o in ('--scenario', '--case', '--size', '--baseline-seeds', '--effect-seeds'):
        assert option_help(gap, o), o


def test_zero_cycles_refused(tmp_path):
    for args in (('study', '--size', 'tiny', '--cycles', '0'), ('diff', 'r05', '--cycles', '0'),
                 ('gap', '--make-library', '--cycles', '0')):
        p = run(*args, cwd=tmp_path)
        assert p.returncode != 0 and '--cycles must be at least 1' in p.stderr, (args, p.stderr)
    assert os.listdir(tmp_path) == []


def test_gap_prints_what_its_library_can_detect_first_and_warns_on_a_worse_held_out_rut(tmp_path):
    """Issue 20: the detectability table of the library comes before the diagnosis, and a named model
    that predicts the held-out rut worse than today's model says so in its verdict. The observation is
    a Debian YADE blind case (results/gap/blind2028, case14: a soft subgrade, named, whose fitted model
    overshoots the later rut: 1.36 -> 2.54 mm)."""
    lib = os.path.join(ROOT, 'results', 'gap', 'library_r07_G_medium_c6')
    obs = os.path.join(ROOT, 'results', 'gap', 'blind2028_r07_G_medium_c6', 'cases', 'case14', 'observed.csv')
    p = run('gap', '--observed', obs, '--library', lib, '--out', str(tmp_path / 'out'))
    assert p.returncode == 0, p.stderr
    out = p.stdout
    assert out.startswith('## What this library can detect'), out[:200]
    assert out.index('| subgrade | 13.5 (1) | 0.2500 .. 1.0000 |') < out.index('# Gap diagnosis')
    assert 'Verdict: **subgrade' in out
    assert '**Warning**: the chosen model predicts the held-out rut worse than today\'s model (rut RMS 1.36 -> 2.54 mm' in out
    assert '| rut_mm | 0.24 | 0.47 | -93 % |' in out
    md = (tmp_path / 'out' / 'report.md').read_text()
    assert '## What this library can detect' in md and '**Warning**: the chosen model predicts the held-out rut' in md


def test_gap_library_for_the_users_test_conditions(tmp_path):
    """Issue 20: a user names their test's plate, load and layer; the library's runs carry them to
    study.py (seen in each run's summary.json, the specimen generated at that layer), library.json
    records them, and completing the library or making blind sets with other conditions is refused
    before any run starts. r07 tiny, 2 cycles, 2 baseline seeds and 1 per effect strength (~15 s)."""
    lib = tmp_path / 'lib'
    p = run('gap', '--make-library', '--scenario', 'r07', '--size', 'tiny', '--cycles', '2', '--baseline-seeds', '2',
            '--effect-seeds', '1', '--plate-d', '0.08', '--peak-kpa', '400', '--layer', '0.2', '--library', str(lib))
    assert p.returncode == 0, p.stderr[-2000:]
    import json
    for run_dir in ('base_s1', 'rolling_0_s1', 'subgrade_2_s1'):
        par = json.load(open(lib / run_dir / 'summary.json'))['params']
        assert (par['piston_d'], par['peak_kpa'], par['layer']) == (0.08, 400, 0.2), (run_dir, par)
    spec = json.load(open(lib / 'base_s1' / 'specimen.json'))['params']
    assert spec['layer'] == 0.2
    assert json.load(open(lib / 'library.json'))['test'] == {'piston_d': 0.08, 'peak_kpa': 400.0, 'layer': 0.2}
    p = run('gap', '--make-library', '--scenario', 'r07', '--size', 'tiny', '--cycles', '2', '--baseline-seeds', '3',
            '--effect-seeds', '1', '--plate-d', '0.08', '--peak-kpa', '300', '--layer', '0.2', '--library', str(lib))
    assert p.returncode != 0 and '--peak-kpa 400' in p.stderr, p.stderr
    assert not (lib / 'base_s3').exists()
    p = run('gap', '--make-observed', str(tmp_path / 'blind'), '--size', 'tiny', '--cycles', '2', '--library', str(lib))
    assert p.returncode != 0 and 'the library was built for' in p.stderr, p.stderr
    assert not (tmp_path / 'blind' / 'cases').exists()
    p = run('gap', '--make-library', '--peak-kpa', '20', '--library', str(tmp_path / 'x'))
    assert p.returncode != 0 and 'must exceed the seating pressure' in p.stderr, p.stderr
