# Run a script unchanged with O.timingEnabled = True and write the engines' timings (YADE's
# Engine.execTime / execCount / timingDeltas) to a JSON file when the script ends:
#   yade -n -x yade_ref/bench/timed_run.py TIMINGS.json SCRIPT [ARGS...]
#   compat run yade_ref/bench/timed_run.py TIMINGS.json SCRIPT [ARGS...]
# `compat bench` uses it for the per-engine breakdown of script scenes, both engines side by side.
# The timings are those of the engine list in place at the end (a script that replaces O.engines
# keeps only its last list's numbers), summed over every step that list ran.
import atexit, json, sys

out, script = sys.argv[1], sys.argv[2]
sys.argv = [script] + sys.argv[3:]
O.timingEnabled = True


def _dump():
    rows = []
    for e in O.engines:
        d = e.timingDeltas
        rows.append({'engine': e.label or e.__class__.__name__, 'class': e.__class__.__name__, 'count': int(e.execCount),
                     'ns': int(e.execTime), 'deltas': [[str(x[0]), int(x[1]), int(x[2])] for x in d.data] if d else []})
    with open(out, 'w') as f:
        json.dump({'iter': O.iter, 'engines': rows}, f, indent=1)


atexit.register(_dump)
g = globals()
g['__file__'] = script
with open(script) as f:
    code = compile(f.read(), script, 'exec')
exec(code, g)
