"""`compat run` / `compat batch` end to end: the Rust CLI starting the yade package on real scripts."""
import json
import os
import shutil
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
COMPAT = os.environ.get('COMPAT', os.path.join(ROOT, 'target', 'release', 'compat'))
SCRIPTS = os.path.join(HERE, 'data', 'scripts')

pytestmark = pytest.mark.skipif(not os.path.exists(COMPAT), reason='build the compat binary first (cargo build --release)')


def run(*args, cwd=None, env_extra=None):
    env = dict(os.environ, RYADE_PYTHON=sys.executable, **(env_extra or {}))
    return subprocess.run([COMPAT] + list(args), capture_output=True, text=True, cwd=cwd, env=env, timeout=300)


def test_unsupported_class_fails_with_name_file_and_line():
    # refused by the check before the first line runs
    p = run('run', os.path.join(SCRIPTS, 'unsupported_class.py'))
    assert p.returncode == 1
    assert 'before' not in p.stdout
    assert 'ryade does not support class FlowEngine yet' in p.stderr
    assert 'unsupported_class.py, line 4' in p.stderr
    # without the check, the run stops where it reaches the class
    p = run('run', '--no-check', os.path.join(SCRIPTS, 'unsupported_class.py'))
    assert p.returncode == 1
    assert 'before' in p.stdout and 'never printed' not in p.stdout
    assert 'ryade does not support class FlowEngine yet' in p.stderr
    assert 'unsupported_class.py, line 4' in p.stderr


def test_unsupported_method_fails_clearly():
    for flags in ((), ('--no-check',)):
        p = run('run', *flags, os.path.join(SCRIPTS, 'unsupported_method.py'))
        assert p.returncode == 1
        assert 'O.bodies.erase' in p.stderr and 'unsupported_method.py, line 2' in p.stderr


def test_late_unsupported_call_refused_before_the_first_step(tmp_path):
    """Issue 18: a 20,000-step script whose last line is a call ryade lacks (it was O.save() before issue 19
    implemented it; O.addScene() now) used to run every step and then die, writing nothing; `compat run` now
    refuses it before step 1, naming the call and its line."""
    script = os.path.join(SCRIPTS, 'late_unsupported.py')
    p = run('run', script, cwd=tmp_path)
    assert p.returncode == 1
    assert 'started' not in p.stdout and 'step' not in p.stdout
    assert 'ryade does not support O.addScene yet (late_unsupported.py, line 18)' in p.stderr
    assert 'refused before the first step' in p.stderr and '--no-check' in p.stderr
    # --check only lists; --no-check runs every step and then stops at the call, as before
    p = run('run', '--check', script, cwd=tmp_path)
    assert p.returncode == 1 and 'started' not in p.stdout and 'late_unsupported.py, line 18' in p.stderr
    p = run('run', '--no-check', script, cwd=tmp_path)
    assert p.returncode == 1 and 'step 15000' in p.stdout
    assert 'O.addScene' in p.stderr and 'line 18' in p.stderr


def test_check_finds_every_kind_of_unsupported_name(tmp_path):
    """Each kind the static check resolves, and what it must not report."""
    script = tmp_path / 's.py'
    script.write_text("""from yade import utils, export
import yade.polyhedra_utils
from yade.export import gmshGeo
O.engines = [NewtonIntegrator(densityScaling=True), PyRunner(command='O.bodies.erase(3)', iterPeriod=1)]
x = utils.sumTorques
facetBox((0, 0, 0), (1, 1, 1))
O.interactions.clear()
Omega().addScene()
try:
    FlowEngine()
except NotImplementedError:
    pass
if False:  # YADE only
    O.addScene()
def sumForces(*a):  # the script's own definitions are not YADE's
    return 0
sumForces()
y = undefined_in_both_engines
print(O.energy.total(), utils.getStress(), export.VTKExporter)
""")
    p = run('run', '--check', str(script))
    assert p.returncode == 1
    lines = [l for l in p.stderr.splitlines() if l.startswith('compat run: ryade')]
    want = ['the module yade.polyhedra_utils yet (s.py, line 2)',
            'yade.export.gmshGeo yet (s.py, line 3)',
            'NewtonIntegrator.densityScaling yet (s.py, line 4)',
            'O.bodies.erase yet (s.py, line 4)',
            'utils.sumTorques yet (s.py, line 5)',
            "the name 'facetBox' of YADE's script namespace yet (s.py, line 6)",
            'O.interactions.clear yet (s.py, line 7)',
            'O.addScene yet (s.py, line 8)',
            'class FlowEngine yet (s.py, line 10)',
            'O.addScene yet (s.py, line 14)']
    assert len(lines) == len(want), p.stderr
    for l, w in zip(lines, want):
        assert w in l, (l, w)
    assert 'not refused' in lines[-2] and 'not refused' in lines[-1]
    assert '8 unsupported name(s)' in p.stderr


def test_check_passes_the_scripts_that_run_today():
    """No yade_ref script, test script or listed YADE example is refused (study.py's YADE-only branch is
    marked `# YADE only`)."""
    import glob
    try:
        from yade import _check   # the installed package (the source tree has no compiled _ryade)
    except ImportError:
        sys.path.insert(0, os.path.join(ROOT, 'compat', 'python'))
        from yade import _check
    files = glob.glob(os.path.join(ROOT, 'yade_ref', '**', '*.py'), recursive=True)
    files += glob.glob(os.path.join(SCRIPTS, '*.py'))
    files += glob.glob(os.path.join(ROOT, 'calibration', '**', '*.py'), recursive=True)
    ex = os.environ.get('YADE_EXAMPLES', '/usr/share/doc/yade/examples')
    for l in open(os.path.join(ROOT, 'yade_ref', 'examples', 'list.txt')):
        if l.strip() and not l.startswith('#') and os.path.isdir(ex):
            files.append(os.path.join(ex, l.split()[0]))
    expected = {'unsupported_class.py', 'unsupported_method.py', 'late_unsupported.py', 'yade_name_missing.py',  # on purpose
                'make_dense.py'}  # yade_ref/bench: a YADE-only script (PeriIsoCompressor)
    refused = sorted(os.path.basename(f) for f in files if any(not x.guarded for x in _check.check_file(f)))
    assert set(refused) <= expected, refused
    assert 'study.py' not in refused


def test_live_references_and_argv(tmp_path):
    out = tmp_path / 'o.json'
    p = run('run', os.path.join(SCRIPTS, 'live_refs.py'), str(out), '--flag', 'x')
    assert p.returncode == 0, p.stderr
    d = json.load(open(out))
    assert d['vel'] == [0, 0, 0.1]            # b.state.vel[2] = 0.1 changes the body
    assert d['angVel'] == [5, 0, 0]           # v = s.angVel; v[0] = 5 changes it too
    assert d['pos'] == [0, 0, 0]              # YADE: pos is a computed copy, item assignment is lost
    assert d['blocked'] == 'xyzXYZ'           # body.dynamic = False
    assert d['argv'] == [str(out), '--flag', 'x']


def test_missing_script_is_reported():
    p = run('run', '/nonexistent/script.py')
    assert p.returncode == 2 and 'no such script' in p.stderr


def test_batch_runs_four_lines_and_summarises(tmp_path):
    for f in ('batch_job.py', 'batch.table'):
        shutil.copy(os.path.join(SCRIPTS, f), tmp_path / f)
    p = run('batch', 'batch.table', 'batch_job.py', '-j', '2', cwd=tmp_path)
    assert p.returncode == 0, p.stdout + p.stderr
    results = sorted(f for f in os.listdir(tmp_path) if f.startswith('result.'))
    assert results == ['result.high.txt', 'result.low.txt', 'result.mid.txt', 'result.none.txt']
    vals = {f.split('.')[1]: [float(x) for x in open(tmp_path / f).read().split()] for f in results}
    assert vals['mid'][0] == 0.2 and vals['high'][0] == 0.4
    # a falling sphere ends lower after 200 steps than after 50 (physics, not bookkeeping)
    assert vals['low'][1] < vals['none'][1]
    summary = open(tmp_path / 'batch.logs' / 'summary.csv').read()
    assert summary.count('\n') >= 5 and 'high' in summary


def test_stop_at_iter_semantics_match_yade():
    # expected lines printed by Debian YADE 2023.02a for the same script
    p = run('run', os.path.join(SCRIPTS, 'stop_at_iter.py'))
    assert p.returncode == 0, p.stderr
    got = [l for l in p.stdout.splitlines() if l[:2] in ('A ', 'B ', 'C ', 'D ', 'E ')]
    assert got == ['A 0', 'B -1 10', 'C -1 20', 'D -1 21', 'E -1 31']


def test_fast_path_flag_runs_the_fast_path(tmp_path):
    """O.ryadeFastPath = True: the fast path follows the YADE-order path (bit-identical to YADE) to
    round-off on a small periodic scene with sliding and spin, keeps the contacts across two runs,
    and refuses a scene it does not model (a spinning facet) with the reason."""
    out = tmp_path / 'o.json'
    p = run('run', os.path.join(SCRIPTS, 'fast_path.py'), str(out))
    assert p.returncode == 0, p.stderr
    r = json.load(open(out))
    assert r['iter'] == 60
    assert r['real_ref'] == r['real_fast'] >= 1
    assert r['max_dpos'] < 1e-15
    # round-off only, and not zero: the fast path (reciprocal masses) really ran
    assert 0 < r['max_dvel'] < 1e-12
    assert 'O.ryadeFastPath' in r['refused'] and 'Facet' in r['refused']


def test_threads_give_yades_bits_in_the_study(tmp_path):
    """`compat run -j 2` (YADE's `-jN`): O.numThreads reports 2 and the study's r05 G tiny case (grid,
    facets, boxes, the per-step Python controller) writes the history YADE wrote on one thread, byte
    for byte (golden/study, regenerated by YADE in CI)."""
    out = tmp_path / 'o'
    # the tiny scene is below the default size for threads (Scene::par_min_slots): force them
    p = run('run', '-j', '2', os.path.join(ROOT, 'yade_ref', 'study', 'study.py'), '--ratio', '0.5', '--case', 'G',
            '--size', 'tiny', '--seed', '1', '--out', str(out), cwd=ROOT, env_extra={'RYADE_PAR_MIN_SLOTS': '0'})
    assert p.returncode == 0, p.stderr
    with open(out / 'history.csv', 'rb') as a, open(os.path.join(ROOT, 'golden', 'study', 'r05_G_tiny_s1', 'history.csv'), 'rb') as b:
        assert a.read() == b.read()
    nt = tmp_path / 'nt.py'
    nt.write_text('from yade import O\nprint("threads", O.numThreads)\n')
    assert 'threads 2' in run('run', '-j', '2', str(nt)).stdout
    assert 'threads 1' in run('run', str(nt)).stdout
    bad = run('run', '-j', '0', str(nt))
    assert bad.returncode != 0 and 'start at 1' in bad.stderr
