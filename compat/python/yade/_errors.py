"""Errors of the compatibility layer: anything ryade does not implement fails loudly, naming what and
where (the user's script file and line), never as a silent no-op."""

import sys

#: Path of the script `compat run` executes (set by yade.runner), used to point at the user's line.
SCRIPT = None


class UnsupportedError(NotImplementedError, AttributeError):
    """A YADE class, function, attribute or keyword that ryade does not implement yet. It is also an
    AttributeError so that `hasattr()` feature tests in scripts answer False instead of crashing."""


def script_location():
    """'(script.py, line N)' for the innermost frame of the user's script, or '' when not running one."""
    f = sys._getframe(1)
    best = None
    while f is not None:
        fn = f.f_code.co_filename
        if SCRIPT is not None and fn == SCRIPT:
            best = f
            break
        if best is None and not fn.startswith(_PKG_DIR) and not fn.startswith('<frozen'):
            best = f
        f = f.f_back
    if best is None:
        return ''
    return '(%s, line %d)' % (best.f_code.co_filename, best.f_lineno)


def unsupported(what, hint=None):
    """Raise UnsupportedError for `what` (e.g. 'class HydroForceEngine', 'NewtonIntegrator.kinSplit')."""
    msg = 'ryade does not support %s yet %s' % (what, script_location())
    if hint:
        msg += ': ' + hint
    e = UnsupportedError(msg.rstrip())
    e.what, e.hint = what, hint
    raise e


def _non_finite(v, path):
    """(path, value) of the first NaN/inf in `v` (a vector of numbers is reported whole)."""
    if isinstance(v, float):
        return None if v == v and v not in (float('inf'), float('-inf')) else (path, v)
    if isinstance(v, dict):
        for k, x in v.items():
            r = _non_finite(x, '%s.%s' % (path, k) if path else str(k))
            if r:
                return r
    elif isinstance(v, (list, tuple)):
        for i, x in enumerate(v):
            r = _non_finite(x, '%s[%d]' % (path, i))
            if r:
                if all(isinstance(y, (int, float)) for y in v):
                    return (path, tuple(v))
                return r
    return None


def bridge_json(obj, what):
    """JSON for the Rust core. JSON has no NaN or infinity: a non-finite number stops here, naming
    `what` (e.g. 'O.bodies.append(body)'), the attribute and its value, instead of a parse error
    about a column of a JSON text the user never wrote."""
    import json
    try:
        return json.dumps(obj, allow_nan=False)
    except ValueError:
        found = _non_finite(obj, '')
        if not found:
            raise
        where = '%s: %s' % (what, found[0]) if found[0] else what
        raise ValueError('%s = %r is not finite; ryade cannot take NaN or infinity into the simulation %s'
                         % (where, found[1], script_location()))


import os as _os  # noqa: E402

_PKG_DIR = _os.path.dirname(_os.path.abspath(__file__))
