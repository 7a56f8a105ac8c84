"""``compat batch``: run a script once per line of a parameter table (ryade's ``yade-batch``).

Usage::

    compat batch TABLE [SCRIPT.py] [-j N] [--lines 2,4-6] [--log DIR] [--dry-run]
                 [--command 'yade -n -x'] [--job-threads N] [--nice N] [--timeout S]
                 [--emit-slurm FILE [--slurm-opt OPT ...]]
    python -m yade.batch ...            # the same

Table format and parameter semantics: ``yade._table`` (identical to YADE 2023.02a's
``TableParamReader``/``readParamsFromTable``). Each selected data line is one job:

* environment: ``YADE_BATCH=<TABLE as given on the command line>:<line>`` (exactly what
  yade-batch passes; the line is the 1-based line number in the file, comments and blank lines
  counted), ``DISPLAY=`` (empty, as yade-batch), ``OMP_NUM_THREADS=<threads>``, and one
  variable per ``!NAME`` column (``NAME=<cell>``; one pair of surrounding quotes is removed, as the
  shell in yade-batch's command line would). Jobs run in the current directory, so the relative
  table path resolves as it does for yade-batch.
* special ``!`` columns, as in yade-batch: ``!OMP_NUM_THREADS`` / ``!THREADS`` (threads of the
  job, default ``--job-threads``, 1), ``!SCRIPT`` (script of that line; SCRIPT may then be
  omitted), ``!EXEC`` (command of that line, like ``--command``); ``!COUNT`` and ``!AFFINITY``
  are accepted and ignored.
* command: ``--command CMD`` or else ``$RYADE_BATCH_RUNNER`` or else
  ``<this python> -m yade.runner``; split like a shell line; ``{script}`` and ``{threads}`` in
  it are substituted, otherwise the script is appended. When the program is ``yade*`` and the
  template has no ``{threads}``, ``--threads=N`` is inserted after it as yade-batch does (real
  YADE resets ``OMP_NUM_THREADS`` to 1 without ``-j``), so ``--command 'yade -n -x'`` runs the
  same table under real YADE.
* scheduling: like yade-batch, ``-j N`` (default: number of CPUs) is a budget of cores; a job
  takes its thread count out of it, a job larger than the budget runs alone. Jobs run at
  ``--nice`` 10 (yade-batch's default).
* log: ``<logdir>/<script stem>.<description>.log`` (description sanitised to
  ``[A-Za-z0-9._,=+-]``, other characters become ``_``; long ones are cut and get ``_l<line>``;
  clashes get ``.l<line>``). Default logdir: ``<table dir>/<table stem>.logs/`` (yade-batch
  writes ``<script>.<description>.log`` into the current directory). Job output (stdout and
  stderr) goes there, followed by a JOB SUMMARY block as yade-batch appends.
* exit status: a non-zero exit counts as success if the log has a line starting with
  ``Yade: normal exit.`` (yade-batch's rule, for YADE crashing at exit).
* end: a summary table (line, description, status, exit, wall time, log) on stdout, also written
  as ``<logdir>/summary.csv``. The exit code is 0 only if every job succeeded.
  ``--dry-run`` prints the jobs (environment and command) and runs nothing.

Cluster (Slurm): ``--emit-slurm FILE`` writes an sbatch script and runs nothing. It is a job
array whose task ids *are* the table line numbers (``#SBATCH --array=5,7,9-12``, throttled with
``%N`` when ``-j`` is given), and each task sets ``YADE_BATCH=<table>:$SLURM_ARRAY_TASK_ID``, its
``!`` variables and ``OMP_NUM_THREADS`` (``--cpus-per-task`` is the largest thread count), then
runs the command with output to the same log path as a local run. Paths are written as given,
relative to the directory you generate it in: submit from there
(``cd <that dir> && sbatch FILE``; Slurm starts tasks in the submit directory). Re-run single
lines with ``sbatch --array=7,9 FILE``. Add site options with ``--slurm-opt`` (repeatable, e.g.
``--slurm-opt=--time=02:00:00 --slurm-opt=--partition=short``). With the default command the
script runs ``${RYADE_PYTHON:-python3} -m yade.runner``. Slurm's ``MaxArraySize`` (default
1001) bounds the largest line number.
"""
import argparse
import csv
import os
import re
import shlex
import subprocess
import sys
import time

from ._table import TableError, parse_table

__all__ = ['main', 'plan_jobs', 'parse_line_list', 'Job']

_NORMAL_EXIT = 'Yade: normal exit.'
_IGNORED_SPECIAL = ('!COUNT', '!AFFINITY')


class BatchError(Exception):
    pass


class Job:
    def __init__(self, num, line, description, script, argv, env_add, threads, log):
        self.num, self.line, self.description, self.script = num, line, description, script
        self.argv, self.env_add, self.threads, self.log = argv, env_add, threads, log
        self.status = 'PENDING'  # RUNNING, DONE, NOT RUN
        self.exit = None
        self.started = self.finished = None
        self.proc = None
        self.logf = None

    @property
    def wall(self):
        if self.started is None:
            return None
        return (self.finished or time.time()) - self.started

    @property
    def ok(self):
        return self.status == 'DONE' and self.exit == 0


def parse_line_list(spec):
    """``'2,4-6,9'`` -> ``[2, 4, 5, 6, 9]`` (ranges inclusive, as yade-batch's ``--lines``)."""
    out = []
    for part in spec.split(','):
        part = part.strip()
        if not part:
            continue
        m = re.fullmatch(r'(\d+)\s*-\s*(\d+)', part)
        try:
            if m:
                a, b = int(m.group(1)), int(m.group(2))
                if b < a:
                    raise ValueError
                out.extend(range(a, b + 1))
            else:
                out.append(int(part))
        except ValueError:
            raise BatchError('bad --lines item %r (expected N or N-M, comma separated)' % part) from None
    return out


def _unquote(v):
    if len(v) >= 2 and v[0] == v[-1] and v[0] in '\'"':
        return v[1:-1]
    return v


_SAFE = re.compile(r'[^A-Za-z0-9._,=+-]')


def _sanitise(s, line, limit=180):
    s = _SAFE.sub('_', s).lstrip('.') or 'job'
    if len(s) > limit:
        s = s[:limit] + '_l%d' % line
    return s


def default_command():
    env = os.environ.get('RYADE_BATCH_RUNNER')
    if env:
        return shlex.split(env), False
    return [sys.executable, '-m', 'yade.runner'], True


def build_argv(template, script, threads):
    has_script = any('{script}' in t for t in template)
    has_threads = any('{threads}' in t for t in template)
    argv = [t.replace('{script}', script).replace('{threads}', str(threads)) for t in template]
    if template and not has_threads and os.path.basename(template[0]).startswith('yade'):
        argv.insert(1, '--threads=%d' % threads)
    if not has_script:
        argv.append(script)
    return argv


def plan_jobs(table_path, script=None, lines=None, logdir=None, command=None, job_threads=1):
    """Parse the table and return ``(table, jobs, logdir)`` without running anything.
    *command* is a list (template) or None for the default/``RYADE_BATCH_RUNNER``."""
    table = parse_table(table_path)
    if command is None:
        command, _ = default_command()
    if logdir is None:
        tdir, tname = os.path.split(table_path)
        logdir = os.path.join(tdir, os.path.splitext(tname)[0] + '.logs')
    if lines is None:
        use = table.lines
    else:
        use = []
        for l in lines:
            if l not in table.rows:
                print('compat batch: WARNING: skipping line %d, not a data line of %s (data lines: %s)'
                      % (l, table_path, ','.join(map(str, table.lines))), file=sys.stderr)
            elif l not in use:
                use.append(l)
    jobs, used_logs = [], set()
    for num, l in enumerate(use):
        row = table.rows[l]
        threads, jscript, jcmd, env_add = job_threads, script, command, {}
        for col, val in row.items():
            if not col.startswith('!'):
                continue
            if col in ('!OMP_NUM_THREADS', '!THREADS'):
                try:
                    threads = int(_unquote(val))
                except ValueError:
                    raise TableError(table_path, l, 'column %s must be an integer, got %r' % (col, val)) from None
                if threads < 1:
                    raise TableError(table_path, l, 'column %s must be >= 1, got %r' % (col, val))
            elif col == '!SCRIPT':
                jscript = _unquote(val)
            elif col == '!EXEC':
                jcmd = shlex.split(_unquote(val))
            elif col in _IGNORED_SPECIAL:
                pass
            else:
                env_add[col[1:]] = _unquote(val)
        if not jscript:
            raise BatchError('no script given and the table has no !SCRIPT column')
        env_add['YADE_BATCH'] = '%s:%d' % (table_path, l)
        env_add['DISPLAY'] = ''
        env_add['OMP_NUM_THREADS'] = str(threads)
        desc = row['description']
        stem = os.path.splitext(os.path.basename(jscript))[0]
        name = '%s.%s' % (_sanitise(stem, l), _sanitise(desc, l))
        log = os.path.join(logdir, name + '.log')
        if log in used_logs:
            log = os.path.join(logdir, '%s.l%d.log' % (name, l))
        used_logs.add(log)
        jobs.append(Job(num, l, desc, jscript, build_argv(jcmd, jscript, threads), env_add, threads, log))
    return table, jobs, logdir


def _hms(dt):
    dt = int(dt)
    return '%02d:%02d:%02d' % (dt // 3600, (dt % 3600) // 60, dt % 60)


class _Progress:
    def __init__(self, jobs, stream=sys.stderr):
        self.jobs, self.stream, self.t0 = jobs, stream, time.time()
        self.tty = hasattr(stream, 'isatty') and stream.isatty()
        self.last_draw = 0.0

    def line(self):
        n = len(self.jobs)
        done = [j for j in self.jobs if j.status == 'DONE']
        failed = sum(1 for j in done if j.exit != 0)
        running = [j for j in self.jobs if j.status == 'RUNNING']
        pending = sum(1 for j in self.jobs if j.status == 'PENDING')
        run = ' '.join('l%d' % j.line for j in running[:8]) + (' ...' if len(running) > 8 else '')
        return ('[batch %s] %d/%d done%s, %d running%s, %d pending' %
                (_hms(time.time() - self.t0), len(done), n, ' (%d FAILED)' % failed if failed else '',
                 len(running), ' (%s)' % run if run else '', pending))

    def update(self, event=None):
        self.last_draw = time.time()
        if self.tty:
            if event:
                self.stream.write('\r\x1b[K' + event + '\n')
            self.stream.write('\r\x1b[K' + self.line())
            self.stream.flush()
        elif event:
            self.stream.write(event + '  ' + self.line() + '\n')
            self.stream.flush()

    def close(self):
        if self.tty:
            self.stream.write('\r\x1b[K' + self.line() + '\n')
            self.stream.flush()


def _start(job, nice):
    import signal
    stops = {signal.SIGINT, signal.SIGTERM, signal.SIGHUP}
    # a stop signal is held until the job is recorded as running, so that it is stopped with the
    # others; the job itself starts with them unblocked
    signal.pthread_sigmask(signal.SIG_BLOCK, stops)

    def pre():
        signal.pthread_sigmask(signal.SIG_UNBLOCK, stops)
        if nice:
            os.nice(nice)
    try:
        os.makedirs(os.path.dirname(job.log) or '.', exist_ok=True)
        env = dict(os.environ)
        env.update(job.env_add)
        job.logf = open(job.log, 'wb')
        job.started = time.time()
        job.status = 'RUNNING'
        try:
            job.proc = subprocess.Popen(job.argv, env=env, stdin=subprocess.DEVNULL, stdout=job.logf,
                                        stderr=subprocess.STDOUT, preexec_fn=pre, start_new_session=True)
        except OSError as e:
            job.logf.write(('compat batch: cannot start %s: %s\n' % (shlex.join(job.argv), e)).encode())
            job.proc = None
            _finish(job, 127)
    finally:
        signal.pthread_sigmask(signal.SIG_UNBLOCK, stops)


def _log_says_normal_exit(path):
    try:
        with open(path, 'rb') as f:
            return any(l.startswith(_NORMAL_EXIT.encode()) for l in f)
    except OSError:
        return False


def _finish(job, rc):
    job.finished = time.time()
    job.status = 'DONE'
    job.raw_exit = rc
    job.exit = 0 if rc != 0 and _log_says_normal_exit(job.log) else rc
    if job.logf:
        job.logf.close()
        job.logf = None
    with open(job.log, 'a') as f:
        f.write('\n=================== JOB SUMMARY ================\n'
                'line    : %d\ndesc    : %s\nstatus  : %d (%s)\nduration: %s\ncommand : %s\n'
                'started : %s\nfinished: %s\n' %
                (job.line, job.description, job.exit, 'OK' if job.exit == 0 else 'FAILED', _hms(job.wall),
                 ' '.join('%s=%s' % (k, shlex.quote(v)) for k, v in job.env_add.items()) + ' ' + shlex.join(job.argv),
                 time.asctime(time.localtime(job.started)), time.asctime(time.localtime(job.finished))))


#: the signal that stopped the batch (SIGINT arrives as KeyboardInterrupt; SIGTERM and SIGHUP are made one)
_STOP_SIGNAL = ['SIGINT', 2]


def _on_stop_signal(signum, frame):
    import signal
    _STOP_SIGNAL[:] = [signal.Signals(signum).name, signum]
    raise KeyboardInterrupt


def _stop(job):
    try:
        os.killpg(job.proc.pid, 15)  # the job's own session, started by us
    except (ProcessLookupError, PermissionError):
        pass


def run_jobs(jobs, max_cores, nice=10, timeout=None, progress=None):
    progress = progress or _Progress(jobs)
    try:
        while True:
            running = [j for j in jobs if j.status == 'RUNNING']
            for j in running:
                rc = j.proc.poll()
                if rc is None and timeout and j.wall > timeout:
                    _stop(j)
                    try:
                        rc = j.proc.wait(10)
                    except subprocess.TimeoutExpired:
                        os.killpg(j.proc.pid, 9)
                        rc = j.proc.wait()
                    j.logf.write(('\ncompat batch: killed after --timeout %gs\n' % timeout).encode())
                if rc is not None:
                    _finish(j, rc if rc >= 0 else 128 - rc)
                    progress.update('#%d l%d (%s) %s (exit %d), %s, log %s' %
                                    (j.num, j.line, j.description, 'done' if j.exit == 0 else 'FAILED',
                                     j.exit, _hms(j.wall), j.log))
            running = [j for j in jobs if j.status == 'RUNNING']
            pending = [j for j in jobs if j.status == 'PENDING']
            if not running and not pending:
                break
            free = max_cores - sum(j.threads for j in running)
            for j in pending:
                if j.threads <= free or not running:
                    _start(j, nice)
                    if j.status != 'RUNNING':  # could not start; already finished with exit 127
                        progress.update('#%d l%d (%s) FAILED to start, log %s' % (j.num, j.line, j.description, j.log))
                        continue
                    progress.update('#%d l%d (%s) started%s' % (j.num, j.line, j.description,
                                                                 '' if j.threads == 1 else ' with %d threads' % j.threads))
                    running.append(j)
                    free -= j.threads
                    if free <= 0:
                        break
            time.sleep(0.05)
            if progress.tty and time.time() - progress.last_draw > 0.5:
                progress.update()
    except KeyboardInterrupt:
        stopped = []
        for j in jobs:
            if j.status == 'RUNNING':
                _stop(j)
                stopped.append(j)
            elif j.status == 'PENDING':
                j.status = 'NOT RUN'
        for j in stopped:
            try:
                rc = j.proc.wait(10)
            except subprocess.TimeoutExpired:
                os.killpg(j.proc.pid, 9)
                rc = j.proc.wait()
            _finish(j, rc if rc >= 0 else 128 - rc)
        progress.close()
        done = [j for j in jobs if j.status == 'DONE' and j not in stopped]
        print('compat batch: stopped by %s: %d job(s) had finished (their logs and outputs are kept), %d stopped, '
              '%d not started' % (_STOP_SIGNAL[0], len(done), len(stopped), sum(1 for j in jobs if j.status == 'NOT RUN')),
              file=sys.stderr)
        return False
    progress.close()
    return True


def write_summary(jobs, logdir, out=sys.stdout):
    rows = []
    for j in jobs:
        status = 'OK' if j.ok else ('FAILED' if j.status == 'DONE' else j.status)
        rows.append((str(j.line), j.description, status, '' if j.exit is None else str(j.exit),
                     '' if j.wall is None else '%.2f' % j.wall, j.log))
    head = ('line', 'description', 'status', 'exit', 'wall_s', 'log')
    os.makedirs(logdir, exist_ok=True)
    path = os.path.join(logdir, 'summary.csv')
    with open(path, 'w', newline='') as f:
        w = csv.writer(f)
        w.writerow(head)
        w.writerows(rows)
    widths = [max(len(r[i]) for r in rows + [head]) for i in range(len(head))]
    widths[1] = min(widths[1], 60)
    for r in [head] + rows:
        cells = [c if len(c) <= widths[i] else c[:widths[i] - 3] + '...' for i, c in enumerate(r)]
        print('  '.join(c.ljust(widths[i]) for i, c in enumerate(cells)).rstrip(), file=out)
    nfail = sum(1 for j in jobs if not j.ok)
    print('%d job(s), %d OK, %d failed or not run; summary %s' % (len(jobs), len(jobs) - nfail, nfail, path), file=out)
    return path


def emit_slurm(path, table_path, jobs, logdir, command_is_default, throttle=None, extra=()):
    def ranges(nums):
        out, i = [], 0
        while i < len(nums):
            k = i
            while k + 1 < len(nums) and nums[k + 1] == nums[k] + 1:
                k += 1
            out.append(str(nums[i]) if k == i else '%d-%d' % (nums[i], nums[k]))
            i = k + 1
        return ','.join(out)

    lines = sorted(j.line for j in jobs)
    array = ranges(lines) + ('%%%d' % throttle if throttle else '')
    stem = os.path.splitext(os.path.basename(jobs[0].script))[0]
    s = ['#!/bin/bash',
         '# Generated by `compat batch --emit-slurm` from %s: one array task per table line;' % table_path,
         '# the task id is the line number (YADE_BATCH=%s:$SLURM_ARRAY_TASK_ID).' % table_path,
         '# Paths are relative to the directory this was generated in: submit from there.',
         '#SBATCH --job-name=%s' % _sanitise(stem, 0),
         '#SBATCH --array=%s' % array,
         '#SBATCH --ntasks=1',
         '#SBATCH --cpus-per-task=%d' % max(j.threads for j in jobs),
         '#SBATCH --output=%s' % os.path.join(logdir, 'slurm-%A_%a.out')]
    s += ['#SBATCH %s' % o for o in extra]
    s += ['set -eu', 'cd "${SLURM_SUBMIT_DIR:-.}"', 'LINE="${SLURM_ARRAY_TASK_ID:?not running as a Slurm array task}"',
          'export DISPLAY=', 'case "$LINE" in']
    for j in sorted(jobs, key=lambda j: j.line):
        argv = list(j.argv)
        if command_is_default and argv[:3] == [sys.executable, '-m', 'yade.runner']:
            cmd = '"${RYADE_PYTHON:-python3}" -m yade.runner ' + shlex.join(argv[3:])
        else:
            cmd = shlex.join(argv)
        exports = ' '.join('%s=%s' % (k, shlex.quote(v)) for k, v in j.env_add.items() if k != 'DISPLAY')
        s.append('  %d)  # %s' % (j.line, j.description.replace('\n', ' ')))
        s.append('    export %s' % exports)
        s.append('    LOG=%s' % shlex.quote(j.log))
        s.append('    CMD=(%s) ;;' % cmd)
    s += ['  *) echo "task $LINE is not a job line of %s" >&2; exit 2 ;;' % table_path, 'esac',
          'mkdir -p "$(dirname "$LOG")"',
          'echo "line $LINE: YADE_BATCH=$YADE_BATCH OMP_NUM_THREADS=$OMP_NUM_THREADS ${CMD[*]} > $LOG"',
          'exec "${CMD[@]}" > "$LOG" 2>&1', '']
    with open(path, 'w') as f:
        f.write('\n'.join(s))
    os.chmod(path, 0o755)


def _parser():
    p = argparse.ArgumentParser(prog='compat batch', description=__doc__.split('\n\n')[0],
                                epilog='Full documentation: python -c "import yade.batch; help(yade.batch)"')
    p.add_argument('table', metavar='TABLE', help='parameter table (yade-batch format)')
    p.add_argument('script', metavar='SCRIPT.py', nargs='?', help='script to run (or a !SCRIPT column)')
    p.add_argument('-j', '--jobs', type=int, default=None, metavar='N',
                   help='cores to use at once (default: number of CPUs); each job takes its thread count')
    p.add_argument('-l', '--lines', metavar='LIST', help='table lines to run, e.g. 2,4-6 (default: all)')
    p.add_argument('--log', metavar='DIR', help='log directory (default: <table dir>/<table stem>.logs)')
    p.add_argument('--dry-run', action='store_true', help='print the jobs, run nothing')
    p.add_argument('--command', metavar='CMD',
                   help="job command, e.g. 'yade -n -x' ({script}/{threads} substituted; default: "
                        "$RYADE_BATCH_RUNNER or '<python> -m yade.runner')")
    p.add_argument('--job-threads', type=int, default=1, metavar='N',
                   help='threads per job unless the table sets !OMP_NUM_THREADS/!THREADS (default 1)')
    p.add_argument('--nice', type=int, default=10, help='nice increment of the jobs (default 10)')
    p.add_argument('--timeout', type=float, default=None, metavar='S', help='kill a job after S seconds')
    p.add_argument('--emit-slurm', metavar='FILE', help='write a Slurm job-array script instead of running')
    p.add_argument('--slurm-opt', action='append', default=[], metavar='OPT',
                   help='extra #SBATCH option for --emit-slurm (repeatable), e.g. --slurm-opt=--time=1:00:00')
    return p


def main(argv=None):
    args = _parser().parse_args(sys.argv[1:] if argv is None else argv)
    try:
        if args.command:
            command, is_default = shlex.split(args.command), False
        else:
            command, is_default = default_command()
        lines = parse_line_list(args.lines) if args.lines else None
        table, jobs, logdir = plan_jobs(args.table, args.script, lines, args.log, command, args.job_threads)
    except (TableError, BatchError, OSError, ValueError) as e:
        print('compat batch: error: %s' % e, file=sys.stderr)
        return 2
    if not jobs:
        print('compat batch: error: no jobs selected from %s' % args.table, file=sys.stderr)
        return 2
    max_cores = args.jobs if args.jobs else (os.cpu_count() or 1)
    if args.emit_slurm:
        emit_slurm(args.emit_slurm, args.table, jobs, logdir, is_default, args.jobs, args.slurm_opt)
        print('wrote %s: %d array task(s), lines %s; submit with: sbatch %s'
              % (args.emit_slurm, len(jobs), ','.join(str(j.line) for j in jobs), args.emit_slurm))
        return 0
    print('compat batch: table %s, %d job(s) (lines %s), up to %d core(s), logs in %s'
          % (args.table, len(jobs), ','.join(str(j.line) for j in jobs), max_cores, logdir), file=sys.stderr)
    if args.dry_run:
        for j in jobs:
            env = ' '.join('%s=%s' % (k, shlex.quote(v)) for k, v in j.env_add.items())
            print('#%d line %d (%s):\n    %s %s > %s 2>&1' % (j.num, j.line, j.description, env,
                                                          shlex.join(j.argv), j.log))
        return 0
    import signal
    for sig in (signal.SIGTERM, signal.SIGHUP):
        signal.signal(sig, _on_stop_signal)
    completed = run_jobs(jobs, max_cores, nice=args.nice, timeout=args.timeout)
    write_summary(jobs, logdir)
    if not completed:
        return 128 + _STOP_SIGNAL[1]
    return 0 if all(j.ok for j in jobs) else 1


if __name__ == '__main__':
    sys.exit(main())
