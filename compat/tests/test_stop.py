"""Stopping a `compat` command stops every process it started (issue 18): SIGTERM to `compat batch`, to
`compat gap --make-library` and to `compat study` mid-run leaves no process of theirs (found by an
environment tag every descendant inherits), and each says what it kept. A gap library that is not there
is an error naming its path, not an 11-minute build."""
import os
import signal
import subprocess
import sys
import time
import uuid

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
COMPAT = os.environ.get('COMPAT', os.path.join(ROOT, 'target', 'release', 'compat'))

pytestmark = pytest.mark.skipif(not os.path.exists(COMPAT), reason='build the compat binary first (cargo build --release)')

LONG_JOB = '''readParamsFromTable(n=1, noTableOk=True)
from yade.params import table
O.bodies.append([sphere((0, 0, 0), 0.1), sphere((0, 0, 1), 0.1)])
O.engines = [ForceResetter(), NewtonIntegrator(gravity=(0, 0, -9.81))]
O.dt = 1e-6
O.run(10**12, True)
'''


def tagged(tag):
    """PIDs of the processes whose environment carries RYADE_TEST_TAG=tag."""
    want = ('RYADE_TEST_TAG=%s' % tag).encode()
    out = []
    for p in os.listdir('/proc'):
        if not p.isdigit():
            continue
        try:
            with open('/proc/%s/environ' % p, 'rb') as f:
                if want in f.read().split(b'\0'):
                    out.append(int(p))
        except OSError:
            pass
    return out


def start(args, cwd, tag):
    env = dict(os.environ, RYADE_PYTHON=sys.executable, RYADE_TEST_TAG=tag)
    return subprocess.Popen([COMPAT] + args, cwd=cwd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, start_new_session=True)


def wait_for(pred, timeout, what):
    t0 = time.time()
    while time.time() - t0 < timeout:
        if pred():
            return
        time.sleep(0.1)
    raise AssertionError('timed out waiting for ' + what)


def stop_and_check(p, tag, sig=signal.SIGTERM):
    p.send_signal(sig)
    try:
        out, err = p.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        raise AssertionError('compat did not stop within 60 s of the signal')
    left = []
    t0 = time.time()
    while time.time() - t0 < 5:
        left = tagged(tag)
        if not left:
            break
        time.sleep(0.2)
    for pid in left:  # do not leave them to the next test
        try:
            os.kill(pid, signal.SIGKILL)
        except OSError:
            pass
    assert not left, 'processes left running after the signal: %s\n%s' % (left, err)
    return p.returncode, out, err


def test_sigterm_stops_compat_batch_and_its_jobs(tmp_path):
    (tmp_path / 'job.py').write_text(LONG_JOB)
    (tmp_path / 't.table').write_text('description n\na 1\nb 2\nc 3\n')
    tag = uuid.uuid4().hex
    p = start(['batch', 't.table', 'job.py', '-j', '2'], tmp_path, tag)
    # the batch and two jobs running
    wait_for(lambda: len(tagged(tag)) >= 3, 60, 'two batch jobs to start')
    rc, out, err = stop_and_check(p, tag)
    assert rc == 128 + signal.SIGTERM, err
    assert 'stopped by SIGTERM: 0 job(s) had finished' in err and '2 stopped, 1 not started' in err, err


def test_sigterm_stops_compat_gap_building_a_library(tmp_path):
    tag = uuid.uuid4().hex
    lib = tmp_path / 'lib'
    p = start(['gap', '--make-library', '--library', str(lib), '--size', 'tiny', '--cycles', '1',
               '--baseline-seeds', '4', '--effect-seeds', '1', '-j', '2'], tmp_path, tag)
    # compat gap, its yade.batch and at least one job
    wait_for(lambda: len(tagged(tag)) >= 3, 120, 'the library jobs to start')
    rc, out, err = stop_and_check(p, tag)
    assert rc == 128 + signal.SIGTERM, err
    assert 'compat: stopped by SIGTERM' in err, err
    assert 'kept in %s' % lib in err and '--make-library' in err, err


def test_sigterm_stops_compat_study(tmp_path):
    tag = uuid.uuid4().hex
    p = start(['study', '--size', 'tiny', '--ratios', 'r07', '--cases', 'N,G', '-j', '2', '--out', 'st'], tmp_path, tag)
    wait_for(lambda: len(tagged(tag)) >= 2, 60, 'the study runs to start')
    rc, out, err = stop_and_check(p, tag)
    assert rc == 128 + signal.SIGTERM, err
    assert 'kept 0 finished run(s) in st' in err, err


def test_sigint_stops_a_long_compat_run(tmp_path):
    """A Ctrl-C (or SIGTERM) reaches a run that is inside O.run(n, True) in Rust."""
    (tmp_path / 'job.py').write_text(LONG_JOB)
    tag = uuid.uuid4().hex
    p = start(['run', 'job.py'], tmp_path, tag)
    wait_for(lambda: len(tagged(tag)) >= 1, 30, 'compat run')
    time.sleep(2)
    rc, out, err = stop_and_check(p, tag, signal.SIGINT)
    assert rc == 128 + signal.SIGINT, err
    assert 'compat run: stopped by SIGINT at iteration' in err, err


def test_missing_gap_library_is_an_error_naming_it(tmp_path):
    obs = os.path.join(ROOT, 'results', 'gap', 'blind2028_r07_G_medium_c6', 'cases', 'case04', 'observed.csv')
    p = subprocess.run([COMPAT, 'gap', '--observed', obs, '--library', str(tmp_path / 'typo')], capture_output=True,
                       text=True, timeout=60, cwd=tmp_path, env=dict(os.environ, RYADE_PYTHON=sys.executable))
    assert p.returncode != 0
    assert 'no gap library at %s' % (tmp_path / 'typo') in p.stderr and '--make-library' in p.stderr, p.stderr
    assert not (tmp_path / 'typo').exists(), 'nothing is built without --make-library'
