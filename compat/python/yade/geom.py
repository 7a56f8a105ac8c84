"""`yade.geom` over ryade: facet boxes, cylinders, cones and bunkers built exactly as YADE's py/geom.py builds them
(same vertex arithmetic and order, so the facets are the same doubles)."""

import math

from . import utils
from ._errors import unsupported
from .minieigen import Quaternion, Vector3

__all__ = ['facetBox', 'facetParallelepiped', 'facetCylinder', 'facetCone', 'facetBunker']


def _linspace(start, stop, num):
    """numpy.linspace(start, stop, num, endpoint=True) without numpy: i*step + start, last = stop."""
    if num == 1:
        return [float(start)]
    div = num - 1
    delta = stop - start
    step = delta / div
    if step == 0:
        y = [(i / div) * delta + start for i in range(num)]
    else:
        y = [i * step + start for i in range(num)]
    y[-1] = float(stop)
    return y


def facetBox(center, extents, orientation=Quaternion((0, 1, 0), 0.0), wallMask=63, **kw):
    return facetParallelepiped(center=center, extents=extents, height=extents[2], orientation=orientation, wallMask=wallMask, **kw)


def facetParallelepiped(center, extents, height, orientation=Quaternion((0, 1, 0), 0.0), wallMask=63, **kw):
    if height < 0:
        raise RuntimeError("The height should have the positive value")
    if height > extents[2]:
        raise RuntimeError("The height should be smaller or equal as extents[2]")
    if wallMask > 63:
        print("wallMask must be 63 or less")
        wallMask = 63
    if extents[0] == 0:
        wallMask = 1
    elif extents[1] == 0:
        wallMask = 4
    elif extents[2] == 0 or height == 0:
        wallMask = 16
    if ((extents[0] == 0) and (extents[1] == 0)) or ((extents[0] == 0) and (extents[2] == 0)) or ((extents[1] == 0) and (extents[2] == 0)):
        raise RuntimeError("Please, specify at least 2 none-zero dimensions in extents!")
    beta = 0
    dx = 0
    if height > 0:
        beta = math.asin(height / extents[2])
        dx = math.cos(beta) * extents[2]
    mn, mx = [-extents[i] for i in (0, 1, 2)], [extents[i] for i in (0, 1, 2)]
    center = Vector3(*center)

    def doWall(a, b, c, d):
        return [utils.facet((a, b, c), **kw), utils.facet((a, c, d), **kw)]

    ret = []
    mn[2] = -height
    mx[2] = +height
    A = orientation * Vector3(mn[0], mn[1], mn[2]) + center
    B = orientation * Vector3(mx[0], mn[1], mn[2]) + center
    C = orientation * Vector3(mx[0], mx[1], mn[2]) + center
    D = orientation * Vector3(mn[0], mx[1], mn[2]) + center
    E = orientation * Vector3(mn[0] + dx, mn[1], mx[2]) + center
    F = orientation * Vector3(mx[0] + dx, mn[1], mx[2]) + center
    G = orientation * Vector3(mx[0] + dx, mx[1], mx[2]) + center
    H = orientation * Vector3(mn[0] + dx, mx[1], mx[2]) + center
    if wallMask & 1:
        ret += doWall(A, D, H, E)
    if wallMask & 2:
        ret += doWall(B, F, G, C)
    if wallMask & 4:
        ret += doWall(A, E, F, B)
    if wallMask & 8:
        ret += doWall(D, C, G, H)
    if wallMask & 16:
        ret += doWall(A, B, C, D)
    if wallMask & 32:
        ret += doWall(E, H, G, F)
    return ret


def facetCylinder(center, radius, height, orientation=Quaternion((0, 1, 0), 0.0), segmentsNumber=10, wallMask=7,
                  angleRange=None, closeGap=False, radiusTopInner=-1, radiusBottomInner=-1, **kw):
    if radius <= 0:
        raise RuntimeError("The radius should have the positive value")
    if height <= 0:
        wallMask = 1
    if closeGap:
        unsupported('geom.facetCylinder(closeGap=True)')
    if radiusTopInner > 0 or radiusBottomInner > 0:
        unsupported('geom.facetCylinder with inner radii')
    return _cylinder_cone(center, radius, height, orientation, segmentsNumber, wallMask, angleRange, -1, **kw)


def facetCone(center, radiusTop, radiusBottom, height, orientation=Quaternion((0, 1, 0), 0.0), segmentsNumber=10,
              wallMask=7, angleRange=None, closeGap=False, radiusTopInner=-1, radiusBottomInner=-1, **kw):
    """A cone (frustum) of facets: top and bottom discs and the side, as facetCylinder with two radii."""
    if radiusBottom <= 0 and radiusTop <= 0:
        raise RuntimeError("The radiusBottom or radiusTop should have the positive value")
    if closeGap:
        unsupported('geom.facetCone(closeGap=True)')
    if radiusTopInner > 0 or radiusBottomInner > 0:
        unsupported('geom.facetCone with inner radii')
    return _cylinder_cone(center, radiusTop, height, orientation, segmentsNumber, wallMask, angleRange, radiusBottom, **kw)


def facetBunker(center, dBunker, dOutput, hBunker, hOutput, hPipe=0.0, orientation=Quaternion((0, 1, 0), 0.0),
                segmentsNumber=10, wallMask=4, angleRange=None, closeGap=False, **kw):
    """A bunker of facets: an outlet pipe (height hPipe, diameter dOutput), a cone up to dBunker (height hOutput)
    and a cylinder above it (height hBunker), built about the origin, then rotated by `orientation` and moved
    to `center` (each facet's position; its orientation set to `orientation`)."""
    for v, what, strict in ((dBunker, 'The diameter dBunker', True), (dOutput, 'The diameter dOutput', True),
                            (hBunker, 'The height hBunker', False), (hOutput, 'The height hOutput', True),
                            (hPipe, 'The height hPipe', False)):
        if v < 0 or (strict and v == 0):
            raise RuntimeError('%s should have the positive value%s' % (what, '' if strict else ' or zero'))
    ret = []
    parts = []
    if hPipe > 0 or wallMask & 2:
        parts.append((facetCylinder, Vector3(0, 0, hPipe / 2.0), dict(radius=dOutput / 2.0, height=hPipe,
                                                                       wallMask=wallMask & 6)))
    parts.append((facetCone, Vector3(0.0, 0.0, hPipe + hOutput / 2.0),
                  dict(radiusTop=dBunker / 2.0, radiusBottom=dOutput / 2.0, height=hOutput, wallMask=wallMask & 4)))
    if hBunker > 0:
        parts.append((facetCylinder, Vector3(0.0, 0.0, hPipe + hOutput + hBunker / 2.0),
                      dict(radius=dBunker / 2.0, height=hBunker, wallMask=wallMask & 5)))
    for make, c, args in parts:
        ret += make(center=c, segmentsNumber=segmentsNumber, angleRange=angleRange, closeGap=closeGap, **args, **kw)
    for b in ret:
        b.state.pos = orientation * b.state.pos + Vector3(*center)
        b.state.ori = orientation
    return ret


def _cylinder_cone(center, radiusTop, height, orientation, segmentsNumber, wallMask, angleRange, radiusBottom, **kw):
    """py/geom.py::facetCylinderConeGenerator without inner radii and gap closing."""
    if radiusBottom == -1:
        radiusBottom = radiusTop
    if segmentsNumber < 3:
        raise RuntimeError("The segmentsNumber should be at least 3")
    if height < 0:
        raise RuntimeError("The height should have the positive value")
    if angleRange is None:
        angleRange = (0, 2 * math.pi)
    if isinstance(angleRange, float):
        print(u'WARNING: geom.facetCylinder,angleRange should be (Θmin,Θmax), not just Θmax (one number), update your code.')
        angleRange = (0, angleRange)
    if abs(angleRange[1] - angleRange[0]) > 2.0 * math.pi:
        raise RuntimeError("The |angleRange| cannot be larger 2.0*math.pi")
    if angleRange[1] < angleRange[0]:
        raise RuntimeError("angleRange[1] should be larger or equal angleRange[1]")
    center = Vector3(*center)
    PTop = [Vector3(0, 0, +height / 2)]
    PBottom = [Vector3(0, 0, -height / 2)]
    for i in _linspace(angleRange[0], angleRange[1], segmentsNumber + 1):
        PTop.append(Vector3(radiusTop * math.cos(i), radiusTop * math.sin(i), +height / 2))
        PBottom.append(Vector3(radiusBottom * math.cos(i), radiusBottom * math.sin(i), -height / 2))
    for i in range(0, len(PTop)):
        PTop[i] = orientation * PTop[i] + center
        PBottom[i] = orientation * PBottom[i] + center
    ret = []
    for i in range(2, len(PTop)):
        if (wallMask & 1) and (radiusTop != 0):
            ret.append(utils.facet((PTop[0], PTop[i], PTop[i - 1]), **kw))
        if (wallMask & 2) and (radiusBottom != 0):
            ret.append(utils.facet((PBottom[0], PBottom[i - 1], PBottom[i]), **kw))
        if wallMask & 4:
            if radiusBottom != 0:
                ret.append(utils.facet((PTop[i], PBottom[i], PBottom[i - 1]), **kw))
            if radiusTop != 0:
                ret.append(utils.facet((PBottom[i - 1], PTop[i - 1], PTop[i]), **kw))
    return ret


def __getattr__(name):
    if name.startswith('__'):
        raise AttributeError(name)
    unsupported('yade.geom.%s' % name)
