"""Tests of yade.minieigen (pure-Python minieigen) against YADE 2023.02a.

The expected values in data/minieigen_expect.json come from
``yade -n -x yade_ref/compat/minieigen_ref.py`` (YADE's own yade.minieigenHP): for every
expression the repr of the result (or ERROR:<ExceptionType>) and the exact bits of every float
in it.  Here the same expressions are evaluated with yade.minieigen and must agree exactly.
The live-view tests at the end use a fake engine getter/setter.
"""
import copy
import json
import math
import os
import pickle
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, '..', 'python'))



def _load_minieigen():
    """yade.minieigen; loaded from its file if the yade package itself cannot be imported
    (e.g. the native extension is not built): the module has no dependencies."""
    try:
        from yade import minieigen
        return minieigen
    except Exception:  # noqa: BLE001
        import importlib.util
        path = os.path.join(HERE, '..', 'python', 'yade', 'minieigen.py')
        spec = importlib.util.spec_from_file_location('_minieigen_standalone', path)
        mod = importlib.util.module_from_spec(spec)
        sys.modules[spec.name] = mod          # so that pickling finds the classes
        spec.loader.exec_module(mod)
        return mod


me = _load_minieigen()
Matrix3, Matrix6, Quaternion = me.Matrix3, me.Matrix6, me.Quaternion
Vector2, Vector2i, Vector3, Vector3i, Vector6 = me.Vector2, me.Vector2i, me.Vector3, me.Vector3i, me.Vector6
to_vec3 = me.to_vec3

with open(os.path.join(HERE, 'data', 'minieigen_expect.json')) as _f:
    EXPECT = json.load(_f)

ORDER = EXPECT['order']


def floats_of(r):
    """Every float in a result as float.hex ('nan'/'-nan' keep the sign); same as the ref script."""
    if isinstance(r, bool) or isinstance(r, int) or isinstance(r, str) or r is None:
        return []
    if isinstance(r, float):
        if r != r:
            return ['-nan' if math.copysign(1.0, r) < 0 else 'nan']
        return [r.hex()]
    if isinstance(r, (tuple, list)):
        return [h for x in r for h in floats_of(x)]
    name = type(r).__name__
    if name.startswith(('Vector', 'Matrix', 'Quaternion')):
        return [h for x in r for h in floats_of(x)]
    return []


def evaluate(expr):
    ns = {'math': math, 'pickle': pickle, 'copy': copy}
    ns.update((k, getattr(me, k)) for k in me.__all__)      # = from yade.minieigen import *
    parts = expr.split(';')
    for stmt in parts[:-1]:
        exec(stmt.strip(), ns)
    return eval(parts[-1].strip(), ns)


# Deliberate, documented differences from YADE: expr -> (what yade.minieigen gives, why).
KNOWN_DIFFERENT = {
    'Vector3(1,2,3).norm(1)': (
        'ERROR:TypeError',
        'a wrong number of arguments to a method raises plain TypeError (Python\'s own), not '
        'Boost.Python\'s ArgumentError, which is a TypeError subclass'),
}


def test_battery_size():
    assert len(ORDER) >= 60
    assert len(ORDER) == len(EXPECT['results'])


@pytest.mark.parametrize('expr', ORDER)
def test_against_yade(expr):
    want = EXPECT['results'][expr]
    if expr in KNOWN_DIFFERENT:
        want = KNOWN_DIFFERENT[expr][0]
    try:
        r = evaluate(expr)
    except Exception as ex:  # noqa: BLE001 - the exception type is what is compared
        got = 'ERROR:' + type(ex).__name__
        assert got == want, '%s raised %r' % (expr, ex)
        return
    got = repr(r)
    assert got == want
    assert floats_of(r) == EXPECT['floats'].get(expr, [])


# ----------------------------------------------------------------------------
# exact evaluation-order checks that do not need YADE
# ----------------------------------------------------------------------------

def test_norm_evaluation_order_bitwise():
    x, y, z = 1.0, 1e-16, 1e-16          # left-to-right would lose both small terms
    v = Vector3(x, y, z)
    assert v.squaredNorm() == x * x + (y * y + z * z)
    assert v.dot(Vector3(1.0, 1.0, 1.0)) == x + (y + z)
    assert v.dot(Vector3(1.0, 1.0, 1.0)) != (x + y) + z
    q = Quaternion(0.7, 0.1, 0.2, 0.3)   # coefficients x, y, z, w = 0.1, 0.2, 0.3, 0.7
    assert q.norm() == math.sqrt((0.1 * 0.1 + 0.2 * 0.2) + (0.3 * 0.3 + 0.7 * 0.7))


def test_normalize_divides():
    v = Vector3(0.1, 0.2, 0.3)
    n = math.sqrt(0.1 * 0.1 + (0.2 * 0.2 + 0.3 * 0.3))
    v.normalize()
    assert list(v) == [0.1 / n, 0.2 / n, 0.3 / n]


def test_quaternion_product_order():
    a = Quaternion(0.3, -0.1, 0.7, 0.2)
    b = Quaternion(-0.6, 0.25, 0.1, 0.9)
    aw, ax, ay, az = 0.3, -0.1, 0.7, 0.2
    bw, bx, by, bz = -0.6, 0.25, 0.1, 0.9
    p = a * b
    assert list(p) == [aw * bx + ax * bw + ay * bz - az * by,
                       aw * by + ay * bw + az * bx - ax * bz,
                       aw * bz + az * bw + ax * by - ay * bx,
                       aw * bw - ax * bx - ay * by - az * bz]


def test_matrix_vector_order():
    m = Matrix3(1.0, 1e-16, 1e-16, 0, 1, 0, 0, 0, 1)
    v = m * Vector3(1, 1, 1)
    assert v[0] == 1.0 + (1e-16 + 1e-16)


# ----------------------------------------------------------------------------
# live views
# ----------------------------------------------------------------------------

class FakeEngine:
    """Holds values the way the Rust engine would; counts accesses."""

    def __init__(self, value):
        self.value = tuple(value)
        self.gets = 0
        self.sets = []

    def get(self):
        self.gets += 1
        return self.value

    def set(self, t):
        assert isinstance(t, tuple)
        self.sets.append(t)
        self.value = tuple(t)


def test_view_reads_through():
    e = FakeEngine((1.0, 2.0, 3.0))
    v = Vector3._view(e.get, e.set)
    assert isinstance(v, Vector3) and type(v) is Vector3
    assert repr(v) == 'Vector3(1,2,3)'
    e.value = (4.0, 5.0, 6.0)              # engine moved on: the view follows
    assert v[0] == 4.0 and list(v) == [4.0, 5.0, 6.0]
    assert v == Vector3(4, 5, 6)
    assert v.norm() == Vector3(4, 5, 6).norm()
    assert str(v) == 'Vector3(4,5,6)'
    assert len(v) == 3


def test_view_item_assignment_writes_through():
    e = FakeEngine((0.0, 0.0, 0.0))
    vel = Vector3._view(e.get, e.set)
    vel[2] = 0.1                            # b.state.vel[2] = 0.1
    assert e.value == (0.0, 0.0, 0.1)
    v = vel                                 # v = s.vel; v[0] = 5
    v[0] = 5
    assert e.value == (5.0, 0.0, 0.1)
    assert all(type(x) is float for x in e.value)
    with pytest.raises(IndexError):
        vel[3] = 1.0
    with pytest.raises(IndexError):
        vel[-1] = 1.0
    with pytest.raises(TypeError):
        vel[0] = 'x'
    assert e.value == (5.0, 0.0, 0.1)


def test_view_inplace_ops_write_through():
    e = FakeEngine((1.0, 2.0, 3.0))
    v = Vector3._view(e.get, e.set)
    alias = v
    v += Vector3(1, 1, 1)
    assert e.value == (2.0, 3.0, 4.0)
    assert alias == Vector3(2, 3, 4)
    # YADE: `a += b` modifies the object in place but rebinds `a` to a new, equal object
    # (`a is alias` is False there too), so `v` is now a plain copy and `alias` is still the view
    assert v is not alias and not v._is_view and alias._is_view
    e.value = (2.0, 3.0, 4.5)
    assert alias[2] == 4.5 and v[2] == 4.0
    e.value = (2.0, 3.0, 4.0)
    w = Vector3._view(e.get, e.set)
    w -= (0.5, 0.5, 0.5)
    assert e.value == (1.5, 2.5, 3.5)
    w = Vector3._view(e.get, e.set)
    w *= 2
    assert e.value == (3.0, 5.0, 7.0)
    w = Vector3._view(e.get, e.set)
    w /= 2
    assert e.value == (1.5, 2.5, 3.5)
    w = Vector3._view(e.get, e.set)
    w.normalize()
    n = Vector3(1.5, 2.5, 3.5).normalized()
    assert e.value == tuple(n)


def test_view_arithmetic_returns_plain():
    e = FakeEngine((1.0, 2.0, 3.0))
    v = Vector3._view(e.get, e.set)
    for r in (v + (1, 1, 1), v - v, v * 2, 2 * v, v / 2, -v, v.normalized(), v.cross((0, 0, 1)),
              copy.copy(v), copy.deepcopy(v), pickle.loads(pickle.dumps(v))):
        assert type(r) is Vector3 and not r._is_view
    c = v + (1, 1, 1)
    c[0] = 100
    assert e.value == (1.0, 2.0, 3.0)
    assert e.sets == []
    assert v.__reduce__()[1] == (1.0, 2.0, 3.0)


def test_view_other_types():
    eq = FakeEngine((1.0, 0.0, 0.0, 0.0))          # (w, x, y, z)
    q = Quaternion._view(eq.get, eq.set)
    assert repr(q) == 'Quaternion((1,0,0),0)'
    q[3] = 0.5                                     # index 3 is w
    assert eq.value == (0.5, 0.0, 0.0, 0.0)
    q[0] = 0.5                                     # index 0 is x
    assert eq.value == (0.5, 0.5, 0.0, 0.0)
    q.normalize()
    assert eq.value == tuple(Quaternion(0.5, 0.5, 0, 0).normalized().__reduce__()[1])
    q *= Quaternion((0, 0, 1), 0.3)
    assert len(eq.sets) == 4
    assert type(q * Vector3(1, 0, 0)) is Vector3

    ei = FakeEngine((1, 2, 3))
    vi = Vector3i._view(ei.get, ei.set)
    vi[1] = 7
    assert ei.value == (1, 7, 3) and type(ei.value[1]) is int
    vi += (1, 1, 1)
    assert ei.value == (2, 8, 4)

    em = FakeEngine((1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0))  # row-major
    m = Matrix3._view(em.get, em.set)
    m[0, 1] = 5
    assert em.value == (1.0, 5.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)
    m[2] = (7, 8, 9)
    assert em.value[6:] == (7.0, 8.0, 9.0)
    row = m[0]                       # rows are copies, as in minieigen
    row[0] = 42
    assert em.value[0] == 1.0
    m2 = m
    m *= 2
    assert em.value[1] == 10.0
    # as in YADE, an in-place operator returns a new (plain) object: m is rebound, m2 stays a view
    assert not m._is_view and m2._is_view
    m = m2
    em.value = ((1.0, 2.0, 3.0), (4.0, 5.0, 6.0), (7.0, 8.0, 9.0))   # nested rows are accepted
    assert m == Matrix3(1, 2, 3, 4, 5, 6, 7, 8, 9)
    assert m.trace() == 15.0


def test_class_constants_are_fresh():
    z = Vector3.Zero
    z[0] = 1
    assert Vector3.Zero == Vector3(0, 0, 0)
    i = Matrix3.Identity
    i[0, 0] = 5
    assert Matrix3.Identity[0, 0] == 1.0
    q = Quaternion.Identity
    q[0] = 3
    assert list(Quaternion.Identity) == [0.0, 0.0, 0.0, 1.0]


def test_to_vec3():
    assert to_vec3((1, 2, 3), 'pos') == (1.0, 2.0, 3.0)
    assert to_vec3([1.5, 2, True], 'pos') == (1.5, 2.0, 1.0)
    assert to_vec3(Vector3(1, 2, 3), 'pos') == (1.0, 2.0, 3.0)
    assert to_vec3(Vector3i(1, 2, 3), 'pos') == (1.0, 2.0, 3.0)
    r = to_vec3(range(3), 'pos')
    assert r == (0.0, 1.0, 2.0) and all(type(x) is float for x in r)
    for bad in ((1, 2), (1, 2, 3, 4), 'abc', None, 5, (1, 'a', 3), {1: 2}, Matrix3.Identity):
        with pytest.raises(TypeError) as ei:
            to_vec3(bad, 'State.pos')
        assert 'State.pos' in str(ei.value)


def test_to_vec3_numpy():
    np = pytest.importorskip('numpy')
    assert to_vec3(np.array([1.0, 2.0, 3.0]), 'x') == (1.0, 2.0, 3.0)
    assert Vector3(np.array([1, 2, 3])) == Vector3(1, 2, 3)
    assert Vector3(1, 2, 3) * np.float64(0.5) == Vector3(0.5, 1, 1.5)
    assert Vector3(1, 2, 3) == np.array([1.0, 2.0, 3.0]).tolist()


def test_argument_error_is_type_error():
    assert issubclass(me.ArgumentError, TypeError)
    with pytest.raises(TypeError):
        Vector3('abc')


def test_not_implemented_decompositions():
    with pytest.raises(NotImplementedError):
        Matrix3.Identity.svd()


def test_public_names():
    names = set(me.__all__)
    assert {'Vector2', 'Vector2i', 'Vector3', 'Vector3i', 'Vector6', 'Quaternion', 'Matrix3',
            'Matrix6'} <= names
    assert Vector2(1, 2) == Vector2i(1, 2)
    assert Matrix6.Identity * Vector6.Ones == Vector6.Ones
