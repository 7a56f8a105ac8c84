"""Pure-Python replacement for YADE's ``minieigen`` / ``yade.minieigenHP`` types.

The classes reproduce what YADE 2023.02a (minieigen over Eigen 3.4, double
precision, no FMA, no vectorisation) does, including

* the repr format (``Vector3(1,2,3)``, 19 significant digits for non-integral
  values, ``Quaternion((axis),angle)``, ``Matrix6(\\n\\t(...),...)``);
* the floating-point evaluation order of Eigen's unrolled reductions
  (``a0 + (a1 + a2)`` for three terms, ``(a0 + a1) + (a2 + a3)`` for four,
  recursive halving in general), so that e.g. ``v.norm()`` is bit-identical;
* the quirks of minieigen: negative indices raise ``IndexError``, division by
  zero gives ``inf``/``nan`` instead of raising, ``a += b`` (and ``-=``, ``*=``,
  ``/=``) modifies the object in place, so aliases see the change, but rebinds
  ``a`` to a new equal object (``a is alias`` is False afterwards, as in YADE);
  ``Vector3.Zero`` & co. are fresh objects on every access; tuples/lists are
  accepted wherever a vector (or a Matrix3: 9 numbers or 3 rows) is expected;
  wrong argument types raise ``ArgumentError`` (a ``TypeError`` subclass, as
  Boost.Python's); ``vector * matrix`` computes ``matrix * vector``;
  ``Quaternion(axis, angle)`` normalises the quaternion (not the axis); the
  repr of a quaternion is its angle-axis form computed as Eigen does.

Not provided (the error a script gets): ``VectorX``/``MatrixX``/complex types,
``AlignedBox*``, ``Vector*.pruned()`` (crashes YADE with an Eigen assertion)
and ``Quaternion - Quaternion`` (gives a VectorX in YADE) -> ``AttributeError``
/ ``TypeError``; Matrix3/Matrix6 ``jacobiSVD``, ``svd``,
``polarDecomposition``, ``selfAdjointEigenDecomposition``,
``spectralDecomposition``, ``computeUnitaryPositive`` -> ``NotImplementedError``.
``Quaternion(u, v)``/``setFromTwoVectors`` for exactly opposite ``u``, ``v``
picks a valid but not necessarily Eigen's rotation axis (Eigen uses an SVD).
A wrong number of arguments to a method raises Python's ``TypeError`` instead
of ``ArgumentError``.  Uninitialised default values (``Quaternion()``,
``Matrix3()``, ``Vector2()``, ``Vector6()`` hold garbage in YADE) are the
identity / zero here.

Live views
----------
``Vector3._view(get, set)`` (likewise for every vector class, ``Matrix3``,
``Matrix6`` and ``Quaternion``) makes an object whose every read calls
``get()`` and whose every modification (item assignment, ``+=`` & co.,
``normalize()``) calls ``set(tuple)`` with the complete new value.  Formats:

* vectors: ``get()`` returns the N coefficients; ``set`` receives an N-tuple;
* ``Matrix3``/``Matrix6``: ``get()`` returns the coefficients row-major, flat
  (9 or 36 values) or as rows; ``set`` receives a flat row-major tuple;
* ``Quaternion``: ``get()`` returns ``(w, x, y, z)``; ``set`` receives
  ``(w, x, y, z)`` (the constructor's order, not the indexing order, which is
  ``x, y, z, w`` as in minieigen).

Arithmetic on a view returns plain (non-view) values; ``copy.copy`` and
pickling of a view give a plain value too.

``to_vec3(x, what)`` converts anything YADE accepts as a Vector3 to a tuple of
three floats, raising ``TypeError`` naming ``what`` otherwise.
"""

import math
import operator
import random as _random
import sys

__all__ = ['Vector2', 'Vector2i', 'Vector3', 'Vector3i', 'Vector4', 'Vector6', 'Vector6i',
           'Matrix3', 'Matrix6', 'Quaternion']

_EPS = sys.float_info.epsilon          # NumTraits<double>::epsilon()
_DUMMY = 1e-12                         # NumTraits<double>::dummy_precision()
_DBL_MAX = sys.float_info.max
_NEG_NAN = math.copysign(math.nan, -1.0)   # what x86 produces for invalid operations


class ArgumentError(TypeError):
    """Raised where Boost.Python would raise ``Boost.Python.ArgumentError``."""


# ----------------------------------------------------------------------------
# scalar helpers
# ----------------------------------------------------------------------------

def _fmt(x):
    """Format a Real as YADE does (C++ stream, precision 19, default floatfield)."""
    if x != x:
        return '-nan' if math.copysign(1.0, x) < 0 else 'nan'
    return '%.19g' % x


def _div(a, b):
    """IEEE division (C semantics: no ZeroDivisionError)."""
    try:
        return a / b
    except ZeroDivisionError:
        if a != a:
            return a
        if a == 0:
            return _NEG_NAN
        return math.copysign(math.inf, a) * math.copysign(1.0, b)


def _sin(x):
    try:
        return math.sin(x)
    except ValueError:      # sin(+-inf)
        return _NEG_NAN


def _cos(x):
    try:
        return math.cos(x)
    except ValueError:
        return _NEG_NAN


def _sqrt(x):
    try:
        return math.sqrt(x)
    except ValueError:      # negative argument
        return _NEG_NAN


def _acos(x):
    try:
        return math.acos(x)
    except ValueError:
        return math.nan


def _tofloat(x):
    """Boost.Python's double converter: int/bool or anything with __float__; None if not."""
    t = type(x)
    if t is float:
        return x
    if t is int or t is bool:
        return float(x)
    if isinstance(x, (str, bytes, bytearray)):
        return None
    if hasattr(t, '__float__'):
        try:
            return float(x)
        except (TypeError, ValueError):
            return None
    if hasattr(t, '__index__'):
        return float(operator.index(x))
    return None


_I32_MIN = -2 ** 31
_I32_MAX = 2 ** 31 - 1


def _toint(x):
    """Boost.Python's int converter (Python ints and bools; also __index__ objects)."""
    t = type(x)
    if t is int:
        v = x
    elif t is bool:
        v = int(x)
    elif isinstance(x, float) or isinstance(x, (str, bytes, bytearray)):
        return None
    elif hasattr(t, '__index__'):
        v = operator.index(x)
    else:
        return None
    if v > _I32_MAX:
        raise OverflowError('bad numeric conversion: positive overflow')
    if v < _I32_MIN:
        raise OverflowError('bad numeric conversion: negative overflow')
    return v


def _wrap32(v):
    """int32 two's complement wrap-around, as Eigen's int arithmetic does on x86."""
    if _I32_MIN <= v <= _I32_MAX:
        return v
    return ((v + 2 ** 31) & 0xFFFFFFFF) - 2 ** 31


def _index(i, n):
    """Index check as minieigen: integers only, 0 <= i < n (no negative indices)."""
    if type(i) is not int:
        if isinstance(i, (float, str, bytes, slice, tuple, list)) or not hasattr(type(i), '__index__'):
            return None
        i = operator.index(i)
    if i < 0 or i >= n:
        raise IndexError('Index %d out of range 0..%d' % (i, n - 1))
    return i


def _argerr(cls_name, meth, args, sigs):
    types = ', '.join([cls_name] + [type(a).__name__ for a in args])
    return ArgumentError('Python argument types in\n    %s.%s(%s)\ndid not match C++ signature:\n    %s'
                         % (cls_name, meth, types, '\n    '.join(sigs)))


# --- Eigen reductions ---------------------------------------------------------

def _tree(v, op):
    """Eigen's completely unrolled reduction of a fixed-size object: recursive halving,
    the first half having n//2 terms (3 terms: a0 + (a1 + a2); 4: (a0 + a1) + (a2 + a3)).
    Verified against YADE for 2, 3, 4, 6, 9 and 36 terms (Matrix6.squaredNorm)."""
    n = len(v)
    if n == 1:
        return v[0]
    h = n >> 1
    return op(_tree(v[:h], op), _tree(v[h:], op))


def _add(a, b):
    return a + b


def _mul(a, b):
    return a * b


def _max(a, b):          # std::max
    return b if a < b else a


def _min(a, b):          # std::min
    return b if b < a else a


def _sqnorm(v):
    """squaredNorm = cwiseAbs2().sum()."""
    return _tree([x * x for x in v], _add)


def _dot(a, b):
    """dot = cwiseProduct().sum(); also every coefficient of a (lazy) matrix product."""
    return _tree([x * y for x, y in zip(a, b)], _add)


def _norm3(x, y, z):
    return math.sqrt(x * x + (y * y + z * z))


def _stable_norm(v):
    """Eigen's stableNorm for a vector that fits into one block."""
    if len(v) == 1:
        return abs(v[0])
    scale = 0.0
    inv_scale = 1.0
    ssq = 0.0
    max_coeff = _tree([abs(x) for x in v], _max)
    if max_coeff > scale:
        ssq = ssq * ((scale / max_coeff) * (scale / max_coeff))
        tmp = _div(1.0, max_coeff)
        if tmp > _DBL_MAX:
            inv_scale = _DBL_MAX
            scale = 1.0 / inv_scale
        elif max_coeff > _DBL_MAX:
            inv_scale = 1.0
            scale = max_coeff
        else:
            scale = max_coeff
            inv_scale = tmp
    elif max_coeff != max_coeff:
        scale = max_coeff
    if scale > 0:
        ssq += _sqnorm([x * inv_scale for x in v])
    return scale * _sqrt(ssq)


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0]]


def _is_approx(a, b, prec):
    """Eigen isApprox: ||a-b||^2 <= prec^2 * min(||a||^2, ||b||^2)."""
    d = [x - y for x, y in zip(a, b)]
    return _sqnorm(d) <= prec * prec * min(_sqnorm(a), _sqnorm(b))


# --- conversion of Python objects to coefficient lists ----------------------

def _seq_items(obj, n):
    """Items of a Python sequence of length n, or None."""
    if isinstance(obj, (str, bytes, bytearray, dict)):
        return None
    if not hasattr(type(obj), '__getitem__'):
        return None
    try:
        if len(obj) != n:
            return None
        return [obj[i] for i in range(n)]
    except Exception:
        return None


def _conv_seq(obj, n, conv):
    """Coefficients from an object convertible to an n-vector with scalar converter conv."""
    if isinstance(obj, _VecBase):
        if obj._N != n:
            return None
        items = obj._r()
    else:
        items = _seq_items(obj, n)
        if items is None:
            return None
    out = []
    for it in items:
        c = conv(it)
        if c is None:
            return None
        out.append(c)
    return out


def to_vec3(x, what='value'):
    """Return ``x`` as a tuple of 3 floats if YADE would accept it as a Vector3.

    Raises ``TypeError`` naming ``what`` otherwise."""
    try:
        v = _conv_seq(x, 3, _tofloat)
    except (OverflowError, TypeError, ValueError):
        v = None
    if v is None:
        raise TypeError('%s: expected a Vector3 or a sequence of 3 numbers, got %s'
                        % (what, _short(x)))
    return (v[0], v[1], v[2])


def _short(x):
    try:
        r = repr(x)
    except Exception:
        r = '<unprintable>'
    if len(r) > 60:
        r = r[:57] + '...'
    return '%s %s' % (type(x).__name__, r)


_MISSING = object()


class _ClassConst:
    """Class attribute returning a fresh object on each access (like minieigen's static properties)."""

    def __init__(self, fn):
        self.fn = fn

    def __get__(self, obj, cls):
        return self.fn(cls)


# ----------------------------------------------------------------------------
# common base: fixed-size dense object with optional live-view storage
# ----------------------------------------------------------------------------

class _Dense:
    __slots__ = ('_v', '_g', '_s')
    _N = 0            # number of coefficients
    _INT = False

    # construction -----------------------------------------------------------
    @classmethod
    def _new(cls, vals):
        o = object.__new__(cls)
        o._v = vals
        o._g = None
        o._s = None
        return o

    @classmethod
    def _view(cls, get, set):
        """A live view: reads call ``get()``, modifications call ``set(tuple)``."""
        o = object.__new__(cls)
        o._v = None
        o._g = get
        o._s = set
        return o

    def _r(self):
        """Current coefficients (list or tuple, must not be modified)."""
        g = self._g
        if g is None:
            return self._v
        return self._from_get(g())

    @classmethod
    def _from_get(cls, t):
        return t if type(t) is tuple else tuple(t)

    def _w(self, vals):
        """Store new coefficients (through the setter for views)."""
        if self._g is None:
            self._v = list(vals)
        else:
            self._s(tuple(vals))

    def _copy(self):
        return self._new(list(self._r()))

    @property
    def _is_view(self):
        return self._g is not None

    _scal = staticmethod(_tofloat)

    # Python protocol ---------------------------------------------------------
    __hash__ = object.__hash__

    def __copy__(self):
        return self._copy()

    def __deepcopy__(self, memo):
        return self._copy()

    def __getinitargs__(self):
        return tuple(self._r())

    def __reduce__(self):
        return (type(self), tuple(self._r()), None)

    def __str__(self):
        return self.__repr__()

    def __eq__(self, other):
        b = self._conv(other)
        if b is None:
            return NotImplemented
        a = self._r()
        for x, y in zip(a, b):
            if not x == y:
                return False
        return True

    def __ne__(self, other):
        r = self.__eq__(other)
        if r is NotImplemented:
            return r
        return not r

    @classmethod
    def _conv(cls, o):
        raise NotImplementedError


class _Redux:
    """Eigen-style reductions over the coefficients in storage order."""
    __slots__ = ()

    def _storage(self):
        return self._r()

    def sum(self):
        return _tree(list(self._storage()), _add)

    def prod(self):
        return _tree(list(self._storage()), _mul)

    def maxCoeff(self):
        return _tree(list(self._storage()), _max)

    def minCoeff(self):
        return _tree(list(self._storage()), _min)

    def maxAbsCoeff(self):
        return _tree([abs(x) for x in self._storage()], _max)

    def mean(self):
        s = self.sum()
        if self._INT:
            q = abs(s) // self._N
            return q if s >= 0 else -q
        return s / float(self._N)

    def isApprox(self, other, prec=None):
        b = self._conv(other)
        if b is None:
            raise _argerr(type(self).__name__, 'isApprox', (other,), ['isApprox(other, prec)'])
        if prec is None:
            prec = 0 if self._INT else _DUMMY
        a = self._r()
        if self._INT:
            return all(x == y for x, y in zip(a, b)) if prec == 0 else _is_approx(a, b, prec)
        return _is_approx(list(a), list(b), prec)



# ----------------------------------------------------------------------------
# vectors
# ----------------------------------------------------------------------------

class _VecBase(_Redux, _Dense):
    __slots__ = ()

    @classmethod
    def _conv(cls, o):
        if type(o) is cls:
            return o._r()
        try:
            return _conv_seq(o, cls._N, cls._scal)
        except OverflowError:
            return None

    _SIGS = ()

    def _init_generic(self, args, kw, names, required):
        cls = type(self)
        allargs = args + tuple(kw.values())
        if not kw and len(args) == 1:
            v = cls._conv(args[0])
            if v is not None:
                self._v = list(v)
                return
        if not allargs:
            self._v = [cls._zero] * cls._N
            return
        if len(args) > len(names):
            raise _argerr(cls.__name__, '__init__', allargs, cls._SIGS)
        vals = list(args) + [_MISSING] * (len(names) - len(args))
        for k, x in kw.items():
            if k not in names or vals[names.index(k)] is not _MISSING:
                raise _argerr(cls.__name__, '__init__', allargs, cls._SIGS)
            vals[names.index(k)] = x
        out = []
        for i, x in enumerate(vals):
            if x is _MISSING:
                if i < required:
                    raise _argerr(cls.__name__, '__init__', allargs, cls._SIGS)
                out.append(cls._zero)
                continue
            c = cls._scal(x)
            if c is None:
                raise _argerr(cls.__name__, '__init__', allargs, cls._SIGS)
            out.append(c)
        self._v = out

    # sequence protocol -------------------------------------------------------
    def __len__(self):
        return self._N

    def __getitem__(self, i):
        j = _index(i, self._N)
        if j is None:
            raise _argerr(type(self).__name__, '__getitem__', (i,), ['__getitem__(%s, long)' % type(self).__name__])
        return self._r()[j]

    def __setitem__(self, i, value):
        j = _index(i, self._N)
        if j is None:
            raise _argerr(type(self).__name__, '__setitem__', (i, value),
                          ['__setitem__(%s, long, value)' % type(self).__name__])
        c = self._scal(value)
        if c is None:
            raise _argerr(type(self).__name__, '__setitem__', (i, value),
                          ['__setitem__(%s, long, value)' % type(self).__name__])
        v = list(self._r())
        v[j] = c
        self._w(v)

    def __iter__(self):
        return iter(list(self._r()))

    def __repr__(self):
        f = str if self._INT else _fmt
        parts = []
        for i, x in enumerate(self._r()):
            if i:
                parts.append(', ' if i % 3 == 0 else ',')
            parts.append(f(x))
        return '%s(%s)' % (type(self).__name__, ''.join(parts))

    # arithmetic --------------------------------------------------------------
    def _fin(self, r):
        if self._INT:
            return [_wrap32(x) for x in r]
        return r

    def __add__(self, o):
        b = self._conv(o)
        if b is None:
            return NotImplemented
        return self._new(self._fin([x + y for x, y in zip(self._r(), b)]))

    def __sub__(self, o):
        b = self._conv(o)
        if b is None:
            return NotImplemented
        return self._new(self._fin([x - y for x, y in zip(self._r(), b)]))

    def __mul__(self, s):
        c = self._scal(s) if not isinstance(s, _Dense) else None
        if c is None:
            return NotImplemented
        return self._new(self._fin([x * c for x in self._r()]))

    def __rmul__(self, s):
        c = self._scal(s) if not isinstance(s, _Dense) else None
        if c is None:
            return NotImplemented
        return self._new(self._fin([c * x for x in self._r()]))

    def __neg__(self):
        return self._new(self._fin([-x for x in self._r()]))

    def _inplace(self, r, meth, o):
        """minieigen's in-place operators modify self and return a new (equal) object."""
        if r is NotImplemented or type(r) is not type(self):
            raise _argerr(type(self).__name__, meth, (o,), ['%s(%s, %s)' % (meth, type(self).__name__, type(self).__name__)])
        self._w(r._v)
        return r

    def __iadd__(self, o):
        return self._inplace(self.__add__(o), '__iadd__', o)

    def __isub__(self, o):
        return self._inplace(self.__sub__(o), '__isub__', o)

    def __imul__(self, s):
        return self._inplace(self.__mul__(s), '__imul__', s)

    # common methods ------------------------------------------------------------
    def dot(self, other):
        b = self._conv(other)
        if b is None:
            raise _argerr(type(self).__name__, 'dot', (other,), ['dot(%s, %s)' % ((type(self).__name__,) * 2)])
        a = self._r()
        if self._N == 3:
            return a[0] * b[0] + (a[1] * b[1] + a[2] * b[2])
        r = _dot(a, b)
        return _wrap32(r) if self._INT else r

    def rows(self):
        return self._N

    def cols(self):
        return 1

    def outer(self, other):
        b = self._conv(other)
        if b is None:
            raise _argerr(type(self).__name__, 'outer', (other,), ['outer(%s, %s)' % ((type(self).__name__,) * 2)])
        mcls = self._MAT
        if mcls is None:
            raise TypeError('No to_python (by-value) converter found for C++ type: %s' % self._MATNAME)
        a = self._r()
        return mcls._new([x * y for x in a for y in b])

    def asDiagonal(self):
        mcls = self._MAT
        if mcls is None:
            raise TypeError('No to_python (by-value) converter found for C++ type: %s' % self._MATNAME)
        n = self._N
        a = self._r()
        m = [0.0] * (n * n)
        for i in range(n):
            m[i * n + i] = a[i]
        return mcls._new(m)

    _MAT = None
    _MATNAME = ''

    @classmethod
    def Unit(cls, i):
        j = _index(i, cls._N)
        if j is None:
            raise _argerr(cls.__name__, 'Unit', (i,), ['Unit(long)'])
        v = [cls._zero] * cls._N
        v[j] = cls._one
        return cls._new(v)

    @classmethod
    def Random(cls):
        if cls._INT:
            return cls._new([_random.randint(-2 ** 31, 2 ** 31 - 1) for _ in range(cls._N)])
        return cls._new([_random.uniform(-1.0, 1.0) for _ in range(cls._N)])

    Zero = _ClassConst(lambda cls: cls._new([cls._zero] * cls._N))
    Ones = _ClassConst(lambda cls: cls._new([cls._one] * cls._N))
    Identity = _ClassConst(lambda cls: cls._new([cls._one] + [cls._zero] * (cls._N - 1)))


class _Normed:
    """`norm`, `normalized`, `normalize` shared by float vectors and matrices (Eigen divides each
    coefficient by sqrt(squaredNorm), leaving a zero value untouched)."""
    __slots__ = ()

    def norm(self):
        return math.sqrt(self.squaredNorm())

    __abs__ = norm

    def normalized(self):
        a = self._r()
        n2 = self.squaredNorm()
        if n2 > 0:
            n = math.sqrt(n2)
            return self._new([_div(x, n) for x in a])
        return self._new(list(a))

    def normalize(self):
        n2 = self.squaredNorm()
        if n2 > 0:
            n = math.sqrt(n2)
            self._w([_div(x, n) for x in self._r()])


class _VecF(_Normed, _VecBase):
    """Real-valued vector."""
    __slots__ = ()
    _zero = 0.0
    _one = 1.0

    def __truediv__(self, s):
        c = _tofloat(s) if not isinstance(s, _Dense) else None
        if c is None:
            return NotImplemented
        return self._new([_div(x, c) for x in self._r()])

    __div__ = __truediv__

    def __itruediv__(self, s):
        return self._inplace(self.__truediv__(s), '__itruediv__', s)

    __idiv__ = __itruediv__

    def squaredNorm(self):
        a = self._r()
        if self._N == 3:
            return a[0] * a[0] + (a[1] * a[1] + a[2] * a[2])
        return _sqnorm(a)



class _VecI(_VecBase):
    """Integer-valued vector."""
    __slots__ = ()
    _INT = True
    _zero = 0
    _one = 1
    _scal = staticmethod(_toint)


def _swizzle(i, j):
    def f(self):
        a = self._r()
        return self._V2._new([a[i], a[j]])
    return f


class Vector2(_VecF):
    __slots__ = ()
    _N = 2
    _MATNAME = 'Eigen::Matrix<double, 2, 2, 0, 2, 2>'
    _SIGS = ('__init__(_object*, double x, double y)', '__init__(_object*, Vector2 other)', '__init__(_object*)')
    UnitX = _ClassConst(lambda cls: cls._new([1.0, 0.0]))
    UnitY = _ClassConst(lambda cls: cls._new([0.0, 1.0]))

    def __init__(self, *args, **kw):
        self._g = self._s = None
        self._init_generic(args, kw, ('x', 'y'), 2)


class Vector2i(_VecI):
    __slots__ = ()
    _N = 2
    _MATNAME = 'Eigen::Matrix<int, 2, 2, 0, 2, 2>'
    _SIGS = ('__init__(_object*, int x, int y)', '__init__(_object*, Vector2i other)', '__init__(_object*)')
    UnitX = _ClassConst(lambda cls: cls._new([1, 0]))
    UnitY = _ClassConst(lambda cls: cls._new([0, 1]))

    def __init__(self, *args, **kw):
        self._g = self._s = None
        self._init_generic(args, kw, ('x', 'y'), 2)


class Vector3(_VecF):
    __slots__ = ()
    _N = 3
    _V2 = Vector2
    _SIGS = ('__init__(_object*, double x=0.0, double y=0.0, double z=0.0)',
             '__init__(_object*, Vector3 other)', '__init__(_object*)')
    UnitX = _ClassConst(lambda cls: cls._new([1.0, 0.0, 0.0]))
    UnitY = _ClassConst(lambda cls: cls._new([0.0, 1.0, 0.0]))
    UnitZ = _ClassConst(lambda cls: cls._new([0.0, 0.0, 1.0]))

    def __init__(self, *args, **kw):
        self._g = self._s = None
        if not kw and len(args) == 3:
            x, y, z = args
            tx, ty, tz = type(x), type(y), type(z)
            if (tx is float or tx is int) and (ty is float or ty is int) and (tz is float or tz is int):
                self._v = [float(x), float(y), float(z)]
                return
        self._init_generic(args, kw, ('x', 'y', 'z'), 0)

    # fast paths for the most used operations
    def __getitem__(self, i):
        if type(i) is int and 0 <= i < 3:
            g = self._g
            return self._v[i] if g is None else g()[i]
        return _VecF.__getitem__(self, i)

    def __add__(self, o):
        b = o._r() if type(o) is Vector3 else self._conv(o)
        if b is None:
            return NotImplemented
        a = self._r()
        return Vector3._new([a[0] + b[0], a[1] + b[1], a[2] + b[2]])

    def __sub__(self, o):
        b = o._r() if type(o) is Vector3 else self._conv(o)
        if b is None:
            return NotImplemented
        a = self._r()
        return Vector3._new([a[0] - b[0], a[1] - b[1], a[2] - b[2]])

    def __mul__(self, s):
        c = s if type(s) is float else (self._scal(s) if not isinstance(s, _Dense) else None)
        if c is None:
            return NotImplemented
        a = self._r()
        return Vector3._new([a[0] * c, a[1] * c, a[2] * c])

    def __rmul__(self, s):
        c = s if type(s) is float else (self._scal(s) if not isinstance(s, _Dense) else None)
        if c is None:
            return NotImplemented
        a = self._r()
        return Vector3._new([c * a[0], c * a[1], c * a[2]])

    def cross(self, other):
        b = self._conv(other)
        if b is None:
            raise _argerr('Vector3', 'cross', (other,), ['cross(Vector3, Vector3)'])
        return Vector3._new(_cross(self._r(), b))

    xy = _swizzle(0, 1)
    yx = _swizzle(1, 0)
    xz = _swizzle(0, 2)
    zx = _swizzle(2, 0)
    yz = _swizzle(1, 2)
    zy = _swizzle(2, 1)


class Vector3i(_VecI):
    __slots__ = ()
    _N = 3
    _V2 = Vector2i
    _MATNAME = 'Eigen::Matrix<int, 3, 3, 0, 3, 3>'
    _SIGS = ('__init__(_object*, int x=0, int y=0, int z=0)',
             '__init__(_object*, Vector3i other)', '__init__(_object*)')
    UnitX = _ClassConst(lambda cls: cls._new([1, 0, 0]))
    UnitY = _ClassConst(lambda cls: cls._new([0, 1, 0]))
    UnitZ = _ClassConst(lambda cls: cls._new([0, 0, 1]))

    def __init__(self, *args, **kw):
        self._g = self._s = None
        self._init_generic(args, kw, ('x', 'y', 'z'), 0)

    def cross(self, other):
        b = self._conv(other)
        if b is None:
            raise _argerr('Vector3i', 'cross', (other,), ['cross(Vector3i, Vector3i)'])
        return Vector3i._new([_wrap32(x) for x in _cross(self._r(), b)])

    xy = _swizzle(0, 1)
    yx = _swizzle(1, 0)
    xz = _swizzle(0, 2)
    zx = _swizzle(2, 0)
    yz = _swizzle(1, 2)
    zy = _swizzle(2, 1)


class Vector4(_VecF):
    __slots__ = ()
    _N = 4
    _MATNAME = 'Eigen::Matrix<double, 4, 4, 0, 4, 4>'
    _SIGS = ('__init__(_object*, double v0, double v1, double v2, double v3)',
             '__init__(_object*, Vector4 other)', '__init__(_object*)')

    def __init__(self, *args, **kw):
        self._g = self._s = None
        self._init_generic(args, kw, ('v0', 'v1', 'v2', 'v3'), 4)


class _Vec6Mixin:
    __slots__ = ()

    def _init6(self, args, kw):
        cls = type(self)
        if not kw and len(args) == 2:
            h = cls._V3._conv(args[0])
            t = cls._V3._conv(args[1])
            if h is not None and t is not None:
                self._v = list(h) + list(t)
                return
        self._init_generic(args, kw, ('v0', 'v1', 'v2', 'v3', 'v4', 'v5'), 6)

    def head(self, *args):
        if args:
            raise _argerr(type(self).__name__, 'head', args, ['head(%s)' % type(self).__name__])
        return self._V3._new(list(self._r()[:3]))

    def tail(self, *args):
        if args:
            raise _argerr(type(self).__name__, 'tail', args, ['tail(%s)' % type(self).__name__])
        return self._V3._new(list(self._r()[3:]))


class Vector6(_Vec6Mixin, _VecF):
    __slots__ = ()
    _N = 6
    _V3 = Vector3
    _SIGS = ('__init__(_object*, double v0, double v1, double v2, double v3, double v4, double v5)',
             '__init__(_object*, Vector3 head, Vector3 tail)',
             '__init__(_object*, Vector6 other)', '__init__(_object*)')

    def __init__(self, *args, **kw):
        self._g = self._s = None
        self._init6(args, kw)


class Vector6i(_Vec6Mixin, _VecI):
    __slots__ = ()
    _N = 6
    _V3 = Vector3i
    _MATNAME = 'Eigen::Matrix<int, 6, 6, 0, 6, 6>'
    _SIGS = ('__init__(_object*, int v0, int v1, int v2, int v3, int v4, int v5)',
             '__init__(_object*, Vector3i head, Vector3i tail)',
             '__init__(_object*, Vector6i other)', '__init__(_object*)')

    def __init__(self, *args, **kw):
        self._g = self._s = None
        self._init6(args, kw)


# ----------------------------------------------------------------------------
# matrices (stored row-major; reductions run in Eigen's column-major order)
# ----------------------------------------------------------------------------

class _MatBase(_Normed, _Redux, _Dense):
    __slots__ = ()
    _D = 3          # dimension
    _zero = 0.0
    _one = 1.0

    @classmethod
    def _from_get(cls, t):
        t = tuple(t)
        if len(t) == cls._D and hasattr(t[0], '__len__'):
            return tuple(x for row in t for x in row)
        return t

    def _storage(self):
        d = self._D
        a = self._r()
        return [a[r * d + c] for c in range(d) for r in range(d)]

    @classmethod
    def _conv(cls, o):
        """Coefficients (row-major) of something convertible to this matrix type, or None."""
        if type(o) is cls:
            return o._r()
        if isinstance(o, _Dense):
            return None
        d = cls._D
        items = _seq_items(o, d)
        if items is not None:
            rows = [_conv_seq(it, d, _tofloat) for it in items]
            if all(r is not None for r in rows):
                return [x for r in rows for x in r]
        return _conv_seq(o, d * d, _tofloat) if not isinstance(o, _Dense) else None

    def __len__(self):
        return self._D

    def __getitem__(self, i):
        d = self._D
        if type(i) is tuple:
            if len(i) != 2:
                raise IndexError('Index must be integer or a 2-tuple')
            r = _index(i[0], d)
            c = _index(i[1], d)
            if r is None or c is None:
                raise _argerr(type(self).__name__, '__getitem__', (i,), ['__getitem__(%s, tuple)' % type(self).__name__])
            return self._r()[r * d + c]
        r = _index(i, d)
        if r is None:
            raise _argerr(type(self).__name__, '__getitem__', (i,), ['__getitem__(%s, tuple)' % type(self).__name__,
                                                                    '__getitem__(%s, long)' % type(self).__name__])
        return self._V._new(list(self._r()[r * d:(r + 1) * d]))

    def __setitem__(self, i, value):
        d = self._D
        v = list(self._r())
        if type(i) is tuple:
            if len(i) != 2:
                raise IndexError('Index must be integer or a 2-tuple')
            r = _index(i[0], d)
            c = _index(i[1], d)
            x = _tofloat(value)
            if r is None or c is None or x is None:
                raise _argerr(type(self).__name__, '__setitem__', (i, value), ['__setitem__(%s, tuple, double)' % type(self).__name__])
            v[r * d + c] = x
        else:
            r = _index(i, d)
            row = self._V._conv(value)
            if r is None or row is None:
                raise _argerr(type(self).__name__, '__setitem__', (i, value), ['__setitem__(%s, long, %s)' % (type(self).__name__, self._V.__name__)])
            v[r * d:(r + 1) * d] = row
        self._w(v)

    def __iter__(self):
        d = self._D
        a = list(self._r())
        return iter([self._V._new(a[r * d:(r + 1) * d]) for r in range(d)])

    # arithmetic ----------------------------------------------------------------
    def __add__(self, o):
        b = self._conv(o)
        if b is None:
            return NotImplemented
        return self._new([x + y for x, y in zip(self._r(), b)])

    def __sub__(self, o):
        b = self._conv(o)
        if b is None:
            return NotImplemented
        return self._new([x - y for x, y in zip(self._r(), b)])

    def __neg__(self):
        return self._new([-x for x in self._r()])

    def _matmul(self, b):
        d = self._D
        a = self._r()
        out = []
        for i in range(d):
            row = a[i * d:(i + 1) * d]
            for j in range(d):
                out.append(_dot(row, [b[k * d + j] for k in range(d)]))
        return out

    def _matvec(self, v):
        d = self._D
        a = self._r()
        return [_dot(a[i * d:(i + 1) * d], v) for i in range(d)]

    def __mul__(self, o):
        if type(o) is type(self):
            return self._new(self._matmul(o._r()))
        if isinstance(o, (_MatBase, Quaternion)):
            return NotImplemented
        if not isinstance(o, _Dense):
            c = _tofloat(o)
            if c is not None:
                return self._new([x * c for x in self._r()])
        v = self._V._conv(o)
        if v is not None:
            return self._V._new(self._matvec(v))
        b = self._conv(o)
        if b is not None:
            return self._new(self._matmul(b))
        return NotImplemented

    def __rmul__(self, o):
        if not isinstance(o, _Dense):
            c = _tofloat(o)
            if c is not None:
                return self._new([c * x for x in self._r()])
        # minieigen quirk: vector*matrix is evaluated as matrix*vector
        v = self._V._conv(o)
        if v is not None:
            return self._V._new(self._matvec(v))
        return NotImplemented

    def __truediv__(self, s):
        c = _tofloat(s) if not isinstance(s, _Dense) else None
        if c is None:
            return NotImplemented
        return self._new([_div(x, c) for x in self._r()])

    __div__ = __truediv__

    def _inplace(self, r, meth, o):
        if r is NotImplemented or type(r) is not type(self):
            raise _argerr(type(self).__name__, meth, (o,), ['%s(%s, %s)' % (meth, type(self).__name__, type(self).__name__)])
        self._w(r._v)
        return r

    def __iadd__(self, o):
        return self._inplace(self.__add__(o), '__iadd__', o)

    def __isub__(self, o):
        return self._inplace(self.__sub__(o), '__isub__', o)

    def __imul__(self, o):
        r = NotImplemented if isinstance(o, _VecBase) else self.__mul__(o)
        return self._inplace(r, '__imul__', o)

    def __itruediv__(self, s):
        return self._inplace(self.__truediv__(s), '__itruediv__', s)

    __idiv__ = __itruediv__

    # methods -------------------------------------------------------------------
    def rows(self):
        return self._D

    def cols(self):
        return self._D

    def row(self, i):
        d = self._D
        r = _index(i, d)
        if r is None:
            raise _argerr(type(self).__name__, 'row', (i,), ['row(%s, long)' % type(self).__name__])
        return self._V._new(list(self._r()[r * d:(r + 1) * d]))

    def col(self, i):
        d = self._D
        c = _index(i, d)
        if c is None:
            raise _argerr(type(self).__name__, 'col', (i,), ['col(%s, long)' % type(self).__name__])
        a = self._r()
        return self._V._new([a[r * d + c] for r in range(d)])

    def diagonal(self):
        d = self._D
        a = self._r()
        return self._V._new([a[i * d + i] for i in range(d)])

    def trace(self):
        d = self._D
        a = self._r()
        return _tree([a[i * d + i] for i in range(d)], _add)

    def transpose(self):
        d = self._D
        a = self._r()
        return self._new([a[c * d + r] for r in range(d) for c in range(d)])

    def squaredNorm(self):
        return _sqnorm(self._storage())


    def __repr__(self):
        a = self._r()
        parts = []
        for i, x in enumerate(a):
            if i:
                parts.append(', ' if i % 3 == 0 else ',')
            parts.append(_fmt(x))
        return '%s(%s)' % (type(self).__name__, ''.join(parts))

    @classmethod
    def Random(cls):
        return cls._new([_random.uniform(-1.0, 1.0) for _ in range(cls._D * cls._D)])

    Zero = _ClassConst(lambda cls: cls._new([0.0] * (cls._D * cls._D)))
    Ones = _ClassConst(lambda cls: cls._new([1.0] * (cls._D * cls._D)))
    Identity = _ClassConst(lambda cls: cls._new([1.0 if r == c else 0.0 for r in range(cls._D) for c in range(cls._D)]))

    def _not_implemented(name):
        def f(self, *args, **kw):
            raise NotImplementedError('yade.minieigen (ryade): %s.%s is not implemented'
                                      % (type(self).__name__, name))
        f.__name__ = name
        return f

    jacobiSVD = _not_implemented('jacobiSVD')
    svd = _not_implemented('svd')
    polarDecomposition = _not_implemented('polarDecomposition')
    selfAdjointEigenDecomposition = _not_implemented('selfAdjointEigenDecomposition')
    spectralDecomposition = _not_implemented('spectralDecomposition')
    computeUnitaryPositive = _not_implemented('computeUnitaryPositive')
    del _not_implemented


def _cof3(m, i, j):
    """Cofactor (i,j) of a row-major 3x3 matrix (cyclic index form)."""
    i1 = (i + 1) % 3
    i2 = (i + 2) % 3
    j1 = (j + 1) % 3
    j2 = (j + 2) % 3
    return m[i1 * 3 + j1] * m[i2 * 3 + j2] - m[i1 * 3 + j2] * m[i2 * 3 + j1]


class Matrix3(_MatBase):
    __slots__ = ()
    _D = 3
    _N = 9
    _V = Vector3
    _SIGS = ('__init__(object, Vector3 r0, Vector3 r1, Vector3 r2, bool cols=False)',
             '__init__(object, double m00, double m01, double m02, double m10, double m11, double m12, '
             'double m20, double m21, double m22)',
             '__init__(object, Vector3 diag)', '__init__(_object*, Matrix3 other)',
             '__init__(_object*, Quaternion q)', '__init__(_object*)')
    _KEYS = ('m00', 'm01', 'm02', 'm10', 'm11', 'm12', 'm20', 'm21', 'm22')

    def __init__(self, *args, **kw):
        self._g = self._s = None
        allargs = args + tuple(kw.values())
        if not args and not kw:
            self._v = [0.0] * 9
            return
        if len(allargs) == 1:
            a = allargs[0]
            if kw and list(kw) not in (['other'], ['q'], ['diag']):
                raise _argerr('Matrix3', '__init__', allargs, self._SIGS)
            if type(a) is Matrix3:
                self._v = list(a._r())
                return
            if isinstance(a, Quaternion):
                self._v = a._rotmat()
                return
            d = Vector3._conv(a)
            if d is not None:
                self._v = [d[0], 0.0, 0.0, 0.0, d[1], 0.0, 0.0, 0.0, d[2]]
                return
            m = Matrix3._conv(a)
            if m is not None:
                self._v = list(m)
                return
            raise _argerr('Matrix3', '__init__', allargs, self._SIGS)
        if len(allargs) == 9:
            vals = list(args) + [None] * (9 - len(args))
            for k, x in kw.items():
                if k not in self._KEYS or vals[self._KEYS.index(k)] is not None:
                    raise _argerr('Matrix3', '__init__', allargs, self._SIGS)
                vals[self._KEYS.index(k)] = x
            out = [_tofloat(x) for x in vals]
            if any(x is None for x in out):
                raise _argerr('Matrix3', '__init__', allargs, self._SIGS)
            self._v = out
            return
        if 3 <= len(allargs) <= 4:
            names = ('r0', 'r1', 'r2', 'cols')
            vals = list(args) + [None] * (4 - len(args))
            for k, x in kw.items():
                if k not in names or vals[names.index(k)] is not None:
                    raise _argerr('Matrix3', '__init__', allargs, self._SIGS)
                vals[names.index(k)] = x
            rows = [Vector3._conv(x) if x is not None else None for x in vals[:3]]
            cols = vals[3]
            if all(r is not None for r in rows) and (cols is None or isinstance(cols, (bool, int))):
                m = [x for r in rows for x in r]
                if cols:
                    m = [m[c * 3 + r] for r in range(3) for c in range(3)]
                self._v = m
                return
        raise _argerr('Matrix3', '__init__', allargs, self._SIGS)

    def __mul__(self, o):
        if type(o) is Vector3:
            v = o._r()
            a = self._r()
            return Vector3._new([a[0] * v[0] + (a[1] * v[1] + a[2] * v[2]),
                                 a[3] * v[0] + (a[4] * v[1] + a[5] * v[2]),
                                 a[6] * v[0] + (a[7] * v[1] + a[8] * v[2])])
        return _MatBase.__mul__(self, o)

    def determinant(self):
        m = self._r()
        return (m[0] * (m[4] * m[8] - m[5] * m[7])
                - m[1] * (m[3] * m[8] - m[5] * m[6])
                + m[2] * (m[3] * m[7] - m[4] * m[6]))

    def inverse(self):
        m = self._r()
        c0 = [_cof3(m, 0, 0), _cof3(m, 1, 0), _cof3(m, 2, 0)]
        det = c0[0] * m[0] + (c0[1] * m[3] + c0[2] * m[6])
        invdet = _div(1.0, det)
        out = [0.0] * 9
        for r in range(3):
            for c in range(3):
                cof = c0[c] if r == 0 else _cof3(m, c, r)
                out[r * 3 + c] = cof * invdet
        return Matrix3._new(out)


class Matrix6(_MatBase):
    __slots__ = ()
    _D = 6
    _N = 36
    _V = Vector6
    _SIGS = ('__init__(object, Vector6 l0, Vector6 l1, Vector6 l2, Vector6 l3, Vector6 l4, Vector6 l5, bool cols=False)',
             '__init__(object, Matrix3 ul, Matrix3 ur, Matrix3 ll, Matrix3 lr)',
             '__init__(object, Vector6 diag)', '__init__(_object*, Matrix6 other)', '__init__(_object*)')

    def __init__(self, *args, **kw):
        self._g = self._s = None
        allargs = args + tuple(kw.values())
        if not allargs:
            self._v = [0.0] * 36
            return
        if len(allargs) == 1:
            a = allargs[0]
            if type(a) is Matrix6:
                self._v = list(a._r())
                return
            d = Vector6._conv(a)
            if d is not None:
                m = [0.0] * 36
                for i in range(6):
                    m[i * 7] = d[i]
                self._v = m
                return
            m = Matrix6._conv(a)
            if m is not None:
                self._v = list(m)
                return
        elif len(allargs) == 4 and not kw:
            blocks = [Matrix3._conv(x) for x in args]
            if all(b is not None for b in blocks):
                ul, ur, ll, lr = blocks
                m = []
                for r in range(3):
                    m += list(ul[r * 3:r * 3 + 3]) + list(ur[r * 3:r * 3 + 3])
                for r in range(3):
                    m += list(ll[r * 3:r * 3 + 3]) + list(lr[r * 3:r * 3 + 3])
                self._v = m
                return
        elif 6 <= len(allargs) <= 7:
            names = ('l0', 'l1', 'l2', 'l3', 'l4', 'l5', 'cols')
            vals = list(args) + [None] * (7 - len(args))
            ok = True
            for k, x in kw.items():
                if k not in names or vals[names.index(k)] is not None:
                    ok = False
                else:
                    vals[names.index(k)] = x
            if ok:
                rows = [Vector6._conv(x) if x is not None else None for x in vals[:6]]
                cols = vals[6]
                if all(r is not None for r in rows) and (cols is None or isinstance(cols, (bool, int))):
                    m = [x for r in rows for x in r]
                    if cols:
                        m = [m[c * 6 + r] for r in range(6) for c in range(6)]
                    self._v = m
                    return
        raise _argerr('Matrix6', '__init__', allargs, self._SIGS)

    def _block(self, r0, c0):
        a = self._r()
        return Matrix3._new([a[(r0 + r) * 6 + c0 + c] for r in range(3) for c in range(3)])

    def ul(self):
        return self._block(0, 0)

    def ur(self):
        return self._block(0, 3)

    def ll(self):
        return self._block(3, 0)

    def lr(self):
        return self._block(3, 3)

    def _lu(self):
        """Partial-pivoting LU (unblocked, as Eigen for small sizes)."""
        n = 6
        lu = [list(self._r()[r * n:(r + 1) * n]) for r in range(n)]
        perm = list(range(n))
        ntransp = 0
        for k in range(n):
            best = k
            bestv = abs(lu[k][k])
            for i in range(k + 1, n):
                if abs(lu[i][k]) > bestv:
                    best = i
                    bestv = abs(lu[i][k])
            if best != k:
                lu[k], lu[best] = lu[best], lu[k]
                perm[k], perm[best] = perm[best], perm[k]
                ntransp += 1
            if lu[k][k] != 0:
                p = lu[k][k]
                for i in range(k + 1, n):
                    lu[i][k] = _div(lu[i][k], p)
            for i in range(k + 1, n):
                lik = lu[i][k]
                for j in range(k + 1, n):
                    lu[i][j] = lu[i][j] - lik * lu[k][j]
        return lu, perm, ntransp

    def determinant(self):
        lu, perm, nt = self._lu()
        d = _tree([lu[i][i] for i in range(6)], _mul)
        return (-1.0 if nt % 2 else 1.0) * d

    def inverse(self):
        """Inverse as Eigen computes it: partial-pivoting LU, then the identity (permuted) is
        solved with Eigen's panel-blocked triangular solves (panel width 4 for doubles without
        vectorisation: substitution inside a panel, a dot-product update below/above it)."""
        n = 6
        lu, perm, nt = self._lu()
        out = [[0.0] * n for _ in range(n)]
        for j in range(n):
            b = [1.0 if perm[i] == j else 0.0 for i in range(n)]
            # unit lower triangular, forward; panels rows 0..3 and 4..5
            for p0, pw in ((0, 4), (4, 2)):
                for i in range(p0, p0 + pw):
                    xi = b[i]
                    for r in range(i + 1, p0 + pw):
                        b[r] = b[r] - xi * lu[r][i]
                for r in range(p0 + pw, n):
                    acc = 0.0
                    for c in range(p0, p0 + pw):
                        acc = acc + lu[r][c] * b[c]
                    b[r] = b[r] - acc
            # upper triangular, backward; panels rows 5..2 and 1..0
            for top, pw in ((2, 4), (0, 2)):
                for i in range(top + pw - 1, top - 1, -1):
                    b[i] = b[i] * _div(1.0, lu[i][i])
                    xi = b[i]
                    for r in range(top, i):
                        b[r] = b[r] - xi * lu[r][i]
                for r in range(0, top):
                    acc = 0.0
                    for c in range(top, top + pw):
                        acc = acc + lu[r][c] * b[c]
                    b[r] = b[r] - acc
            for i in range(n):
                out[i][j] = b[i]
        return Matrix6._new([x for r in out for x in r])

    def __repr__(self):
        a = self._r()
        rows = ['(' + ','.join(_fmt(x) for x in a[r * 6:(r + 1) * 6]) + ')' for r in range(6)]
        return 'Matrix6(\n\t' + ',\n\t'.join(rows) + '\n)'


Vector3._MAT = Matrix3
Vector6._MAT = Matrix6


# ----------------------------------------------------------------------------
# quaternion (stored as [w, x, y, z]; indexed x, y, z, w)
# ----------------------------------------------------------------------------

def _qmul(a, b):
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return [aw * bw - ax * bx - ay * by - az * bz,
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by + ay * bw + az * bx - ax * bz,
            aw * bz + az * bw + ax * by - ay * bx]


def _qsqnorm(q):
    w, x, y, z = q
    return (x * x + y * y) + (z * z + w * w)


def _qrotate(q, v):
    """Eigen's _transformVector: v + w*uv + vec x uv, uv = 2 (vec x v)."""
    w = q[0]
    vec = q[1:]
    uv = _cross(vec, v)
    uv = [u + u for u in uv]
    c = _cross(vec, uv)
    return [v[i] + w * uv[i] + c[i] for i in range(3)]


def _angle_axis(q):
    """AngleAxis from quaternion (Eigen 3.4 algorithm): returns (angle, [ax, ay, az])."""
    w, x, y, z = q
    n = math.sqrt(x * x + (y * y + z * z))
    if n < _EPS:
        n = _stable_norm([x, y, z])
    if n != 0:
        angle = 2.0 * math.atan2(n, abs(w))
        if w < 0:
            n = -n
        return angle, [_div(x, n), _div(y, n), _div(z, n)]
    return 0.0, [1.0, 0.0, 0.0]


def _from_angle_axis(angle, axis):
    ha = 0.5 * angle
    s = _sin(ha)
    return [_cos(ha), s * axis[0], s * axis[1], s * axis[2]]


def _normalized4(q):
    n2 = _qsqnorm(q)
    if n2 > 0:
        n = math.sqrt(n2)
        return [_div(c, n) for c in q]
    return q


def _from_rotmat(m):
    """Quaternion [w,x,y,z] from a row-major rotation matrix (Eigen's algorithm)."""
    t = m[0] + (m[4] + m[8])
    if t > 0:
        t = _sqrt(t + 1.0)
        w = 0.5 * t
        t = _div(0.5, t)
        return [w, (m[7] - m[5]) * t, (m[2] - m[6]) * t, (m[3] - m[1]) * t]
    i = 0
    if m[4] > m[0]:
        i = 1
    if m[8] > m[i * 4]:
        i = 2
    j = (i + 1) % 3
    k = (j + 1) % 3
    t = _sqrt(m[i * 4] - m[j * 4] - m[k * 4] + 1.0)
    xyz = [0.0, 0.0, 0.0]
    xyz[i] = 0.5 * t
    t = _div(0.5, t)
    w = (m[k * 3 + j] - m[j * 3 + k]) * t
    xyz[j] = (m[j * 3 + i] + m[i * 3 + j]) * t
    xyz[k] = (m[k * 3 + i] + m[i * 3 + k]) * t
    return [w] + xyz


def _two_vectors(a, b):
    """Quaternion [w,x,y,z] rotating a onto b (Eigen's setFromTwoVectors)."""
    v0 = Vector3._new(list(a)).normalized()._v
    v1 = Vector3._new(list(b)).normalized()._v
    c = v1[0] * v0[0] + (v1[1] * v0[1] + v1[2] * v0[2])
    if c < -1.0 + _DUMMY:
        # Antiparallel vectors: Eigen picks the axis from an SVD; we use a
        # deterministic perpendicular axis (same rotation up to the axis choice).
        c = max(c, -1.0)
        ax = [abs(x) for x in v0]
        k = ax.index(min(ax))
        e = [0.0, 0.0, 0.0]
        e[k] = 1.0
        axis = _cross(v0, e)
        n = _norm3(*axis)
        axis = [x / n for x in axis]
        w2 = (1.0 + c) * 0.5
        s = _sqrt(1.0 - w2)
        return [_sqrt(w2), axis[0] * s, axis[1] * s, axis[2] * s]
    axis = _cross(v0, v1)
    s = _sqrt((1.0 + c) * 2.0)
    invs = _div(1.0, s)
    return [s * 0.5, axis[0] * invs, axis[1] * invs, axis[2] * invs]


_QSIGS = ('__init__(_object*, Quaternion other)', '__init__(_object*, Matrix3 rotMatrix)',
          '__init__(_object*, double w, double x, double y, double z)',
          '__init__(object, Vector3 u, Vector3 v)', '__init__(object, double angle, Vector3 axis)',
          '__init__(object, Vector3 axis, double angle)', '__init__(_object*)')


class Quaternion(_Dense):
    __slots__ = ()
    _N = 4

    def __init__(self, *args, **kw):
        self._g = self._s = None
        allargs = args + tuple(kw.values())
        if not allargs:
            self._v = [1.0, 0.0, 0.0, 0.0]
            return
        if len(allargs) == 1:
            a = allargs[0]
            if isinstance(a, Quaternion):
                self._v = list(a._r())
                return
            m = Matrix3._conv(a)
            if m is not None:
                self._v = _from_rotmat(m)
                return
        elif len(allargs) == 4:
            names = ('w', 'x', 'y', 'z')
            vals = list(args) + [None] * (4 - len(args))
            ok = True
            for k, x in kw.items():
                if k not in names or vals[names.index(k)] is not None:
                    ok = False
                else:
                    vals[names.index(k)] = x
            if ok:
                c = [_tofloat(x) for x in vals]
                if all(x is not None for x in c):
                    self._v = c
                    return
        elif len(allargs) == 2:
            if not kw:
                a0, a1 = args
            else:
                keys = set(kw)
                if keys == {'axis', 'angle'}:
                    a0, a1 = kw['axis'], kw['angle']
                elif keys == {'angle'}:          # Quaternion(axis, angle=...)
                    a0, a1 = args[0], kw['angle']
                elif keys == {'axis'}:           # Quaternion(angle, axis=...)
                    a0, a1 = kw['axis'], args[0]
                elif keys == {'u', 'v'}:
                    a0, a1 = kw['u'], kw['v']
                elif keys == {'v'}:
                    a0, a1 = args[0], kw['v']
                else:
                    raise _argerr('Quaternion', '__init__', allargs, _QSIGS)
            # (axis, angle)
            ax = Vector3._conv(a0)
            an = _tofloat(a1) if not isinstance(a1, _Dense) else None
            if ax is not None and an is not None:
                self._v = _normalized4(_from_angle_axis(an, ax))
                return
            # (angle, axis)
            an = _tofloat(a0) if not isinstance(a0, _Dense) else None
            ax = Vector3._conv(a1)
            if ax is not None and an is not None:
                self._v = _normalized4(_from_angle_axis(an, ax))
                return
            # (u, v)
            u = Vector3._conv(a0)
            v = Vector3._conv(a1)
            if u is not None and v is not None:
                self._v = _two_vectors(u, v)
                return
        raise _argerr('Quaternion', '__init__', allargs, _QSIGS)

    # storage helpers -----------------------------------------------------------
    _IDX = (1, 2, 3, 0)     # python index -> storage position

    def __len__(self):
        return 4

    def __getitem__(self, i):
        j = _index(i, 4)
        if j is None:
            raise _argerr('Quaternion', '__getitem__', (i,), ['__getitem__(Quaternion, long)'])
        return self._r()[self._IDX[j]]

    def __setitem__(self, i, value):
        j = _index(i, 4)
        c = _tofloat(value)
        if j is None or c is None:
            raise _argerr('Quaternion', '__setitem__', (i, value), ['__setitem__(Quaternion, long, double)'])
        v = list(self._r())
        v[self._IDX[j]] = c
        self._w(v)

    def __iter__(self):
        w, x, y, z = self._r()
        return iter([x, y, z, w])

    def _storage(self):
        w, x, y, z = self._r()
        return [x, y, z, w]

    @classmethod
    def _conv(cls, o):
        if isinstance(o, Quaternion):
            return o._r()
        return None

    def __repr__(self):
        angle, axis = _angle_axis(self._r())
        return 'Quaternion((%s,%s,%s),%s)' % (_fmt(axis[0]), _fmt(axis[1]), _fmt(axis[2]), _fmt(angle))

    # algebra -------------------------------------------------------------------
    def __mul__(self, o):
        if isinstance(o, Quaternion):
            return Quaternion._new(_qmul(self._r(), o._r()))
        if isinstance(o, _MatBase):
            return NotImplemented
        v = Vector3._conv(o)
        if v is not None:
            return Vector3._new(_qrotate(self._r(), v))
        return NotImplemented

    def __imul__(self, o):
        if not isinstance(o, Quaternion):
            raise _argerr('Quaternion', '__imul__', (o,), ['__imul__(Quaternion, Quaternion)'])
        r = Quaternion._new(_qmul(self._r(), o._r()))
        self._w(r._v)
        return r

    def Rotate(self, v):
        b = Vector3._conv(v)
        if b is None:
            raise _argerr('Quaternion', 'Rotate', (v,), ['Rotate(Quaternion, Vector3)'])
        return Vector3._new(_qrotate(self._r(), b))

    def conjugate(self):
        w, x, y, z = self._r()
        return Quaternion._new([w, -x, -y, -z])

    def inverse(self):
        q = self._r()
        n2 = _qsqnorm(q)
        if n2 > 0:
            w, x, y, z = q
            return Quaternion._new([w / n2, -x / n2, -y / n2, -z / n2])
        return Quaternion._new([0.0, 0.0, 0.0, 0.0])

    def norm(self):
        return math.sqrt(_qsqnorm(self._r()))

    __abs__ = norm

    def normalized(self):
        q = self._r()
        n2 = _qsqnorm(q)
        if n2 > 0:
            n = math.sqrt(n2)
            return Quaternion._new([_div(c, n) for c in q])
        return Quaternion._new(list(q))

    def normalize(self):
        q = self._r()
        n2 = _qsqnorm(q)
        if n2 > 0:
            n = math.sqrt(n2)
            self._w([_div(c, n) for c in q])

    def toAxisAngle(self):
        angle, axis = _angle_axis(self._r())
        return (Vector3._new(axis), angle)

    def toAngleAxis(self):
        angle, axis = _angle_axis(self._r())
        return (angle, Vector3._new(axis))

    def toRotationVector(self):
        angle, axis = _angle_axis(self._r())
        return Vector3._new([angle * axis[0], angle * axis[1], angle * axis[2]])

    def _rotmat(self):
        w, x, y, z = self._r()
        tx = 2.0 * x
        ty = 2.0 * y
        tz = 2.0 * z
        twx = tx * w
        twy = ty * w
        twz = tz * w
        txx = tx * x
        txy = ty * x
        txz = tz * x
        tyy = ty * y
        tyz = tz * y
        tzz = tz * z
        return [1.0 - (tyy + tzz), txy - twz, txz + twy,
                txy + twz, 1.0 - (txx + tzz), tyz - twx,
                txz - twy, tyz + twx, 1.0 - (txx + tyy)]

    def toRotationMatrix(self):
        return Matrix3._new(self._rotmat())

    def angularDistance(self, other):
        if not isinstance(other, Quaternion):
            raise _argerr('Quaternion', 'angularDistance', (other,), ['angularDistance(Quaternion, Quaternion)'])
        d = _qmul(self._r(), other.conjugate()._v)
        return 2.0 * math.atan2(_norm3(d[1], d[2], d[3]), abs(d[0]))

    def slerp(self, t, other):
        tt = _tofloat(t)
        if tt is None or not isinstance(other, Quaternion):
            raise _argerr('Quaternion', 'slerp', (t, other), ['slerp(Quaternion, double t, Quaternion other)'])
        t = tt
        one = 1.0 - _EPS
        a = self._r()
        b = other._r()
        aw, ax, ay, az = a
        bw, bx, by, bz = b
        d = (ax * bx + ay * by) + (az * bz + aw * bw)
        abs_d = abs(d)
        if abs_d >= one:
            scale0 = 1.0 - t
            scale1 = t
        else:
            theta = _acos(abs_d)
            sin_theta = _sin(theta)
            scale0 = _div(_sin((1.0 - t) * theta), sin_theta)
            scale1 = _div(_sin(t * theta), sin_theta)
        if d < 0:
            scale1 = -scale1
        return Quaternion._new([scale0 * p + scale1 * q for p, q in zip(a, b)])

    def setFromTwoVectors(self, u, v):
        a = Vector3._conv(u)
        b = Vector3._conv(v)
        if a is None or b is None:
            raise _argerr('Quaternion', 'setFromTwoVectors', (u, v), ['setFromTwoVectors(Quaternion, Vector3 u, Vector3 v)'])
        self._w(_two_vectors(a, b))

    Identity = _ClassConst(lambda cls: cls._new([1.0, 0.0, 0.0, 0.0]))


def _install_fast_getitem():
    """`Vector3.__getitem__` in C when the yade package's extension is there (``v[2]`` is read
    everywhere in scripts): ``yade._ryade._install_vector_getitem`` gives a method descriptor doing
    what the Python definition does for an ``int`` index in 0..2 and calling that definition, kept
    as ``Vector3._py_getitem``, for anything else. Loaded standalone (no package), the module stays
    pure Python."""
    try:
        from ._ryade import _install_vector_getitem
    except ImportError:
        return
    py = Vector3.__dict__['__getitem__']
    fast = _install_vector_getitem(Vector3, Vector3._N)
    if fast is not None:
        Vector3._py_getitem = py
        Vector3.__getitem__ = fast


_install_fast_getitem()
