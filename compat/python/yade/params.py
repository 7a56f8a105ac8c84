"""Parameter namespaces of a simulation, as in YADE's ``yade.params``.

Initially empty. :func:`yade.utils.saveVars` / :func:`yade.utils.loadVars` (implemented in
``yade._table``) create synthesized sub-modules ``yade.params.<mark>`` and register them in
``sys.modules``, so that both of these work after ``readParamsFromTable(...)``::

    from yade.params.table import *
    from yade.params import table; table.x

This is a plain module, not a package, exactly like YADE's ``py/params.py``: the sub-modules are
never files, they exist only in ``sys.modules`` and as attributes of this module.
"""
# initially empty; yade._table.loadVars appends the marks (and, for loadVars(None), the names)
__all__ = []
