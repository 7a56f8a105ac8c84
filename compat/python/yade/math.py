"""`yade.math` of a double-precision YADE (py/high-precision/math.py + `_math`): Real is Python's float.

The elementary functions are the C library's (as `std::cos` etc. in YADE's `_math`), so they give
YADE's bits; `toHP1`/`Real` refuse a float as YADE does (a string or int is fine), `radiansHP1` and
`degreesHP1` keep YADE's order of operations. A name of YADE's module that is not here raises the
"does not support" error.
"""

import math as _m

from ._errors import unsupported as _unsupported

Pi = _m.pi
Euler = 0.57721566490153286061
Log2 = _m.log(2.0)
Catalan = 0.91596559417721901505


class RealHPConfig(object):
    """Precision of the default Real: double (15 decimal digits, 53 bits)."""

    @staticmethod
    def getDigits10(n=1):
        return 15

    @staticmethod
    def getDigits2(n=1):
        return 53

    @staticmethod
    def getSupportedByMinieigen():
        return (1,)


getDigits10 = RealHPConfig.getDigits10
getDigits2 = RealHPConfig.getDigits2


def needsMpmathAtN(N):
    return False


def usesHP():
    return False


def getRealHPCppDigits10():
    return (15,)


def getRealHPPythonDigits10():
    return (15,)


def toHP1(arg):
    """YADE's toHP1: a float is refused (it would cut the digits in a high-precision build)."""
    if type(arg) == float:
        raise RuntimeError("Error: only first 15 digits would be used for arg = " + str(arg) +
                           ", better pass the argument as string or python mpmath high precision type.")
    return float(arg)


Real = toHP1
Real1 = toHP1


class HP1(object):
    toHP1 = staticmethod(toHP1)

    @staticmethod
    def Pi():
        return _m.pi


def radiansHP1(arg):
    return HP1.Pi() * toHP1(arg) / toHP1(180)


def degreesHP1(arg):
    if type(arg) == float:
        return toHP1(180) * arg / HP1.Pi()
    return toHP1(180) * toHP1(arg) / HP1.Pi()


radians = radiansHP1
degrees = degreesHP1


def linspace(a, b, num):
    import numpy
    return numpy.linspace(a, b, num=num)


def eig(a):
    import numpy
    return numpy.linalg.eig(a)


def toDouble(x):
    return float(x)


def toInt(x):
    return int(x)


toLong = toInt
toLongDouble = toDouble

# the C library's functions (YADE's _math wraps std::cos, ... for Real = double)
acos, acosh, asin, asinh, atan, atan2, atanh = _m.acos, _m.acosh, _m.asin, _m.asinh, _m.atan, _m.atan2, _m.atanh
cos, cosh, sin, sinh, tan, tanh = _m.cos, _m.cosh, _m.sin, _m.sinh, _m.tan, _m.tanh
exp, expm1, log, log10, log1p, log2 = _m.exp, _m.expm1, _m.log, _m.log10, _m.log1p, _m.log2
sqrt, pow, hypot, fmod, erf, erfc = _m.sqrt, _m.pow, _m.hypot, _m.fmod, _m.erf, _m.erfc
lgamma, tgamma, ldexp, frexp, modf = _m.lgamma, _m.gamma, _m.ldexp, _m.frexp, _m.modf
isnan, isinf, isfinite = _m.isnan, _m.isinf, _m.isfinite
fabs = _m.fabs


def abs(x):
    return _m.fabs(x)


def ceil(x):
    return float(_m.ceil(x))


def floor(x):
    return float(_m.floor(x))


def trunc(x):
    return float(_m.trunc(x))


def exp2(x):
    return 2.0 ** x


def cbrt(x):
    return _m.copysign(_m.fabs(x) ** (1.0 / 3.0), x) if not hasattr(_m, 'cbrt') else _m.cbrt(x)


def max(a, b):
    return a if a >= b else b


def min(a, b):
    return a if a <= b else b


def sign(x):
    return float((x > 0) - (x < 0))


sgn = sign


def epsilon():
    return 2.220446049250313e-16


def __getattr__(name):
    if name.startswith('__'):
        raise AttributeError(name)
    _unsupported('yade.math.%s' % name)
