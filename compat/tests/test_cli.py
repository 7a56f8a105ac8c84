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
