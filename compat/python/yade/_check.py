"""`compat run --check script.py`: every YADE name a script can reach that ryade does not provide, found
without running it, so that a long run is refused before its first step instead of dying at its last
line (`compat run` checks first; `--no-check` runs anyway).

A static pass over the script's syntax tree (and over the code strings it gives PyRunner and
PeriTriaxController.doneHook), resolved against the package's own objects and YADE 2023.02a's name
tables (`_yade_classes.json`, `_yade_names.json`, dumped from the installed YADE by
yade_ref/compat/dump_{classes,names}.py). It reports:

* YADE classes ryade lacks, when called (`HydroForceEngine(...)`);
* names of YADE's `yade -x` startup namespace, of a YADE module (`yade.utils.X`, `from yade.pack import
  X`, `import yade.X`) or of `O` and its containers (`O.save`, `O.bodies.erase`) that ryade does not
  have, or has only as a stub that raises;
* constructor keywords of implemented classes that ryade refuses (`NewtonIntegrator(densityScaling=True)`),
  found by building the object from the literal keywords.

Names the script binds itself (assignment, def, import, loop variable...) are its own and never
reported; a name YADE does not know either is a plain NameError/AttributeError in both engines and is
left to Python. Code inside `try:` with a handler that catches the error, and the body of an `if` whose
line carries a `# YADE only` comment (a branch the script takes only in YADE), are reported as guarded
and do not refuse the run. Only what depends on run-time values (an attribute of a body or interaction,
`kineticEnergy(findMaxId=flag)`) is still found when reached.
"""

import ast
import builtins
import inspect
import json
import os
import re
import types

_HERE = os.path.dirname(os.path.abspath(__file__))
#: the comment that marks an `if` branch the script takes in YADE only
_YADE_ONLY = re.compile(r'#.*\byade[- ]only\b', re.IGNORECASE)
_TABLES = None

#: exception names whose handler catches an UnsupportedError (or the NameError of a missing name)
_CATCHING = {'Exception', 'BaseException', 'NotImplementedError', 'AttributeError', 'NameError', 'ImportError',
             'UnsupportedError', 'RuntimeError', 'ModuleNotFoundError'}


def _tables():
    global _TABLES
    if _TABLES is None:
        with open(os.path.join(_HERE, '_yade_names.json')) as f:
            _TABLES = json.load(f)
    return _TABLES


class Finding(object):
    def __init__(self, line, what, hint=None, guarded=False):
        self.line, self.what, self.hint, self.guarded = line, what, hint, guarded

    def message(self, script):
        m = 'ryade does not support %s yet (%s, line %d)' % (self.what, os.path.basename(script), self.line)
        if self.hint:
            m += ': ' + self.hint
        if self.guarded:
            m += ' [guarded by try/except or a `# YADE only` branch: not refused]'
        return m


def _stub_reason(obj):
    """What an object of the package raises UnsupportedError for whenever it is used: a YADE class stub
    (`_ryade_unsupported`), or a function whose body only calls `unsupported(...)`."""
    if isinstance(obj, type):
        return obj.__dict__.get('_ryade_unsupported')
    fn = getattr(obj, '__func__', obj)
    if not isinstance(fn, types.FunctionType):
        return None
    cached = _STUBS.get(fn)
    if cached is not None:
        return cached or None
    reason = ''
    try:
        tree = ast.parse(_dedent(inspect.getsource(fn)))
        body = tree.body[0].body
        if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
            body = body[1:]  # docstring
        if (len(body) == 1 and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Call)
                and isinstance(body[0].value.func, ast.Name) and body[0].value.func.id == 'unsupported'):
            args = body[0].value.args
            if args and isinstance(args[0], ast.Constant):
                reason = args[0].value
            else:
                reason = fn.__qualname__
            if len(args) > 1 and isinstance(args[1], ast.Constant):
                _HINTS[reason] = args[1].value
    except (OSError, TypeError, SyntaxError, IndexError, AttributeError):
        reason = ''
    _STUBS[fn] = reason
    return reason or None


_STUBS = {}
_HINTS = {}


def _dedent(src):
    lines = src.splitlines()
    pad = min((len(l) - len(l.lstrip()) for l in lines if l.strip()), default=0)
    return '\n'.join(l[pad:] for l in lines)


def _literal(node):
    try:
        return True, ast.literal_eval(node)
    except (ValueError, TypeError, SyntaxError, MemoryError, RecursionError):
        return False, None


class _Bound(ast.NodeVisitor):
    """Every name the script binds anywhere (any scope)."""

    def __init__(self):
        self.names = set()

    def visit_Name(self, n):
        if isinstance(n.ctx, (ast.Store, ast.Del)):
            self.names.add(n.id)

    def visit_FunctionDef(self, n):
        self.names.add(n.name)
        a = n.args
        for x in a.posonlyargs + a.args + a.kwonlyargs + ([a.vararg] if a.vararg else []) + ([a.kwarg] if a.kwarg else []):
            self.names.add(x.arg)
        self.generic_visit(n)

    visit_AsyncFunctionDef = visit_FunctionDef

    def visit_Lambda(self, n):
        a = n.args
        for x in a.posonlyargs + a.args + a.kwonlyargs + ([a.vararg] if a.vararg else []) + ([a.kwarg] if a.kwarg else []):
            self.names.add(x.arg)
        self.generic_visit(n)

    def visit_ClassDef(self, n):
        self.names.add(n.name)
        self.generic_visit(n)

    def visit_Import(self, n):
        for a in n.names:
            self.names.add(a.asname or a.name.split('.')[0])

    def visit_ImportFrom(self, n):
        for a in n.names:
            if a.name != '*':
                self.names.add(a.asname or a.name)

    def visit_ExceptHandler(self, n):
        if n.name:
            self.names.add(n.name)
        self.generic_visit(n)

    def visit_Global(self, n):
        self.names.update(n.names)

    visit_Nonlocal = visit_Global

    def visit_MatchAs(self, n):
        if n.name:
            self.names.add(n.name)
        self.generic_visit(n)


class Checker(ast.NodeVisitor):
    def __init__(self, namespace, bound, line0=None, lines=()):
        self.lines = lines             # the script's source lines (for `# YADE only` markers)
        self.ns = namespace            # name -> object: what `compat run` gives the script
        self.bound = bound             # names the script binds itself
        self.line0 = line0             # report every finding at this line (code strings)
        self.aliases = {}              # name -> 'yade.X' for modules imported under a name
        self.star_yade = set()         # names YADE's `from yade.X import *` would add
        self.guard = 0
        self.findings = []
        self._seen = set()

    # ---- reporting
    def add(self, node, what, hint=None):
        hint = hint or _HINTS.get(what)
        line = self.line0 if self.line0 is not None else getattr(node, 'lineno', 0)
        key = (line, what)
        if key in self._seen:
            return
        self._seen.add(key)
        self.findings.append(Finding(line, what, hint, guarded=self.guard > 0))

    # ---- guarded regions
    def _visit_guarded(self, body, guarded, rest):
        """`body` (as guarded code when `guarded`), then `rest`."""
        self.guard += guarded
        for s in body:
            self.visit(s)
        self.guard -= guarded
        for s in rest:
            self.visit(s)

    def visit_Try(self, n):
        catches = any(h.type is None or any(isinstance(t, ast.Name) and t.id in _CATCHING or
                                            isinstance(t, ast.Attribute) and t.attr in _CATCHING
                                            for t in (h.type.elts if isinstance(h.type, ast.Tuple) else [h.type]))
                      for h in n.handlers)
        self._visit_guarded(n.body, catches, n.handlers + n.orelse + n.finalbody)

    visit_TryStar = visit_Try

    def visit_If(self, n):
        line = self.lines[n.lineno - 1] if 0 < n.lineno <= len(self.lines) else ''
        marked = self.line0 is None and bool(_YADE_ONLY.search(line))
        self.visit(n.test)
        self._visit_guarded(n.body, marked, n.orelse)

    # ---- imports
    def _module(self, dotted):
        """The package's module for 'yade.X' (None if ryade has none), without running YADE-only code."""
        import importlib
        try:
            return importlib.import_module(dotted)
        except Exception:
            return None

    def visit_Import(self, n):
        for a in n.names:
            if a.name == 'yade' or a.name.startswith('yade.'):
                parts = a.name.split('.')
                if len(parts) >= 2 and not self._has_module(parts[1]):
                    self.add(n, 'the module yade.%s' % parts[1])
                    continue
                if a.asname:
                    self.aliases[a.asname] = a.name

    def _has_module(self, m):
        return os.path.exists(os.path.join(_HERE, m + '.py')) or m in ('wrapper', 'system', 'config')

    def visit_ImportFrom(self, n):
        mod = n.module or ''
        if n.level or not (mod == 'yade' or mod.startswith('yade.')):
            return
        parts = mod.split('.')
        if len(parts) >= 2 and not self._has_module(parts[1]):
            self.add(n, 'the module yade.%s' % parts[1])
            return
        if len(parts) > 2:
            return
        sub = parts[1] if len(parts) == 2 else None
        for a in n.names:
            if sub is None:
                # from yade import X: a module or a name of the yade package
                if a.name == '*':
                    continue
                if a.name in _tables()['modules'] or self._has_module(a.name):
                    if not self._has_module(a.name):
                        self.add(n, 'the module yade.%s' % a.name)
                    else:
                        self.aliases[a.asname or a.name] = 'yade.' + a.name
                    continue
                self._check_member(n, 'yade', a.name)
            else:
                if a.name == '*':
                    self.star_yade.update(_tables()['modules'].get(sub, {}).get('names', ()))
                    m = self._module('yade.' + sub)
                    if m is not None:
                        for k in getattr(m, '__all__', [k for k in dir(m) if not k.startswith('_')]):
                            self.ns.setdefault(k, getattr(m, k, None))
                    continue
                self._check_member(n, 'yade.' + sub, a.name)

    def _member(self, node, obj, name, table, label):
        """`obj`'s attribute `name` without running it; when it has none, `label` is reported if YADE's
        `table` has the name, and _MISSING returned."""
        try:
            return inspect.getattr_static(obj, name)
        except AttributeError:
            if name in table:
                self.add(node, label)
            return _MISSING

    def _check_member(self, node, dotted, name, called=False):
        """`name` of YADE's module `dotted` ('yade' or 'yade.X'); a class stub counts when `called`.
        (yade's own names are the classes and modules, handled elsewhere.)"""
        m = self._module(dotted)
        if m is None:
            return
        table = () if dotted == 'yade' else _tables()['modules'].get(dotted.split('.', 1)[1], {}).get('names', ())
        obj = self._member(node, m, name, table, '%s.%s' % (dotted, name))
        if obj is not _MISSING:
            self._report_obj(node, obj, called)

    # ---- names and attribute chains
    def _chain(self, node):
        """['O', 'bodies', 'erase'] for O.bodies.erase; Omega() counts as O; None if not a plain chain."""
        parts = []
        while isinstance(node, ast.Attribute):
            parts.append(node.attr)
            node = node.value
        if isinstance(node, ast.Name):
            parts.append(node.id)
        elif (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == 'Omega'
              and not node.args and 'Omega' not in self.bound):
            parts.append('O')
        else:
            return None
        return parts[::-1]

    def _resolve(self, node, chain, called):
        first = chain[0]
        if first in self.aliases:
            dotted = self.aliases[first]
            if len(chain) >= 2:
                self._attr_of_module(node, dotted, chain[1:], called)
            return
        if first in self.bound:
            return
        if first in self.ns:
            obj = self.ns[first]
        else:
            if hasattr(builtins, first):
                return
            if first in _tables()['namespace'] or first in self.star_yade:
                self.add(node, "the name '%s' of YADE's script namespace" % first)
            return
        if isinstance(obj, types.ModuleType) and obj.__name__.startswith('yade'):
            if len(chain) >= 2:
                self._attr_of_module(node, obj.__name__, chain[1:], called)
            return
        if first in ('O', 'Omega') and len(chain) >= 2:
            self._attr_of_omega(node, chain[1:], called)
            return
        if len(chain) == 1:
            self._report_obj(node, obj, called)

    def _report_obj(self, node, obj, called):
        r = _stub_reason(obj)
        if r and (called or not isinstance(obj, type)):
            self.add(node, r)

    def _attr_of_module(self, node, dotted, rest, called):
        if dotted == 'yade' and rest:
            if rest[0] in _tables()['modules'] or self._has_module(rest[0]):
                if not self._has_module(rest[0]):
                    self.add(node, 'the module yade.%s' % rest[0])
                    return
                if len(rest) >= 2:
                    self._attr_of_module(node, 'yade.' + rest[0], rest[1:], called)
                return
        if len(rest) != 1:
            return
        self._check_member(node, dotted, rest[0], called)

    _OMEGA_TABLES = {(): 'O', ('bodies',): 'O.bodies', ('interactions',): 'O.interactions', ('forces',): 'O.forces',
                     ('materials',): 'O.materials', ('cell',): 'O.cell', ('energy',): 'O.energy', ('tags',): 'O.tags'}

    def _attr_of_omega(self, node, rest, called):
        O = self.ns.get('O')
        if O is None:
            return
        obj = O
        for k, name in enumerate(rest):
            key = self._OMEGA_TABLES.get(tuple(rest[:k]))
            if key is None:
                return
            nxt = self._member(node, obj, name, _tables()['objects'].get(key, ()), '%s.%s' % (key, name))
            if nxt is _MISSING:
                return
            r = _stub_reason(nxt)
            if r:
                self.add(node, r)
                return
            if isinstance(nxt, property):
                return
            obj = nxt

    def visit_Name(self, n):
        if isinstance(n.ctx, ast.Load):
            self._resolve(n, [n.id], called=False)

    def visit_Attribute(self, n):
        chain = self._chain(n)
        if chain is not None and isinstance(n.ctx, ast.Load):
            self._resolve(n, chain, called=False)
            return  # the prefixes are the same chain's, checked by _resolve
        self.generic_visit(n)

    def visit_Call(self, n):
        chain = self._chain(n.func)
        if chain is not None:
            self._resolve(n, chain, called=True)
            self._check_ctor(n, chain)
        else:
            self.visit(n.func)
        for a in n.args:
            self.visit(a)
        for k in n.keywords:
            self.visit(k.value)

    def _check_ctor(self, n, chain):
        """A call of a class ryade implements: the literal keywords it refuses, and code strings."""
        if len(chain) != 1 or chain[0] in self.bound:
            return
        cls = self.ns.get(chain[0])
        if not isinstance(cls, type) or _stub_reason(cls):
            return
        from . import wrapper
        from ._errors import UnsupportedError
        if not issubclass(cls, wrapper.Serializable) or cls.__module__ not in ('yade.wrapper', 'yade.export'):
            return
        # code strings run later in the script's globals
        if issubclass(cls, wrapper.PyRunner):
            for a in n.args:
                ok, v = _literal(a)
                if ok and isinstance(v, str):
                    self._code_string(n, v)
            for k in n.keywords:
                if k.arg == 'command':
                    ok, v = _literal(k.value)
                    if ok and isinstance(v, str):
                        self._code_string(n, v)
        for k in n.keywords:
            if k.arg == 'doneHook':
                ok, v = _literal(k.value)
                if ok and isinstance(v, str):
                    self._code_string(n, v)
        try:
            obj = cls.__new__(cls)
            wrapper.Serializable.__init__(obj)
        except Exception:
            return
        for k in n.keywords:
            if k.arg is None:
                continue
            ok, v = _literal(k.value)
            try:
                if ok:
                    setattr(obj, k.arg, v)
                elif k.arg not in obj._all_attrs() and not isinstance(getattr(cls, k.arg, None), property):
                    obj._missing(k.arg)
            except UnsupportedError as e:
                self.add(n, getattr(e, 'what', '%s(%s=...)' % (cls.__name__, k.arg)), getattr(e, 'hint', None))
            except Exception:
                pass
        if isinstance(obj, (wrapper.Engine, wrapper.Functor)) and not n.args:
            try:
                obj._json()
            except UnsupportedError as e:
                self.add(n, getattr(e, 'what', cls.__name__), getattr(e, 'hint', None))
            except Exception:
                pass

    def _code_string(self, node, code):
        try:
            tree = ast.parse(code)
        except SyntaxError:
            return
        sub = Checker(self.ns, self.bound, line0=self.line0 if self.line0 is not None else node.lineno)
        sub.aliases, sub.star_yade, sub.guard = self.aliases, self.star_yade, self.guard
        sub.visit(tree)
        for f in sub.findings:
            if (f.line, f.what) not in self._seen:
                self._seen.add((f.line, f.what))
                self.findings.append(f)


_MISSING = object()


def namespace():
    """The names `compat run` gives a script (yade.runner's startup namespace)."""
    from . import runner
    mod = types.ModuleType('__ryade_check__')
    runner._namespace(mod)
    return dict(mod.__dict__)


def check_source(src, filename='<script>'):
    """Findings (sorted by line) for the script source `src`; SyntaxError propagates."""
    tree = ast.parse(src, filename)
    b = _Bound()
    b.visit(tree)
    text = src.decode('utf-8', 'replace') if isinstance(src, bytes) else src
    c = Checker(namespace(), b.names, lines=text.splitlines())
    c.visit(tree)
    return sorted(c.findings, key=lambda f: (f.line, f.what))


def yade_name(name):
    """What YADE calls `name` when a script that uses it is stopped by a NameError: "the name 'X' of
    YADE's script namespace", 'yade.M.X' for a public name of YADE's module M (e.g. one `from yade.M
    import *` brings), 'class X'; None for a name YADE does not define either (a plain NameError)."""
    t = _tables()
    if name in t['namespace']:
        return "the name '%s' of YADE's script namespace" % name
    for m in sorted(t['modules']):
        if name in t['modules'][m].get('names', ()):
            return 'yade.%s.%s' % (m, name)
    from . import wrapper
    if name in wrapper.YADE_CLASSES:
        return 'class %s' % name
    return None


def check_file(path):
    with open(path, 'rb') as f:
        return check_source(f.read(), path)
