"""Stand-in for `past.builtins`: the Python 2 builtins YADE's examples use, on Python 3."""
import functools

from yade.runner import execfile  # noqa: F401  (YADE's execfile: the caller's globals by default)

basestring = str
unicode = str
long = int
xrange = range
raw_input = input
unichr = chr
reduce = functools.reduce
