"""`yade.timing`: the per-engine timing table of YADE (py/timing.py there).

With `O.timingEnabled = True` every engine collects `execTime` (ns of wall time) and `execCount` (runs
in which it was activated). `stats()` prints them as YADE does: one row per engine (its label in
quotes, else its class), the run count, the time in microseconds and the share of the total; under an
engine with checkpoints (`timingDeltas`: NewtonIntegrator, as in Debian's YADE build) one indented row
per checkpoint and their TOTAL; then a TOTAL row for all engines.

Engines run by the Rust core are timed around their own run; Python engines (PyRunner) around their
command. YADE times from the end of the previous activated engine, so there a skipped engine's
activation test is charged to the next engine: nanoseconds per step.
"""

from ._core import Omega

_WIDTHS = (40, 20, 20, 20)
_LEVELS = 3  # YADE pads the number columns for three nesting levels


def reset():
    """Zero every engine's `execTime`, `execCount` and checkpoints."""
    for e in Omega().engines:
        if e.timingDeltas is not None:
            e.timingDeltas.reset()
        e.execTime = 0
        e.execCount = 0


def runtime():
    """Total `execTime` of the engines, in ns (the TOTAL row of `stats()`)."""
    return sum(e.execTime for e in Omega().engines)


def _row(name, count, ns, total, level=0):
    """One line of the table; `count` < 0 leaves the count column empty (TOTAL rows)."""
    cells = (
        str(count) if count >= 0 else '',
        str(ns / 1000) + 'us',
        '%6.2f%%' % (ns * 100. / total) if total > 0 else '',
    )
    pad = ' ' * 2 * (_LEVELS - level)
    return ' '.join([(' ' * 2 * level + name).ljust(_WIDTHS[0])] + [(c + pad).rjust(w) for c, w in zip(cells, _WIDTHS[1:])])


def table():
    """The rows of `stats()` as (level, name, count, ns, ns of the parent), in print order."""
    engines = Omega().engines
    total = sum(e.execTime for e in engines)
    rows = []
    for e in engines:
        rows.append((0, '"%s"' % e.label if e.label else type(e).__name__, e.execCount, e.execTime, total))
        deltas = e.timingDeltas.data if e.timingDeltas is not None else []
        for name, ns, count in deltas:
            rows.append((1, name, count, ns, e.execTime))
        if len(deltas) > 1:
            rows.append((1, 'TOTAL', sum(d[2] for d in deltas), sum(d[1] for d in deltas), e.execTime))
    if len(engines) > 1:
        rows.append((0, 'TOTAL', -1, total, total))
    return rows


def stats():
    """Print the timing table (enable collection first with `O.timingEnabled = True`)."""
    print(' '.join(['Name'.ljust(_WIDTHS[0])] + [h.rjust(w) for h, w in zip(('Count', 'Time', 'Rel. time'), _WIDTHS[1:])]))
    print('-' * (sum(_WIDTHS) + len(_WIDTHS) - 1))
    for level, name, count, ns, parent in table():
        print(_row(name, count, ns, parent, level))
    print()
