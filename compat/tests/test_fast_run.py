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
    for mode, why in (('rotfacet', 'rotating Facet'), ('pyrunner', 'PyRunner')):
        p0, ref, _ = run([], mode)
        p1, got, notes = run(['--fast'], mode)
        assert p1.returncode == 0, p1.stderr
        assert len(notes) == 1 and why in notes[0], (mode, notes)
        assert got == ref  # the YADE-order path: the same bits as without --fast


@needs_compat
def test_fast_strict_refuses_with_the_reason():
    p, _, _ = run(['--fast=strict'], 'rotfacet')
    assert p.returncode != 0
    assert '--fast=strict' in p.stderr and 'Facet' in p.stderr, p.stderr[-600:]


@needs_compat
def test_fast_runs_a_fixed_facet_in_a_periodic_cell():
    """A fixed facet in a periodic cell is on the fast path (issue 16 item 2): no fallback line, the YADE-order
    path's result to round-off."""
    p0, ref, _ = run([], 'facet')
    p1, fast, notes = run(['--fast'], 'facet')
    assert p0.returncode == 0 and p1.returncode == 0, p1.stderr
    assert notes == []
    diffs = [abs(a - b) for i in ref for a, b in zip(ref[i], fast[i])]
    assert max(diffs) < 1e-12 and ref != fast


DEPOSIT = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), 'yade_ref', 'bench',
                       'deposit_script.py')


def deposit(flags, seed):
    """deposit_script.py: 1,000 spheres fallen into an open facet box, at rest after 20,000 steps."""
    p = subprocess.run([COMPAT, 'run'] + flags + [DEPOSIT, '1000', '1', '20000', str(seed)], capture_output=True, text=True,
                       timeout=600, env=dict(os.environ, RYADE_PYTHON=sys.executable))
    assert p.returncode == 0, p.stderr[-800:]
    assert not [l for l in p.stderr.splitlines() if l.startswith('[ryade] --fast')], p.stderr[-800:]
    line = [l for l in p.stdout.splitlines() if l.startswith('STATE')][0]
    st = {k: float(v) for k, v in (x.split('=') for x in line.split()[1:])}
    st['contacts'] = int([l for l in p.stdout.splitlines() if l.startswith('BENCH')][0].split('contacts=')[1].split()[0])
    return st


@needs_compat
def test_fast_deposit_in_a_facet_box_agrees_with_the_yade_order_path():
    """Walls of facets on the fast path (issue 16 item 2): a pile at rest puts its weight on the facets
    (gravity and the facets are the only external forces), and its contact count lies inside the seed band
    of the YADE-order path (bit-identical to YADE). Measured when written (seeds 1-3): facet load / weight
    0.966, 0.970, 0.971 (fast) and 0.957, 0.974, 0.949 (YADE-order): a few % short of 1 on both paths, as
    Cundall's damping of the residual vibrations biases the mean contact force; contacts 2115, 2154, 2135
    (fast) against 2114, 2150, 2079."""
    import statistics
    fast = [deposit(['--fast'], s) for s in (1, 2, 3)]
    ref = [deposit([], s) for s in (1, 2, 3)]
    for st in fast + ref:
        assert st['kinetic'] < 1e-3 * st['weight'] * 0.1   # at rest: kinetic energy << weight x 0.1 m
        assert abs(-st['facetFz'] / st['weight'] - 1) < 0.06, st
    cf, cr = [s['contacts'] for s in fast], [s['contacts'] for s in ref]
    band = 3 * statistics.stdev(cr) + 0.01 * statistics.mean(cr)
    assert abs(statistics.mean(cf) - statistics.mean(cr)) < band, (cf, cr)


@needs_compat
def test_fast_threads_from_the_environment():
    """RYADE_FAST_THREADS sets the fast path's threads for `compat run --fast`: 2 threads give other bits
    than 1 (the chunks' summation order), the same physics to round-off; a bad value is refused up front."""
    def run_env(threads):
        p = subprocess.run([COMPAT, 'run', '--fast', SCRIPT], capture_output=True, text=True, timeout=300,
                           env=dict(os.environ, RYADE_PYTHON=sys.executable, RYADE_FAST_THREADS=threads))
        states = {int(l.split()[1]): [float(x) for x in l.split()[2:]] for l in p.stdout.splitlines() if l.startswith('S ')}
        return p, states
    p1, one = run_env('1')
    p2, two = run_env('2')
    assert p1.returncode == 0 and p2.returncode == 0, p2.stderr[-600:]
    diffs = [abs(a - b) for i in one for a, b in zip(one[i], two[i])]
    assert max(diffs) < 1e-12
    p0, _ = run_env('zero')
    assert p0.returncode != 0 and 'RYADE_FAST_THREADS' in p0.stderr, p0.stderr[-600:]
