#!/usr/bin/env python3
"""Record what real YADE 2023.02a does with the tables in this directory.

    python3 yade_ref/compat/batch/gen_expect.py [OUT.json]

Default OUT: compat/tests/data/batch/yade_expect.json. Needs `yade` and `yade-batch` on PATH.
Each case runs `probe.py` in its own `yade -n -x` process with YADE_BATCH set by hand (as
yade-batch does: `YADE_BATCH=<table as given>:<line>`, cwd = this directory); the `batch`
section runs real `yade-batch` on batchenv.table. See README.md.
"""
import json, os, shutil, subprocess, sys, tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, '..', '..', '..'))
OUT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, 'compat', 'tests', 'data', 'batch', 'yade_expect.json')

T_DEF = {'a': 0, 'b': 0.0, 'c': 'pi/2', 's': 'z'}
# (name, table, YADE_BATCH (None: unset), call kwargs incl. defaults, divergence note or None)
CASES = [
    ('tricky_l5', 'tricky.table', 'tricky.table:5', dict(T_DEF, extra=42, name='run'), None),
    ('tricky_l6_star_float', 'tricky.table', 'tricky.table:6', dict(T_DEF, c=0.5), 'star'),
    ('tricky_l6_star_str', 'tricky.table', 'tricky.table:6', dict(T_DEF), None),
    ('tricky_l6_star_badstr', 'tricky.table', 'tricky.table:6', dict(T_DEF, c='lin'), 'star'),
    ('tricky_l7', 'tricky.table', 'tricky.table:7', dict(T_DEF), None),
    ('tricky_l9_dupdesc', 'tricky.table', 'tricky.table:9', dict(T_DEF), None),
    ('tricky_l10_tab_eq', 'tricky.table', 'tricky.table:10', dict(T_DEF), None),
    ('tricky_unknown', 'tricky.table', 'tricky.table:5', {'a': 0, 'c': 0, 's': ''}, None),
    ('tricky_unknownOk', 'tricky.table', 'tricky.table:5', {'a': 0, 'c': 0, 's': '', 'unknownOk': True}, None),
    ('tricky_arg', 'tricky.table', None, dict(T_DEF, tableFileLine='tricky.table:7'), None),
    ('tricky_arg_overrides_env', 'tricky.table', 'tricky.table:5', dict(T_DEF, tableFileLine='tricky.table:7'), None),
    ('tricky_badline', 'tricky.table', 'tricky.table:4', dict(T_DEF), None),
    ('no_table', None, None, {'a': 1, 'b': 'x'}, None),
    ('empty_env', None, '', {'a': 1}, None),
    ('no_table_not_ok', None, None, {'a': 1, 'noTableOk': False}, None),
    ('bang_l3', 'bang.table', 'bang.table:3', {'n': 0, 'rate': 0.1, 'mode': 'x'}, None),
    ('bang_l4', 'bang.table', 'bang.table:4', {'n': 0, 'rate': 0.1, 'mode': 'x'}, None),
    ('bang_l5_dup', 'bang.table', 'bang.table:5', {'n': 0, 'rate': 0.1, 'mode': 'x'}, None),
    ('desc_l2_bangname', 'desc.table', 'desc.table:2', {'x': 0, 'y': 0}, None),
    ('desc_l3_unknownOk', 'desc.table', 'desc.table:3', {'x': 0, 'y': 0, 'unknownOk': True}, None),
    ('desc_l4_star', 'desc.table', 'desc.table:4', {'x': 9, 'y': 0, 'unknownOk': True}, 'star'),
    ('firsteq_l3', 'firsteq.table', 'firsteq.table:3', {'p': 0, 'q': 0}, 'firsteq'),
    ('firsteq_l2', 'firsteq.table', 'firsteq.table:2', {'p': 0, 'q': 0}, 'firsteq'),
    ('nonl_l3', 'nonl.table', 'nonl.table:3', {'u': 0, 'v': 0}, 'nonl'),
]
DIVERGENCES = {
    'star': "YADE replaces '*' by the default and eval()s it, which raises TypeError for a "
            "non-string default and NameError/SyntaxError for a string default that is not a valid "
            "expression; when the eval succeeds the result is discarded and the default is assigned "
            "unchanged. ryade skips the eval: it always assigns the default unchanged.",
    'firsteq': "YADE resolves '=' on the first data line from the LAST data line (lines[i-1] with "
               "i=0). ryade rejects the whole table with TableError (for every line).",
    'nonl': "YADE strips the last character of every line (l[:-1]), so on a last line without a "
            "newline it drops a real character ('45' -> '4'). ryade reads the value as written.",
}


def run_case(name, table, yb, kw, tmp):
    case = {'defaults': {k: v for k, v in kw.items() if k not in ('tableFileLine', 'noTableOk', 'unknownOk')}}
    for k in ('tableFileLine', 'noTableOk', 'unknownOk'):
        if k in kw:
            case[k] = kw[k]
    if table:
        case['table'] = table
    env = {k: v for k, v in os.environ.items() if k != 'YADE_BATCH'}
    if yb is not None:
        env['YADE_BATCH'] = yb
    out = os.path.join(tmp, name + '.json')
    env.update(PROBE_CASE=repr(case), PROBE_OUT=out, OMP_NUM_THREADS='1')
    p = subprocess.run(['yade', '-n', '-x', 'probe.py'], cwd=HERE, env=env, capture_output=True, text=True, timeout=120)
    if not os.path.exists(out):
        raise SystemExit('%s: probe wrote nothing (rc %d)\n%s' % (name, p.returncode, p.stdout[-2000:] + p.stderr[-2000:]))
    with open(out) as f:
        res = json.load(f)
    return {'name': name, 'table': table, 'YADE_BATCH': yb, 'call': case, 'result': res}


def run_batch(tmp):
    outdir = os.path.join(tmp, 'batch')
    os.makedirs(outdir)
    work = os.path.join(tmp, 'bw')
    os.makedirs(work)
    for f in ('batchenv.table', 'batchenv.py'):
        shutil.copy(os.path.join(HERE, f), work)
    env = dict(os.environ, PROBE_OUTDIR=outdir)
    env.pop('YADE_BATCH', None)
    p = subprocess.run(['yade-batch', '--disable-pynotify', '-j', '2', '--lines', '4,6-7', 'batchenv.table', 'batchenv.py'],
                       cwd=work, env=env, capture_output=True, text=True, timeout=300)
    logs = [l.split(':', 1)[1].split() for l in p.stdout.splitlines() if l.startswith('Log files:')]
    jobs = {}
    for fn in sorted(os.listdir(outdir)):
        with open(os.path.join(outdir, fn)) as f:
            jobs[fn[:-5]] = json.load(f)
    cmds = [l.strip() for l in p.stdout.splitlines() if l.strip().startswith('#') and 'YADE_BATCH=' in l]
    return {'argv': ['--lines', '4,6-7', 'batchenv.table', 'batchenv.py'], 'returncode': p.returncode,
            'log_files': logs[0] if logs else None, 'job_commands': cmds, 'jobs': jobs}


def main():
    tables = {}
    for fn in sorted(os.listdir(HERE)):
        if fn.endswith('.table'):
            with open(os.path.join(HERE, fn)) as f:
                tables[fn] = f.read()
    with tempfile.TemporaryDirectory() as tmp:
        cases = []
        for name, table, yb, kw, div in CASES:
            c = run_case(name, table, yb, kw, tmp)
            if div:
                c['divergent'] = div
            cases.append(c)
            print(name, c['result'].get('error') or c['result'].get('return'))
        batch = run_batch(tmp)
    ver = subprocess.run(['yade', '--version'], capture_output=True, text=True).stdout.strip().splitlines()
    doc = {'generator': 'yade_ref/compat/batch/gen_expect.py', 'yade_version': ver[0] if ver else None,
           'divergences': DIVERGENCES, 'tables': tables, 'cases': cases, 'batch': batch}
    os.makedirs(os.path.dirname(OUT), exist_ok=True)
    with open(OUT, 'w') as f:
        json.dump(doc, f, indent=1, sort_keys=True)
        f.write('\n')
    print('wrote', OUT)


if __name__ == '__main__':
    main()
