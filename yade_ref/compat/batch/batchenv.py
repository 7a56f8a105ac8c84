# Run by real yade-batch (gen_expect.py): record the job environment and the tags.
import json, os
n = readParamsFromTable(a=0, b='none')
from yade.params.table import *
ident = O.tags['id']
rec = {'env': {k: os.environ.get(k) for k in ('YADE_BATCH', 'OMP_NUM_THREADS', 'DISPLAY')},
       'return': n, 'a': a, 'b': b,
       'tags': {k: O.tags[k].replace(ident, '{id}') for k in O.tags.keys()
                if k not in ('author', 'isoTime', 'id') and not k.startswith('pickled')}}
with open(os.path.join(os.environ['PROBE_OUTDIR'], O.tags['line'] + '.json'), 'w') as f:
    json.dump(rec, f, indent=1, sort_keys=True)
