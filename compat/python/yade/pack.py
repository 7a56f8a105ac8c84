"""`yade.pack` over ryade: `SpherePack` with `makeCloud` reproduced bit for bit by the Rust core."""

from . import _ryade, utils
from ._core import Omega, Sphere
from ._errors import unsupported
from .minieigen import Matrix3, Quaternion, Vector3, to_vec3

__all__ = ['SpherePack']


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

    def __getattr__(self, k):
        if k.startswith('_'):
            raise AttributeError(k)
        unsupported('SpherePack.%s' % k)


def _g6(x):
    """C++ `ostream << double` with the default precision (6 significant digits, %g style)."""
    return '%g' % x


def __getattr__(name):
    if name.startswith('__'):
        raise AttributeError(name)
    unsupported('yade.pack.%s' % name)
