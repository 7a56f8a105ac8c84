"""`yade.pack` over ryade: `SpherePack` with `makeCloud` reproduced bit for bit by the Rust core; the solid
predicates of YADE's `_packPredicates` (inSphere, inAlignedBox, inCylinder and their boolean combinations)
and the regular packings `regularOrtho` / `regularHexa` clipped by them (py/pack/pack.py)."""

from . import _ryade, utils
from ._core import Omega, Sphere
from ._errors import unsupported
from .minieigen import Matrix3, Quaternion, Vector3, to_vec3

__all__ = ['SpherePack', 'Predicate', 'PredicateUnion', 'PredicateIntersection', 'PredicateDifference',
           'PredicateSymmetricDifference', 'inSphere', 'inAlignedBox', 'inCylinder', 'inEllipsoid',
           'inHyperboloid', 'inParallelepiped', 'notInNotch', 'inGtsSurface', 'regularOrtho', 'regularHexa',
           'arange', 'gtsSurface2Facets', 'sweptPolylines2gtsSurface', 'revolutionSurfaceMeridians', 'hexaNet']

import itertools as _itertools  # noqa: E402
import math as _math  # noqa: E402
import warnings as _warnings  # noqa: E402

try:
    from numpy import arange  # YADE's pack imports it, and its startup namespace has it from there
except ImportError:  # pragma: no cover
    def arange(*a, **k):
        unsupported('numpy.arange (numpy is not installed)')


class SpherePack(object):
    """A list of (center, radius) with an optional periodic cell (preprocessing/dem/SpherePack.cpp)."""

    def __init__(self, lst=None):
        self._sp = []
        self.cellSize = Vector3(0, 0, 0)
        self.isPeriodic = False
        self.appliedPsdScaling = 1.0
        if lst:
            for c, r in lst:
                self.add(c, r)

    def add(self, c, r):
        self._sp.append((to_vec3(c, 'center'), float(r)))

    def __len__(self):
        return len(self._sp)

    def __iter__(self):
        return iter([(Vector3(*c), r) for c, r in self._sp])

    def __getitem__(self, i):
        c, r = self._sp[i]
        return Vector3(*c), r

    def makeCloud(self, minCorner=Vector3(0, 0, 0), maxCorner=Vector3(0, 0, 0), rMean=-1, rRelFuzz=0, num=-1,
                  periodic=False, porosity=0.65, psdSizes=[], psdCumm=[], distributeMass=False, seed=-1,
                  hSize=Matrix3(0, 0, 0, 0, 0, 0, 0, 0, 0)):
        h = [[float(hSize[i, j]) for j in range(3)] for i in range(3)]
        h = None if all(x == 0.0 for row in h for x in row) else h
        cell = tuple(self.cellSize) if self.isPeriodic else None
        n, spheres, cell_size, is_periodic, scaling, warnings = _ryade.make_cloud(
            self._sp, cell, to_vec3(minCorner, 'minCorner'), to_vec3(maxCorner, 'maxCorner'), float(rMean),
            float(rRelFuzz), int(num), bool(periodic), float(porosity), [float(x) for x in psdSizes],
            [float(x) for x in psdCumm], bool(distributeMass), int(seed), h)
        for w in warnings:
            print('WARN  ' + w)
        self._sp = [(tuple(c), r) for c, r in spheres]
        if cell_size is not None:
            self.cellSize = Vector3(*cell_size)
        self.isPeriodic = is_periodic
        self.appliedPsdScaling = scaling
        return n

    def toSimulation(self, rot=Matrix3.Identity, **kw):
        if isinstance(rot, Quaternion):
            rot = rot.toRotationMatrix()
        O = Omega()
        if self.isPeriodic:
            O.periodic = True
        if self.cellSize != Vector3(0, 0, 0) and self.isPeriodic:
            O.cell.hSize = rot * Matrix3(self.cellSize[0], 0, 0, 0, self.cellSize[1], 0, 0, 0, self.cellSize[2])
        return O.bodies.append([utils.sphere(rot * c, r, **kw) for c, r in self])

    def fromSimulation(self):
        O = Omega()
        self._sp = [(tuple(b.state.pos), b.shape.radius) for b in O.bodies if isinstance(b.shape, Sphere)]
        if O.periodic:
            self.cellSize = O.cell.size
            self.isPeriodic = True
        return self

    def hasClumps(self):
        return False

    def aabb(self):
        lo = [min(c[i] - r for c, r in self._sp) for i in range(3)]
        hi = [max(c[i] + r for c, r in self._sp) for i in range(3)]
        return Vector3(*lo), Vector3(*hi)

    def dim(self):
        a, b = self.aabb()
        return b - a

    def center(self):
        a, b = self.aabb()
        return .5 * (a + b)

    def save(self, fileName):
        """Same text as YADE (C++ ostream default precision: 6 significant digits)."""
        with open(fileName, 'w') as f:
            if self.isPeriodic:
                f.write('##PERIODIC:: %s %s %s\n' % tuple(_g6(x) for x in self.cellSize))
            for c, r in self._sp:
                f.write('%s %s %s %s -1\n' % (_g6(c[0]), _g6(c[1]), _g6(c[2]), _g6(r)))

    def load(self, fileName):
        self._sp = []
        self.isPeriodic = False
        with open(fileName) as f:
            for line in f:
                t = line.split()
                if not t:
                    continue
                if t[0] == '##PERIODIC::':
                    self.cellSize = Vector3(*[float(x) for x in t[1:4]])
                    self.isPeriodic = True
                    continue
                if t[0].startswith('#'):
                    continue
                if len(t) > 4 and int(t[4]) >= 0:
                    unsupported('SpherePack.load of clumped spheres (clumpId %s in %s)' % (t[4], fileName))
                self._sp.append(((float(t[0]), float(t[1]), float(t[2])), float(t[3])))

    def toList(self):
        return [(Vector3(*c), r) for c, r in self._sp]

    def psd(self, bins=50, mass=True):
        """`SpherePack::psd` (preprocessing/dem/SpherePack.cpp): (bin edges of the diameters, cumulative
        fraction by mass or by number), with YADE's operation order."""
        if not self._sp:
            return ([], [])
        inf = float('inf')
        min_d, max_d, vol = inf, -inf, 0.0
        n = len(self._sp)
        for _, r in self._sp:
            max_d = max(2 * r, max_d)
            min_d = min(2 * r, min_d)
            vol += _math.pow(r, 3)
        if min_d == max_d:
            min_d -= .5
            max_d += .5
        bins = int(bins)
        hist = [0.0] * bins
        cumm = [0.0] * (bins + 1)
        edges = [min_d + i * (max_d - min_d) / bins for i in range(bins + 1)]
        for _, r in self._sp:
            b = min(int(bins * (2 * r - min_d) / (max_d - min_d)), bins - 1)
            hist[b] += _math.pow(r, 3) / vol if mass else 1. / n
        for i in range(bins):
            cumm[i + 1] = min(1., cumm[i] + hist[i])
        return (edges, cumm)

    def __getattr__(self, k):
        if k.startswith('_'):
            raise AttributeError(k)
        unsupported('SpherePack.%s' % k)


# ---------------------------------------------------------------- predicates (py/pack/_packPredicates.cpp)

def _v(x, what):
    return Vector3(*to_vec3(x, what))


def _cwise(f, a, b):
    return Vector3(*[f(a[i], b[i]) for i in range(3)])


def _min(a, b):  # std::min
    return b if b < a else a


def _max(a, b):  # std::max
    return b if a < b else a


class Predicate(object):
    """A solid: `p(pt, pad)` is True when `pt` lies inside, at least `pad` from the boundary; `aabb()` is its
    (min, max) box. `|`, `&`, `-`, `^` combine two predicates."""

    def __call__(self, pt, pad=0.):
        raise NotImplementedError

    def aabb(self):
        raise NotImplementedError

    def dim(self):
        mn, mx = self.aabb()
        return mx - mn

    def center(self):
        mn, mx = self.aabb()
        return .5 * (mn + mx)

    def __or__(self, other):
        return PredicateUnion(self, other)

    def __and__(self, other):
        return PredicateIntersection(self, other)

    def __sub__(self, other):
        return PredicateDifference(self, other)

    def __xor__(self, other):
        return PredicateSymmetricDifference(self, other)


class _PredicateBoolean(Predicate):
    def __init__(self, A, B):
        self.A, self.B = A, B

    def _boxes(self, lo, hi):
        """(lo of the two minima, hi of the two maxima), per coordinate."""
        (a0, a1), (b0, b1) = self.A.aabb(), self.B.aabb()
        return _cwise(lo, a0, b0), _cwise(hi, a1, b1)


class PredicateUnion(_PredicateBoolean):
    def __call__(self, pt, pad=0.):
        return self.A(pt, pad) or self.B(pt, pad)

    def aabb(self):
        return self._boxes(_min, _max)


class PredicateIntersection(_PredicateBoolean):
    def __call__(self, pt, pad=0.):
        return self.A(pt, pad) and self.B(pt, pad)

    def aabb(self):
        return self._boxes(_max, _min)


class PredicateDifference(_PredicateBoolean):
    def __call__(self, pt, pad=0.):
        return self.A(pt, pad) and not self.B(pt, -pad)

    def aabb(self):
        return self.A.aabb()


class PredicateSymmetricDifference(_PredicateBoolean):
    def __call__(self, pt, pad=0.):
        a, b = self.A(pt, pad), self.B(pt, pad)
        return a != b

    def aabb(self):
        return self._boxes(_min, _max)


class inSphere(Predicate):
    def __init__(self, center, radius):
        self._c, self._r = _v(center, 'center'), float(radius)

    def __call__(self, pt, pad=0.):
        return (_v(pt, 'pt') - self._c).norm() <= self._r - pad

    def aabb(self):
        c, r = self._c, self._r
        return Vector3(c[0] - r, c[1] - r, c[2] - r), Vector3(c[0] + r, c[1] + r, c[2] + r)


class inAlignedBox(Predicate):
    def __init__(self, minAABB, maxAABB):
        self._mn, self._mx = _v(minAABB, 'minAABB'), _v(maxAABB, 'maxAABB')

    def __call__(self, pt, pad=0.):
        p, mn, mx = _v(pt, 'pt'), self._mn, self._mx
        return all(mn[i] + pad <= p[i] and mx[i] - pad >= p[i] for i in range(3))

    def aabb(self):
        return Vector3(*self._mn), Vector3(*self._mx)


class inCylinder(Predicate):
    def __init__(self, centerBottom, centerTop, radius):
        self._c1, self._c2 = _v(centerBottom, 'centerBottom'), _v(centerTop, 'centerTop')
        self._c12 = self._c2 - self._c1
        self._r = float(radius)
        self._ht = self._c12.norm()

    def __call__(self, pt, pad=0.):
        p, ht = _v(pt, 'pt'), self._ht
        u = (p.dot(self._c12) - self._c1.dot(self._c12)) / (ht * ht)  # position along the axis, 0..1
        if u * ht < 0 + pad or u * ht > ht - pad:
            return False
        return not (p - self._c1).cross(p - self._c2).norm() / ht > self._r - pad

    def aabb(self):
        a, b, ht = self._c1, self._c2, self._ht
        k = Vector3(_math.sqrt((a[1] - b[1]) ** 2 + (a[2] - b[2]) ** 2) / ht,
                    _math.sqrt((a[0] - b[0]) ** 2 + (a[2] - b[2]) ** 2) / ht,
                    _math.sqrt((a[0] - b[0]) ** 2 + (a[1] - b[1]) ** 2) / ht)
        mn, mx = _cwise(_min, a, b), _cwise(_max, a, b)
        return mn - self._r * k, mx + self._r * k


def _csqrt(x):
    """C's sqrt: NaN for a negative argument (Python's raises)."""
    return _math.sqrt(x) if x >= 0 else float('nan')


class inEllipsoid(Predicate):
    """_packPredicates.cpp inEllipsoid (axis-aligned, center c, semi-axes abc). YADE's test, kept on
    purpose: pt is inside when |pt - c| <= |e - c| for the point e of the (padded) ellipsoid's surface
    with pt's y and z (no such point: outside)."""

    def __init__(self, centerPoint, abc):
        self._c, self._abc = _v(centerPoint, 'centerPoint'), _v(abc, 'abc')

    def __call__(self, pt, pad=0.):
        p, c, abc = _v(pt, 'pt'), self._c, self._abc
        pw = _math.pow
        x = _csqrt((1 - pw(p[1] - c[1], 2) / ((abc[1] - pad) * (abc[1] - pad))
                    - pw(p[2] - c[2], 2) / ((abc[2] - pad) * (abc[2] - pad))) * ((abc[0] - pad) * (abc[0] - pad))) + c[0]
        return (p - c).norm() <= (Vector3(x, p[1], p[2]) - c).norm()

    def aabb(self):
        c, abc = self._c, self._abc
        return (Vector3(c[0] - abc[0], c[1] - abc[1], c[2] - abc[2]), Vector3(c[0] + abc[0], c[1] + abc[1], c[2] + abc[2]))


class inHyperboloid(Predicate):
    """_packPredicates.cpp inHyperboloid: a hyperboloid of one sheet between centers c1 and c2, radius R
    at the ends and r at the waist (pad taken perpendicular to the axis, as YADE does)."""

    def __init__(self, centerBottom, centerTop, radius, skirt):
        self._c1, self._c2 = _v(centerBottom, 'centerBottom'), _v(centerTop, 'centerTop')
        self._R, self._a = float(radius), float(skirt)
        self._c12 = self._c2 - self._c1
        self._ht = self._c12.norm()
        self._c = self._ht / (2 * _csqrt(_math.pow(self._R / self._a, 2) - 1))

    def __call__(self, pt, pad=0.):
        p, ht = _v(pt, 'pt'), self._ht
        v = (p.dot(self._c12) - self._c1.dot(self._c12)) / (ht * ht)
        if v * ht < 0 + pad or v * ht > ht - pad:
            return False
        u = (v - .5) * ht / self._c
        r_here = self._a * _csqrt(1 + u * u)
        return not ((p - self._c1).cross(p - self._c2).norm() / ht > r_here - pad)

    def aabb(self):
        return inCylinder(self._c1, self._c2, self._R).aabb()


class inParallelepiped(Predicate):
    """_packPredicates.cpp inParallelepiped: the parallelepiped with corner o and edges to a, b, c."""

    def __init__(self, o, a, b, c):
        o, a, b, c = (_v(x, k) for x, k in ((o, 'o'), (a, 'a'), (b, 'b'), (c, 'c')))
        A, B, C, D, E, F, G, H = o, a, a + (b - o), b, c, c + (a - o), c + (a - o) + (b - o), c + (b - o)
        x, y, z = B - A, D - A, E - A
        n0, n2, n4 = -y.cross(z).normalized(), -z.cross(x).normalized(), -x.cross(y).normalized()
        self._planes = ((n0, A), (-n0, B), (n2, A), (-n2, D), (n4, A), (-n4, E))
        mn, mx = Vector3(A), Vector3(A)
        for q in (B, C, D, E, F, G, H):
            mn, mx = _cwise(_min, mn, q), _cwise(_max, mx, q)
        self._mn, self._mx = mn, mx

    def __call__(self, pt, pad=0.):
        p = _v(pt, 'pt')
        return not any((p - q).dot(n) > -pad for n, q in self._planes)

    def aabb(self):
        return Vector3(self._mn), Vector3(self._mx)


class notInNotch(Predicate):
    """_packPredicates.cpp notInNotch: everything but a notch (edge direction, opening `normal`, width
    `aperture`) cut from `centerPoint`; unbounded. YADE's test for a point below the notch uses the distance
    above it (distUp), kept on purpose."""

    def __init__(self, centerPoint, edge, normal, aperture):
        self._c = _v(centerPoint, 'centerPoint')
        e = _v(edge, 'edge').normalized()
        n = _v(normal, 'normal')
        n = (n - e * e.dot(n)).normalized()
        self._edge, self._normal, self._inside = e, n, e.cross(n)
        self._aperture = float(aperture)

    def __call__(self, pt, pad=0.):
        d = _v(pt, 'pt') - self._c
        up = self._normal.dot(d) - self._aperture / 2
        down = -self._normal.dot(d) - self._aperture / 2
        in_plane = -self._inside.dot(d)
        if in_plane >= pad or up >= pad or down >= pad:
            return True
        if in_plane < 0:
            return False
        if up > 0 or down > 0:
            return _math.sqrt(_math.pow(in_plane, 2) + _math.pow(up, 2)) >= pad
        return False

    def aabb(self):
        inf = float('inf')
        return Vector3(-inf, -inf, -inf), Vector3(inf, inf, inf)


def _orient3d(a, b, c, d):
    """Shewchuk's orient3d sign (as GTS's gts_point_orientation_3d): the sign of det[a-d; b-d; c-d],
    exact (a float estimate, redone in rationals when it is within its error bound of zero)."""
    adx, ady, adz = a.x - d.x, a.y - d.y, a.z - d.z
    bdx, bdy, bdz = b.x - d.x, b.y - d.y, b.z - d.z
    cdx, cdy, cdz = c.x - d.x, c.y - d.y, c.z - d.z
    det = adx * (bdy * cdz - bdz * cdy) + bdx * (cdy * adz - cdz * ady) + cdx * (ady * bdz - adz * bdy)
    perm = (abs(adx) * (abs(bdy * cdz) + abs(bdz * cdy)) + abs(bdx) * (abs(cdy * adz) + abs(cdz * ady))
            + abs(cdx) * (abs(ady * bdz) + abs(adz * bdy)))
    if abs(det) > 1e-14 * perm:
        return 1 if det > 0 else -1
    from fractions import Fraction as F
    ax, ay, az = (F(a.x) - F(d.x), F(a.y) - F(d.y), F(a.z) - F(d.z))
    bx, by, bz = (F(b.x) - F(d.x), F(b.y) - F(d.y), F(b.z) - F(d.z))
    cx, cy, cz = (F(c.x) - F(d.x), F(c.y) - F(d.y), F(c.z) - F(d.z))
    e = ax * (by * cz - bz * cy) + bx * (cy * az - cz * ay) + cx * (ay * bz - az * by)
    return (e > 0) - (e < 0)


def _ray_crosses(D, E, tri):
    """GTS's ray_intersects_triangle (surface.c): does segment D-E cross triangle tri (its oriented
    vertices A, B, C)? Exact orientations; a zero one (the segment touching an edge or a vertex, where
    GTS breaks the tie by the objects' memory addresses) counts as a crossing here."""
    A, B, C = tri
    abce, abcd = _orient3d(A, B, C, E), _orient3d(A, B, C, D)
    if abce < 0 or abcd > 0:
        D, E, abce, abcd = E, D, abcd, abce
    if abce < 0 or abcd > 0:
        return False
    return _orient3d(A, D, C, E) >= 0 and _orient3d(A, B, D, E) >= 0 and _orient3d(B, C, D, E) >= 0


class inGtsSurface(Predicate):
    """_packPredicates.cpp inGtsSurface: inside the closed GTS surface `surface` (GTS's
    gts_point_is_inside_surface: the parity of the crossings of a ray shot in +z from the point; an
    "open" surface, of negative volume, inverts it); with a pad, the six points at +-pad along the axes
    must be inside too, unless `noPad`."""

    def __init__(self, surface, noPad=False):
        surf = surface
        if not surf.is_closed():
            raise ValueError('Surface is not closed.')
        self._surf, self._noPad = surf, bool(noPad)
        self._open = surf.volume() < 0.
        self._tris = []
        for f in surf.faces():
            vs = f.vertices()
            xs, ys, zs = [v.x for v in vs], [v.y for v in vs], [v.z for v in vs]
            self._tris.append((vs, min(xs), max(xs), min(ys), max(ys), max(zs)))
        self._ztop = max(t[5] for t in self._tris)

    def surface(self):
        return self._surf

    def _check(self, p):
        class _P(object):
            __slots__ = ('x', 'y', 'z')

            def __init__(self, x, y, z):
                self.x, self.y, self.z = x, y, z
        D, E = _P(p[0], p[1], p[2]), _P(p[0], p[1], self._ztop + abs(self._ztop) / 10.)
        n = 0
        for vs, x1, x2, y1, y2, z2 in self._tris:  # gts_bbox_is_stabbed by the +z ray, then the exact test
            if x1 <= D.x <= x2 and y1 <= D.y <= y2 and D.z <= z2 and _ray_crosses(D, E, vs):
                n += 1
        return (n % 2 == 0) if self._open else (n % 2 != 0)

    def __call__(self, pt, pad=0.):
        p = _v(pt, 'pt')
        if self._noPad:
            return self._check(p)
        return all(self._check(q) for q in (p, p - Vector3(pad, 0, 0), p + Vector3(pad, 0, 0), p - Vector3(0, pad, 0),
                                             p + Vector3(0, pad, 0), p - Vector3(0, 0, pad), p + Vector3(0, 0, pad)))

    def aabb(self):
        inf = float('inf')
        mn, mx = Vector3(inf, inf, inf), Vector3(-inf, -inf, -inf)
        for v in self._surf.vertices():
            q = Vector3(v.x, v.y, v.z)
            mn, mx = _cwise(_min, mn, q), _cwise(_max, mx, q)
        return mn, mx


# ---------------------------------------------------------------- regular packings (py/pack/pack.py)

def _finite_aabb(predicate):
    mn, mx = predicate.aabb()
    if max(mx[i] - mn[i] for i in range(3)) == float('inf'):
        raise ValueError('Aabb of the predicate must not be infinite (an unbounded predicate joined with | '
                         'instead of intersected with &?)')
    return mn, mx


def regularOrtho(predicate, radius, gap, **kw):
    """Spheres of `radius` on an orthogonal grid of spacing 2 radius + gap inside `predicate`."""
    mn, mx = _finite_aabb(predicate)
    axes = [arange(mn[i] + radius, mx[i] - radius, 2 * radius + gap) for i in range(3)]
    ret = [utils.sphere(xyz, radius=radius, **kw) for xyz in _itertools.product(*axes) if predicate(xyz, radius)]
    if not ret:
        _warnings.warn('No spheres are produced by regularOrtho-function', category=RuntimeWarning)
    return ret


def regularHexa(predicate, radius, gap, **kw):
    """Spheres of `radius` on a hexagonal close-packed lattice (spacing 2 radius + gap) inside `predicate`."""
    a = 2 * radius + gap
    hy, hz = a * _math.sqrt(3) / 2., a * _math.sqrt(6) / 3.
    mn, mx = _finite_aabb(predicate)
    dim = [mx[i] - mn[i] for i in range(3)]
    ret = []
    for i, j, k in _itertools.product(range(int(dim[0] / a) + 1), range(int(dim[1] / hy) + 1),
                                      range(int(dim[2] / hz) + 1)):
        # simple hcp lattice: layers shifted by half a spacing in x, and by a third of a row in y
        c = Vector3(2 * i + (j + k) % 2, _math.sqrt(3.) * (j + 1. / 3. * (k % 2)),
                    2. * _math.sqrt(6.) / 3. * k) * (a / 2.0) + mn
        if predicate(c, radius):
            ret.append(utils.sphere(c, radius=radius, **kw))
    if not ret:
        _warnings.warn('No spheres are produced by regularHexa-function', category=RuntimeWarning)
    return ret


# ---------------------------------------------------------------- GTS surfaces (py/pack/pack.py)

def _gts():
    """PyGTS when importable (YADE's), else ryade's stand-in (yade/_gts.py)."""
    try:
        import gts
    except ImportError:
        from . import _gts as gts
    return gts


def gtsSurface2Facets(surf, **kw):
    """A facet (utils.facet, given **kw) per face of the GTS surface `surf`, with the face's oriented
    vertices, in the surface's face order."""
    return [utils.facet([v.coords() for v in face.vertices()], **kw) for face in surf.faces()]


def sweptPolylines2gtsSurface(pts, threshold=0, capStart=False, capEnd=False):
    """The GTS surface swept by the polylines `pts` (all of the same length): between consecutive
    polylines, two triangles per segment, cut along the diagonal from point j of one to point j+1 of
    the next; `capStart`/`capEnd` close the first/last polyline by a fan of triangles from its first
    point. With `threshold` > 0, faces with an edge shorter than it are not made and the surface is
    cleaned up (vertices closer than it merged) at the end, as YADE's pack.py does."""
    gts = _gts()
    if len(set(len(line) for line in pts)) != 1:
        raise RuntimeError("Polylines must be all of the same length!")
    vtx = [[gts.Vertex(x, y, z) for x, y, z in line] for line in pts]
    n = len(vtx[0])
    # along[i][j]: point j to j+1 of polyline i; across[i][2j]: point j of line i to point j of line i+1,
    # across[i][2j+1]: point j of line i to point j+1 of line i+1 (the diagonal)
    along = [[gts.Edge(line[j], line[j + 1]) for j in range(n - 1)] for line in vtx]
    across = []
    for i in range(len(vtx) - 1):
        row = []
        for j in range(n):
            row.append(gts.Edge(vtx[i][j], vtx[i + 1][j]))
            if j < n - 1:
                row.append(gts.Edge(vtx[i][j], vtx[i + 1][j + 1]))
        across.append(row)
    if threshold > 0:  # an edge shorter than threshold becomes None: its faces are skipped
        for row in along + across:
            for k, e in enumerate(row):
                if (Vector3(e.v1.x, e.v1.y, e.v1.z) - Vector3(e.v2.x, e.v2.y, e.v2.z)).norm() < threshold:
                    row[k] = None
    surf = gts.Surface()
    for i in range(len(vtx) - 1):
        for j in range(n - 1):
            for tri in ((across[i][2 * j + 1], along[i + 1][j], across[i][2 * j]),
                        (along[i][j], across[i][2 * j + 2], across[i][2 * j + 1])):
                if None not in tri:
                    surf.add(gts.Face(*tri))

    def cap(line, edges, start):
        fan = [edges[0]] + [gts.Edge(line[k], line[0]) for k in range(2, len(line))]
        return [gts.Face(fan[k - 1], fan[k], edges[k]) if start else gts.Face(fan[k - 1], edges[k], fan[k])
                for k in range(1, len(edges))]

    caps = (cap(vtx[0], along[0], True) if capStart else []) + (cap(vtx[-1], along[-1], False) if capEnd else [])
    for f in caps:
        surf.add(f)
    if threshold > 0:
        surf.cleanup(threshold)
    return surf


def revolutionSurfaceMeridians(sects, angles, origin=Vector3.Zero, orientation=Quaternion.Identity):
    """The meridians of a surface of revolution: section i (2d points (r, z)) turned about the z axis by
    angles[i], then placed by `orientation` and `origin`; a list of lists of 3-tuples."""
    def place(x, y, z):
        return tuple(origin + orientation * Vector3(x, y, z))
    return [[place(r * _math.cos(angles[i]), r * _math.sin(angles[i]), z) for r, z in sects[i]]
            for i in range(len(sects))]


def hexaNet(radius, cornerCoord=[0, 0, 0], xLength=1., yLength=0.5, mos=0.08, a=0.04, b=0.04, startAtCorner=True,
            isSymmetric=False, **kw):
    """The spheres of a hexagonal wire net in the x-y plane for WireMatPM (py/pack/pack.py hexaNet): double
    twists of length `a` every `mos` along x, rows `a` + `b` apart along y, corner particles first;
    returns [spheres, lx, ly] (the net's exact size). **kw goes to utils.sphere."""
    if xLength < mos:
        raise ValueError("xLength must be greater than mos!")
    if yLength < 2 * a + b:
        raise ValueError("yLength must be greater than 2*a+b!")
    x0, y0, z = cornerCoord[0], cornerCoord[1], cornerCoord[2]
    ab = a + b
    ny = int((yLength - a) / ab) + 1
    ly = ny * a + (ny - 1) * b
    jump = 0
    if isSymmetric:
        nx = int(xLength / mos) + 1
        lx = (nx - 1) * mos
        if not startAtCorner:
            nx += -1
    else:
        nx = int((xLength - 0.5 * mos) / mos) + 1
        lx = (nx - 1) * mos + 0.5 * mos

    def at(x, y):
        return utils.sphere((x, y, z), radius=radius, **kw)
    lower_left, upper_left = (x0, y0), (x0, y0 + ly)
    lower_right, upper_right = (x0 + lx, y0), (x0 + lx, y0 + ly)
    even = ny % 2 == 0  # an even number of rows: no symmetry in y
    if startAtCorner:
        if even:
            corners = [upper_left, upper_right if isSymmetric else lower_right]
        else:
            corners = [] if isSymmetric else [lower_right, upper_right]
        jump = 1
    else:
        if even:
            corners = [lower_left, lower_right if isSymmetric else upper_right]
        else:
            corners = [lower_left, upper_left] + ([lower_right, upper_right] if isSymmetric else [])
        x0 += 0.5 * mos
    net = [at(*c) for c in corners]
    for i in range(ny):
        y = y0 + i * ab
        for j in range(nx):
            x = x0 + j * mos
            net += [at(x, y), at(x, y + a)]  # one double twist
        # the next row starts half a mesh to the other side (and, symmetric, has one twist more or less)
        x0 = x0 - 0.5 * mos * pow(-1, i + jump)
        if isSymmetric:
            nx = int(nx + 1 * pow(-1, i + jump))
    return [net, lx, ly]


def _g6(x):
    """C++ `ostream << double` with the default precision (6 significant digits, %g style)."""
    return '%g' % x


def __getattr__(name):
    if name.startswith('__'):
        raise AttributeError(name)
    unsupported('yade.pack.%s' % name)
