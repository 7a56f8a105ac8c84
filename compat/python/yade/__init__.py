"""`yade`: YADE's Python API over ryade (a Rust reimplementation of YADE's DEM core).

`import yade` gives what YADE's startup gives a script: every YADE class name (implemented ones work,
the others raise UnsupportedError naming the class and script line), the minieigen types, and `O`/`Omega`
in builtins. `compat run script.py` (module `yade.runner`) adds `utils`, `pack`, `geom` and `math` as
YADE's `yade -x` does.
"""

import builtins as _builtins

from . import wrapper as _wrapper
from .minieigen import *  # noqa: F401,F403
from .minieigen import Matrix3, Quaternion, Vector2, Vector3, Vector3i  # noqa: F401

globals().update(_wrapper.all_classes())

from ._core import (Body, Box, Cell, Clump, Facet, GridConnection, GridNode, Interaction, Omega, Shape, Sphere,  # noqa: E402,F401
                    State, Wall)
from ._errors import UnsupportedError  # noqa: E402,F401
from .export import VTKRecorder  # noqa: E402,F401  (a YADE engine class implemented in Python)

O = Omega()
from . import _table as _tbl  # noqa: E402
_tbl.set_omega(O)
_builtins.O = O
_builtins.Omega = Omega

__version__ = '2023.02a-ryade'
version = __version__


def __getattr__(name):
    if name.startswith('__'):
        raise AttributeError(name)
    import importlib
    try:
        return importlib.import_module('yade.' + name)
    except ModuleNotFoundError as e:
        if e.name != 'yade.' + name:
            raise
    from ._errors import unsupported
    unsupported('the module yade.%s' % name)
