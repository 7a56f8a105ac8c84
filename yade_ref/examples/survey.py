#!/usr/bin/env python3
"""Survey: every example script of YADE's Debian package under YADE and under ryade's `compat run`.

  python3 yade_ref/examples/survey.py [--out DIR] [--only PATTERN] [--limit N] [--cap S] ...

Each example runs headless through run_example.py (O.run capped at --max-steps per call, then --extra
more steps, the final bodies dumped), first under `yade -n -x`, then under `compat run`, one process at
a time, each in a fresh folder holding a copy of the example's own folder, each killed after --cap
seconds. DIR/survey.csv gets a row per example (example, yade status, ryade status, first blocker,
final-state agreement, ...), DIR/survey.md the counts and the blockers by count. An example YADE itself
cannot run headless (Python 2 syntax, missing data or modules, GUI only, its own errors, past the cap)
is marked so and not counted against ryade.

Resuming: the rows of an existing DIR/survey.csv are kept and their examples skipped; --redo-ryade
runs ryade again on them (keeping YADE's results and dumps, e.g. after a ryade change), --redo-blocked
only on those ryade did not run. When a final state differs, YADE runs the example a second time:
if YADE disagrees with itself the example is 'yade-nondeterministic' (a seedless random scene).

Which ryade: --compat (default $COMPAT, else target/release/compat of this checkout); the `yade`
Python package is whatever that Python imports (PYTHONPATH=compat/python with a built
compat/python/yade/_ryade.abi3.so runs a checkout's package without installing it); the survey prints
the package's path first.
"""

import argparse
import csv
import fnmatch
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
RUNNER = os.path.join(HERE, 'run_example.py')
FIELDS = ['example', 'yade', 'ryade', 'blocker', 'agreement', 'yade_s', 'ryade_s', 'yade_detail', 'ryade_detail']

# ---- classifying a run's log


def _last_error_line(log):
    lines = [l.strip() for l in log.splitlines() if l.strip()]
    for l in reversed(lines):
        if re.match(r'^[A-Za-z_.]*(Error|Exception|Interrupt)\b', l) or l.startswith('compat run:'):
            return l[:200]
    return lines[-1][:200] if lines else ''


def yade_cannot(log):
    """Why YADE could not run an example headless (a short label), from its log."""
    if re.search(r'Missing parentheses in call to|SyntaxError', log):
        return 'python2-or-syntax'
    if re.search(r'No such file or directory|FileNotFoundError|IOError|cannot open|Unable to open', log):
        return 'missing-file'
    if re.search(r"No module named|ModuleNotFoundError|ImportError", log):
        m = re.search(r"No module named '?([\w.]+)", log)
        return 'missing-module %s' % (m.group(1) if m else '')
    if re.search(r'DISPLAY|qt\.|Qt|GUI', log):
        return 'gui'
    return 'error'


def blocker(log):
    """The first thing that stopped ryade, as a short name to count by."""
    m = re.search(r'ryade does not support (.+?) yet', log)
    if m:
        return m.group(1)
    m = re.search(r"NameError: name '([^']+)' is not defined", log)
    if m:
        return 'NameError %s' % m.group(1)
    m = re.search(r"No module named '([^']+)'", log)
    if m:
        return 'module %s' % m.group(1)
    m = re.search(r"cannot import name '([^']+)' from '([^']+)'", log)
    if m:
        return '%s.%s (import)' % (m.group(2), m.group(1))
    m = re.search(r"AttributeError: (.*)", log)
    if m:
        return 'AttributeError ' + m.group(1)[:100]
    return _last_error_line(log) or 'unknown'


# ---- comparing final states


def agreement(a, b):
    """'exact', 'close <rel>' or 'differs <what>' between two run_example.py dumps."""
    if a['iter'] != b['iter']:
        return 'differs iter %d/%d' % (a['iter'], b['iter'])
    if len(a['bodies']) != len(b['bodies']):
        return 'differs bodies %d/%d' % (len(a['bodies']), len(b['bodies']))
    worst, exact = 0.0, True
    for x, y in zip(a['bodies'], b['bodies']):
        if x['id'] != y['id']:
            return 'differs ids'
        for k in ('pos', 'vel', 'angVel', 'ori'):
            for u, v in zip(x[k], y[k]):
                if u != v:
                    exact = False
                    d = abs(u - v) / max(abs(u), abs(v), 1e-300)
                    if not d <= worst:  # NaN counts
                        worst = d if d == d else float('inf')
    if exact:
        return 'exact'
    return ('close %.1e' if worst < 1e-6 else 'differs %.1e') % worst


AGREES = ('exact', 'close')

# ---- running one example


def run_one(engine, cmd, example_path, ex_root, out_json, args, work):
    """(status, seconds, log) of one engine on one example, in a fresh copy of its folder."""
    rel = os.path.relpath(example_path, ex_root)
    d = os.path.join(work, 'run')
    shutil.rmtree(d, ignore_errors=True)
    shutil.copytree(os.path.dirname(example_path), d)
    script = os.path.join(d, os.path.basename(example_path))
    if os.path.exists(out_json):
        os.remove(out_json)
    env = dict(os.environ, OMP_NUM_THREADS='1', OPENBLAS_NUM_THREADS='1')
    env.pop('DISPLAY', None)
    t0 = time.time()
    p = subprocess.Popen(cmd + [RUNNER, script, out_json, str(args.max_steps), str(args.extra)], cwd=d, env=env,
                         stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                         start_new_session=True)
    try:
        out, _ = p.communicate(timeout=args.cap)
        status = 'ok' if p.returncode == 0 and os.path.exists(out_json) else 'error'
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        out, _ = p.communicate()
        status = 'timeout'
    dt = time.time() - t0
    log = out.decode('utf-8', 'replace')
    shutil.rmtree(d, ignore_errors=True)
    logdir = os.path.join(args.out, 'logs')
    os.makedirs(logdir, exist_ok=True)
    with open(os.path.join(logdir, '%s.%s.txt' % (rel.replace('/', '__'), engine)), 'w') as f:
        f.write(log[-20000:])
    return status, dt, log


def survey_one(ex, args, ex_root, row):
    """Fill `row` (a dict of FIELDS) for example `ex` (relative path)."""
    path = os.path.join(ex_root, ex)
    key = ex.replace('/', '__')
    yj = os.path.join(args.out, 'yade', key + '.json')
    rj = os.path.join(args.out, 'ryade', key + '.json')
    work = os.path.join(args.out, 'work')
    if not row.get('yade'):
        st, dt, log = run_one('yade', args.yade_cmd, path, ex_root, yj, args, work)
        row['yade_s'] = '%.1f' % dt
        if st == 'ok':
            row['yade'], row['yade_detail'] = 'ok', ''
        elif st == 'timeout':
            row['yade'], row['yade_detail'] = 'timeout', 'past %g s' % args.cap
        else:
            row['yade'], row['yade_detail'] = 'cannot ' + yade_cannot(log), _last_error_line(log)
    st, dt, log = run_one('ryade', args.compat_cmd, path, ex_root, rj, args, work)
    row['ryade_s'] = '%.1f' % dt
    row['ryade'] = st
    row['blocker'] = '' if st == 'ok' else ('timeout' if st == 'timeout' else blocker(log))
    row['ryade_detail'] = '' if st == 'ok' else _last_error_line(log)
    row['agreement'] = ''
    if st == 'ok' and row['yade'] == 'ok' and os.path.exists(yj):
        a = agreement(json.load(open(yj)), json.load(open(rj)))
        if not a.startswith(AGREES) and args.recheck_yade:
            y2 = yj + '.again'
            st2, _, _ = run_one('yade-again', args.yade_cmd, path, ex_root, y2, args, work)
            if st2 == 'ok' and not agreement(json.load(open(yj)), json.load(open(y2))).startswith(AGREES):
                a = 'yade-nondeterministic (%s)' % a
            if os.path.exists(y2):
                os.remove(y2)
        row['agreement'] = a
    return row


# ---- report


def counts(rows):
    c = {'total': len(rows)}
    c['yade_ok'] = sum(r['yade'] == 'ok' for r in rows)
    c['yade_cannot'] = sum(r['yade'] != 'ok' for r in rows)
    c['ryade_ok'] = sum(r['ryade'] == 'ok' for r in rows)
    c['both_ok'] = sum(r['ryade'] == 'ok' and r['yade'] == 'ok' for r in rows)
    c['agree'] = sum(r['agreement'].startswith(AGREES) for r in rows)
    c['exact'] = sum(r['agreement'] == 'exact' for r in rows)
    c['nondet'] = sum(r['agreement'].startswith('yade-nondeterministic') for r in rows)
    c['differs'] = sum(r['agreement'].startswith('differs') for r in rows)
    c['nameerror'] = sum(r['blocker'].startswith('NameError') for r in rows if r['yade'] == 'ok')
    return c


def write_report(rows, args):
    rows = sorted(rows, key=lambda r: r['example'])
    with open(os.path.join(args.out, 'survey.csv'), 'w', newline='') as f:
        w = csv.DictWriter(f, FIELDS)
        w.writeheader()
        w.writerows(rows)
    c = counts(rows)
    L = ['# Survey of YADE\'s examples under ryade', '',
         'Examples: %(total)d; YADE runs %(yade_ok)d headless (%(yade_cannot)d it cannot: not counted); '
         'ryade runs %(ryade_ok)d, %(both_ok)d of them also run by YADE; final state agrees with YADE\'s: '
         '%(agree)d (%(exact)d bit for bit); YADE disagrees with itself (seedless random): %(nondet)d; '
         'differs: %(differs)d; bare NameError: %(nameerror)d.' % c, '',
         'Settings: cap %g s per run, O.run capped at %d steps per call, %d extra steps after the script.'
         % (args.cap, args.max_steps, args.extra), '',
         '## What stops ryade (examples YADE runs), by count', '', '| blocker | examples |', '|---|---|']
    by = {}
    for r in rows:
        if r['yade'] == 'ok' and r['ryade'] != 'ok':
            by.setdefault(r['blocker'], []).append(r['example'])
    for b, exs in sorted(by.items(), key=lambda kv: (-len(kv[1]), kv[0])):
        L.append('| %s | %d: %s |' % (b.replace('|', '\\|'), len(exs), ', '.join(exs[:6]) + (' ...' if len(exs) > 6 else '')))
    L += ['', '## Runs under both engines', '', '| example | agreement |', '|---|---|']
    L += ['| %s | %s |' % (r['example'], r['agreement']) for r in rows if r['agreement']]
    L += ['', '## YADE cannot run headless (not counted)', '', '| example | why |', '|---|---|']
    L += ['| %s | %s |' % (r['example'], r['yade']) for r in rows if r['yade'] != 'ok']
    with open(os.path.join(args.out, 'survey.md'), 'w') as f:
        f.write('\n'.join(L) + '\n')
    return c


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--examples', default=os.environ.get('YADE_EXAMPLES', '/usr/share/doc/yade/examples'))
    ap.add_argument('--out', default='survey_out')
    ap.add_argument('--only', action='append', help='fnmatch pattern on the relative path (repeatable)')
    ap.add_argument('--limit', type=int, help='at most N examples not yet in the CSV')
    ap.add_argument('--every', type=int, default=1, help='a spread sample: every N-th example (sorted by path)')
    ap.add_argument('--cap', type=float, default=25.0, help='seconds per run (default 25)')
    ap.add_argument('--max-steps', type=int, default=1000, help='cap of each O.run call (default 1000)')
    ap.add_argument('--extra', type=int, default=200, help='steps after the script (default 200)')
    ap.add_argument('--compat', default=os.environ.get('COMPAT', os.path.join(ROOT, 'target/release/compat')))
    ap.add_argument('--yade', default='yade')
    ap.add_argument('--redo-ryade', action='store_true', help='run ryade again on examples already in the CSV')
    ap.add_argument('--redo-blocked', action='store_true', help='... only on those ryade did not run')
    ap.add_argument('--no-recheck-yade', dest='recheck_yade', action='store_false')
    ap.add_argument('--report-only', action='store_true', help='rewrite survey.md from the CSV')
    args = ap.parse_args(argv)
    args.out = os.path.abspath(args.out)
    args.yade_cmd = [args.yade, '-n', '-x']
    args.compat_cmd = [args.compat, 'run']
    for d in ('yade', 'ryade', 'logs'):
        os.makedirs(os.path.join(args.out, d), exist_ok=True)
    csv_path = os.path.join(args.out, 'survey.csv')
    rows = {}
    if os.path.exists(csv_path):
        for r in csv.DictReader(open(csv_path)):
            rows[r['example']] = {k: r.get(k, '') or '' for k in FIELDS}
    if args.report_only:
        print(write_report(list(rows.values()), args))
        return 0
    ex_root = os.path.abspath(args.examples)
    allex = []
    for dp, dn, fn in os.walk(ex_root):
        for f in fn:
            if f.endswith('.py'):
                rel = os.path.relpath(os.path.join(dp, f), ex_root)
                if not args.only or any(fnmatch.fnmatch(rel, p) for p in args.only):
                    allex.append(rel)
    allex.sort()
    todo = []
    for rel in allex[::max(args.every, 1)]:
        if rel in rows:
            r = rows[rel]
            if not (args.redo_ryade or (args.redo_blocked and r['ryade'] != 'ok')):
                continue
        todo.append(rel)
    new = [e for e in todo if e not in rows]
    if args.limit is not None:
        keep = set(new[:args.limit])
        todo = [e for e in todo if e in rows or e in keep]
    pkg = subprocess.run([sys.executable, '-c', 'import yade, os; print(os.path.dirname(yade.__file__))'],
                         capture_output=True, text=True).stdout.strip()
    print('survey: %d example(s) to run; ryade: %s, yade package of %s: %s' % (len(todo), args.compat, sys.executable,
                                                                              pkg or '?'), flush=True)
    for i, ex in enumerate(todo):
        row = rows.get(ex) or {k: '' for k in FIELDS}
        row['example'] = ex
        rows[ex] = survey_one(ex, args, ex_root, row)
        r = rows[ex]
        print('[%d/%d] %-60s yade %-28s ryade %-8s %s' % (i + 1, len(todo), ex, r['yade'][:28], r['ryade'],
                                                          r['agreement'] or r['blocker']), flush=True)
        write_report(list(rows.values()), args)
    c = write_report(list(rows.values()), args)
    print('survey: %s' % json.dumps(c))
    return 0


if __name__ == '__main__':
    sys.exit(main())
