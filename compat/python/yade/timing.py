"""`yade.timing`: ryade does not collect per-engine timings yet; `stats()` says so and reports what it
knows (iterations and wall time) instead of printing an empty table."""

import time as _time

from ._core import Omega

_t0 = _time.time()


def reset():
    global _t0
    _t0 = _time.time()


def stats():
    O = Omega()
    dt = _time.time() - _t0
    print('ryade: per-engine timing is not collected (yade.timing.stats); %d iterations, %.3f s wall time since '
          'the last timing.reset()' % (O.iter, dt))
    for k, e in enumerate(O.engines):
        print('  %2d %s%s' % (k, type(e).__name__, (' (%s)' % e.label) if e.label else ''))


def runtime():
    return _time.time() - _t0
