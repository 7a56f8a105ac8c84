"""`compat run --fast` (issue 16 item 4): an unchanged script runs on the fast path where its scene allows;
where it does not, one line says why and the YADE-order path runs with YADE's bits; `--fast=strict` makes
that an error."""
import os
import subprocess
import sys

from _scripts import COMPAT, SCRIPTS, needs_compat

SCRIPT = os.path.join(SCRIPTS, 'fast_run.py')


def run(flags, mode=''):
    p = subprocess.run([COMPAT, 'run'] + flags + [SCRIPT] + ([mode] if mode else []), capture_output=True, text=True,
                       timeout=300, env=dict(os.environ, RYADE_PYTHON=sys.executable))
    states = {int(l.split()[1]): [float(x) for x in l.split()[2:]] for l in p.stdout.splitlines() if l.startswith('S ')}
    notes = [l for l in p.stderr.splitlines() if l.startswith('[ryade] --fast')]
    return p, states, notes


@needs_compat
def test_fast_runs_the_sphere_scene_on_the_fast_path():
    p0, ref, _ = run([])
    p1, fast, notes = run(['--fast'])
    assert p0.returncode == 0 and p1.returncode == 0, p1.stderr
    assert notes == []  # no fallback line: the fast path took the run
    # the fast path's free summation order: the same physics to round-off, not YADE's bits
    diffs = [abs(a - b) for i in ref for a, b in zip(ref[i], fast[i])]
    assert max(diffs) < 1e-12
    assert ref != fast, 'identical bits: the fast path did not run'


@needs_compat
def test_fast_falls_back_with_one_line_and_yade_bits():
    for mode, why in (('facet', 'Facet'), ('pyrunner', 'PyRunner')):
        p0, ref, _ = run([], mode)
        p1, got, notes = run(['--fast'], mode)
        assert p1.returncode == 0, p1.stderr
        assert len(notes) == 1 and why in notes[0], (mode, notes)
        assert got == ref  # the YADE-order path: the same bits as without --fast


@needs_compat
def test_fast_strict_refuses_with_the_reason():
    p, _, _ = run(['--fast=strict'], 'facet')
    assert p.returncode != 0
    assert '--fast=strict' in p.stderr and 'Facet' in p.stderr, p.stderr[-600:]
