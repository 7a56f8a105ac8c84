"""A stand-in for PyGTS (the `gts` module YADE's Python ships, py/3rd-party/pygts-0.3.1 over the GNU
Triangulated Surface library): the triangulated-surface objects YADE's `pack` and its example scripts
use (Vertex, Edge, Face, Surface with add / faces / vertices / edges / area / volume / is_closed /
cleanup / translate / scale / rotate / write, and `read` of GTS files), in pure Python.

A deliberate difference: GTS keeps a surface's faces and vertices in hash tables keyed by their memory
addresses, so YADE lists them (`Surface.faces()`, hence the ids of `pack.gtsSurface2Facets`' facets, and
which vertex survives `cleanup`) in an order that changes from run to run. This stand-in keeps them in
insertion order. As PyGTS, an Edge between two vertices an Edge already joins is that Edge, and a Face on
three edges a Face already uses is that Face (so `pack.sweptPolylines2gtsSurface` of one polyline capped
at both ends has the start cap's faces only, as in YADE). Anything of PyGTS not listed above fails with ryade's does-not-support error.

`import gts` finds this module under `compat run` (yade/_fallback/gts.py), and yade.pack uses it when
no real PyGTS is importable.
"""

import math

from ._errors import unsupported

__all__ = ['Point', 'Vertex', 'Segment', 'Edge', 'Triangle', 'Face', 'Surface', 'read']


class Object(object):
    @property
    def id(self):
        return id(self)

    def is_unattached(self):
        return False


def _transform(p, m):
    """gts_point_transform (GTS point.c): p <- m p with the 3x4 affine matrix m, in GTS's sum order."""
    x = m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3]
    y = m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3]
    z = m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]
    p.x, p.y, p.z = x, y, z


def _rotation(dx, dy, dz, a):
    """gts_matrix_rotate (GTS matrix.c): the axis normalised (when not zero), then Rodrigues' matrix with
    c = cos a, c1 = 1 - c, s = sin a."""
    n = math.sqrt(dx * dx + dy * dy + dz * dz)
    if n > 0.:
        dx, dy, dz = dx / n, dy / n, dz / n
    c, s = math.cos(a), math.sin(a)
    c1 = 1. - c
    return ((dx * dx * c1 + c, dx * dy * c1 - dz * s, dx * dz * c1 + dy * s, 0.),
            (dy * dx * c1 + dz * s, dy * dy * c1 + c, dy * dz * c1 - dx * s, 0.),
            (dz * dx * c1 - dy * s, dz * dy * c1 + dx * s, dz * dz * c1 + c, 0.))


def _scaling(dx, dy, dz):
    return ((dx, 0., 0., 0.), (0., dy, 0., 0.), (0., 0., dz, 0.))


def _translation(dx, dy, dz):
    return ((1., 0., 0., dx), (0., 1., 0., dy), (0., 0., 1., dz))


class Point(Object):
    """A point (x, y, z)."""

    def __init__(self, x=0, y=0, z=0):
        self.x, self.y, self.z = float(x), float(y), float(z)

    def coords(self):
        return (self.x, self.y, self.z)

    def set(self, x=0, y=0, z=0):
        self.x, self.y, self.z = float(x), float(y), float(z)

    def __getitem__(self, i):
        return self.coords()[i]

    def __len__(self):
        return 3

    def __iter__(self):
        return iter(self.coords())

    def distance2(self, p):
        dx, dy, dz = self.x - p.x, self.y - p.y, self.z - p.z
        return dx * dx + dy * dy + dz * dz

    def distance(self, p):
        return math.sqrt(self.distance2(p))

    def translate(self, dx=0, dy=0, dz=0):
        _transform(self, _translation(float(dx), float(dy), float(dz)))

    def scale(self, dx=1, dy=1, dz=1):
        _transform(self, _scaling(float(dx), float(dy), float(dz)))

    def rotate(self, dx=0, dy=0, dz=0, a=0):
        _transform(self, _rotation(float(dx), float(dy), float(dz), float(a)))

    def __repr__(self):
        return '<%s object at %#x (%g, %g, %g)>' % (type(self).__name__, id(self), self.x, self.y, self.z)


class Vertex(Point):
    """A point that ends segments (it knows them, as a GtsVertex does)."""

    def __init__(self, x=0, y=0, z=0):
        Point.__init__(self, x, y, z)
        self._segments = []

    def is_unattached(self):
        return not self._segments

    def replace(self, v):
        """gts_vertex_replace: every segment ending at this vertex ends at `v` instead."""
        for s in list(self._segments):
            if s.v1 is self:
                s.v1 = v
            if s.v2 is self:
                s.v2 = v
            v._segments.append(s)
        self._segments = []

    def is_connected(self, v):
        return _connecting(self, v) is not None


def _connecting(v1, v2):
    """gts_vertices_are_connected: a segment joining v1 and v2, or None."""
    for s in v1._segments:
        if (s.v1 is v1 and s.v2 is v2) or (s.v1 is v2 and s.v2 is v1):
            return s
    return None


class Segment(Object):
    """A segment between two distinct vertices. As PyGTS's (segment.c/edge.c new), asking again for a
    segment of this class (or a subclass) between two vertices it already joins returns that one."""

    def __new__(cls, v1=None, v2=None):
        if isinstance(v1, Vertex) and isinstance(v2, Vertex) and v1 is not v2:
            for s in v1._segments:
                if isinstance(s, cls) and s.connects(v1, v2):
                    return s
        return object.__new__(cls)

    def __init__(self, v1, v2):
        if 'v1' in self.__dict__:  # an existing segment returned by __new__
            return
        if not (isinstance(v1, Vertex) and isinstance(v2, Vertex)):
            raise TypeError('expected two Vertices')
        if v1 is v2:
            raise ValueError('v1 and v2 are the same')
        self.v1, self.v2 = v1, v2
        v1._segments.append(self)
        v2._segments.append(self)
        self._triangles = []

    def is_unattached(self):
        return not self._triangles

    def touches(self, s):
        return bool({id(self.v1), id(self.v2)} & {id(s.v1), id(s.v2)})

    def connects(self, v1, v2):
        return (self.v1 is v1 and self.v2 is v2) or (self.v1 is v2 and self.v2 is v1)


class Edge(Segment):
    pass


def _common(a, b):
    for v in (a.v1, a.v2):
        if v is b.v1 or v is b.v2:
            return v
    return None


def _edges_of(o1, o2, o3):
    """The three edges a triangle is asked for: the segments given, or for three vertices the Edges
    joining them (existing Edges reused, as PyGTS; a plain Segment between them is not one); None for
    anything else (the constructor says why)."""
    if all(isinstance(o, Vertex) for o in (o1, o2, o3)):
        if o1 is o2 or o2 is o3 or o3 is o1:
            return None
        return [Edge(a, b) for a, b in ((o1, o2), (o2, o3), (o3, o1))]
    if all(isinstance(o, Segment) for o in (o1, o2, o3)):
        return [o1, o2, o3]
    return None


class Triangle(Object):
    """A triangle of three edges, each touching the two others (or built from three vertices, reusing
    the edges that already join them)."""

    def __new__(cls, o1=None, o2=None, o3=None):
        # PyGTS (triangle.c/face.c new): a triangle of this class (or a subclass) on the same three edges,
        # in any order, is returned instead of a second one (gts_triangle_use_edges)
        es = _edges_of(o1, o2, o3)
        if es is not None:
            for t in es[0]._triangles:
                if isinstance(t, cls) and all(any(e is f for f in t._edges()) for e in es[1:]):
                    return t
        return object.__new__(cls)

    def __init__(self, o1, o2, o3):
        if 'e1' in self.__dict__:  # an existing triangle returned by __new__
            return
        if all(isinstance(o, Vertex) for o in (o1, o2, o3)):
            o1, o2, o3 = _edges_of(o1, o2, o3)
        if not all(isinstance(o, Segment) for o in (o1, o2, o3)):
            raise TypeError('expected three Edges or three Vertices')
        if not (o1.touches(o2) and o2.touches(o3) and o3.touches(o1)):
            raise RuntimeError('Edges in triangle must connect')
        self.e1, self.e2, self.e3 = o1, o2, o3
        for e in (o1, o2, o3):
            e._triangles.append(self)

    def vertices(self):
        """gts_triangle_vertices (GTS triangle.c): the oriented summits, read off e1 and e2."""
        a, b = self.e1, self.e2
        if a.v2 is b.v1:
            return (a.v1, a.v2, b.v2)
        if a.v2 is b.v2:
            return (a.v1, a.v2, b.v1)
        if a.v1 is b.v1:
            return (a.v2, a.v1, b.v2)
        return (a.v2, a.v1, b.v1)

    def vertex(self):
        """The vertex not on e1."""
        return self.vertices()[2]

    def normal(self):
        """gts_triangle_normal: (v2 - v1) x (v3 - v1) of the oriented vertices (twice the area long)."""
        p1, p2, p3 = self.vertices()
        x1, y1, z1 = p2.x - p1.x, p2.y - p1.y, p2.z - p1.z
        x2, y2, z2 = p3.x - p1.x, p3.y - p1.y, p3.z - p1.z
        return (y1 * z2 - z1 * y2, z1 * x2 - x1 * z2, x1 * y2 - y1 * x2)

    def area(self):
        x, y, z = self.normal()
        return math.sqrt(x * x + y * y + z * z) / 2.

    def perimeter(self):
        return sum(e.v1.distance(e.v2) for e in (self.e1, self.e2, self.e3))

    def revert(self):
        self.e1, self.e2 = self.e2, self.e1

    def _edges(self):
        return (self.e1, self.e2, self.e3)

    def _is_ok(self):
        """gts_triangle_is_ok without the duplicate test: non-degenerate edges touching pairwise."""
        es = self._edges()
        if any(e.v1 is e.v2 for e in es):
            return False
        return es[0].touches(es[1]) and es[0].touches(es[2]) and es[1].touches(es[2])


class Face(Triangle):
    pass


class Surface(Object):
    """A set of faces, in insertion order (see the module's note on YADE's order)."""

    def __init__(self):
        self._faces = []
        self._ids = set()

    def add(self, f):
        if isinstance(f, Surface):
            for g in f._faces:
                self.add(g)
            return
        if not isinstance(f, Face):
            raise TypeError('expected a Face or a Surface')
        if id(f) not in self._ids:
            self._ids.add(id(f))
            self._faces.append(f)

    def remove(self, f):
        if id(f) in self._ids:
            self._ids.discard(id(f))
            self._faces.remove(f)

    def faces(self, edges=None):
        if edges is None:
            return tuple(self._faces)
        es = set(id(e) for e in edges)
        return tuple(f for f in self._faces if any(id(e) in es for e in f._edges()))

    def __iter__(self):
        return iter(tuple(self._faces))

    def __len__(self):
        return len(self._faces)

    def edges(self):
        seen, out = set(), []
        for f in self._faces:
            for e in f._edges():
                if id(e) not in seen:
                    seen.add(id(e))
                    out.append(e)
        return tuple(out)

    def vertices(self):
        seen, out = set(), []
        for f in self._faces:
            for v in f.vertices():
                if id(v) not in seen:
                    seen.add(id(v))
                    out.append(v)
        return tuple(out)

    @property
    def Nfaces(self):
        return len(self._faces)

    @property
    def Nedges(self):
        return len(self.edges())

    @property
    def Nvertices(self):
        return len(self.vertices())

    def area(self):
        """gts_surface_area: the sum of the faces' areas."""
        a = 0.
        for f in self._faces:
            a += f.area()
        return a

    def volume(self):
        """gts_surface_volume: the signed volume, a sixth of the sum over faces of the triple product of
        the oriented vertices (v1 . (v2 x v3))."""
        if not self.is_closed():
            raise RuntimeError('Surface is not closed')
        if not self.is_orientable():
            raise RuntimeError('Surface is not orientable')
        vol = 0.
        for f in self._faces:
            a, b, c = f.vertices()
            vol += (a.x * (b.y * c.z - b.z * c.y) + b.x * (c.y * a.z - c.z * a.y) + c.x * (a.y * b.z - a.z * b.y))
        return vol / 6.

    def _edge_faces(self):
        count = {}
        for f in self._faces:
            for e in f._edges():
                count[id(e)] = count.get(id(e), 0) + 1
        return count

    def is_manifold(self):
        return all(n <= 2 for n in self._edge_faces().values())

    def is_orientable(self):
        """No two faces run through an edge in the same sense (their oriented vertices)."""
        seen = set()
        for f in self._faces:
            a, b, c = f.vertices()
            for p, q in ((a, b), (b, c), (c, a)):
                if (id(p), id(q)) in seen:
                    return False
                seen.add((id(p), id(q)))
        return True

    def is_closed(self):
        """Every edge shared by exactly two faces of the surface."""
        return bool(self._faces) and all(n == 2 for n in self._edge_faces().values())

    def _transform(self, m):
        for v in self.vertices():
            _transform(v, m)

    def translate(self, dx=0, dy=0, dz=0):
        self._transform(_translation(float(dx), float(dy), float(dz)))

    def scale(self, dx=1, dy=1, dz=1):
        self._transform(_scaling(float(dx), float(dy), float(dz)))

    def rotate(self, dx=0, dy=0, dz=0, a=0):
        self._transform(_rotation(float(dx), float(dy), float(dz), float(a)))

    def cleanup(self, threshold=0.):
        """PyGTS's cleanup (cleanup.cpp): merge vertices within `threshold` of each other per coordinate
        (the first one in the surface's vertex order stays), replace duplicate edges by the edge they
        duplicate, then drop the faces left degenerate or duplicated."""
        verts = self.vertices()
        gone = set()
        for v in verts:
            if id(v) in gone:
                continue
            for w in verts:
                if w is v or id(w) in gone:
                    continue
                if (abs(w.x - v.x) <= threshold and abs(w.y - v.y) <= threshold and abs(w.z - v.z) <= threshold):
                    w.replace(v)
                    gone.add(id(w))
        for e in self.edges():
            if e.v1 is e.v2:
                continue
            dup = next((s for s in e.v1._segments if s is not e and s.connects(e.v1, e.v2)), None)
            if dup is not None:
                for t in list(e._triangles):
                    t.e1, t.e2, t.e3 = [dup if x is e else x for x in t._edges()]
                    dup._triangles.append(t)
                e._triangles = []
                for v in (e.v1, e.v2):
                    if e in v._segments:
                        v._segments.remove(e)
        kept = []
        for f in self._faces:
            es = set(id(e) for e in f._edges())
            if f._is_ok() and not any(set(id(e) for e in g._edges()) == es for g in kept):
                kept.append(f)
        self._faces = kept
        self._ids = set(id(f) for f in kept)

    def write(self, f):
        """The surface in GTS's ascii format (gts_surface_write): 'nv ne nf' and the class names, the
        vertices (coordinates with 10 significant digits, as GTS prints them), the edges as 1-based vertex
        indices, the faces as 1-based edge indices; in this stand-in's order, not GTS's."""
        vs, es = self.vertices(), self.edges()
        vi = {id(v): i + 1 for i, v in enumerate(vs)}
        ei = {id(e): i + 1 for i, e in enumerate(es)}
        f.write('%d %d %d GtsSurface GtsFace GtsEdge GtsVertex\n' % (len(vs), len(es), len(self._faces)))
        for v in vs:
            f.write('%.10g %.10g %.10g\n' % (v.x, v.y, v.z))
        for e in es:
            f.write('%d %d\n' % (vi[id(e.v1)], vi[id(e.v2)]))
        for t in self._faces:
            f.write('%d %d %d\n' % tuple(ei[id(e)] for e in t._edges()))

    def __getattr__(self, name):
        if name.startswith('__'):
            raise AttributeError(name)
        unsupported('gts.Surface.%s (ryade\'s stand-in for PyGTS)' % name)


def read(f):
    """A Surface from a file in GTS's ascii format (a file object, as PyGTS's read takes): a header line
    'nv ne nf' (more fields ignored), nv lines 'x y z', ne lines of two 1-based vertex indices, nf lines
    of three 1-based edge indices; '#' starts a comment line."""
    lines = (ln.split() for ln in f.read().splitlines())
    rows = [ln for ln in lines if ln and not ln[0].startswith('#')]
    try:
        nv, ne, nf = (int(x) for x in rows[0][:3])
        vs = [Vertex(*(float(x) for x in r[:3])) for r in rows[1:1 + nv]]
        es = [Edge(vs[int(r[0]) - 1], vs[int(r[1]) - 1]) for r in rows[1 + nv:1 + nv + ne]]
        s = Surface()
        for r in rows[1 + nv + ne:1 + nv + ne + nf]:
            s.add(Face(*(es[int(x) - 1] for x in r[:3])))
    except (IndexError, ValueError) as e:
        raise RuntimeError('gts.read: not a GTS surface file (%s)' % e)
    if len(vs) != nv or len(es) != ne or s.Nfaces != nf:
        raise RuntimeError('gts.read: the file ends before its %d vertices, %d edges and %d faces' % (nv, ne, nf))
    return s


def __getattr__(name):
    if name.startswith('__'):
        raise AttributeError(name)
    unsupported('gts.%s (ryade\'s stand-in for PyGTS)' % name)
