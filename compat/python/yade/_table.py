"""yade-batch parameter tables and ``readParamsFromTable``, with YADE 2023.02a's semantics.

Public pieces (``yade.utils`` re-exports the YADE names):

* :func:`parse_table` / :class:`ParamTable`: parse a table file (used by ``yade.batch`` too).
* :class:`TableParamReader`: YADE's class (``TableParamReader(file).paramDict()``).
* :func:`readParamsFromTable`, :func:`runningInBatch`, :func:`waitIfBatch`,
  :func:`saveVars`, :func:`loadVars`: YADE's functions of the same names.
* :func:`set_omega`: the package registers its ``O`` here; tags are written to ``O.tags``.

Table format (what YADE's ``TableParamReader`` does, checked against real YADE, see
``yade_ref/compat/batch/``):

* ``#`` starts a comment anywhere on a line (no quoting: ``'a#b'`` is cut at ``#``). Blank and
  comment-only lines are ignored but counted: a job's line number is the 1-based line number of
  the file, as a text editor shows it.
* The first non-blank line holds the column names; cells are separated by runs of blanks/tabs,
  there is no quoting (a cell cannot contain blanks).
* ``=`` as a cell repeats the value of the same column on the previous data line (recursively).
* ``*`` as a cell means "the script's default" (resolved by ``readParamsFromTable``).
* Columns whose name starts with ``!`` (``!OMP_NUM_THREADS``, ``!FOO``) are not parameters:
  ``readParamsFromTable`` skips them, ``yade-batch`` turns them into job settings / env vars.
* If there is no ``description`` column, one is synthesized for each line as
  ``name=value,name=value,...`` over the columns whose name *ends* in ``!`` (the ``!`` removed
  from the column name), or over all columns if none ends in ``!``; every ``!`` is removed from
  the names and every ``'`` and ``"`` from the whole string (``!FOO`` gives ``FOO=...``).
  A description equal to an earlier line's gets ``__line=N__`` appended. Only when the table has
  no ``description`` column are the trailing ``!`` stripped from column names (YADE quirk: with a
  description column, a column ``y!`` is a parameter named ``y!``).

Deliberate differences from YADE (which crashes or silently misreads in these cases):

* A data line with a different number of cells than the header, ``=`` on the first data line
  (YADE takes the value from the *last* data line), duplicate column names (YADE keeps the last),
  an empty table: :class:`TableError` naming file and line.
* A last line without a newline is read as written (YADE drops its last character).
* ``*`` yields the default unchanged; YADE ``eval()``s the default first, which raises TypeError
  for any non-string default (the value YADE finally assigns is the unchanged default too).
* ``file:line`` is split at the last ``:`` (YADE: the first), so paths may contain ``:``.
"""
import math
import os
import pickle
import re
import sys
import time
import types
import warnings

__all__ = ['TableError', 'ParamTable', 'parse_table', 'TableParamReader', 'readParamsFromTable',
           'runningInBatch', 'waitIfBatch', 'saveVars', 'loadVars', 'set_omega', 'split_table_line']

_COMMENT = re.compile(r'\s*#.*')


class TableError(ValueError):
    """A malformed parameter table; ``str()`` starts with ``file:line:``."""

    def __init__(self, path, line, msg):
        self.path, self.line, self.msg = path, line, msg
        super().__init__('%s:%s: %s' % (path, line if line is not None else '?', msg))


class ParamTable:
    """A parsed table. ``rows`` maps line number -> {column: cell text} in column order, with the
    ``=`` resolved and ``description`` (given or synthesized) as the last key if synthesized.
    ``columns`` are the column names as keys of ``rows`` (trailing ``!`` removed when the
    description was synthesized); ``header_line`` is the line number of the header."""

    def __init__(self, path, header_line, columns, rows, has_description):
        self.path, self.header_line, self.columns = path, header_line, columns
        self.rows, self.has_description = rows, has_description

    @property
    def lines(self):
        return list(self.rows)

    def params(self, line):
        "Parameter columns of a line (no ``description``, no ``!`` columns)."
        return {k: v for k, v in self.rows[line].items() if k != 'description' and not k.startswith('!')}

    def env_columns(self, line):
        "The ``!`` columns of a line, names without the leading ``!``."
        return {k[1:]: v for k, v in self.rows[line].items() if k.startswith('!')}

    def description(self, line):
        return self.rows[line]['description']

    def paramDict(self):
        return {l: dict(v) for l, v in self.rows.items()}


def _read_lines(path):
    with open(path, 'r', encoding='utf-8', errors='surrogateescape') as f:
        raw = f.readlines()
    return [l[:-1] if l.endswith('\n') else l for l in raw]


def parse_table(path):
    """Parse a yade-batch parameter table; see the module docstring for the format."""
    try:
        lines = _read_lines(path)
    except OSError as e:
        raise TableError(path, None, 'cannot read table: %s' % e) from e
    usable = []  # (line number, cells)
    for i, text in enumerate(lines, start=1):
        text = _COMMENT.sub('', text)
        if text.strip():
            usable.append((i, text.split()))
    if not usable:
        raise TableError(path, len(lines) or 1, 'table has no header line (only blank lines and comments)')
    header_line, headings = usable[0]
    has_description = 'description' in headings
    if has_description:
        names, desc_heads = list(headings), None
    else:
        desc_heads = [h[:-1] for h in headings if h.endswith('!')] or list(headings)
        names = [h[:-1] if h.endswith('!') else h for h in headings]
    seen = {}
    for h, n in zip(headings, names):
        if n in ('', '!'):
            raise TableError(path, header_line, 'invalid column name %r' % h)
        if n in seen:
            raise TableError(path, header_line, 'duplicate column name %r (columns %r and %r)' % (n, seen[n], h))
        seen[n] = h
    if not usable[1:]:
        raise TableError(path, header_line, 'table has a header but no data lines')
    rows = {}
    prev = None
    for lineno, cells in usable[1:]:
        if len(cells) != len(names):
            raise TableError(path, lineno, 'expected %d cells (columns: %s), found %d: %s' %
                             (len(names), ' '.join(headings), len(cells), ' '.join(cells)))
        row = {}
        for n, c in zip(names, cells):
            if c == '=':
                if prev is None:
                    raise TableError(path, lineno, "'=' in column %r on the first data line: there is no "
                                     "previous line to copy the value from" % n)
                c = prev[n]
            row[n] = c
        rows[lineno] = row
        prev = row
    if not has_description:
        descs = set()
        for lineno, row in rows.items():
            dd = ','.join(h.replace('!', '') + '=' + row[h] for h in desc_heads)
            dd = dd.replace("'", '').replace('"', '')
            if dd in descs:
                dd += '__line=%d__' % lineno
            row['description'] = dd
            descs.add(dd)
    return ParamTable(path, header_line, names, rows, has_description)


class TableParamReader:
    """YADE's reader: ``TableParamReader(file).paramDict()`` maps line numbers to
    ``{column: cell text}`` with ``=`` resolved, trailing ``!`` stripped from column names (only
    when the description is synthesized) and ``description`` present."""

    def __init__(self, file):
        self.table = parse_table(file)
        self.values = self.table.paramDict()

    def paramDict(self):
        return self.values


# ---------------------------------------------------------------- Omega hook

_O = None


class _FallbackOmega:
    "Used only when no O was registered with set_omega and yade.O does not exist."

    def __init__(self):
        self.tags = {}

    def wait(self):
        pass


_fallback = None


def set_omega(O):
    """Register the package's ``O``; ``O.tags`` must be a mutable str -> str mapping."""
    global _O
    _O = O


def _omega():
    global _fallback
    if _O is not None:
        return _O
    mod = sys.modules.get('yade')
    O = getattr(mod, 'O', None) if mod is not None else None
    if O is not None and hasattr(O, 'tags'):
        return O
    if _fallback is None:
        _fallback = _FallbackOmega()
    return _fallback


def _ensure_id(tags):
    "YADE's O.tags['id'] is date, time and pid, like 20100413T144723p7625."
    try:
        return tags['id']
    except KeyError:
        ident = time.strftime('%Y%m%dT%H%M%S') + 'p%d' % os.getpid()
        tags['id'] = ident
        return ident


# ---------------------------------------------------------------- batch API

def runningInBatch():
    "Tell whether we are running inside the batch (``YADE_BATCH`` defined, even if empty)."
    return 'YADE_BATCH' in os.environ


def waitIfBatch():
    "``O.wait()`` if running inside a batch, so that the script does not end prematurely."
    if runningInBatch():
        wait = getattr(_omega(), 'wait', None)
        if wait is not None:
            wait()


def split_table_line(spec):
    "``'file.table:4'`` -> ``('file.table', 4)``; the split is at the last ``:``."
    path, sep, line = str(spec).rpartition(':')
    try:
        if not sep or not path:
            raise ValueError
        return path, int(line)
    except ValueError:
        raise ValueError("table line spec %r is not of the form 'FILE:LINE' (as in YADE_BATCH=file.table:4)"
                         % (spec,)) from None


def readParamsFromTable(tableFileLine=None, noTableOk=True, unknownOk=False, **kw):
    """Read parameters from the table line named by *tableFileLine* (``'file:line'``) or, if not
    given, by the ``YADE_BATCH`` environment variable; the other keyword arguments are the
    parameters' default values. Evaluates each cell with the ``math`` module in scope and puts
    every parameter (table values and defaults) into ``yade.params.table``.

    Tags set on ``O.tags``: ``line`` (``'l<line>'``, or ``'l!'`` without a table),
    ``description``, ``id.d`` (id + '.' + description), ``d.id`` (description + '.' + id),
    ``params`` (``'name=cell,...'``, table columns in table order) and ``defaultParams``
    (``'name=default,...'`` for the parameters left at their defaults).

    :param bool noTableOk: if False, raise EnvironmentError when there is no table.
    :param bool unknownOk: accept table columns that have no default (else NameError).
    :return: the number of parameters assigned from the table.
    """
    O = _omega()
    tags = O.tags
    tagsParams = []
    dictParams, dictDefaults = {}, {}
    if not tableFileLine and os.environ.get('YADE_BATCH', '') == '':
        if not noTableOk:
            raise EnvironmentError("YADE_BATCH is not defined in the environment")
        tags['line'] = 'l!'
    else:
        if not tableFileLine:
            tableFileLine = os.environ['YADE_BATCH']
        tableFile, tableLine = split_table_line(tableFileLine)
        table = parse_table(tableFile)
        if tableLine not in table.rows:
            raise RuntimeError("Table %s doesn't contain valid line number %d" % (tableFile, tableLine))
        vv = dict(table.rows[tableLine])
        ident = _ensure_id(tags)
        tags['line'] = 'l%d' % tableLine
        tags['description'] = vv['description']
        tags['id.d'] = ident + '.' + vv['description']
        tags['d.id'] = vv['description'] + '.' + ident
        for col, cell in vv.items():
            if col == 'description' or col.startswith('!'):
                continue
            if col not in kw and not unknownOk:
                raise NameError("Parameter `%s' has no default value assigned" % col)
            if cell == '*':
                if col not in kw:
                    raise KeyError("%s:%d: column %r is '*' (use the default) but no default was given"
                                   % (tableFile, tableLine, col))
                # YADE leaves the parameter in the defaults too (it shows in both tags)
                tagsParams.append('%s=%s' % (col, kw[col]))
                dictParams[col] = kw[col]
                continue
            kw.pop(col, None)
            tagsParams.append('%s=%s' % (col, cell))
            try:
                dictParams[col] = eval(cell, dict(vars(math)))
            except Exception as e:
                e.add_note('while evaluating column %r = %r of %s:%d' % (col, cell, tableFile, tableLine))
                raise
    defaults = []
    for k, v in kw.items():
        dictDefaults[k] = v
        defaults.append('%s=%s' % (k, v))
    tags['defaultParams'] = ','.join(defaults)
    tags['params'] = ','.join(tagsParams)
    dictParams.update(dictDefaults)
    saveVars('table', loadNow=True, **dictParams)
    return len(tagsParams)


# ---------------------------------------------------------------- saveVars / loadVars

_TAG = 'pickledPythonVariablesDictionary'
_unpicklable = {}  # mark -> dict, for values that cannot be pickled into O.tags


def _stored(tags, mark):
    if mark in _unpicklable and (_TAG + mark) not in _tag_keys(tags):
        return dict(_unpicklable[mark])
    return pickle.loads(tags[_TAG + mark].encode('latin-1'))


def _tag_keys(tags):
    try:
        return list(tags.keys())
    except Exception:
        return []


def saveVars(mark='', loadNow=True, **kw):
    """Save variables into ``O.tags`` (pickled) so that they are saved with the simulation;
    merged with those already saved under *mark*. With *loadNow*, :func:`loadVars` them into
    ``yade.params.<mark>``."""
    tags = _omega().tags
    try:
        d = _stored(tags, mark)
        d.update(kw)
    except KeyError:
        d = dict(kw)
    try:
        tags[_TAG + mark] = pickle.dumps(d, 0).decode('latin-1')
        _unpicklable.pop(mark, None)
    except Exception:
        # values our O cannot pickle (native objects): keep them in memory instead
        _unpicklable[mark] = d
        try:
            del tags[_TAG + mark]
        except Exception:
            pass
    if loadNow:
        _load_one(d, mark)


def _load_one(d, mark):
    from . import params
    if mark:
        if mark in params.__dict__:
            warnings.warn('Overwriting yade.params.%s which already exists.' % mark)
        modName = params.__name__ + '.' + mark
        mod = types.ModuleType(modName)
        mod.__dict__.update(d)
        mod.__all__ = list(d.keys())  # so that names starting with _ are imported by *
        sys.modules[modName] = mod
        params.__all__.append(mark)
        setattr(params, mark, mod)
    else:
        params.__all__ += list(d.keys())
        params.__dict__.update(d)


def loadVars(mark=None):
    """Load variables saved by :func:`saveVars` into ``yade.params.<mark>`` (or, for the empty
    mark, into ``yade.params``); ``mark=None`` loads every saved set."""
    tags = _omega().tags
    if mark is not None:
        _load_one(_stored(tags, mark), mark)
    else:
        marks = [k[len(_TAG):] for k in _tag_keys(tags) if k.startswith(_TAG)]
        marks += [m for m in _unpicklable if m not in marks]
        for m in marks:
            _load_one(_stored(tags, m), m)
