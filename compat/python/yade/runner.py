"""usage: compat run [-j N] [--check | --no-check] SCRIPT.py [ARGS...]

Run an unmodified YADE script as `yade -n -x SCRIPT.py ARGS` would (headless).

The script runs as `__main__` with YADE's startup namespace (`from yade import *`, `utils`, `pack`,
`geom`, `from yade.utils import *`, `from yade.pack import *`, `from math import *`), `O`/`Omega` in
builtins and ARGS in `sys.argv`.

Before the first line runs, the script is checked for YADE names ryade does not provide (classes,
functions, O's methods, refused keywords; also in PyRunner command strings): if it uses any, every one
is listed with its line and the run is refused with exit code 1, so that a long run cannot die at its
last line. Anything the check cannot see (it depends on run-time values) still stops the run with exit
code 1 and a message naming it and the script line when it is reached.

  --check      only check: list what ryade lacks, run nothing (exit 0: nothing found, 1: found)
  --no-check   run without checking first (stops at the first unsupported name it reaches)
  -j N         threads (as `yade -jN`; the results have the same bits for any N)
"""

import os
import sys
import traceback
import types


def execfile(filename, globals=None, locals=None):
    """YADE's `execfile` (its startup takes it from `past.builtins`): run the Python file `filename` in
    the caller's globals and locals, or in the given ones (locals default to globals)."""
    if globals is None:
        caller = sys._getframe(1)
        globals, locals = caller.f_globals, caller.f_locals
    elif locals is None:
        locals = globals
    with open(filename, 'rb') as f:
        code = compile(f.read(), filename, 'exec')
    exec(code, globals, locals)


def name_error_message(e):
    """For a NameError on a name YADE defines (its script namespace, its modules, its classes): the
    compat layer's 'ryade does not support X yet (script, line N)', at the innermost line outside this
    package; None for a name YADE lacks too (Python's own NameError stands)."""
    from yade import _check, _errors
    name = getattr(e, 'name', None)
    what = _check.yade_name(name) if name else None
    if what is None:
        return None
    where = ''
    for fr in traceback.extract_tb(e.__traceback__):
        if not os.path.abspath(fr.filename).startswith(_errors._PKG_DIR + os.sep):
            where = ' (%s, line %d)' % (fr.filename, fr.lineno)
    return 'ryade does not support %s yet%s' % (what, where)


def _namespace(mod, script=None, args=()):
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
    ns['execfile'] = execfile
    # the modules YADE's startup namespace holds (its utils has no __all__, and the yade launcher
    # imports more); gts is ryade's stand-in for PyGTS (yade/_gts.py); mpmath and remote are not provided
    ns['gts'] = pack._gts()
    import argparse, doctest, itertools, json as _json, os as _os, random, time, types as _types, warnings
    ns.update({'math': math, 'random': random, 'argparse': argparse, 'doctest': doctest, 'itertools': itertools,
               'json': _json, 'os': _os, 'sys': sys, 'time': time, 'types': _types, 'warnings': warnings,
               'yade': yade})
    try:
        import numpy
        ns['numpy'] = numpy
    except ImportError:
        pass
    # YADE's parsed command line (`yade -n -x SCRIPT ARGS`), which its scripts read as `opts`
    ns['opts'] = argparse.Namespace(
        version=False, threads=None, cores=None, updateScripts=None, nice=None, exitAfter=True, verbosity=None,
        nogui=True, test=False, check=False, checkall=False, performance=False, quickperformance=False,
        stdperformance=None, script=script, args=([script] if script else []) + list(args), impLibraries=None,
        mpi_mode=False)
    ns['__ryade_script__'] = True


def check(path, script, show_guarded):
    """List the script's unsupported names on stderr (the guarded ones only if `show_guarded`); the
    number of those that refuse the run (not inside a try/except or a `# YADE only` branch)."""
    from yade import _check
    try:
        findings = _check.check_file(path)
    except SyntaxError:
        return 0  # Python reports it, with its line, when the script is compiled
    for f in findings:
        if show_guarded or not f.guarded:
            sys.stderr.write('compat run: %s\n' % f.message(script))
    return sum(1 for f in findings if not f.guarded)


def run(script, args, mode='check'):
    from yade import _errors
    path = os.path.abspath(script)
    if not os.path.isfile(path):
        sys.stderr.write("compat run: no such script: %s\n" % script)
        return 2
    if mode in ('check', 'only'):
        bad = check(path, script, show_guarded=(mode == 'only'))
        if mode == 'only':
            if not bad:
                sys.stderr.write('compat run --check: nothing in %s refuses the run (the static check sees names, '
                                 'not run-time values)\n' % script)
            else:
                sys.stderr.write('compat run --check: %d unsupported name(s) in %s\n' % (bad, script))
            return 1 if bad else 0
        if bad:
            sys.stderr.write('compat run: refused before the first step: %s uses %d name(s) ryade does not support '
                             '(listed above); `compat run --no-check` runs it anyway, until the first of them\n'
                             % (script, bad))
            return 1
    _errors.SCRIPT = path
    sys.argv = [script] + list(args)
    sys.path.insert(0, os.path.dirname(path))
    # YADE's yade/__init__.py puts its package folder on sys.path (index 2), so that scripts import its
    # modules without the prefix (`from bf import evalClump`)
    sys.path.insert(2, os.path.dirname(os.path.abspath(__file__)))
    # stand-ins for `past`/`future` (YADE's Python has python3-future), after everything installed
    sys.path.append(os.path.join(os.path.dirname(os.path.abspath(__file__)), '_fallback'))
    mod = types.ModuleType('__main__')
    mod.__file__ = path
    mod.__builtins__ = __builtins__
    sys.modules['__main__'] = mod
    _namespace(mod, path, args)
    with open(path, 'rb') as f:
        code = compile(f.read(), path, 'exec')
    import signal
    stop = ['SIGINT', 2]

    def on_stop(signum, frame):
        stop[:] = [signal.Signals(signum).name, signum]
        raise KeyboardInterrupt
    for sig in (signal.SIGTERM, signal.SIGHUP):
        signal.signal(sig, on_stop)
    try:
        exec(code, mod.__dict__)
    except KeyboardInterrupt:
        import yade
        sys.stderr.write('compat run: stopped by %s at iteration %d; what %s wrote so far is kept\n'
                         % (stop[0], yade.O.iter, script))
        return 128 + stop[1]
    except SystemExit as e:
        return e.code if isinstance(e.code, int) else (0 if e.code is None else 1)
    except _errors.UnsupportedError as e:
        sys.stderr.write('compat run: %s\n' % e)
        return 1
    except NameError as e:
        msg = name_error_message(e)
        if msg is None:
            traceback.print_exc()
        else:
            sys.stderr.write('compat run: %s\n' % msg)
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
    argv = list(sys.argv[1:] if argv is None else argv)
    mode = 'check'
    while argv and argv[0] in ('--check', '--no-check'):
        mode = 'only' if argv.pop(0) == '--check' else 'none'
    if not argv or argv[0] in ('-h', '--help'):
        print(__doc__)
        return 0 if argv else 2
    rc = run(argv[0], argv[1:], mode)
    sys.stdout.flush()
    sys.stderr.flush()
    return rc


if __name__ == '__main__':
    sys.exit(main())
