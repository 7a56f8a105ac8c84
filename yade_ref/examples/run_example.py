# Run one of YADE's own example scripts unchanged, then dump the final body states with full precision.
#   yade -n -x yade_ref/examples/run_example.py EXAMPLE.py OUT.json [MAXSTEPS]
#   compat run yade_ref/examples/run_example.py EXAMPLE.py OUT.json [MAXSTEPS [EXTRA]]
# Background runs (O.run() without wait) are made synchronous and capped at MAXSTEPS so that both
# engines execute exactly the same steps (YADE's background thread would make the count racy). Under
# headless YADE, `from yade import qt` fails ("Connecting to DISPLAY ... failed"), so a no-op qt
# module is installed first, as ryade's compat layer provides one. A script that leaves the running to
# the GUI (no O.run at all) is stepped MAXSTEPS times after it ends, as a user pressing "play" would.
# EXTRA (the survey, survey.py): EXTRA more steps after the script in every case, and a script that ends
# with sys.exit()/exit() is still dumped (the goldens of list.txt pass no EXTRA and keep the old rules).
import builtins as _rx_builtins, json as _rx_json, os as _rx_os, sys as _rx_sys, types as _rx_types

_rx_example, _rx_out = _rx_sys.argv[1], _rx_sys.argv[2]
_rx_max = int(_rx_sys.argv[3]) if len(_rx_sys.argv) > 3 else 2000
_rx_extra = int(_rx_sys.argv[4]) if len(_rx_sys.argv) > 4 else None
_rx_O = O

try:
    from yade import qt as _rx_qt  # noqa: F401
except ImportError:
    class _RxNoGui(object):
        def __init__(self, *a, **k): pass
        def __getattr__(self, k): return _RxNoGui()
        def __call__(self, *a, **k): return _RxNoGui()
    _rx_stub = _rx_types.ModuleType('yade.qt')
    def _rx_stub_attr(name):
        if name.startswith('__'):  # __file__, __path__...: what inspect.stack() (yade.mpy) asks of every module
            raise AttributeError(name)
        return _RxNoGui()
    _rx_stub.__getattr__ = _rx_stub_attr
    _rx_stub.View = _rx_stub.Controller = _rx_stub.Renderer = _RxNoGui
    _rx_stub.views = lambda: []
    _rx_sys.modules['yade.qt'] = _rx_stub
    import yade as _rx_yade
    _rx_yade.qt = _rx_stub


class _RxSyncO(object):
    """Forwards everything to O, but O.run() runs synchronously for a bounded number of steps."""

    def run(self, nSteps=-1, wait=False):
        _rx_O.run(min(nSteps if nSteps > 0 else _rx_max, _rx_max), True)

    def wait(self):
        pass

    def __getattr__(self, k):
        return getattr(_rx_O, k)

    def __setattr__(self, k, v):
        setattr(_rx_O, k, v)


_rx_builtins.O = O = _RxSyncO()
try:  # ryade's compat layer: point its messages at the example's lines, not at this wrapper's
    from yade import _errors as _rx_errors
    _rx_errors.SCRIPT = _rx_os.path.abspath(_rx_example)
except ImportError:
    pass
_rx_sys.argv = [_rx_example]
try:
    exec(compile(open(_rx_example).read(), _rx_example, 'exec'), globals())
except SystemExit:
    if _rx_extra is None:
        raise
finally:
    _rx_builtins.O = O = _rx_O
if _rx_O.iter == 0 and len(_rx_O.engines) > 0:
    _rx_O.run(_rx_max, True)
if _rx_extra and len(_rx_O.engines) > 0:
    _rx_O.run(_rx_extra, True)


def _rx_v(x):
    return [float(c) for c in x]


_rx_bodies = []
for _rx_b in _rx_O.bodies:
    _rx_s = _rx_b.state
    _rx_q = _rx_s.ori
    _rx_bodies.append({'id': _rx_b.id, 'pos': _rx_v(_rx_s.pos), 'vel': _rx_v(_rx_s.vel), 'angVel': _rx_v(_rx_s.angVel),
                       'ori': [_rx_q[3], _rx_q[0], _rx_q[1], _rx_q[2]]})
_rx_json.dump({'example': _rx_os.path.basename(_rx_example), 'iter': _rx_O.iter, 'time': _rx_O.time, 'bodies': _rx_bodies},
              open(_rx_out, 'w'), indent=0)
print('dumped', len(_rx_bodies), 'bodies at iter', _rx_O.iter)
_rx_sys.stdout.flush()
