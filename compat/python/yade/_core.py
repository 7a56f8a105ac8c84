"""`O` (Omega) and the containers a YADE script talks to: bodies, materials, engines, interactions,
forces, the periodic cell. Each object is a view onto the Rust scene (`_ryade.Sim`), addressed by id, so
YADE's live-reference semantics hold (`O.bodies[1].state.vel[2] = 0.1` moves the body)."""

import builtins
import json
import math
import operator
import os
import sys

from . import _ryade
from ._errors import bridge_json, unsupported
from .minieigen import Matrix3, Quaternion, Vector3, Vector3i, to_vec3
from .wrapper import BubbleMat, Engine, FrictMat, LudingMat, Material, Serializable, YADE_CLASSES


def _blocked_bits(s):
    bits = 0
    for c in s:
        try:
            bits |= {'x': 1, 'y': 2, 'z': 4, 'X': 8, 'Y': 16, 'Z': 32}[c]
        except KeyError:
            raise ValueError("invalid character '%s' in blockedDOFs '%s': use letters from 'xyzXYZ'" % (c, s))
    return bits


def _blocked_str(bits):
    return ''.join(c for c, b in zip('xyzXYZ', (1, 2, 4, 8, 16, 32)) if bits & b)


# ---------------------------------------------------------------- shapes


def _fast_threads_env():
    """RYADE_FAST_THREADS (default 1): the fast path's thread count for `compat run --fast`."""
    v = os.environ.get('RYADE_FAST_THREADS', '1')
    try:
        n = int(v)
    except ValueError:
        n = 0
    if n < 1:
        raise RuntimeError('RYADE_FAST_THREADS=%r: give a thread count of 1 or more' % v)
    return n


class Shape(Serializable):
    _attrs = {'color': (1.0, 1.0, 1.0), 'wire': False, 'highlight': False}

    def _bind(self, omega, body_id):
        object.__setattr__(self, '_owner', (omega, body_id))


class Sphere(Shape):
    _attrs = {'radius': float('nan')}
    _positional = ('radius',)

    def _read(self, k):
        if k == 'radius' and self._owner is not None:
            omega, bid = self._owner
            return omega._sim.get_scalar(bid, 'radius')
        return self._values[k]

    def _changed(self, k):
        if k == 'radius' and self._owner is not None:
            omega, bid = self._owner
            omega._sim.set_scalar(bid, 'radius', float(self._values['radius']))

    def _json(self):
        return {'class': 'Sphere', 'radius': float(self._values['radius'])}


class Facet(Shape):
    _attrs = {'vertices': [], 'normal': None, 'area': None}

    def _convert(self, k, v):
        if k == 'vertices':
            if self._owner is not None:
                unsupported('changing Facet.vertices of a body already in O.bodies')
            if len(v) != 3:
                raise ValueError('a Facet needs exactly 3 vertices, got %d' % len(v))
            return [to_vec3(x, 'Facet vertex') for x in v]
        return v

    def _read(self, k):
        if k == 'vertices':
            return [Vector3(*x) for x in self._values['vertices']]
        if k in ('normal', 'area'):
            a, b, c = [Vector3(*x) for x in self._values['vertices']]
            n = (b - a).cross(c - b)
            return 0.5 * n.norm() if k == 'area' else n / n.norm()
        return self._values[k]

    def _json(self):
        return {'class': 'Facet', 'vertices': [list(v) for v in self._values['vertices']]}


class GridNode(Sphere):
    """A grid vertex (carries mass; no bound, mask 0 when made by gridpfacet.gridNode)."""

    def _json(self):
        return {'class': 'GridNode', 'radius': float(self._values['radius']), 'connections': []}

    def getConnections(self):
        if self._owner is None:
            return []
        omega, bid = self._owner
        d = json.loads(omega._sim.shape_json(bid))
        return [omega.bodies[i] for i in d.get('connections', [])]


class GridConnection(Sphere):
    """A cylinder between two GridNodes (created by gridpfacet.gridConnection)."""
    _attrs = {'node1': None, 'node2': None, 'periodic': False, 'cellDist': (0, 0, 0)}

    def _json(self):
        unsupported('appending a GridConnection body directly', 'use yade.gridpfacet.gridConnection')

    def getLength(self):
        return self.getSegment().norm()

    def getSegment(self):
        omega = self._owner[0]
        seg = self.node2.state.pos - self.node1.state.pos
        if omega.periodic:
            h, c = omega.cell.hSize, self.cellDist
            seg = seg + h * Vector3(c[0], c[1], c[2])
        return seg


class Wall(Shape):
    _attrs = {'axis': 0, 'sense': 0}

    def _json(self):
        return {'class': 'Wall', 'axis': int(self._values['axis']), 'sense': int(self._values['sense'])}


class Box(Shape):
    _attrs = {'extents': (0.0, 0.0, 0.0)}

    def _convert(self, k, v):
        return to_vec3(v, 'Box.extents') if k == 'extents' else v

    def _read(self, k):
        return Vector3(*self._values['extents']) if k == 'extents' else self._values[k]

    def _json(self):
        return {'class': 'Box', 'extents': list(self._values['extents'])}


class Clump(Shape):
    """`Clump`: a rigid aggregate of spheres, made by `O.bodies.appendClumped` or `O.bodies.clump`
    (discretization 0). The members and their poses in the clump frame live in the Rust core."""

    def _json(self):
        unsupported('appending a Clump body directly', 'use O.bodies.appendClumped or O.bodies.clump')

    def _members(self):
        if self._owner is None:
            return []
        omega, bid = self._owner
        return json.loads(omega._sim.shape_json(bid))['members']

    @property
    def members(self):
        """{memberId: (relPos, relOri)}, the members' poses in the clump's principal frame."""
        return {m['id']: (Vector3(*m['relPos']), Quaternion(*m['relOri'])) for m in self._members()}

    @property
    def ids(self):
        return [m['id'] for m in self._members()]


# ---------------------------------------------------------------- state and body

_STATE_VEC = ('pos', 'vel', 'angVel', 'inertia')


class State(Serializable, _ryade.StateBase):
    """`State`: kinematic state. Unbound (before O.bodies.append) it stores values; bound it is a view.

    Its hot paths are in the Rust base `_ryade.StateBase` (controllers read and set velocities every
    step): `__setattr__` stores a plain Vector3 into pos/vel/angVel/inertia of a bound state straight
    into the scene (the same effect as `Serializable._assign`: convert, then `_changed`) and hands every
    other assignment to `_slow_setattr`; `pos` (a copy, YADE computes it), `vel` and `angVel` (live
    views) are read there, unbound ones through `_read`."""
    _attrs = {'pos': (0.0, 0.0, 0.0), 'vel': (0.0, 0.0, 0.0), 'angVel': (0.0, 0.0, 0.0), 'inertia': (0.0, 0.0, 0.0),
              'ori': (1.0, 0.0, 0.0, 0.0), 'mass': 0.0, 'blockedDOFs': '', 'isDamped': True,
              'refPos': (0.0, 0.0, 0.0), 'refOri': (1.0, 0.0, 0.0, 0.0), 'angMom': (0.0, 0.0, 0.0),
              'densityScaling': -1.0}

    __setattr__ = _ryade._state_setattr(Vector3)
    _slow_setattr = Serializable.__setattr__

    def _bind(self, omega, body_id):
        object.__setattr__(self, '_owner', (omega, body_id))
        self._rs_bind(omega._sim, body_id)

    def _missing(self, k):
        # a CpmMat body's state is a CpmState in YADE (post-processing values CpmStateUpdater writes)
        if k in YADE_CLASSES.get('CpmState', {}).get('attrs', ()):
            unsupported('the attribute CpmState.%s' % k)
        Serializable._missing(self, k)

    # copy/pickle: the Python attributes (the Rust base's binding is re-made from _owner)
    def __getstate__(self):
        return self.__dict__

    def __setstate__(self, d):
        self.__dict__.update(d)
        o = d.get('_owner')
        if o is not None:
            self._rs_bind(o[0]._sim, o[1])

    def _convert(self, k, v):
        if k in _STATE_VEC or k in ('refPos', 'angMom'):
            return to_vec3(v, 'State.' + k)
        if k in ('ori', 'refOri'):
            if isinstance(v, Quaternion):
                return (v[3], v[0], v[1], v[2])
            raise TypeError('State.%s must be a Quaternion' % k)
        if k == 'blockedDOFs':
            _blocked_bits(v)
            return v
        if k == 'mass':
            return float(v)
        return v

    def _changed(self, k):
        if self._owner is None:
            return
        omega, bid = self._owner
        sim, v = omega._sim, self._values[k]
        if k in _STATE_VEC:
            sim.set_vec3(bid, k, tuple(v))
        elif k == 'ori':
            sim.set_ori(bid, tuple(v))
        elif k == 'mass':
            sim.set_scalar(bid, 'mass', v)
        elif k == 'blockedDOFs':
            sim.set_int(bid, 'blockedDOFs', _blocked_bits(v))
        elif k == 'isDamped':
            sim.set_int(bid, 'isDamped', int(bool(v)))
        elif k == 'angMom':
            sim.set_vec3(bid, 'angMom', tuple(v))
        elif k in ('refPos', 'refOri'):
            pass  # bookkeeping only (used by utils displacement helpers)
        else:
            unsupported('State.%s' % k)

    def _read(self, k):
        if self._owner is None:
            v = self._values[k]
            if k in _STATE_VEC or k in ('refPos', 'angMom'):
                return Vector3(*v)
            if k in ('ori', 'refOri'):
                return Quaternion(*v)
            return v
        omega, bid = self._owner
        sim = omega._sim
        if k == 'pos':
            # YADE quirk kept on purpose: pos and ori are computed properties (se3), so
            # `b.state.pos[1] = 3` changes a temporary copy and leaves the body where it was
            return Vector3(*sim.get_vec3(bid, 'pos'))
        if k in _STATE_VEC:
            return Vector3._view(lambda: sim.get_vec3(bid, k), lambda t: sim.set_vec3(bid, k, tuple(t)))
        if k == 'ori':
            return Quaternion(*sim.get_ori(bid))
        if k == 'mass':
            return sim.get_scalar(bid, 'mass')
        if k == 'blockedDOFs':
            return _blocked_str(sim.get_int(bid, 'blockedDOFs'))
        if k == 'isDamped':
            return bool(sim.get_int(bid, 'isDamped'))
        if k == 'angMom':
            return Vector3(*sim.get_vec3(bid, 'angMom'))
        if k == 'refPos':
            return Vector3(*self._values['refPos'])
        if k == 'refOri':
            return Quaternion(*self._values['refOri'])
        return self._values[k]

    def displ(self):
        """`State::displ` (core/State.hpp): pos - refPos (a method, as in YADE)."""
        return self.pos - self.refPos

    def rot(self):
        """`State::rot`: the rotation vector of refOri.conjugate() * ori (axis times angle)."""
        return (self.refOri.conjugate() * self.ori).toRotationVector()

    def _json_into(self, d):
        v = self._values
        d.update({'pos': list(v['pos']), 'vel': list(v['vel']), 'angVel': list(v['angVel']), 'ori': list(v['ori']),
                  'mass': float(v['mass']), 'inertia': list(v['inertia']), 'blockedDOFs': _blocked_bits(v['blockedDOFs']),
                  'isDamped': bool(v['isDamped'])})


class Body(Serializable):
    _attrs = {'shape': None, 'state': None, 'material': None, 'groupMask': 1, 'bounded': True, 'aspherical': False,
              'bound': None, 'clumpId': -1, 'iterBorn': -1, 'timeBorn': -1.0, 'flags': 0}

    def __init__(self, **kw):
        Serializable.__init__(self, **kw)
        if self._values['state'] is None:
            self._values['state'] = State()
        # `b.state` is read every step by controllers: a plain instance attribute (no property call),
        # kept equal to _values['state'] by _assign
        self.__dict__['state'] = self._values['state']
        object.__setattr__(self, '_id', -1)

    @property
    def id(self):
        return self._id

    @property
    def mat(self):
        return self.material

    @mat.setter
    def mat(self, m):
        self.material = m

    @property
    def mask(self):
        return self.groupMask

    @mask.setter
    def mask(self, m):
        self.groupMask = m

    @property
    def dynamic(self):
        return self.state.blockedDOFs != 'xyzXYZ'

    @dynamic.setter
    def dynamic(self, d):
        self.state.blockedDOFs = '' if d else 'xyzXYZ'

    @property
    def clumpId(self):
        """Id of the clump this body belongs to (its own id for a clump), -1 for a standalone body."""
        if self._owner is None:
            return -1
        return self._owner[0]._sim.get_int(self._id, 'clumpId')

    @property
    def isClump(self):
        return isinstance(self._values['shape'], Clump)

    @property
    def isStandalone(self):
        return self.clumpId < 0

    @property
    def isClumpMember(self):
        c = self.clumpId
        return c >= 0 and c != self._id

    def _assign(self, k, v):
        Serializable._assign(self, k, v)
        if k == 'state':
            self.__dict__['state'] = self._values['state']

    def _changed(self, k):
        if self._owner is None:
            return
        omega, bid = self._owner
        if k == 'groupMask':
            omega._sim.set_int(bid, 'mask', int(self._values['groupMask']))
        elif k == 'bounded':
            omega._sim.set_int(bid, 'bounded', int(bool(self._values['bounded'])))
        else:
            unsupported('changing Body.%s of a body already in O.bodies' % k)

    def intrs(self):
        # Body::py_intrs (core/Body.cpp): the real ones, in the order of Body::intrs, a map by the other id
        if not self._owner:
            return []
        mine = [i for i in self._owner[0].interactions if i.id1 == self._id or i.id2 == self._id]
        return sorted(mine, key=lambda i: i.id2 if i.id1 == self._id else i.id1)

    def _json(self, material_json):
        d = {'id': 0, 'shape': self._values['shape']._json(), 'material': material_json,
             'mask': int(self._values['groupMask']), 'bounded': bool(self._values['bounded'])}
        self._values['state']._json_into(d)
        return d


# ---------------------------------------------------------------- containers

class _YadeMembers(object):
    """A member YADE's container has and ryade's lacks fails with the "does not support" message (the
    script's line named), not a bare AttributeError; `_yade_table` names its list in _yade_names.json."""
    _yade_table = None

    def __getattr__(self, k):
        if not k.startswith('_'):
            from ._check import _tables
            if k in _tables()['objects'].get(self._yade_table, ()):
                unsupported('%s.%s' % (self._yade_table, k))
        raise AttributeError("'%s' object has no attribute '%s'" % (type(self).__name__, k))


class BodyContainer(_YadeMembers):
    _yade_table = 'O.bodies'

    def __init__(self, omega):
        self._o = omega
        self._objs = []

    def append(self, b):
        if isinstance(b, (list, tuple)):
            return [self.append(x) for x in b]
        if not isinstance(b, Body):
            raise TypeError('O.bodies.append takes a Body or a list of Bodies, not %s' % type(b).__name__)
        if getattr(b, '_pending_append', False):
            # a gridConnection body: the core created it (and its bond) already, with the next id
            object.__setattr__(b, '_pending_append', False)
            return b.id
        if any(getattr(x, '_pending_append', False) for x in self._objs[-8:]):
            unsupported('appending other bodies between gridConnection() and O.bodies.append() of its result')
        if b._owner is not None:
            raise IndexError('body already has id %d set; appending such body (for the second time) is not allowed' % b.id)
        o = self._o
        if b.shape is None:
            raise ValueError('a Body needs a shape before it is appended')
        mat = b.material
        if mat is None:
            mat = o.materials._default()
            b._values['material'] = mat
        if not isinstance(mat, (FrictMat, LudingMat, BubbleMat)):
            unsupported('material class %s' % type(mat).__name__)
        if o._sim.in_step():
            unsupported('adding bodies from inside a PyRunner during a step', 'add them between O.run calls')
        bid = o._sim.add_body(bridge_json(b._json(mat._json()), 'O.bodies.append: body #%d' % len(self._objs)))
        object.__setattr__(b, '_id', bid)
        b._bind_all(o, bid) if hasattr(b, '_bind_all') else None
        object.__setattr__(b, '_owner', (o, bid))
        b._values['shape']._bind(o, bid)
        b._values['state']._bind(o, bid)
        if mat._owner is None:
            mat._bind(o, o._sim.material_index_of_body(bid))
        b._values['iterBorn'] = o.iter
        b._values['timeBorn'] = o.time
        self._objs.append(b)
        return bid

    def _adopt(self, bid, shape, material):
        """A Python view for a body the Rust core created (gridConnection's connection body)."""
        b = Body()
        b._values['shape'] = shape
        b._values['material'] = material
        object.__setattr__(b, '_id', bid)
        object.__setattr__(b, '_owner', (self._o, bid))
        shape._bind(self._o, bid)
        b._values['state']._bind(self._o, bid)
        b._values['groupMask'] = self._o._sim.get_int(bid, 'mask')
        b._values['bounded'] = bool(self._o._sim.get_int(bid, 'bounded'))
        if len(self._objs) != bid:
            raise RuntimeError('internal: body ids out of sync (%d vs %d)' % (len(self._objs), bid))
        self._objs.append(b)
        return b

    def __getitem__(self, i):
        if not isinstance(i, int):
            raise TypeError('body ids are integers')
        n = len(self._objs)
        if i < 0 or i >= n:
            raise IndexError('Body id out of range.')
        return self._objs[i]

    def __len__(self):
        return len(self._objs)

    def __iter__(self):
        return iter(list(self._objs))

    def erase(self, i, eraseClumpMembers=False):
        unsupported('O.bodies.erase')

    def clump(self, ids, discretization=0):
        """Clump the bodies `ids` (standalone spheres) into a new rigid clump body appended after them
        (YADE's `Clump::add` + `Clump::updateProperties` with discretization 0); returns its id."""
        if discretization:
            unsupported('clump discretization=%d (inertia by volume integration of the overlaps)' % discretization,
                        'use discretization=0, the default')
        o = self._o
        if o._sim.in_step():
            unsupported('making clumps from inside a PyRunner during a step', 'make them between O.run calls')
        ids = [int(i) for i in ids]
        cid = o._sim.make_clump(ids, 0)
        b = self._adopt(cid, Clump(), None)
        b._values['aspherical'] = bool(o._sim.get_int(cid, 'aspherical'))
        b._values['iterBorn'] = o.iter
        b._values['timeBorn'] = o.time
        return cid

    def appendClumped(self, bodies, discretization=0):
        """Append `bodies` and clump them; returns (clumpId, [memberIds])."""
        if discretization:
            unsupported('clump discretization=%d (inertia by volume integration of the overlaps)' % discretization,
                        'use discretization=0, the default')
        ids = self.append(list(bodies))
        return (self.clump(ids, discretization), ids)

    def clear(self):
        unsupported('O.bodies.clear')

    def replace(self, bodies):
        unsupported('O.bodies.replace')


def _get_roundness(self, excludeList=[]):
    """O.bodies.getRoundness (py/wrapper/yadeWrapper.cpp): the mean over standalone spheres (1 each) and
    clumps (R1/R2: R1 the radius of the sphere of the clump's volume, mass / its last member's density;
    R2 the radius of the smallest sphere about the clump's center holding its members) of the bodies not
    in `excludeList`; 0 when there are none."""
    import warnings
    excl = set(int(i) for i in excludeList)
    total, n = 0.0, 0
    for b in self:
        if b is None or b.id in excl:
            continue
        if isinstance(b.shape, Sphere) and b.isStandalone:
            total += 1.0
            n += 1
        if isinstance(b.shape, Clump):
            r2 = dens = vol = 0.0
            for mid in sorted(b.shape.members.keys()):
                m = self[mid]
                if isinstance(m.shape, Sphere):
                    r2 = max((m.state.pos - b.state.pos).norm() + m.shape.radius, r2)
                    dens = m.material.density
            if dens > 0.:
                vol = b.state.mass / dens
            r1 = math.pow((3. * vol) / (4. * math.pi), 1. / 3.)
            if r2 < r1:
                warnings.warn('Something went wrong in getRoundness method (R2 < R1 detected).', UserWarning)
                return 0
            total += r1 / r2
            n += 1
    return total / (n if n else 1)


BodyContainer.getRoundness = _get_roundness


def _unsupported_clump_op(name, hint=None):
    def op(self, *a, **kw):
        unsupported('O.bodies.' + name, hint)
    op.__name__ = name
    return op


# the clump operations beyond appendClumped/clump (YADE's BodyContainer has them)
for _name, _hint in (('replaceByClumps', 'build the clumps with O.bodies.appendClumped'), ('addToClump', None),
                     ('releaseFromClump', None), ('deleteClumpMember', None), ('deleteClumpBody', None),
                     ('updateClumpProperties', None)):
    setattr(BodyContainer, _name, _unsupported_clump_op(_name, _hint))


class MaterialContainer(_YadeMembers):
    _yade_table = 'O.materials'

    def __init__(self, omega):
        self._o = omega
        self._mats = []

    def append(self, m):
        if isinstance(m, (list, tuple)):
            return [self.append(x) for x in m]
        if not isinstance(m, Material):
            raise TypeError('O.materials.append takes a Material')
        if not isinstance(m, (FrictMat, LudingMat, BubbleMat)):
            unsupported('material class %s' % type(m).__name__)
        mid = len(self._mats)
        m._values['id'] = mid
        idx = self._o._sim.add_material(bridge_json(m._json(), 'O.materials.append(%s)' % type(m).__name__))
        m._bind(self._o, idx)
        self._mats.append(m)
        return mid

    def _default(self):
        """`utils.defaultMaterial()` appended when a body takes material=-1 and O.materials is empty."""
        if not self._mats:
            from .utils import defaultMaterial
            self.append(defaultMaterial())
        return self._mats[-1]

    def __getitem__(self, k):
        if isinstance(k, str):
            for m in self._mats:
                if m.label == k:
                    return m
            raise KeyError("No material labeled '%s'." % k)
        return self._mats[k]

    def __len__(self):
        return len(self._mats)

    def __iter__(self):
        return iter(list(self._mats))


class _GeomView(object):
    """`i.geom` of a real interaction: ScGeom attributes (plus 6-D and grid ones) read live."""
    _fields = {'normal': 'v', 'penetrationDepth': 's', 'contactPoint': 'v', 'shearInc': 'v', 'refR1': 's', 'refR2': 's'}
    _cls = 'ScGeom'
    _role = 0

    def __init__(self, omega, a, b):
        object.__setattr__(self, '_k', (omega, a, b))

    def __getattr__(self, k):
        if k in self._fields:
            omega, a, b = self._k
            v = omega._sim.intr_get(a, b, k)
            return Vector3(*v) if self._fields[k] == 'v' else v
        if k in ('twist', 'bending', 'relPos', 'isDuplicate', 'trueInt') and self._cls == 'ScGeom':
            omega, a, b = self._k
            v = omega._sim.intr_get_ext(a, b, k)
            if v is not None:
                return Vector3(*v) if k == 'bending' else v
        if k in YADE_CLASSES.get(self._cls, {}).get('attrs', ()):
            unsupported('%s.%s' % (self._cls, k))
        raise AttributeError("'%s' object has no attribute '%s'" % (self._cls, k))

    def __setattr__(self, k, v):
        unsupported('setting %s.%s' % (self._cls, k))

    @property
    def __class__(self):
        from .wrapper import class_by_name
        omega, a, b = self._k
        return class_by_name(omega._sim.intr_classes(a, b)[type(self)._role])

    def dict(self):
        return {k: getattr(self, k) for k in self._fields}


class _PhysView(_GeomView):
    _fields = {'normalForce': 'v', 'shearForce': 'v', 'kn': 's', 'ks': 's', 'tangensOfFrictionAngle': 's'}
    _cls = 'FrictPhys'
    _role = 1
    _ext = {'kr': 's', 'ktw': 's', 'unp': 's', 'unpMax': 's', 'normalAdhesion': 's', 'shearAdhesion': 's',
            'cohesionBroken': 'b', 'momentRotationLaw': 'b', 'moment_twist': 'v', 'moment_bending': 'v'}

    _mindlin = ('kno', 'kso', 'maxBendPl', 'normalViscous', 'shearViscous', 'shearElastic', 'usElastic', 'usTotal',
                'momentBend', 'momentTwist', 'radius', 'adhesionForce', 'isAdhesive', 'isSliding', 'betan', 'betas',
                'kr', 'ktw')

    _cpm = ('omega', 'Fn', 'Fs', 'epsN', 'epsT', 'sigmaN', 'sigmaT', 'kappaD', 'epsNPl', 'epsTPl', 'relResidualStrength',
            'E', 'G', 'tanFrictionAngle', 'undamagedCohesion', 'crossSection', 'refLength', 'refPD', 'epsCrackOnset',
            'relDuctility', 'epsFracture', 'equivStrainShearContrib', 'dmgTau', 'dmgRateExp', 'dmgStrain',
            'dmgOverstress', 'plTau', 'plRateExp', 'isoPrestress', 'neverDamage', 'damLaw', 'isCohesive')

    def __getattr__(self, k):
        if k in self._cpm:
            omega, a, b = self._k
            v = omega._sim.intr_cpm(a, b, k)
            if v is not None:
                import json
                v = json.loads(v)
                if isinstance(v, list):
                    return Vector3(*v)
                return float('nan') if v == 'nan' else v
        if k in self._mindlin:
            omega, a, b = self._k
            v = omega._sim.intr_mindlin(a, b, k)
            if v is not None:
                import json
                v = json.loads(v)
                if isinstance(v, list):
                    return Vector3(*v)
                return float('nan') if v == 'nan' else v
        if k in self._ext:
            omega, a, b = self._k
            v = omega._sim.intr_get_ext(a, b, k)
            if v is None:
                raise AttributeError("'FrictPhys' object has no attribute '%s'" % k)
            return Vector3(*v) if self._ext[k] == 'v' else v
        return _GeomView.__getattr__(self, k)

    def __setattr__(self, k, v):
        omega, a, b = self._k
        if k in ('normalForce', 'shearForce'):
            omega._sim.intr_set_vec3(a, b, k, to_vec3(v, k))
            return
        if k in ('kn', 'ks', 'kr', 'ktw', 'unp', 'unpMax', 'momentRotationLaw'):
            omega._sim.intr_set_scalar(a, b, k, float(v))
            return
        unsupported('setting the interaction attribute phys.%s' % k)


_NAMED = {}


def _named_class(name):
    if name not in _NAMED:
        _NAMED[name] = type(name, (object,), {})
    return _NAMED[name]


class Interaction(object):
    def __init__(self, omega, a, b):
        self._o, self._a, self._b = omega, a, b

    def _get(self, k):
        return self._o._sim.intr_get(self._a, self._b, k)

    @property
    def id1(self):
        return self._get('id1')

    @property
    def id2(self):
        return self._get('id2')

    @property
    def isReal(self):
        return self._get('isReal')

    @property
    def iterMadeReal(self):
        return self._get('iterMadeReal')

    @property
    def iterBorn(self):
        return self._get('iterBorn')

    @property
    def cellDist(self):
        return Vector3i(*self._get('cellDist'))

    @property
    def geom(self):
        return _GeomView(self._o, self._a, self._b) if self.isReal else None

    @property
    def phys(self):
        return _PhysView(self._o, self._a, self._b) if self.isReal else None

    def __repr__(self):
        return '<Interaction instance at %#x>' % id(self)


class InteractionContainer(_YadeMembers):
    _yade_table = 'O.interactions'

    def __init__(self, omega):
        self._o = omega

    def __iter__(self):
        return iter([Interaction(self._o, a, b) for a, b in self._o._sim.intr_list(True)])

    def all(self, onlyReal=False):
        return [Interaction(self._o, a, b) for a, b in self._o._sim.intr_list(bool(onlyReal))]

    def __len__(self):
        return len(self._o._sim.intr_list(False))

    def __getitem__(self, key):
        a, b = key
        if not self._o._sim.intr_exists(a, b):
            raise IndexError('No such interaction')
        return Interaction(self._o, a, b)

    def has(self, a, b, onlyReal=False):
        if not self._o._sim.intr_exists(a, b):
            return False
        return self._o._sim.intr_get(a, b, 'isReal') if onlyReal else True

    def countReal(self):
        return self._o._sim.intr_count_real()

    def withBody(self, bid):
        return [i for i in self if i.id1 == bid or i.id2 == bid]

    def withBodyAll(self, bid):
        return [i for i in self.all(False) if i.id1 == bid or i.id2 == bid]

    def nth(self, n):
        return self.all(False)[n]

    def erase(self, a, b):
        unsupported('O.interactions.erase')

    def clear(self):
        unsupported('O.interactions.clear')


class ForceContainer(_YadeMembers):
    _yade_table = 'O.forces'

    def __init__(self, omega):
        self._o = omega
        # O.forces.f(id, sync=False) / O.forces.t(id, sync=False), read every step by controllers:
        # C functions bound to the scene that build the Vector3 themselves (Sim.force_vec/torque_vec
        # for anything but f(id))
        self.f = _ryade._forces_accessor(omega._sim, False)
        self.t = _ryade._forces_accessor(omega._sim, True)

    def m(self, bid, sync=False):
        return self.t(bid)

    def addF(self, bid, f, permanent=False):
        if permanent:
            unsupported('O.forces.addF(..., permanent=True)', 'use O.forces.setPermF')
        self._o._sim.add_force(bid, to_vec3(f, 'force'))

    def addT(self, bid, t, permanent=False):
        if permanent:
            unsupported('O.forces.addT(..., permanent=True)', 'use O.forces.setPermT')
        self._o._sim.add_torque(bid, to_vec3(t, 'torque'))

    def setPermF(self, bid, f):
        self._o._sim.set_perm_force(bid, to_vec3(f, 'force'))

    def setPermT(self, bid, t):
        self._o._sim.set_perm_torque(bid, to_vec3(t, 'torque'))

    def sync(self):
        pass


class Cell(object):
    def __init__(self, omega):
        self._o = omega

    def _h(self):
        h = self._o._sim.get_cell()
        if h is None:
            raise RuntimeError('the scene is not periodic (set O.periodic=True first)')
        return h

    def setBox(self, *args):
        size = to_vec3(args[0] if len(args) == 1 else args, 'Cell.setBox')
        self._o._sim.set_cell([[size[0], 0.0, 0.0], [0.0, size[1], 0.0], [0.0, 0.0, size[2]]])
        self._o._sim.set_cell_matrix('trsf', [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])

    def _m(self, name):
        self._h()
        return Matrix3(*[x for row in self._o._sim.cell_matrix(name) for x in row])

    def _set_m(self, name, m):
        self._h()
        self._o._sim.set_cell_matrix(name, [[float(m[i, j]) for j in range(3)] for i in range(3)])

    @property
    def hSize(self):
        return Matrix3(*[x for row in self._h() for x in row])

    @hSize.setter
    def hSize(self, m):
        self._o._sim.set_cell([[float(m[i, j]) for j in range(3)] for i in range(3)])

    @property
    def refHSize(self):
        return self.hSize

    @property
    def hSize0(self):
        return self.trsf.inverse() * self.hSize

    @property
    def size(self):
        self._h()
        return Vector3(*self._o._sim.cell_size())

    @property
    def refSize(self):
        # Cell::getRefSize: column lengths of trsf^-1 * hSize
        h = self.hSize0
        return Vector3(*[math.sqrt(h[0, j] * h[0, j] + (h[1, j] * h[1, j] + h[2, j] * h[2, j])) for j in range(3)])

    @refSize.setter
    def refSize(self, s):
        self.setBox(s)

    @property
    def volume(self):
        self._h()
        return self._o._sim.cell_volume()

    @property
    def trsf(self):
        return self._m('trsf')

    @trsf.setter
    def trsf(self, m):
        self._set_m('trsf', m)

    def getDefGrad(self):
        return self.trsf

    @property
    def velGrad(self):
        # a copy: YADE's getter; assigning the whole matrix takes effect in NewtonIntegrator (nextVelGrad)
        return self._m('velGrad')

    @velGrad.setter
    def velGrad(self, m):
        self._set_m('velGrad', m)

    @property
    def nextVelGrad(self):
        # live, as in YADE: O.cell.nextVelGrad[0, 0] = 1 works
        def get():
            return tuple(x for row in self._o._sim.cell_matrix('nextVelGrad') for x in row)

        def put(t):
            self._o._sim.set_cell_matrix('nextVelGrad', [list(t[0:3]), list(t[3:6]), list(t[6:9])])
        self._h()
        return Matrix3._view(get, put)

    @nextVelGrad.setter
    def nextVelGrad(self, m):
        self._set_m('nextVelGrad', m)

    @property
    def prevVelGrad(self):
        return self._m('prevVelGrad')

    @property
    def velGradChanged(self):
        self._h()
        return self._o._sim.cell_vel_grad_changed()

    @property
    def homoDeform(self):
        self._h()
        return self._o._sim.cell_homo_deform()

    @homoDeform.setter
    def homoDeform(self, h):
        self._h()
        self._o._sim.set_cell_homo_deform(int(h))

    def wrap(self, p):
        return Vector3(*self._o._sim.cell_wrap(to_vec3(p, 'point')))

    def wrapPt(self, p):
        return self.wrap(p)


class EnergyTracker(object):
    """`O.energy` (YADE's EnergyTracker, kept by the Rust core): filled while `O.trackEnergy` by
    NewtonIntegrator (nonviscDamp, kinetic, gravWork), the laws (elastPotential, plastDissip, shearDissip,
    bendingDissip, twistDissip) and PeriTriaxController (velGradWork), in YADE's arithmetic and order."""

    def __init__(self, omega):
        self._o = omega

    def keys(self):
        return [k for k, _ in self._o._sim.energy_items()]

    def items(self):
        return list(self._o._sim.energy_items())

    def __getitem__(self, k):
        v = self._o._sim.energy_get(str(k))
        if v is None:
            raise KeyError("Unknown energy name '%s'." % k)
        return v

    def __setitem__(self, k, v):
        self._o._sim.energy_set(str(k), float(v))

    def total(self):
        return self._o._sim.energy_total()

    def clear(self):
        self._o._sim.energy_clear()

    def __getattr__(self, k):
        if k.startswith('__') or k == '_o':
            raise AttributeError(k)
        if k in ('energies', 'dict', 'updateAttrs', 'dispHierarchy', '_perThreadData'):
            unsupported('O.energy.%s' % k)
        raise AttributeError("'EnergyTracker' object has no attribute '%s'" % k)


# ---------------------------------------------------------------- Omega

class Omega(_ryade.OmegaBase):
    """`O`: the simulation. `Omega()` returns the same object, as in YADE. `O.iter` and `O.time` are
    read by the Rust base class (`_ryade.OmegaBase`, controllers read them every step)."""
    _instance = None

    def __new__(cls, *a, **kw):
        if Omega._instance is None:
            inst = _ryade.OmegaBase.__new__(cls)
            inst._init()
            Omega._instance = inst
        return Omega._instance

    def _init(self):
        self._sim = _ryade.Sim()
        self._sim._set_vector3(Vector3)
        self._rs_set_sim(self._sim)
        self.bodies = BodyContainer(self)
        self.materials = MaterialContainer(self)
        self.interactions = InteractionContainer(self)
        self.forces = ForceContainer(self)
        self._cell = Cell(self)
        self.energy = EnergyTracker(self)
        self.tags = {}
        self._engines = []
        self._external = []
        self._native_stop = False
        self._pending_engines = None
        self._paused = False
        self._background = None
        self.stopAtIter = 0
        self.stopAtTime = 0.0
        self.dynDt = False
        # ryade only: O.run(n, True) without Python engines runs on the fast path (issue 6; same physics,
        # free summation order, so agreement with YADE is statistical) with this many threads
        self.ryadeFastPath = False
        # (env RYADE_FAST_THREADS: the default for `compat run --fast`; each count gives its own bits)
        self.ryadeFastThreads = _fast_threads_env()
        # `compat run --fast[=strict]` (env RYADE_FAST=on|strict): every O.run the fast path can take runs
        # there; any other says why once and runs on the YADE-order path ('strict': an error instead)
        self._fast_env = os.environ.get('RYADE_FAST', '')
        self._fast_said = set()
        self._saved = {}
        self._default_engines()

    def _default_engines(self):
        """A fresh YADE `O` has a default engine list (core.md §1), labelled as YADE labels it (scripts use
        `collider`, `newton`... without defining them); `O.reset()` empties it."""
        from .wrapper import (ForceResetter, GlobalStiffnessTimeStepper, InsertionSortCollider, InteractionLoop,
                              NewtonIntegrator)
        self.engines = [ForceResetter(), InsertionSortCollider(label='collider'), InteractionLoop(label='interactionLoop'),
                        GlobalStiffnessTimeStepper(label='timeStepper'), NewtonIntegrator(damping=0.2, label='newton')]

    # ---- time ----
    # O.iter and O.time: OmegaBase
    dt = property(operator.attrgetter('_sim.dt'), lambda self, v: setattr(self._sim, 'dt', float(v)))

    @property
    def realtime(self):
        import time as _t
        return _t.time() - _START

    @property
    def numThreads(self):
        # `compat run -jN` (YADE: `yade -jN`); ryade's YADE-order path gives the same bits for any N
        return self._sim.threads

    @property
    def usesTimeStepper(self):
        return any(type(e).__name__ == 'GlobalStiffnessTimeStepper' and e.active for e in self._engines)

    @usesTimeStepper.setter
    def usesTimeStepper(self, v):
        for e in self._engines:
            if type(e).__name__ == 'GlobalStiffnessTimeStepper':
                e.active = bool(v)

    @property
    def cell(self):
        return self._cell if self._sim.get_cell() is not None else None

    @property
    def periodic(self):
        return self._sim.get_cell() is not None

    @periodic.setter
    def periodic(self, p):
        if p and self._sim.get_cell() is None:
            self._sim.set_cell([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
        elif not p:
            self._sim.set_cell(None)

    @property
    def timingEnabled(self):
        """YADE's `O.timingEnabled`: engines then collect `execTime` (ns) and `execCount` (see
        `yade.timing.stats()`); kept across `O.reset()`, as YADE's flag is."""
        return self._sim.timing_enabled

    @timingEnabled.setter
    def timingEnabled(self, on):
        self._sim.timing_enabled = bool(on)

    @property
    def trackEnergy(self):
        return self._sim.track_energy

    @trackEnergy.setter
    def trackEnergy(self, on):
        self._sim.track_energy = bool(on)

    # ---- engines ----
    @property
    def engines(self):
        return list(self._engines)

    @engines.setter
    def engines(self, lst):
        lst = list(lst)
        for e in lst:
            if not isinstance(e, Engine):
                raise TypeError('O.engines takes a list of engines, got %s' % type(e).__name__)
        if self._sim.in_step():
            self._pending_engines = lst   # YADE applies a new list at the next step (Scene::_nextEngines)
            return
        self._apply_engines(lst)

    def _harvest_timing(self):
        """Before the Rust engine list goes: each engine object keeps the time it collected there."""
        for e in self._engines:
            e._timing_detach()

    def _apply_engines(self, lst):
        self._harvest_timing()
        # an engine object already in the list keeps its Rust state (YADE keeps the object)
        old = {id(e): j for j, e in enumerate(self._engines)}
        specs, external, reuse = [], [], []
        for e in lst:
            d = e._json()
            if d.get('class') == 'External':  # a Python engine: run (and timed) by _one_step
                d['id'] = len(external)
                external.append(e)
                reuse.append(None)
            else:
                reuse.append(old.pop(id(e), None))
            specs.append(d)
        for k, d in enumerate(specs):
            bridge_json(d, 'O.engines[%d] (%s)' % (k, d.get('class')))
        self._sim.set_engines(json.dumps(specs), reuse)
        self._external = external
        self._engines = lst
        # an engine of the Rust core may end a run after a step (ryade's RyadePistonController)
        self._native_stop = any(d.get('class') == 'RyadePistonController' for d in specs)
        for k, e in enumerate(lst):
            e._bind(self, k)
            if specs[k].get('class') != 'External':
                e._timing_attach(self._sim, k)
            if e._values.get('dead'):
                self._sim.set_engine_dead(k, True)
            for f in getattr(e, '_functors', lambda: [])():
                object.__setattr__(f, '_owner', e)
        self._map_labels()

    def _map_labels(self):
        """YADE's mapLabeledEntitiesToVariables: labelled engines and functors become builtins."""
        for e in self._engines:
            for obj in [e] + list(getattr(e, '_functors', lambda: [])()):
                lab = obj._values.get('label')
                if lab:
                    setattr(builtins, lab, obj)
                    main = sys.modules.get('__main__')
                    if main is not None and getattr(main, '__ryade_script__', False):
                        # YADE sets only `__builtins__.label`: a global of the script's own (a module it
                        # imported, e.g. `plot` next to a PyRunner labelled 'plot') keeps winning; a
                        # global placed here by an earlier engine list is replaced
                        g = main.__dict__
                        placed = g.setdefault('__ryade_labels__', {})
                        if lab not in g or (lab in placed and g[lab] is placed[lab]):
                            g[lab] = obj
                            placed[lab] = obj

    # ---- stepping ----
    def _one_step(self):
        if self._pending_engines is not None:
            lst, self._pending_engines = self._pending_engines, None
            self._apply_engines(lst)
        sim = self._sim
        timed = sim.timing_enabled  # read once per step, as YADE does
        while True:
            ext = sim.advance()
            if ext is None:
                break
            if ext & _DONE_HOOK:
                # a PeriTriaxController reached its goal: its doneHook runs before the next engine
                self._engines[ext & ~_DONE_HOOK]._run_done_hook()
                continue
            e = self._external[ext]
            if e._is_activated(self):
                if timed:
                    t0 = _time.perf_counter_ns()
                    e._action(self)
                    e._timing_add(_time.perf_counter_ns() - t0)
                else:
                    e._action(self)

    def step(self):
        self._one_step()

    def _run(self, n):
        """YADE's run loop: `O.run(n)` sets `stopAtIter = iter + n` (a PyRunner may move it), the run ends
        at stopAtIter, stopAtTime or O.pause(), and stopAtIter is then reset to -1 (as YADE does)."""
        self._paused = False
        if n > 0:
            self.stopAtIter = self.iter + n
        whole = (not self._external and self._pending_engines is None and n > 0 and self.stopAtTime <= 0
                 and not self._python_hooks())
        if whole:
            if self.ryadeFastPath:
                self._sim.run_steps_fast(n, self.ryadeFastThreads)
            elif self._fast_env and self._fast_run(n):
                pass
            else:
                self._sim.run_steps(n)   # no Python engine: the whole run stays in Rust (a Rust engine may end it early)
            self.stopAtIter = -1
            return
        if self._fast_env:
            self._fast_refused('the engine list calls Python during the run (%s)' % self._python_reason())
        if self.stopAtIter <= 0 and self.stopAtTime <= 0 and not self._external and not self._python_hooks():
            raise RuntimeError('O.run() without a step count and nothing that can stop it (no PyRunner, no '
                               'O.stopAtIter): it would never return; give O.run(nSteps, True)')
        if self._native_stop:
            self._sim.take_stop_request()  # one left by an earlier O.step() does not count
        while not self._paused:
            if self.stopAtIter > 0 and self.iter >= self.stopAtIter:
                self.stopAtIter = -1
                break
            if self.stopAtTime > 0 and self.time >= self.stopAtTime:
                break
            self._one_step()
            if self._native_stop and self._sim.take_stop_request():  # as a PyRunner's O.stopAtIter = O.iter + 1
                self.stopAtIter = -1
                break

    def _fast_refused(self, why):
        """`compat run --fast`: this run stays on the YADE-order path; say why once per reason
        (`--fast=strict`: an error)."""
        if self._fast_env == 'strict':
            raise RuntimeError('compat run --fast=strict: the fast path cannot run this O.run: %s' % why)
        if why not in self._fast_said:
            self._fast_said.add(why)
            print('[ryade] --fast: YADE-order path for this run (from iteration %d): %s' % (self.iter, why), file=sys.stderr,
                  flush=True)

    def _python_reason(self):
        if self._external:  # engines run in Python (PyRunner, ...)
            return ', '.join(type(e).__name__ + (" '%s'" % e.label if getattr(e, 'label', '') else '') for e in self._external)
        if self.stopAtTime > 0:
            return 'O.stopAtTime is set'
        return 'a Python hook (PeriTriaxController.doneHook) or an engine list set during the run'

    def _fast_run(self, n):
        """Try the fast path for a whole O.run(n); False (nothing changed) where its scene is outside it."""
        try:
            self._sim.run_steps_fast(n, self.ryadeFastThreads)
            return True
        except RuntimeError as e:
            msg = str(e)
            if 'fast path does not support' not in msg and 'O.ryadeFastPath' not in msg:
                raise
            self._fast_refused(msg.replace('O.ryadeFastPath: ', ''))
            return False

    def _python_hooks(self):
        """Whether an engine may call back into Python during a step (a PeriTriaxController's doneHook, a
        TriaxialCompressionEngine's snapshot files)."""
        return any(not e.dead and ((type(e).__name__ == 'PeriTriaxController' and e.doneHook)
                                   or (type(e).__name__ == 'TriaxialCompressionEngine' and not e.noFiles))
                   for e in self._engines)

    def run(self, nSteps=-1, wait=False):
        if wait:
            self._run(nSteps)
        else:
            # YADE starts a background run and returns at once; O.wait() joins it. Headless, we run it
            # when the script waits (or not at all if it never does: `yade -x` exits at the script end).
            self._background = nSteps

    def wait(self):
        if self._background is not None:
            n, self._background = self._background, None
            self._run(n)

    def pause(self):
        self._paused = True
        self._background = None

    @property
    def running(self):
        return self._background is not None

    def reset(self):
        self._harvest_timing()
        self._sim.reset()
        self.bodies = BodyContainer(self)
        self.materials = MaterialContainer(self)
        self._engines, self._external, self._pending_engines = [], [], None
        self._native_stop = False
        self.tags = {}

    def resetTime(self):
        self._sim.iter = 0
        self._sim.time = 0.0

    def saveTmp(self, mark='', quiet=False):
        self._sim.save_tmp(mark)
        self._saved[mark] = (list(self.bodies._objs), list(self.materials._mats), self._engines)
        if not mark.startswith('\0'):
            self._scene_file = ':memory:' + mark

    def loadTmp(self, mark='', quiet=False):
        if mark not in self._saved:
            raise RuntimeError("No memory-saved simulation named '%s'" % mark)
        self._sim.load_tmp(mark)
        bodies, mats, engines = self._saved[mark]
        self.bodies._objs = list(bodies)
        self.materials._mats = list(mats)
        self._engines = engines
        if not mark.startswith('\0'):
            self._scene_file = ':memory:' + mark

    #: the name of the scene last saved or loaded (O.filename; ':memory:MARK' for saveTmp/loadTmp)
    _scene_file = None

    @property
    def filename(self):
        return self._scene_file

    def reload(self, quiet=False):
        """Load again the scene last saved or loaded (YADE's O.reload: O.load(O.filename))."""
        f = self._scene_file
        if f is None:
            raise RuntimeError('O.reload: no scene was saved or loaded yet (O.filename is None)')
        if f.startswith(':memory:'):
            self.loadTmp(f[len(':memory:'):], quiet)
        else:
            self.load(f, quiet)

    #: first line of the files O.save writes (a format of ryade's own, not YADE's XML or binary)
    _SAVE_FORMAT = 'ryade-save-1'

    def save(self, fileName, quiet=False):
        """Write the scene to `fileName` in ryade's own format (JSON: the scene as ryade's scene files hold it,
        compressed by gzip/bzip2 when the name ends .gz/.bz2, as YADE's names do) and keep the whole state in
        memory under a token the file carries, so that `O.load(fileName)` in the same run restores it exactly
        (what YADE's O.load does). Reading such a file in another run is not supported yet."""
        import json
        import uuid
        token = uuid.uuid4().hex
        try:
            scene = json.loads(self._sim.scene_json(self.iter))
        except Exception as e:  # the snapshot in memory is what O.load uses; the JSON is for reading
            scene = {'unavailable': str(e)}
        self.saveTmp('\0O.save ' + token)
        text = json.dumps({'format': self._SAVE_FORMAT, 'token': token, 'iter': self.iter, 'time': self.time,
                           'scene': scene}, allow_nan=True)
        with _open_compressed(fileName, 'wt') as f:
            f.write(text)
        self._scene_file = fileName

    def load(self, fileName, quiet=False):
        """Restore a scene written by `O.save` earlier in this run (see save)."""
        import json
        try:
            with _open_compressed(fileName, 'rt') as f:
                d = json.load(f)
        except (ValueError, UnicodeDecodeError, OSError) as e:
            if isinstance(e, FileNotFoundError):
                raise
            d = None
        if not isinstance(d, dict) or d.get('format') != self._SAVE_FORMAT:
            unsupported('O.load of YADE files (.xml/.yade)', 'ryade reads the files its own O.save wrote in the same run')
        mark = '\0O.save ' + d.get('token', '')
        if mark not in self._saved:
            unsupported('O.load of a file saved by another run', 'ryade reads the files its own O.save wrote in the same run')
        self.loadTmp(mark)
        self._scene_file = fileName

    def __getattr__(self, k):
        if k.startswith('_'):
            raise AttributeError(k)
        if k in _OMEGA_ATTRS:
            unsupported('O.%s' % k)
        raise AttributeError("'Omega' object has no attribute '%s'" % k)


import time as _time  # noqa: E402


def _open_compressed(fileName, mode):
    """open(), through gzip or bz2 when the name ends .gz / .bz2."""
    if fileName.endswith('.gz'):
        import gzip
        return gzip.open(fileName, mode)
    if fileName.endswith('.bz2'):
        import bz2
        return bz2.open(fileName, mode)
    return open(fileName, mode)

#: bit of the id `Sim.advance` returns for a PeriTriaxController's doneHook (ryade::scene::DONE_HOOK)
_DONE_HOOK = 1 << 31

_START = _time.time()

#: Omega attributes YADE has (used to tell "unsupported" from "no such attribute")
_OMEGA_ATTRS = {'addScene', 'bexSyncCount', 'childClassesNonrecursive', 'dynDt', 'dynDtAvailable', 'exitNoBacktrace',
                'forceSyncCount', 'interactionsFilter', 'isChildClassOf', 'labeledEngine', 'lsTmp',
                'miscParams', 'numSubSteps', 'plugins', 'realtime', 'resetAllScenes', 'resetCurrentScene',
                'resetThisScene', 'runEngine', 'sceneToString', 'speed', 'stringToScene', 'subD', 'subStep', 'subStepping',
                'switchScene', 'switchToScene', 'tmpFilename', 'tmpToFile', 'tmpToString', 'thisScene'}
