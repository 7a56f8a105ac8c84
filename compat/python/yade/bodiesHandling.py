"""`yade.bodiesHandling` (YADE's py/bodiesHandling.py): bounding dimensions of sphere and facet sets,
and shifting / scaling / rotating (or copying) spheres, with YADE's arithmetic order."""

import math

from . import utils
from ._core import Body, Omega
from .minieigen import Quaternion, Vector3

__all__ = ['spheresPackDimensions', 'facetsDimensions', 'spheresModify', 'sphereDuplicate']


def _O():
    return Omega()


def _ids_or_mask(ids, mask, at_least, empty_msg, few_msg):
    """The bodies to treat: `ids` when not empty, else those whose mask shares a bit with `mask` (YADE
    raises RuntimeWarning for fewer than `at_least` of them, or when there is no mask either)."""
    if len(ids) > 0:
        return ids
    if mask <= -1:
        raise RuntimeWarning(empty_msg)
    found = [b.id for b in _O().bodies if (b.mask & mask) != 0]
    if len(found) < at_least:
        raise RuntimeWarning(few_msg)
    return found


def _body(i, what):
    # YADE tests the type's name: a list of ids (int) or of bodies
    if type(i).__name__ == 'int':
        return _O().bodies[i]
    if isinstance(i, Body):
        return i
    raise TypeError(what)


class _Extent(object):
    """Running min/max per axis with the id that set it; the first body sets both (YADE's counter == 0)."""

    def __init__(self):
        self.lo, self.hi = Vector3.Zero, Vector3.Zero
        self.loId, self.hiId = Vector3.Zero, Vector3.Zero
        self.n = 0

    def add(self, bid, lo, hi):
        for k in range(3):
            if hi[k] > self.hi[k] or self.n == 0:
                self.hi[k], self.hiId[k] = hi[k], bid
            if lo[k] < self.lo[k] or self.n == 0:
                self.lo[k], self.loId[k] = lo[k], bid
        self.n += 1

    def result(self):
        return {'max': self.hi, 'min': self.lo, 'maxId': self.hiId, 'minId': self.loId,
                'center': (self.hi - self.lo) / 2.0 + self.lo, 'extends': self.hi - self.lo}


def spheresPackDimensions(idSpheres=[], mask=-1):
    """Bounding box of the spheres `idSpheres` (ids or bodies; or, when empty, the bodies matching
    `mask`): dict with min, max, minId, maxId, center, extends, volume, mass, number (non-spheres and
    bodies failing `mask` skipped)."""
    ids = _ids_or_mask(idSpheres, mask, 2, 'Only a list of particles with length > 1 can be analyzed',
                       'Not enough bodies to analyze with given mask')
    ext, volume, mass = _Extent(), 0.0, 0.0
    for i in ids:
        b = _body(i, "Unknow type of data, should be list of int's or bodies's")
        if not b:
            continue
        pos = b.state.pos
        if not hasattr(b.shape, 'radius'):
            continue
        r = b.shape.radius
        if mask > -1 and (mask & b.mask) == 0:
            continue
        rv = Vector3(r, r, r)
        ext.add(b.id, pos - rv, pos + rv)
        volume += 4.0 / 3.0 * math.pi * r * r * r
        mass += b.state.mass
    d = ext.result()
    d.update(volume=volume, mass=mass, number=ext.n)
    return d


def facetsDimensions(idFacets=[], mask=-1):
    """Bounding box of the facets `idFacets` (ids or bodies; or, when empty, the bodies matching `mask`):
    dict with min, max, minId, maxId, center, extends, number."""
    ids = _ids_or_mask(idFacets, mask, 2, 'Only a list of particles with length > 1 can be analyzed',
                       'Not enough bodies to analyze with given mask')
    ext = _Extent()
    for i in ids:
        b = _body(i, "Unknow type of data, should be list of int's or bodies's")
        if not b:
            continue
        p, o, vs = b.state.pos, b.state.ori, b.shape.vertices
        pts = [p + o * vs[k] for k in range(3)]
        if mask > -1 and (mask & b.mask) == 0:
            continue
        ext.add(b.id, Vector3(*(min(q[k] for q in pts) for k in range(3))),
                Vector3(*(max(q[k] for q in pts) for k in range(3))))
    d = ext.result()
    d['number'] = ext.n
    return d


def spheresModify(idSpheres=[], mask=-1, shift=Vector3.Zero, scale=1.0, orientation=Quaternion((0, 1, 0), 0.0),
                  copy=False):
    """Rotate the spheres `idSpheres` by `orientation` about their bounding box's center, scale them
    (radius, mass scale^3, inertia scale^5, distance to the center) by `scale`, then shift them by
    `shift`; with `copy`, modify and return copies (not added to O.bodies) instead, else return True."""
    ids = _ids_or_mask(idSpheres, mask, 1, 'No bodies to modify', 'No bodies to modify with given mask')
    center = spheresPackDimensions(ids)['center']
    out = []
    for i in ids:
        b = _body(i, "Unknown type of data, should be list of int's or bodies")
        if not hasattr(b.shape, 'radius'):
            continue
        if mask > -1 and (mask & b.mask) == 0:
            continue
        if copy:
            b = sphereDuplicate(b)
        st = b.state
        st.pos = orientation * (st.pos - center) + center
        b.shape.radius *= scale
        st.mass *= pow(scale, 3)
        st.inertia *= pow(scale, 5)
        st.pos = (st.pos - center) * scale + center
        st.pos += shift
        if copy:
            out.append(b)
    return out if copy else True


def sphereDuplicate(idSphere):
    """A new sphere body (not added to O.bodies) like sphere `idSphere` (id or body): same center,
    radius, fixedness, display flags, material and mask; False for a non-sphere."""
    b = _body(idSphere, "Unknown type of data, should be list of int's or bodies")
    if not hasattr(b.shape, 'radius'):
        return False
    s = b.shape
    return utils.sphere(center=b.state.pos, radius=s.radius, fixed=not b.dynamic, wire=s.wire, color=s.color,
                        highlight=s.highlight, material=b.material, mask=b.mask)
