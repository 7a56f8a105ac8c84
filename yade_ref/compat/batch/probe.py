# Probe of YADE's readParamsFromTable / TableParamReader, run under real YADE:
#   PROBE_CASE="{'defaults': {...}, 'unknownOk': False}" PROBE_OUT=out.json \
#       YADE_BATCH=tricky.table:5 yade -n -x probe.py
# Writes what YADE produced (return value, O.tags, yade.params.table, the parsed table)
# as JSON to $PROBE_OUT. Driven by gen_expect.py; see README.md.
import ast, json, os, sys
import yade.utils

case = ast.literal_eval(os.environ.get('PROBE_CASE', '{}'))
out = {'env': {k: os.environ.get(k) for k in ('YADE_BATCH', 'OMP_NUM_THREADS', 'FOO', 'BAR', 'DISPLAY')}}
ident = O.tags['id']


def scrub(v):
    return v.replace(ident, '{id}') if isinstance(v, str) else v


table = case.get('table')
if table:
    try:
        pd = yade.utils.TableParamReader(table).paramDict()
        out['paramDict'] = {str(k): v for k, v in sorted(pd.items())}
    except Exception as e:
        out['paramDict_error'] = [type(e).__name__, str(e)]

kw = dict(case.get('defaults', {}))
call = {k: case[k] for k in ('tableFileLine', 'noTableOk', 'unknownOk') if k in case}
try:
    out['return'] = readParamsFromTable(**call, **kw)
except Exception as e:
    out['error'] = [type(e).__name__, str(e)]
out['runningInBatch'] = yade.utils.runningInBatch()
out['tags'] = {k: scrub(O.tags[k]) for k in O.tags.keys()
               if k not in ('author', 'isoTime', 'id') and not k.startswith('pickled')}
try:
    import yade.params.table as T
    out['table_vars'] = {k: [type(getattr(T, k)).__name__, repr(getattr(T, k))] for k in sorted(T.__all__)}
except ImportError as e:
    out['table_vars'] = None
import yade.params
out['params_all'] = list(yade.params.__all__)
with open(os.environ['PROBE_OUT'], 'w') as f:
    json.dump(out, f, indent=1, sort_keys=True)
