"""`yade.utils` over ryade: body builders with YADE's exact mass/inertia arithmetic (py/utils.py),
and the C++ helpers (PWaveTimeStep, unbalancedForce, porosity, ...) computed by the Rust core."""

import math
import random

from . import _ryade
from ._core import Body, Box, Facet, Omega, Sphere, Wall
from ._errors import unsupported
from .minieigen import Quaternion, Vector3, to_vec3
from .wrapper import FrictMat, Material
from ._table import (TableParamReader, loadVars, readParamsFromTable, runningInBatch, saveVars,  # noqa: F401
                     waitIfBatch)  # YADE exports them from utils

__all__ = ['sphere', 'facet', 'box', 'wall', 'aabbWalls', 'aabbExtrema', 'aabbDim', 'defaultMaterial', 'PWaveTimeStep',
           'SpherePWaveTimeStep', 'unbalancedForce', 'porosity', 'voxelPorosity', 'kineticEnergy', 'randomColor', 'randomOrientation',
           'typedEngine', 'readParamsFromTable', 'waitIfBatch', 'runningInBatch', 'saveVars', 'loadVars', 'TableParamReader', 'inscribedCircleCenter',
           'boxPorosity', 'avgNumInteractions', 'createInteraction', '_commonBodySetup', 'sumForces', 'sumTorques',
           'getStress', 'growParticle', 'clumpTemplate']


def _O():
    return Omega()


def defaultMaterial():
    return FrictMat(density=1e3, young=1e7, poisson=.3, frictionAngle=.5, label='defaultMat')


def randomOrientation():
    """A uniformly distributed random orientation (YADE's utils.randomOrientation, after Eigen's
    Quaternion::UnitRandom), drawn with Python's `random` in YADE's order: u1, then u2 and u3 scaled by
    pi, giving (w, x, y, z) = (a sin u2, a cos u2, b sin u3, b cos u3) with a = sqrt(1 - u1), b = sqrt(u1)."""
    u1 = random.random()
    u2 = random.random() * math.pi
    u3 = random.random() * math.pi
    a, b = math.sqrt(1 - u1), math.sqrt(u1)
    return Quaternion(a * math.sin(u2), a * math.cos(u2), b * math.sin(u3), b * math.cos(u3))


def randomColor(seed=None):
    random.seed(seed)
    return Vector3(random.random(), random.random(), random.random())


def SpherePWaveTimeStep(radius, density, young):
    return radius / math.sqrt(young / density)


def _material(material):
    O = _O()
    if isinstance(material, int):
        if material < 0 and len(O.materials) == 0:
            O.materials.append(defaultMaterial())
        return O.materials[material]
    if isinstance(material, str):
        return O.materials[material]
    if isinstance(material, Material):
        return material
    if callable(material):
        return material()
    raise TypeError("The 'material' argument must be None (for defaultMaterial), string (for shared material label), "
                    "int (for shared material id) or Material instance.")


def _require_finite(fn, **args):
    """A NaN or infinite argument of a body builder stops here, naming the argument and its value
    (YADE would build the body and the run would fail later; ryade cannot carry it to the core)."""
    from ._errors import script_location
    for name, v in args.items():
        try:
            vals = [float(x) for x in v] if hasattr(v, '__len__') else [float(v)]
        except (TypeError, ValueError):
            continue
        if not all(x == x and x not in (float('inf'), float('-inf')) for x in vals):
            raise ValueError('utils.%s: %s = %r is not finite (ryade cannot take NaN or infinity into the simulation) %s'
                             % (fn, name, v, script_location()))


def _commonBodySetup(b, volume, geomInertia, material, pos, noBound=False, resetState=True, dynamic=None, fixed=False,
                     blockedDOFs='xyzXYZ'):
    """py/utils.py::_commonBodySetup: mass = V·ρ, inertia = geomInertia·ρ (Python arithmetic, as YADE)."""
    b.material = _material(material)
    mass = volume * b.material.density
    st = b.state
    st.mass = mass
    st.inertia = Vector3(*geomInertia) * b.material.density
    st.pos = pos
    st.refPos = pos
    b.bounded = not noBound
    if dynamic is not None:
        fixed = not dynamic
    st.blockedDOFs = blockedDOFs if fixed else ''


def sphere(center, radius, dynamic=None, fixed=False, wire=False, color=None, highlight=False, material=-1, mask=1):
    _require_finite('sphere', center=center, radius=radius)
    b = Body()
    b.shape = Sphere(radius=radius, color=color if color else randomColor(), wire=wire, highlight=highlight)
    V = (4. / 3) * math.pi * radius**3
    geomInert = (2. / 5.) * V * radius**2
    _commonBodySetup(b, V, (geomInert, geomInert, geomInert), material, pos=center, dynamic=dynamic, fixed=fixed)
    b.aspherical = False
    b.mask = mask
    return b


def box(center, extents, orientation=Quaternion(1, 0, 0, 0), dynamic=None, fixed=False, wire=False, color=None,
        highlight=False, material=-1, mask=1):
    _require_finite('box', center=center, extents=extents)
    b = Body()
    b.shape = Box(extents=extents, color=color if color else randomColor(), wire=wire, highlight=highlight)
    V = 8 * extents[0] * extents[1] * extents[2]
    geomInert = (V / 3.) * Vector3(extents[1]**2 + extents[2]**2, extents[0]**2 + extents[2]**2, extents[0]**2 + extents[1]**2)
    _commonBodySetup(b, V, geomInert, material, pos=center, dynamic=dynamic, fixed=fixed)
    b.state.ori = orientation
    b.mask = mask
    b.aspherical = True
    return b


def wall(position, axis, sense=0, color=None, material=-1, mask=1):
    _require_finite('wall', position=position)
    b = Body()
    b.shape = Wall(sense=sense, axis=axis, color=color if color else randomColor())
    if isinstance(position, (int, float)):
        pos2 = Vector3(0, 0, 0)
        pos2[axis] = position
    else:
        pos2 = position
    _commonBodySetup(b, 0, (0, 0, 0), material, pos=pos2, fixed=True)
    b.aspherical = False
    b.mask = mask
    return b


def inscribedCircleCenter(v0, v1, v2):
    """Shop::inscribedCircleCenter, evaluated by the Rust core in YADE's order."""
    return Vector3(*_ryade.inscribed_circle_center(to_vec3(v0, 'v0'), to_vec3(v1, 'v1'), to_vec3(v2, 'v2')))


def facet(vertices, dynamic=None, fixed=True, wire=True, color=None, highlight=False, noBound=False, material=-1, mask=1):
    for k in range(3):
        _require_finite('facet', **{'vertices[%d]' % k: vertices[k]})
    b = Body()
    center = inscribedCircleCenter(vertices[0], vertices[1], vertices[2])
    vertices = Vector3(*vertices[0]) - center, Vector3(*vertices[1]) - center, Vector3(*vertices[2]) - center
    b.shape = Facet(color=color if color else randomColor(), wire=wire, highlight=highlight, vertices=vertices)
    _commonBodySetup(b, 0, (0, 0, 0), material, noBound=noBound, pos=center, fixed=fixed)
    b.aspherical = False
    b.mask = mask
    return b


def aabbExtrema(cutoff=0.0, centers=False):
    if cutoff != 0.0 or centers:
        unsupported('aabbExtrema(cutoff, centers)')
    e = _O()._sim.aabb_extrema()
    if e is None:
        raise RuntimeError('aabbExtrema: no spheres in the scene')
    return Vector3(*e[0]), Vector3(*e[1])


def aabbDim(cutoff=0., centers=False):
    a, b = aabbExtrema(cutoff, centers)
    return b - a


def aabbWalls(extrema=None, thickness=0, oversizeFactor=1.5, **kw):
    walls = []
    if not extrema:
        extrema = aabbExtrema()
    for axis in [0, 1, 2]:
        mi, ma = extrema
        center = [(mi[i] + ma[i]) / 2. for i in range(3)]
        extents = [.5 * oversizeFactor * (ma[i] - mi[i]) for i in range(3)]
        extents[axis] = thickness / 2.
        for j in [0, 1]:
            center[axis] = extrema[j][axis] + (j - .5) * thickness
            walls.append(box(center=center, extents=extents, fixed=True, **kw))
            walls[-1].shape.wire = True
    return walls


def typedEngine(name):
    return [e for e in _O().engines if e.__class__.__name__ == name][0]


def PWaveTimeStep():
    dt = _O()._sim.pwave_time_step()
    if dt is None:
        print('WARN: PWaveTimeStep: no spheres found, returning 1.0 (as YADE does)')
        return 1.0
    return dt


def unbalancedForce(useMaxForce=False):
    return _O()._sim.unbalanced_force(bool(useMaxForce))


def getStress(volume=0):
    """Shop::getStress: Love-Weber stress of the real contacts, divided by the cell volume (periodic) or
    ``volume``."""
    from .minieigen import Matrix3
    return Matrix3(*[x for row in _O()._sim.get_stress(float(volume)) for x in row])


def kineticEnergy(findMaxId=False):
    if findMaxId:
        unsupported('kineticEnergy(findMaxId=True)')
    return _O()._sim.kinetic_energy()


def porosity(volume=-1):
    return _O()._sim.porosity(float(volume) if volume > 0 else None)


def voxelPorosity(resolution=200, start=Vector3(0, 0, 0), end=Vector3(0, 0, 0)):
    O = _O()
    spheres = [(tuple(b.state.pos), b.shape.radius) for b in O.bodies if isinstance(b.shape, Sphere) and b.dynamic]
    return _ryade.voxel_porosity(spheres, int(resolution), to_vec3(start, 'start'), to_vec3(end, 'end'))


def boxPorosity(lo, hi, periodicXY=None):
    """ryade extension: porosity of an axis-aligned box from the exact sphere-box intersection volumes
    (all spheres, periodic images in x and y when `periodicXY=(Lx, Ly)` is given)."""
    O = _O()
    spheres = [(tuple(b.state.pos), b.shape.radius) for b in O.bodies if isinstance(b.shape, Sphere)]
    return _ryade.box_porosity(spheres, to_vec3(lo, 'lo'), to_vec3(hi, 'hi'), periodicXY)


def avgNumInteractions(cutoff=0., skipFree=False, considerClumps=False):
    if cutoff or skipFree or considerClumps:
        unsupported('avgNumInteractions(cutoff, skipFree, considerClumps)')
    O = _O()
    n = sum(1 for b in O.bodies if b.dynamic and isinstance(b.shape, Sphere))
    return 2.0 * O.interactions.countReal() / n if n else float('nan')


def sumForces(ids, direction):
    O = _O()
    d = Vector3(*to_vec3(direction, 'direction'))
    return sum(O.forces.f(i).dot(d) for i in ids)


def createInteraction(id1, id2, virtualI=False):
    """`utils.createInteraction`: geometry forced with the InteractionLoop's functors, physics created."""
    if virtualI:
        unsupported('createInteraction(virtualI=True)')
    O = _O()
    a, b = O._sim.create_interaction(int(id1), int(id2))
    from ._core import Interaction
    return Interaction(O, a, b)


def sumTorques(ids, axis, axisPt):
    unsupported('utils.sumTorques')


def growParticle(bodyID, multiplier, updateMass=True):
    """Scale the radius of sphere `bodyID` by `multiplier` (and its mass by multiplier^3, inertia by
    multiplier^5): Shop::growParticle (preprocessing/dem/Shop_02.cpp). YADE also sets the reference radii
    of the sphere's contacts, which ryade's core does not expose: a sphere with contacts is refused."""
    O = _O()
    b = O.bodies[bodyID]
    if not isinstance(b.shape, Sphere):
        raise TypeError('growParticle: body #%d is not a Sphere' % bodyID)
    if b.intrs():
        unsupported('utils.growParticle of a sphere with contacts (their reference radii follow it in YADE)')
    b.shape.radius = b.shape.radius * multiplier
    if updateMass:
        b.state.mass = b.state.mass * math.pow(multiplier, 3)
        b.state.inertia = b.state.inertia * math.pow(multiplier, 5)


class clumpTemplate(object):
    """A clump template for O.bodies.replaceByClumps: relative radii and relative positions (py/utils.py
    clumpTemplate, with its checks: same lengths, at least two members, 3 coordinates each, no two equal
    positions)."""

    def __init__(self, relRadii=[], relPositions=[[], []]):
        if len(relRadii) != len(relPositions):
            raise ValueError("Given lists must have same length! Given lists does not match clump template structure.")
        if len(relRadii) < 2:
            raise ValueError("One or more of given lists for relative radii have length < 2! Given lists does not match "
                             "clump template structure.")
        for i, p in enumerate(relPositions):
            if len(p) != 3:
                raise ValueError("One or more of given lists for relative positions do not have length of 3! Given lists "
                                 "does not match clump template structure.")
            if any(p == q for q in relPositions[i + 1:]):
                raise ValueError("Two or more of given lists for relative positions are equal! Given lists does not match "
                                 "clump template structure.")
        self.numCM = len(relRadii)
        self.relRadii = relRadii
        self.relPositions = relPositions


def __getattr__(name):
    """A YADE utils function ryade lacks fails with a clear message."""
    if name.startswith('__'):
        raise AttributeError(name)
    unsupported('yade.utils.%s' % name)
