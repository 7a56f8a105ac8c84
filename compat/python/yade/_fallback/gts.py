"""`import gts` under `compat run`: ryade's stand-in for PyGTS (yade/_gts.py), one module object."""
import sys

from yade import _gts

sys.modules[__name__] = _gts
