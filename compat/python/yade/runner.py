"""`compat run script.py [args]`: run an unmodified YADE script as `yade -n -x script.py args` would.

The script runs as `__main__` with YADE's startup namespace (`from yade import *`, `utils`, `pack`,
`geom`, `from yade.utils import *`, `from yade.pack import *`, `from math import *`), `O`/`Omega` in
builtins and the script arguments in `sys.argv`. Anything ryade lacks stops the run with exit code 1
and a message naming it and the script line.
"""

import os
import sys
import traceback
import types


def _namespace(mod):
    import yade
    from yade import geom, pack, utils
    ns = mod.__dict__
    for k in dir(yade):
        if not k.startswith('_'):
            ns[k] = getattr(yade, k)
    ns['utils'], ns['pack'], ns['geom'] = utils, pack, geom
    for m in (utils, pack):
        for k in getattr(m, '__all__', ()):
            ns[k] = getattr(m, k)
    import math
    for k in dir(math):
        if not k.startswith('_'):
            ns[k] = getattr(math, k)
    ns['O'] = yade.O
    # the modules YADE's startup namespace holds (its utils has no __all__, and the yade launcher
    # imports more); gts, mpmath and remote are not provided by ryade
    import argparse, doctest, itertools, json as _json, os as _os, random, time, types as _types, warnings
    ns.update({'math': math, 'random': random, 'argparse': argparse, 'doctest': doctest, 'itertools': itertools,
               'json': _json, 'os': _os, 'sys': sys, 'time': time, 'types': _types, 'warnings': warnings,
               'yade': yade})
    try:
        import numpy
        ns['numpy'] = numpy
    except ImportError:
        pass
    ns['__ryade_script__'] = True


def run(script, args):
    from yade import _errors
    path = os.path.abspath(script)
    if not os.path.isfile(path):
        sys.stderr.write("compat run: no such script: %s\n" % script)
        return 2
    _errors.SCRIPT = path
    sys.argv = [script] + list(args)
    sys.path.insert(0, os.path.dirname(path))
    mod = types.ModuleType('__main__')
    mod.__file__ = path
    mod.__builtins__ = __builtins__
    sys.modules['__main__'] = mod
    _namespace(mod)
    with open(path, 'rb') as f:
        code = compile(f.read(), path, 'exec')
    try:
        exec(code, mod.__dict__)
    except SystemExit as e:
        return e.code if isinstance(e.code, int) else (0 if e.code is None else 1)
    except _errors.UnsupportedError as e:
        sys.stderr.write('compat run: %s\n' % e)
        return 1
    except BaseException:
        traceback.print_exc()
        return 1
    import yade
    if yade.O._background is not None:
        sys.stderr.write('compat run: note: the script started O.run() in the background and ended without '
                         'O.wait(); like `yade -x`, ryade exits without running it (add O.wait()).\n')
    return 0


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if not argv or argv[0] in ('-h', '--help'):
        print(__doc__)
        return 0 if argv else 2
    rc = run(argv[0], argv[1:])
    sys.stdout.flush()
    sys.stderr.flush()
    return rc


if __name__ == '__main__':
    sys.exit(main())
