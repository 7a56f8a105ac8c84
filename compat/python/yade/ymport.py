"""`yade.ymport` over ryade: sphere lists from text files (as YADE's py/ymport.py reads them) and facets
from STL files (as its STLImporter does)."""

import struct

from . import utils
from ._core import Body, Facet
from ._errors import unsupported
from .minieigen import Quaternion, Vector3

__all__ = ['text', 'textExt', 'stl', 'gmsh']


def textExt(fileName, format='x_y_z_r', shift=Vector3(0, 0, 0), scale=1.0, attrs=[], **kw):
    """Spheres from `fileName`; `#format NAME` lines switch the format, other `#` lines are skipped."""
    ret = []
    with open(fileName) as f:
        lines = f.readlines()
    for line in lines:
        data = line.split()
        if not data:
            continue
        if data[0] == "#format":
            format = data[1]
            continue
        elif data[0][0] == "#":
            continue
        if format == 'x_y_z_r':
            pos = Vector3(float(data[0]), float(data[1]), float(data[2]))
            ret.append(utils.sphere(shift + scale * pos, scale * float(data[3]), **kw))
        elif format == 'x_y_z_r_matId':
            pos = Vector3(float(data[0]), float(data[1]), float(data[2]))
            ret.append(utils.sphere(shift + scale * pos, scale * float(data[3]), material=int(data[4]), **kw))
        elif format == 'id_x_y_z_r_matId':
            pos = Vector3(float(data[1]), float(data[2]), float(data[3]))
            ret.append(utils.sphere(shift + scale * pos, scale * float(data[4]), material=int(data[5]), **kw))
        elif format == 'x_y_z_r_attrs':
            pos = Vector3(float(data[0]), float(data[1]), float(data[2]))
            ret.append(utils.sphere(shift + scale * pos, scale * float(data[3]), **kw))
            attrs.append(data[4:])
        else:
            raise RuntimeError("Please, specify a correct format output!")
    return ret


def text(fileName, shift=Vector3(0, 0, 0), scale=1.0, **kw):
    return textExt(fileName=fileName, format='x_y_z_r', shift=shift, scale=scale, **kw)


def _stl_triangles(fileName):
    """The triangles of an STL file as STLImporter's reader (pkg/dem/STLImporter.hpp) gets them: single
    precision coordinates, each vertex replaced by the first equal one read before it. Binary when the size
    is that of the facet count at byte 80, or when one of the 128 bytes after it is above 127; else ASCII,
    read by position after the first line (a last `endfacet` that ends the file without a newline is
    dropped, as its end-of-file test does)."""
    with open(fileName, 'rb') as f:
        data = f.read()
    facenum = struct.unpack('<i', data[80:84])[0] if len(data) >= 84 else -1
    binary = len(data) == 84 + 50 * facenum
    head = data[84:84 + 128]
    if len(head) == 128 and any(c > 127 for c in head):
        binary = True
    tris = []
    if binary:
        for i in range(max(facenum, 0)):
            v = struct.unpack_from('<9f', data, 84 + 50 * i + 12)
            tris.append([v[0:3], v[3:6], v[6:9]])
    else:
        import re
        f32 = lambda t: struct.unpack('<f', struct.pack('<f', float(t)))[0]  # noqa: E731  (fscanf %f)
        body = data[data.index(b'\n') + 1:] if b'\n' in data else b''
        toks = [(m.group(0), m.end()) for m in re.finditer(rb'\S+', body)]
        k = 0
        while k + 21 <= len(toks):
            t = [x[0] for x in toks[k:k + 21]]
            try:
                tri = [tuple(f32(x) for x in t[8 + 4 * j:11 + 4 * j]) for j in range(3)]
            except ValueError:
                break
            if toks[k + 20][1] == len(body):
                break
            tris.append(tri)
            k += 21
    seen, out = {}, []
    for tri in tris:
        out.append([seen.setdefault(v, v) for v in tri])
    return out


def stl(file, dynamic=None, fixed=True, wire=True, color=None, highlight=False, noBound=False, material=-1,
        scale=1.0, shift=Vector3(0, 0, 0)):
    """Facets of an STL file (ASCII or binary), placed at the centre of each triangle's inscribed circle."""
    ret = []
    for tri in _stl_triangles(file):
        v = [Vector3(*x) for x in tri]
        icc = utils.inscribedCircleCenter(v[0], v[1], v[2])
        b = Body()
        b.shape = Facet(color=color if color else utils.randomColor(), wire=wire, highlight=highlight,
                        vertices=tuple((x - icc) * scale for x in v))
        utils._commonBodySetup(b, 0, Vector3(0, 0, 0), material=material, pos=icc * scale + shift, noBound=noBound,
                               dynamic=dynamic, fixed=fixed)
        b.aspherical = False
        ret.append(b)
    return ret


def gmsh(meshfile="file.mesh", shift=Vector3(0, 0, 0), scale=1.0, orientation=Quaternion((0, 1, 0), 0.0), **kw):
    """Facets from the triangles of a GMSH/MEDIT `.mesh` file: vertices scaled, rotated by `orientation` and
    shifted; `kw` goes to utils.facet."""
    with open(meshfile, "r") as f:
        lines = f.readlines()

    def section(start, name):
        k = start
        while lines[k].split()[0] != name:
            k += 1
        return k + 1  # the line with the count

    kv = section(0, 'Vertices')
    nv = int(lines[kv].split()[0])
    nodes = []
    for line in lines[kv + 1:kv + 1 + nv]:
        x = line.split()
        nodes.append(orientation * Vector3(float(x[0]) * scale, float(x[1]) * scale, float(x[2]) * scale) + shift)
    kt = section(kv + nv, 'Triangles')
    nt = int(lines[kt].split()[0])
    ret = []
    for line in lines[kt + 1:kt + 1 + nt]:
        x = line.split()
        ret.append(utils.facet((nodes[int(x[0]) - 1], nodes[int(x[1]) - 1], nodes[int(x[2]) - 1]), **kw))
    return ret


def textFacets(fileName, format='x1_y1_z1_x2_y2_z2_x3_y3_z3', shift=Vector3(0, 0, 0), scale=1.0, attrs=[], **kw):
    """Facets from a text file (YADE's ymport.textFacets), one per line: 'x1_y1_z1_x2_y2_z2_x3_y3_z3'
    (default), '..._matId' (the material by id), 'id_..._matId', or '..._attrs' (YADE appends the line's words from
    the fifth on, as strings, to `attrs`); each vertex is shift + v * scale. A '#format NAME' line
    switches the format; other lines starting with '#' are skipped. `kw` goes to utils.facet."""
    with open(fileName, 'r') as f:
        lines = f.readlines()
    formats = ('x1_y1_z1_x2_y2_z2_x3_y3_z3', 'x1_y1_z1_x2_y2_z2_x3_y3_z3_matId', 'id_x1_y1_z1_x2_y2_z2_x3_y3_z3_matId',
               'x1_y1_z1_x2_y2_z2_x3_y3_z3_attrs')
    shift = Vector3(*shift)
    out = []
    for line in lines:
        d = line.split()
        if d[0] == '#format':  # (an empty line stops YADE with an IndexError, as here)
            format = d[1]
            continue
        if d[0][0] == '#':
            continue
        if format not in formats:
            raise RuntimeError('Please, specify a correct format output!')
        first = 1 if format.startswith('id_') else 0
        v = [Vector3(float(d[first + 3 * k]), float(d[first + 3 * k + 1]), float(d[first + 3 * k + 2])) for k in range(3)]
        vs = tuple(shift + x * scale for x in v)
        if format.endswith('matId'):
            out.append(utils.facet(vs, material=int(d[first + 9]), **kw))
        else:
            out.append(utils.facet(vs, **kw))
            if format.endswith('attrs'):
                attrs.append(d[4:])  # as YADE: the line's words from the fifth on, as strings
    return out


def unv(fileName, shift=(0, 0, 0), scale=1.0, returnConnectivityTable=False, **kw):
    """Triangles of an I-DEAS universal file (.unv, e.g. from Salome) as facets (YADE's ymport.unv):
    dataset 2411 gives the nodes (shift + scale * coordinates), dataset 2412 the elements, of which the
    triangles (type 41) are kept until the first other element after them. `kw` goes to utils.facet;
    with `returnConnectivityTable`, also (nodes, elements with 0-based node ids)."""
    nodes, elements = [], []
    with open(fileName, 'r') as f:
        lines = f.read().split('\n')
    if lines and lines[-1] == '':
        lines.pop()
    mode = None  # 'nodes', 'elements', 'triangles' or 'skip'
    k = 0

    def next_fields():
        nonlocal k
        k += 1
        return lines[k].split() if k < len(lines) else []
    while k < len(lines):
        fields = lines[k].split()
        if len(fields) <= 1:
            # a dataset delimiter (-1) or a dataset number (an empty line stops YADE with an IndexError)
            tag = fields[0]
            if tag != '-1':
                mode = {'2411': 'nodes', '2412': 'elements'}.get(tag, 'skip')
        elif mode == 'nodes':
            c = next_fields()
            nodes.append((shift[0] + scale * float(c[0]), shift[1] + scale * float(c[1]), shift[2] + scale * float(c[2])))
        elif mode == 'elements' and fields[1] != '41':
            next_fields()  # a beam element: a line of beam data, then its nodes
            next_fields()
        elif mode in ('elements', 'triangles'):
            if fields[1] == '41':
                mode = 'triangles'
                c = next_fields()
                elements.append((int(c[0]) - 1, int(c[1]) - 1, int(c[2]) - 1))
            else:
                next_fields()
                mode = 'skip'
        k += 1
    facets = [utils.facet(tuple(nodes[i] for i in e), **kw) for e in elements]
    if returnConnectivityTable:
        return facets, nodes, elements
    return facets


def __getattr__(name):
    if name.startswith('__'):
        raise AttributeError(name)
    unsupported('yade.ymport.%s' % name)
