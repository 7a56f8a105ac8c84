"""`yade.export` over ryade: text dumps and `VTKExporter` writing the same legacy-VTK files as YADE's
py/export.py (ASCII, `%g` numbers), which ParaView opens; plus `VTKRecorder` as a periodic engine."""

import os

from ._core import Facet, Omega, Sphere
from ._errors import unsupported
from .minieigen import Matrix3, Vector3
from .wrapper import PeriodicEngine

__all__ = ['text', 'textExt', 'VTKExporter', 'VTKRecorder']


def _O():
    return Omega()


def textExt(filename, format='x_y_z_r', comment='', mask=-1, attrs=[]):
    """Spheres as text, `x_y_z_r` or `x_y_z_r_matId` (YADE's `%g` format, 6 digits)."""
    if format not in ('x_y_z_r', 'x_y_z_r_matId'):
        unsupported("export.textExt(format='%s')" % format)
    if attrs:
        unsupported('export.textExt(attrs=...)')
    O = _O()
    count = 0
    with open(filename, 'w') as f:
        f.write('#format ' + format + '\n')
        if comment:
            f.write('#' + comment.replace('\n', '\n#') + '\n')
        for b in O.bodies:
            if not isinstance(b.shape, Sphere) or (mask != -1 and not (b.mask & mask)):
                continue
            p, r = b.state.pos, b.shape.radius
            if format == 'x_y_z_r':
                f.write('%g\t%g\t%g\t%g\n' % (p[0], p[1], p[2], r))
            else:
                f.write('%g\t%g\t%g\t%g\t%d\n' % (p[0], p[1], p[2], r, b.material.id))
            count += 1
    return count


def text(filename, mask=-1):
    return textExt(filename=filename, format='x_y_z_r', mask=mask)


class VTKExporter(object):
    """`export.VTKExporter(baseName)`: `exportSpheres`, `exportFacets`, `exportInteractions`,
    `exportPeriodicCell`, each writing `<baseName>-<kind>-%08d.vtk` (legacy VTK, as YADE)."""

    def __init__(self, baseName, startSnap=0):
        self.baseName = baseName
        self.spheresSnapCount = startSnap
        self.facetsSnapCount = startSnap
        self.intrsSnapCount = startSnap
        self.cellSnapCount = startSnap

    def _bodies(self, ids, shape):
        O = _O()
        if ids == 'all':
            return [b for b in O.bodies if isinstance(b.shape, shape)]
        return [O.bodies[i] for i in ids if isinstance(O.bodies[i].shape, shape)]

    def _what(self, f, bodies, what, key):
        import __main__
        for name, command in what.items():
            vals = []
            for b in bodies:
                ns = dict(__main__.__dict__)
                ns[key] = b
                vals.append(eval(command, ns))
            test = vals[0] if vals else 0.0
            if isinstance(test, Matrix3):
                f.write("\nTENSORS %s double\n" % name)
                for t in vals:
                    f.write("%g %g %g\n%g %g %g\n%g %g %g\n\n" % tuple(t[i, j] for i in range(3) for j in range(3)))
            elif isinstance(test, Vector3):
                f.write("\nVECTORS %s double\n" % name)
                for v in vals:
                    f.write("%g %g %g\n" % (v[0], v[1], v[2]))
            elif isinstance(test, (int, float)):
                f.write("\nSCALARS %s double 1\nLOOKUP_TABLE default\n" % name)
                for v in vals:
                    f.write("%g\n" % v)
            else:
                print("WARN: exportSpheres: wrong 'what' parameter, vtk output might be corrupted'")

    def exportSpheres(self, ids='all', what={}, comment="comment", numLabel=None, useRef=False):
        bodies = self._bodies(ids, Sphere)
        if not bodies:
            return
        O = _O()
        fName = self.baseName + '-spheres-%08d' % (numLabel if numLabel else self.spheresSnapCount) + '.vtk'
        with open(fName, 'w') as f:
            f.write("# vtk DataFile Version 3.0.\n%s\nASCII\n\nDATASET POLYDATA\nPOINTS %d double\n" % (comment, len(bodies)))
            for b in bodies:
                pos = b.state.refPos if useRef else b.state.pos if not O.periodic else O.cell.wrap(b.state.pos)
                f.write("%g %g %g\n" % (pos[0], pos[1], pos[2]))
            f.write("\nPOINT_DATA %d\nSCALARS radius double 1\nLOOKUP_TABLE default\n" % len(bodies))
            for b in bodies:
                f.write("%g\n" % b.shape.radius)
            self._what(f, bodies, what, 'b')
        self.spheresSnapCount += 1

    def exportFacets(self, ids='all', what={}, comment="comment", numLabel=None):
        bodies = self._bodies(ids, Facet)
        if not bodies:
            return
        fName = self.baseName + '-facets-%08d' % (numLabel if numLabel else self.facetsSnapCount) + '.vtk'
        n = len(bodies)
        with open(fName, 'w') as f:
            f.write("# vtk DataFile Version 3.0.\n%s\nASCII\n\nDATASET POLYDATA\nPOINTS %d double\n" % (comment, 3 * n))
            for b in bodies:
                p, o = b.state.pos, b.state.ori
                for v in b.shape.vertices:
                    w = p + o * v
                    f.write("%g %g %g\n" % (w[0], w[1], w[2]))
            f.write("\nPOLYGONS %d %d\n" % (n, 4 * n))
            for i in range(n):
                f.write("3 %d %d %d\n" % (3 * i, 3 * i + 1, 3 * i + 2))
            if what:
                f.write("\nCELL_DATA %d" % n)
                self._what(f, bodies, what, 'b')
        self.facetsSnapCount += 1

    def exportFacetsAsMesh(self, ids='all', connectivityTable=None, what={}, comment="comment", numLabel=None):
        """YADE's exportFacetsAsMesh: the facets as one mesh whose nodes are numbered by `connectivityTable`
        (one (n1, n2, n3) per facet, as `ymport.unv(..., returnConnectivityTable=True)` gives). As in YADE,
        the facet matched with table entry k is `bodies[id]` of the selected facets, `id` being the k-th
        selected body's id."""
        bodies = self._bodies(ids, Facet)
        if not bodies:
            return
        sel = [b.id for b in bodies]
        if connectivityTable is None:
            print("Warning (yade.export.VTKExporter.exportFacetsAsMesh): 'connectivityTable' not specified")
            return
        if len(bodies) != len(connectivityTable):
            print("Warning (yade.export.VTKExporter.exportFacetsAsMesh): length of 'connectivityTable' does not "
                  "match length of 'ids', no export")
            return
        nodes = [Vector3(0, 0, 0)] * (max(max(e) for e in connectivityTable) + 1)
        for i, e in zip(sel, connectivityTable):
            b = bodies[i]
            p, o = b.state.pos, b.state.ori
            for k in range(3):
                nodes[e[k]] = p + o * b.shape.vertices[k]
        fName = self.baseName + '-facets-%08d' % (numLabel if numLabel else self.facetsSnapCount) + '.vtk'
        with open(fName, 'w') as f:
            f.write("# vtk DataFile Version 3.0.\n%s\nASCII\n\nDATASET POLYDATA\nPOINTS %d double\n" % (comment, len(nodes)))
            for v in nodes:
                f.write("%g %g %g\n" % (v[0], v[1], v[2]))
            n = len(connectivityTable)
            f.write("\nPOLYGONS %d %d\n" % (n, 4 * n))
            for e in connectivityTable:
                f.write("3 %d %d %d\n" % tuple(e))
            if what:
                f.write("\nCELL_DATA %d" % len(bodies))
                self._what(f, bodies, what, 'b')
        self.facetsSnapCount += 1

    def exportInteractions(self, ids='all', what={}, verticesWhat={}, comment="comment", numLabel=None, useRef=False):
        if ids != 'all' or verticesWhat or useRef:
            unsupported('VTKExporter.exportInteractions(ids/verticesWhat/useRef)')
        O = _O()
        intrs = [i for i in O.interactions if isinstance(O.bodies[i.id1].shape, Sphere) and isinstance(O.bodies[i.id2].shape, Sphere)]
        if not intrs:
            return
        fName = self.baseName + '-intrs-%08d' % (numLabel if numLabel else self.intrsSnapCount) + '.vtk'
        bodies = sorted({i.id1 for i in intrs} | {i.id2 for i in intrs})
        index = {b: k for k, b in enumerate(bodies)}
        with open(fName, 'w') as f:
            f.write("# vtk DataFile Version 3.0.\n%s\nASCII\n\nDATASET POLYDATA\nPOINTS %d double\n" % (comment, len(bodies)))
            for bid in bodies:
                p = O.bodies[bid].state.pos
                f.write("%g %g %g\n" % (p[0], p[1], p[2]))
            f.write("\nLINES %d %d\n" % (len(intrs), 3 * len(intrs)))
            for i in intrs:
                f.write("2 %d %d\n" % (index[i.id1], index[i.id2]))
            if what:
                f.write("\nCELL_DATA %d" % len(intrs))
                self._what(f, intrs, what, 'i')
        self.intrsSnapCount += 1

    def exportPeriodicCell(self, comment="comment", numLabel=None):
        O = _O()
        if not O.periodic:
            print("WARN: exportPeriodicCell: scene is not periodic, no export...")
            return
        h = O.cell.hSize
        fName = self.baseName + '-periCell-%08d' % (numLabel if numLabel else self.cellSnapCount) + '.vtk'
        with open(fName, 'w') as f:
            f.write("# vtk DataFile Version 3.0.\n%s\nASCII\n\nDATASET UNSTRUCTURED_GRID\nPOINTS 8 double\n" % comment)
            cols = [Vector3(h[0, j], h[1, j], h[2, j]) for j in range(3)]
            for k in range(8):
                p = Vector3(0, 0, 0)
                for j in range(3):
                    if k >> j & 1:
                        p = p + cols[j]
                f.write("%g %g %g\n" % (p[0], p[1], p[2]))
            f.write("\nCELLS 1 9\n8 0 1 3 2 4 5 7 6\nCELL_TYPES 1\n12\n")
        self.cellSnapCount += 1

    def __getattr__(self, k):
        if k.startswith('_'):
            raise AttributeError(k)
        unsupported('VTKExporter.%s' % k)


class VTKRecorder(PeriodicEngine):
    """`VTKRecorder(fileName, recorders, iterPeriod)`: at iteration 0 and every period (YADE's initRun),
    writes `<fileName>spheres.<iter>.vtu` (and `facets`) as VTK XML unstructured grids (ASCII) that
    ParaView opens, with YADE's arrays (radii; linVelVec, angVelVec, linVelLen, angVelLen for 'velocity').
    Recorders: 'spheres', 'facets', 'velocity', 'colors' (the shapes' colours: point data `color` of the
    spheres, cell data `color` of the facets, as YADE's VTKRecorder::action), 'id', 'mass', 'all' (=
    spheres, facets, velocity, colors); others fail loudly."""
    _attrs = {'fileName': '', 'recorders': ['all'], 'ascii': False, 'compress': False, 'mask': 0,
              'skipFacetIntr': True, 'skipNondynamic': False, 'multiblock': False, 'initRun': True}
    _supported = {'all', 'spheres', 'facets', 'velocity', 'colors', 'id', 'mass'}

    def _json(self):
        bad = [r for r in self._values['recorders'] if r not in self._supported]
        if bad:
            unsupported('VTKRecorder recorders %s' % bad)
        return {'class': 'External'}

    def _action(self, omega):
        rec = set(self._values['recorders'])
        if 'all' in rec:
            rec |= {'spheres', 'facets', 'velocity', 'colors'}
        base = self._values['fileName']
        d = os.path.dirname(base)
        if d:
            os.makedirs(d, exist_ok=True)
        if 'spheres' in rec:
            bodies = [b for b in omega.bodies if isinstance(b.shape, Sphere)]
            fields = [('radii', 1, [[b.shape.radius] for b in bodies])]
            if 'id' in rec:
                fields.append(('id', 1, [[b.id] for b in bodies]))
            if 'mass' in rec:
                fields.append(('mass', 1, [[b.state.mass] for b in bodies]))
            if 'colors' in rec:
                fields.append(('color', 3, [list(b.shape.color) for b in bodies]))
            if 'velocity' in rec:
                lin, ang = [b.state.vel for b in bodies], [b.state.angVel for b in bodies]
                fields.append(('linVelVec', 3, [list(v) for v in lin]))
                fields.append(('angVelVec', 3, [list(v) for v in ang]))
                fields.append(('linVelLen', 1, [[_norm(v)] for v in lin]))
                fields.append(('angVelLen', 1, [[_norm(v)] for v in ang]))
            _write_vtu('%sspheres.%d.vtu' % (base, omega.iter), [list(b.state.pos) for b in bodies], None, fields)
        if 'facets' in rec:
            bodies = [b for b in omega.bodies if isinstance(b.shape, Facet)]
            pts, cells = [], []
            for b in bodies:
                p, o = b.state.pos, b.state.ori
                cells.append([len(pts), len(pts) + 1, len(pts) + 2])
                pts.extend(list(p + o * v) for v in b.shape.vertices)
            colors = [('color', 3, [list(b.shape.color) for b in bodies])] if 'colors' in rec else []
            _write_vtu('%sfacets.%d.vtu' % (base, omega.iter), pts, cells, [], colors)


def _norm(v):
    """Eigen's norm(): sqrt(x*x + (y*y + z*z))."""
    import math
    return math.sqrt(v[0] * v[0] + (v[1] * v[1] + v[2] * v[2]))


def _write_vtu(path, points, triangles, point_fields, cell_fields=()):
    """VTK XML UnstructuredGrid, ASCII: vertices (one cell per point) or triangles, with point and cell
    data arrays."""
    n = len(points)
    with open(path, 'w') as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">\n<UnstructuredGrid>\n')
        ncells = len(triangles) if triangles is not None else n
        f.write('<Piece NumberOfPoints="%d" NumberOfCells="%d">\n<Points>\n' % (n, ncells))
        f.write('<DataArray type="Float64" NumberOfComponents="3" format="ascii">\n')
        f.write('\n'.join('%r %r %r' % tuple(p) for p in points))
        f.write('\n</DataArray>\n</Points>\n<Cells>\n<DataArray type="Int64" Name="connectivity" format="ascii">\n')
        if triangles is None:
            f.write(' '.join(str(i) for i in range(n)))
            offsets, ctype = range(1, n + 1), 1
        else:
            f.write(' '.join('%d %d %d' % tuple(t) for t in triangles))
            offsets, ctype = range(3, 3 * ncells + 1, 3), 5
        f.write('\n</DataArray>\n<DataArray type="Int64" Name="offsets" format="ascii">\n')
        f.write(' '.join(str(o) for o in offsets))
        f.write('\n</DataArray>\n<DataArray type="UInt8" Name="types" format="ascii">\n')
        f.write(' '.join(str(ctype) for _ in range(ncells)))
        f.write('\n</DataArray>\n</Cells>\n')
        for tag, fields in (('PointData', point_fields), ('CellData', cell_fields)):
            if not fields:
                continue
            f.write('<%s>\n' % tag)
            for name, ncomp, vals in fields:
                f.write('<DataArray type="Float64" Name="%s" NumberOfComponents="%d" format="ascii">\n' % (name, ncomp))
                f.write('\n'.join(' '.join(repr(float(x)) for x in v) for v in vals))
                f.write('\n</DataArray>\n')
            f.write('</%s>\n' % tag)
        f.write('</Piece>\n</UnstructuredGrid>\n</VTKFile>\n')


def __getattr__(name):
    if name.startswith('__'):
        raise AttributeError(name)
    unsupported('yade.export.%s' % name)
