"""yade-batch tables, readParamsFromTable and `compat batch` (yade._table, yade.params, yade.batch).

data/batch/yade_expect.json was written by ``python3 yade_ref/compat/batch/gen_expect.py``: it
holds the tables of yade_ref/compat/batch/ and what real YADE 2023.02a's readParamsFromTable /
TableParamReader / yade-batch produced with them. No engine is needed: jobs run through a small
shim that registers a fake ``O`` and execs the script.
"""
import csv
import json
import os
import shutil
import subprocess
import sys
import textwrap
import types
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
PYDIR = HERE.parent / 'python'
EXPECT = HERE / 'data' / 'batch' / 'yade_expect.json'
REFDIR = ROOT / 'yade_ref' / 'compat' / 'batch'

# The installed package when it holds this tree's sources (editable, or installed from this tree as
# test.sh does); otherwise this tree's modules alone in a stand-in package. The installed one is
# preferred so that the later test modules, which need the compiled extension, import the real package.
_IMPORT_PRELUDE = '''
import sys, types
def _same_source(mod, path):
    try:
        return open(mod.__file__, 'rb').read() == open(path, 'rb').read()
    except Exception:
        return False
try:
    import yade._table
    _ok = _same_source(yade._table, %r)
except Exception:
    _ok = False
if not _ok:  # load our modules alone
    for k in [k for k in sys.modules if k == 'yade' or k.startswith('yade.')]:
        del sys.modules[k]
    sys.path.insert(0, %r)
    pkg = types.ModuleType('yade')
    pkg.__path__ = [%r]
    sys.modules['yade'] = pkg
    import yade._table
''' % (str(PYDIR / 'yade' / '_table.py'), str(PYDIR), str(PYDIR / 'yade'))

exec(_IMPORT_PRELUDE)
import yade._table as T  # noqa: E402
import yade.params as P  # noqa: E402
import yade.batch as B  # noqa: E402

for _m, _name in ((T, '_table.py'), (P, 'params.py'), (B, 'batch.py')):
    assert Path(_m.__file__).read_bytes() == (PYDIR / 'yade' / _name).read_bytes(), _m.__file__

SHIM = _IMPORT_PRELUDE + '''
import os
import yade._table as T
class FakeO:
    def __init__(self):
        ident = 'ID%dT' % os.getpid()
        self.tags = {'id': ident, 'd.id': ident, 'id.d': ident}
    def wait(self):
        pass
O = FakeO()
T.set_omega(O)
script = sys.argv[1]
sys.argv = sys.argv[1:]
g = {'__name__': '__main__', '__file__': script, 'O': O,
     'readParamsFromTable': T.readParamsFromTable, 'waitIfBatch': T.waitIfBatch,
     'runningInBatch': T.runningInBatch}
with open(script) as f:
    code = compile(f.read(), script, 'exec')
exec(code, g)
'''


class FakeO:
    def __init__(self, ident='{id}'):
        self.tags = {'id': ident, 'd.id': ident, 'id.d': ident}
        self.waited = 0

    def wait(self):
        self.waited += 1


@pytest.fixture
def O(monkeypatch):
    """A fresh O registered with set_omega, fresh yade.params, no YADE_BATCH."""
    o = FakeO()
    old = T._O
    T.set_omega(o)
    monkeypatch.delenv('YADE_BATCH', raising=False)
    P.__all__[:] = []
    for name in list(vars(P)):
        if isinstance(getattr(P, name), types.ModuleType) and name != 'types':
            delattr(P, name)
    for k in [k for k in sys.modules if k.startswith('yade.params.')]:
        del sys.modules[k]
    yield o
    T.set_omega(old)


def write(path, text):
    path.write_text(textwrap.dedent(text).lstrip('\n'))
    return path


def table_vars():
    try:
        import yade.params.table as tab
    except ImportError:
        return None
    return {k: [type(getattr(tab, k)).__name__, repr(getattr(tab, k))] for k in sorted(tab.__all__)}


# ------------------------------------------------------------------ parser

def test_parser_tricky(tmp_path):
    p = write(tmp_path / 't.table', '''
        # comment
          # indented comment

        a   b!     !ENV   c!   # header comment
        1   'x y'  e1     2.5
        =   =      *      =
        ''')
    # 'x y' has a blank: no quoting, so the header has 4 cells and line 5 five
    with pytest.raises(T.TableError, match=r't\.table:5: expected 4 cells'):
        T.parse_table(str(p))
    p = write(tmp_path / 't.table', '''
        # comment
          # indented comment

        a   b!     !ENV   c!   # header comment
        1   'x'    e1     2.5
        =   =      *      =

        3   "x"    =      =#c
        ''')
    t = T.parse_table(str(p))
    assert t.header_line == 4
    assert t.lines == [5, 6, 8]
    assert t.columns == ['a', 'b', '!ENV', 'c']
    assert t.rows[6] == {'a': '1', 'b': "'x'", '!ENV': '*', 'c': '2.5', 'description': 'b=x,c=2.5__line=6__'}
    assert t.rows[5]['description'] == 'b=x,c=2.5'
    # quotes are removed from the description, so 'x' and "x" give the same one
    assert t.rows[8]['description'] == 'b=x,c=2.5__line=8__'
    assert t.rows[8]['!ENV'] == '*'
    assert t.params(5) == {'a': '1', 'b': "'x'", 'c': '2.5'}
    assert t.env_columns(5) == {'ENV': 'e1'}


def test_parser_description_all_columns_and_bang_env(tmp_path):
    p = write(tmp_path / 'x.table', '''
        n  !OMP_NUM_THREADS  s
        1  2                 'a'
        1  =                 =
        ''')
    t = T.parse_table(str(p))
    assert t.rows[2]['description'] == 'n=1,OMP_NUM_THREADS=2,s=a'
    assert t.rows[3]['description'] == 'n=1,OMP_NUM_THREADS=2,s=a__line=3__'
    assert list(t.rows[2]) == ['n', '!OMP_NUM_THREADS', 's', 'description']


def test_parser_description_column_kept_and_no_bang_strip(tmp_path):
    p = write(tmp_path / 'd.table', '''
        description  x  y!
        one          1  2
        =            3  4
        ''')
    t = T.parse_table(str(p))
    assert t.rows[2] == {'description': 'one', 'x': '1', 'y!': '2'}
    assert t.rows[3]['description'] == 'one'  # given descriptions are not de-duplicated


def test_parser_crlf_and_no_final_newline(tmp_path):
    p = tmp_path / 'w.table'
    p.write_bytes(b'u v\r\n1 2\r\n3 45')
    t = T.parse_table(str(p))
    assert t.rows[3] == {'u': '3', 'v': '45', 'description': 'u=3,v=45'}


@pytest.mark.parametrize('text,line,msg', [
    ('a b\n1 2\n3\n', 3, 'expected 2 cells'),
    ('a b\n1 2\n3 4 5\n', 3, 'expected 2 cells'),
    ('# c\na b\n\n= 1\n', 4, "'=' in column 'a' on the first data line"),
    ('a b a\n1 2 3\n', 1, "duplicate column name 'a'"),
    ('a a!\n1 2\n', 1, "duplicate column name 'a'"),
    ('# only\n\n', 2, 'no header line'),
    ('a b\n# nothing\n', 1, 'no data lines'),
])
def test_parser_errors(tmp_path, text, line, msg):
    p = tmp_path / 'bad.table'
    p.write_text(text)
    with pytest.raises(T.TableError) as ei:
        T.parse_table(str(p))
    assert str(ei.value).startswith('%s:%d: ' % (p, line))
    assert msg in str(ei.value)
    assert ei.value.line == line and ei.value.path == str(p)


def test_parser_missing_file(tmp_path):
    with pytest.raises(T.TableError, match='cannot read table'):
        T.parse_table(str(tmp_path / 'nope.table'))


def test_table_param_reader_is_yade_shaped(tmp_path):
    p = write(tmp_path / 'r.table', '''
        a b
        1 2
        ''')
    assert T.TableParamReader(str(p)).paramDict() == {2: {'a': '1', 'b': '2', 'description': 'a=1,b=2'}}


# ------------------------------------------------------------------ readParamsFromTable

def test_read_without_table(O):
    assert not T.runningInBatch()
    n = T.readParamsFromTable(a=1, b='x', c=[1, 2])
    assert n == 0
    assert O.tags['line'] == 'l!'
    assert O.tags['params'] == '' and O.tags['defaultParams'] == 'a=1,b=x,c=[1, 2]'
    assert 'description' not in O.tags
    from yade.params.table import a, b, c
    from yade.params import table
    assert (a, b, c) == (1, 'x', [1, 2]) and table.a == 1
    assert P.__all__ == ['table']
    T.waitIfBatch()
    assert O.waited == 0
    with pytest.raises(EnvironmentError, match='YADE_BATCH is not defined'):
        T.readParamsFromTable(noTableOk=False, a=1)


def test_read_with_yade_batch(O, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    write(tmp_path / 's.table', '''
        # sweep
        radius   mode     n  !OMP_NUM_THREADS
        2*pi     'fast'   3  2
        =        *        4  1
        ''')
    monkeypatch.setenv('YADE_BATCH', 's.table:3')
    assert T.runningInBatch()
    n = T.readParamsFromTable(radius=1.0, mode='slow', n=1, extra=7)
    assert n == 3
    from yade.params.table import radius, mode, n as nn, extra
    assert (radius, mode, nn, extra) == (pytest.approx(6.283185307179586), 'fast', 3, 7)
    assert O.tags['line'] == 'l3'
    assert O.tags['description'] == 'radius=2*pi,mode=fast,n=3,OMP_NUM_THREADS=2'
    assert O.tags['id.d'] == '{id}.' + O.tags['description']
    assert O.tags['d.id'] == O.tags['description'] + '.{id}'
    assert O.tags['params'] == "radius=2*pi,mode='fast',n=3"
    assert O.tags['defaultParams'] == 'extra=7'
    T.waitIfBatch()
    assert O.waited == 1
    # '*' = the script default: listed in params and in defaultParams (as YADE)
    monkeypatch.setenv('YADE_BATCH', 's.table:4')
    with pytest.warns(UserWarning, match='Overwriting yade.params.table'):
        assert T.readParamsFromTable(radius=1.0, mode='slow', n=1) == 3
    from yade.params import table
    assert table.mode == 'slow' and table.n == 4
    assert O.tags['params'] == 'radius=2*pi,mode=slow,n=4'
    assert O.tags['defaultParams'] == 'mode=slow'
    # explicit tableFileLine wins over the environment
    with pytest.warns(UserWarning, match='Overwriting yade.params.table'):
        assert T.readParamsFromTable('s.table:3', radius=0, mode='', n=0) == 3
    assert O.tags['line'] == 'l3'


def test_read_errors(O, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    write(tmp_path / 'e.table', '''
        a  b
        1  nosuchname
        ''')
    monkeypatch.setenv('YADE_BATCH', 'e.table:2')
    with pytest.raises(NameError, match="Parameter `b' has no default value assigned"):
        T.readParamsFromTable(a=0)
    with pytest.raises(NameError, match="nosuchname") as ei:
        T.readParamsFromTable(a=0, b=0)
    assert "e.table:2" in ''.join(getattr(ei.value, '__notes__', []))
    monkeypatch.setenv('YADE_BATCH', 'e.table:1')
    with pytest.raises(RuntimeError, match="Table e.table doesn't contain valid line number 1"):
        T.readParamsFromTable(a=0, b=0)
    monkeypatch.setenv('YADE_BATCH', 'e.table')
    with pytest.raises(ValueError, match="FILE:LINE"):
        T.readParamsFromTable(a=0, b=0)


def test_unknownOk_and_save_load_vars(O, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    write(tmp_path / 'u.table', '''
        a  zz
        1  [1,2]
        ''')
    monkeypatch.setenv('YADE_BATCH', 'u.table:2')
    assert T.readParamsFromTable(unknownOk=True, a=0) == 2
    from yade.params.table import zz
    assert zz == [1, 2]
    # the variables are pickled into O.tags and can be re-loaded (after O.load in YADE)
    assert 'pickledPythonVariablesDictionarytable' in O.tags
    del sys.modules['yade.params.table']
    delattr(P, 'table')
    T.loadVars('table')
    from yade.params.table import a
    assert a == 1
    T.saveVars('geom', r=0.5)
    from yade.params.geom import r
    assert r == 0.5


# ------------------------------------------------------------------ against real YADE

_EXP = json.loads(EXPECT.read_text())
_DIVERGENT_TABLES = {'firsteq.table', 'nonl.table'}


def _setup_case(case, tmp_path, monkeypatch):
    for name, text in _EXP['tables'].items():
        (tmp_path / name).write_text(text)
    monkeypatch.chdir(tmp_path)
    if case['YADE_BATCH'] is None:
        monkeypatch.delenv('YADE_BATCH', raising=False)
    else:
        monkeypatch.setenv('YADE_BATCH', case['YADE_BATCH'])
    call = dict(case['call']['defaults'])
    for k in ('tableFileLine', 'noTableOk', 'unknownOk'):
        if k in case['call']:
            call[k] = case['call'][k]
    return call


def _run_case(O, call):
    out = {}
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter('ignore')
        try:
            out['return'] = T.readParamsFromTable(**call)
        except Exception as e:
            out['error'] = [type(e).__name__, str(e)]
    out['runningInBatch'] = T.runningInBatch()
    out['tags'] = {k: v for k, v in O.tags.items() if k != 'id' and not k.startswith('pickled')}
    out['table_vars'] = table_vars()
    out['params_all'] = list(P.__all__)
    return out


@pytest.mark.parametrize('case', [c for c in _EXP['cases'] if 'divergent' not in c], ids=lambda c: c['name'])
def test_matches_yade(case, O, tmp_path, monkeypatch):
    call = _setup_case(case, tmp_path, monkeypatch)
    exp = case['result']
    got = _run_case(O, call)
    for k in ('return', 'error', 'runningInBatch', 'tags', 'table_vars', 'params_all'):
        assert got.get(k) == exp.get(k), k
    if case['table'] and case['table'] not in _DIVERGENT_TABLES:
        pd = T.TableParamReader(case['table']).paramDict()
        assert {str(k): v for k, v in pd.items()} == exp['paramDict']


@pytest.mark.parametrize('case', [c for c in _EXP['cases'] if 'divergent' in c], ids=lambda c: c['name'])
def test_documented_divergences_from_yade(case, O, tmp_path, monkeypatch):
    """Where YADE crashes or misreads, we do what its documentation says (see _table's docstring)."""
    call = _setup_case(case, tmp_path, monkeypatch)
    exp = case['result']
    kind = case['divergent']
    assert kind in _EXP['divergences']
    if kind == 'star':
        assert exp['error'][0] in ('TypeError', 'NameError')  # what YADE does
        got = _run_case(O, call)
        assert 'error' not in got
        for k in ('line', 'description', 'id.d', 'd.id'):  # YADE set these before failing
            assert got['tags'][k] == exp['tags'][k]
        for col, cell in T.parse_table(case['table']).params(int(case['YADE_BATCH'].split(':')[1])).items():
            if cell == '*':
                default = call[col]
                assert got['table_vars'][col] == [type(default).__name__, repr(default)]
                assert '%s=%s' % (col, default) in got['tags']['params'].split(',')
                assert '%s=%s' % (col, default) in got['tags']['defaultParams'].split(',')
    elif kind == 'firsteq':
        # YADE read the table (line 2 took p from the LAST line); we reject the whole table
        assert exp['return'] == 2 and exp['table_vars']['p'] == ['int', '5']
        with pytest.raises(T.TableError, match=r"firsteq\.table:2: '=' in column 'p' on the first data line"):
            T.readParamsFromTable(**call)
    elif kind == 'nonl':
        assert exp['table_vars']['v'] == ['int', '4']  # YADE dropped the last character of '45'
        got = _run_case(O, call)
        assert got['table_vars']['v'] == ['int', '45']
        assert got['tags']['description'] == 'u=3,v=45'
    else:
        pytest.fail('unknown divergence ' + kind)


def test_every_yade_case_is_checked():
    names = [c['name'] for c in _EXP['cases']]
    assert len(names) == len(set(names)) >= 20
    assert set(_EXP['tables']) == {p.name for p in REFDIR.glob('*.table')}
    for name, text in _EXP['tables'].items():
        assert (REFDIR / name).read_text() == text, 'yade_expect.json is stale: rerun gen_expect.py'


# ------------------------------------------------------------------ batch runner

def _shim(tmp_path):
    shim = tmp_path / 'shim.py'
    shim.write_text(SHIM)
    return '%s %s' % (sys.executable, shim)


RESULT_SCRIPT = '''
import json, os
n = readParamsFromTable(a=0, b=1.0, name='none')
from yade.params.table import *
if a < 0:
    raise SystemExit(3)
res = {'n': n, 'a': a, 'b': b, 'name': name, 'line': O.tags['line'], 'description': O.tags['description'],
       'params': O.tags['params'], 'defaultParams': O.tags['defaultParams'],
       'env': {k: os.environ.get(k) for k in ('YADE_BATCH', 'OMP_NUM_THREADS', 'FOO', 'DISPLAY')}}
with open('result.%s.json' % O.tags['line'], 'w') as f:
    json.dump(res, f)
print('job', O.tags['line'], 'finished')
'''


def _sweep(tmp_path):
    write(tmp_path / 'sweep.table', '''
        # four jobs
        a     b        !FOO     !OMP_NUM_THREADS
        1     0.5      'x'      1

        2     =        =        2
        3     pi/2     y        =
        4     *        z        1
        ''')
    (tmp_path / 'job.py').write_text(RESULT_SCRIPT)


def _run_batch(tmp_path, *args, env=None):
    return subprocess.run([sys.executable, '-c', _IMPORT_PRELUDE + 'import yade.batch; sys.exit(yade.batch.main(sys.argv[1:]))',
                           *args], cwd=tmp_path, capture_output=True, text=True, timeout=120,
                          env=dict(os.environ, **(env or {})))


def test_batch_end_to_end(tmp_path):
    _sweep(tmp_path)
    p = _run_batch(tmp_path, 'sweep.table', 'job.py', '-j', '3', '--command', _shim(tmp_path))
    assert p.returncode == 0, p.stdout + p.stderr
    res = {}
    for l in (3, 5, 6, 7):
        res[l] = json.loads((tmp_path / ('result.l%d.json' % l)).read_text())
    assert [res[l]['a'] for l in (3, 5, 6, 7)] == [1, 2, 3, 4]
    assert res[6]['b'] == pytest.approx(1.5707963267948966) and res[7]['b'] == 1.0
    assert res[5]['b'] == 0.5
    assert res[3]['env'] == {'YADE_BATCH': 'sweep.table:3', 'OMP_NUM_THREADS': '1', 'FOO': 'x', 'DISPLAY': ''}
    assert res[5]['env'] == {'YADE_BATCH': 'sweep.table:5', 'OMP_NUM_THREADS': '2', 'FOO': 'x', 'DISPLAY': ''}
    assert res[6]['env']['OMP_NUM_THREADS'] == '2' and res[6]['env']['FOO'] == 'y'
    assert res[7]['defaultParams'] == 'b=1.0,name=none'
    assert res[3]['description'] == 'a=1,b=0.5,FOO=x,OMP_NUM_THREADS=1'
    logdir = tmp_path / 'sweep.logs'
    rows = list(csv.DictReader(open(logdir / 'summary.csv')))
    assert [r['line'] for r in rows] == ['3', '5', '6', '7']
    assert all(r['status'] == 'OK' and r['exit'] == '0' for r in rows)
    assert all(float(r['wall_s']) >= 0 for r in rows)
    log3 = Path(rows[0]['log'])
    assert log3 == Path('sweep.logs', 'job.a=1,b=0.5,FOO=x,OMP_NUM_THREADS=1.log')  # relative to the cwd
    text = (tmp_path / log3).read_text()
    assert 'job l3 finished' in text and 'JOB SUMMARY' in text
    assert 'summary.csv' in p.stdout and 'line' in p.stdout.splitlines()[0]
    assert '4/4 done' in p.stderr


def test_batch_failure_lines_and_env_runner(tmp_path):
    _sweep(tmp_path)
    (tmp_path / 'sweep.table').write_text((tmp_path / 'sweep.table').read_text().replace('3     pi/2', '-3    pi/2'))
    p = _run_batch(tmp_path, 'sweep.table', 'job.py', '--lines', '5-6,99', '--log', 'L',
                   env={'RYADE_BATCH_RUNNER': _shim(tmp_path)})
    assert p.returncode == 1, p.stdout + p.stderr
    assert 'skipping line 99' in p.stderr
    rows = {r['line']: r for r in csv.DictReader(open(tmp_path / 'L' / 'summary.csv'))}
    assert set(rows) == {'5', '6'}
    assert rows['5']['status'] == 'OK' and rows['6']['status'] == 'FAILED' and rows['6']['exit'] == '3'
    assert (tmp_path / 'result.l5.json').exists() and not (tmp_path / 'result.l3.json').exists()


def test_batch_dry_run_and_errors(tmp_path):
    _sweep(tmp_path)
    p = _run_batch(tmp_path, 'sweep.table', 'job.py', '--dry-run', '--command', 'yade -n -x')
    assert p.returncode == 0, p.stderr
    assert "YADE_BATCH=sweep.table:5 DISPLAY='' OMP_NUM_THREADS=2" in p.stdout
    assert 'yade --threads=2 -n -x job.py' in p.stdout
    assert not (tmp_path / 'sweep.logs').exists() and not list(tmp_path.glob('result.*'))
    (tmp_path / 'bad.table').write_text('a b\n1 2\n3\n')
    p = _run_batch(tmp_path, 'bad.table', 'job.py')
    assert p.returncode == 2 and 'bad.table:3: expected 2 cells' in p.stderr


def test_plan_jobs_commands(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    write(tmp_path / 'p.table', '''
        description   x   !SCRIPT   !THREADS  !EXEC
        first/run     1   a.py      3         'yade-float128'
        second        2   b.py      1         python3
        second        3   b.py      1         python3
        ''')
    table, jobs, logdir = B.plan_jobs('p.table', None, [4, 2, 4], None, None, 1)
    assert logdir == 'p.logs'
    assert [j.line for j in jobs] == [4, 2]
    j4, j2 = jobs
    assert j2.argv == ['yade-float128', '--threads=3', 'a.py'] and j2.threads == 3
    assert j2.log == os.path.join('p.logs', 'a.first_run.log')
    assert j4.argv == ['python3', 'b.py']
    _, jobs, _ = B.plan_jobs('p.table', None, None, 'L', ['run', '{script}', '-j{threads}'], 1)
    assert [j.log for j in jobs][1:] == [os.path.join('L', 'b.second.log'), os.path.join('L', 'b.second.l4.log')]
    assert B.build_argv(['compat', 'run', '{script}', '--threads', '{threads}'], 's.py', 2) == \
        ['compat', 'run', 's.py', '--threads', '2']
    assert B.build_argv(['yade', '-n', '-x'], 's.py', 1) == ['yade', '--threads=1', '-n', '-x', 's.py']
    assert B.parse_line_list('2,4-6, 9') == [2, 4, 5, 6, 9]
    with pytest.raises(B.BatchError):
        B.parse_line_list('6-4')


def test_batch_env_matches_real_yade_batch(tmp_path, monkeypatch):
    """Run yade_ref's batchenv.py/batchenv.table through our runner; the per-job results must equal
    what the same script recorded under real yade-batch (env, values, tags)."""
    exp = _EXP['batch']
    assert exp['returncode'] == 0
    for f in ('batchenv.table', 'batchenv.py'):
        shutil.copy(REFDIR / f, tmp_path)
    out = tmp_path / 'out'
    out.mkdir()
    # same job plan: YADE_BATCH/OMP/DISPLAY and the description part of yade-batch's log names
    monkeypatch.chdir(tmp_path)
    _, jobs, _ = B.plan_jobs('batchenv.table', 'batchenv.py', B.parse_line_list('4,6-7'), None, None, 1)
    assert ['batchenv.py.%s.log' % j.description for j in jobs] == exp['log_files']
    p = _run_batch(tmp_path, *exp['argv'], '--command', _shim(tmp_path), env={'PROBE_OUTDIR': str(out)})
    assert p.returncode == 0, p.stdout + p.stderr
    got = {f.stem: json.loads(f.read_text()) for f in sorted(out.glob('*.json'))}
    assert got == exp['jobs']


def test_emit_slurm(tmp_path):
    _sweep(tmp_path)
    p = _run_batch(tmp_path, 'sweep.table', 'job.py', '--emit-slurm', 'sweep.sbatch', '-j', '2',
                   '--slurm-opt=--time=01:00:00')
    assert p.returncode == 0, p.stderr
    s = (tmp_path / 'sweep.sbatch').read_text()
    assert '#SBATCH --array=3,5-7%2' in s
    assert '#SBATCH --cpus-per-task=2' in s and '#SBATCH --time=01:00:00' in s
    assert '"${RYADE_PYTHON:-python3}" -m yade.runner job.py' in s
    assert not list(tmp_path.glob('result.*'))
    if shutil.which('bash'):
        assert subprocess.run(['bash', '-n', str(tmp_path / 'sweep.sbatch')]).returncode == 0
        # run one array task by hand with the shim as python: same as a local job
        shim = tmp_path / 'fakepy'
        shim.write_text('#!/bin/sh\n[ "$1" = -m ] && shift 2\nexec %s %s "$@"\n' % (sys.executable, tmp_path / 'shim.py'))
        shim.chmod(0o755)
        (tmp_path / 'shim.py').write_text(SHIM)
        r = subprocess.run(['bash', str(tmp_path / 'sweep.sbatch')], cwd=tmp_path, capture_output=True, text=True,
                           env=dict(os.environ, SLURM_ARRAY_TASK_ID='6', SLURM_SUBMIT_DIR=str(tmp_path),
                                    RYADE_PYTHON=str(shim)), timeout=60)
        assert r.returncode == 0, r.stdout + r.stderr
        res = json.loads((tmp_path / 'result.l6.json').read_text())
        assert res['env'] == {'YADE_BATCH': 'sweep.table:6', 'OMP_NUM_THREADS': '2', 'FOO': 'y', 'DISPLAY': ''}
        assert (tmp_path / 'sweep.logs' / 'job.a=3,b=pi_2,FOO=y,OMP_NUM_THREADS=2.log').exists()


@pytest.mark.skipif(os.environ.get('RYADE_TEST_REAL_YADE') != '1' or not shutil.which('yade'),
                    reason='opt-in (RYADE_TEST_REAL_YADE=1): runs real YADE, ~3 s')
def test_batch_runs_real_yade(tmp_path):
    """`--command 'yade -n -x'`: our runner drives real YADE and gets what yade-batch got."""
    exp = _EXP['batch']
    for f in ('batchenv.table', 'batchenv.py'):
        shutil.copy(REFDIR / f, tmp_path)
    out = tmp_path / 'out'
    out.mkdir()
    p = _run_batch(tmp_path, *exp['argv'], '--command', 'yade -n -x', env={'PROBE_OUTDIR': str(out)})
    assert p.returncode == 0, p.stdout + p.stderr
    got = {f.stem: json.loads(f.read_text()) for f in sorted(out.glob('*.json'))}
    assert got == exp['jobs']
