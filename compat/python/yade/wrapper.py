"""YADE's wrapper classes (engines, functors, materials, shapes) as thin attribute holders.

Every class YADE 2023.02a has is known (``_yade_classes.json``, dumped from the installed YADE by
``yade_ref/compat/dump_classes.py``): a class or attribute ryade implements works; one that exists in
YADE but not in ryade raises ``UnsupportedError`` naming it and the script line; a name YADE does not
have either raises the usual ``AttributeError``/``NameError``. Physics never happens here: engines are
translated to the engine descriptions the Rust core reads (``_json``).
"""

import json
import math
import os
import sys
import time as _time

from ._errors import bridge_json, unsupported

with open(os.path.join(os.path.dirname(__file__), '_yade_classes.json')) as _f:
    YADE_CLASSES = json.load(_f)


def _yade_attrs(cls_name):
    return set(YADE_CLASSES.get(cls_name, {}).get('attrs', ()))


class Serializable(object):
    """Base of every YADE object: keyword construction, `dict()`, unsupported attributes flagged."""

    #: attribute -> default, for attributes ryade implements (or accepts as harmless: colours, labels)
    _attrs = {}
    #: names of positional constructor arguments
    _positional = ()

    def __init__(self, *args, **kw):
        object.__setattr__(self, '_owner', None)
        object.__setattr__(self, '_values', {})
        for k, v in self._all_attrs().items():
            self._values[k] = _copy_default(v)
        if len(args) > len(self._positional):
            raise TypeError('%s() takes at most %d positional arguments (%d given)' % (type(self).__name__, len(self._positional), len(args)))
        for name, v in zip(self._positional, args):
            setattr(self, name, v)
        for k, v in kw.items():
            setattr(self, k, v)

    @classmethod
    def _all_attrs(cls):
        # merged once per class (scripts set attributes every step: the hot path of PyRunner loops)
        out = cls.__dict__.get('_merged_attrs')
        if out is None:
            out = {}
            for c in reversed(cls.__mro__):
                out.update(c.__dict__.get('_attrs', {}))
            cls._merged_attrs = out
        return out

    def __setattr__(self, k, v):
        if k[0] == '_':
            object.__setattr__(self, k, v)
            return
        prop = getattr(type(self), k, None)
        if isinstance(prop, property):
            prop.__set__(self, v)
            return
        if k in self._all_attrs():
            self._assign(k, v)
            return
        name = type(self).__name__
        known = _yade_attrs(name).union(*[_yade_attrs(b) for b in YADE_CLASSES.get(name, {}).get('bases', ())])
        if name in YADE_CLASSES and k not in known and k not in YADE_CLASSES[name].get('methods', ()):
            object.__setattr__(self, k, v)  # YADE's objects take attributes of the script's own
            return
        self._missing(k)

    def _assign(self, k, v):
        """Store a known attribute (converted) and tell the hook; properties' setters use it too."""
        self._values[k] = self._convert(k, v)
        self._changed(k)

    def __getattr__(self, k):
        if k.startswith('_'):
            raise AttributeError(k)
        vals = object.__getattribute__(self, '_values')
        if k in vals:
            return self._read(k)
        self._missing(k)

    def _missing(self, k):
        name = type(self).__name__
        if k in _yade_attrs(name) or any(k in _yade_attrs(b) for b in YADE_CLASSES.get(name, {}).get('bases', ())):
            unsupported('the attribute %s.%s' % (name, k))
        if k in YADE_CLASSES.get(name, {}).get('methods', ()):
            unsupported('the method %s.%s' % (name, k))
        raise AttributeError("'%s' object has no attribute '%s'" % (name, k))

    def _convert(self, k, v):
        return v

    def _read(self, k):
        return self._values[k]

    def _changed(self, k):
        """Hook: an attribute changed (live engines forward it to the Rust core)."""

    def dict(self):
        return {k: getattr(self, k) for k in self._all_attrs()}

    def __repr__(self):
        return '<%s instance at %#x>' % (type(self).__name__, id(self))


def _copy_default(v):
    if isinstance(v, list):
        return list(v)
    if isinstance(v, dict):
        return dict(v)
    return v


# ---------------------------------------------------------------- functors and engines

class Functor(Serializable):
    _attrs = {'label': ''}

    def _json(self):
        d = {'class': type(self).__name__}
        for k in self._all_attrs():
            if k != 'label':
                d[k] = _jsonable(self._values[k])
        return d

    #: attributes the Rust core takes on a live engine (as `Class.attr` of the owning engine's slot)
    _live = ()

    def _changed(self, k):
        if self._owner is not None and k != 'label':
            if k in self._live and getattr(self._owner, '_owner', None) is not None:
                omega, index = self._owner._owner
                omega._sim.engine_set(index, '%s.%s' % (type(self).__name__, k),
                                      bridge_json(_jsonable(self._values[k]), '%s.%s' % (type(self).__name__, k)))
                return
            unsupported('changing %s.%s after O.engines was assigned' % (type(self).__name__, k),
                        'set it before assigning O.engines')


class BoundFunctor(Functor):
    pass


class Bo1_Sphere_Aabb(BoundFunctor):
    _attrs = {'aabbEnlargeFactor': -1.0}
    _live = ('aabbEnlargeFactor',)


class Bo1_Facet_Aabb(BoundFunctor):
    pass


class Bo1_Box_Aabb(BoundFunctor):
    pass


class Bo1_Wall_Aabb(BoundFunctor):
    pass


class IGeomFunctor(Functor):
    pass


class Ig2_Sphere_Sphere_ScGeom(IGeomFunctor):
    _attrs = {'interactionDetectionFactor': 1.0, 'avoidGranularRatcheting': True}
    _live = ('interactionDetectionFactor',)


class Ig2_Facet_Sphere_ScGeom(IGeomFunctor):
    _attrs = {'shrinkFactor': 0.0, 'hertzian': False}

    def _json(self):
        return {'class': 'Ig2_Facet_Sphere_ScGeom', 'shrinkFactor': self._values['shrinkFactor'],
                'hertzian': bool(self._values['hertzian'])}


class Ig2_Wall_Sphere_ScGeom(IGeomFunctor):
    _attrs = {'noRatch': True, 'hertzian': False}

    def _json(self):
        return {'class': 'Ig2_Wall_Sphere_ScGeom', 'noRatch': self._values['noRatch'],
                'hertzian': bool(self._values['hertzian'])}


class Ig2_Box_Sphere_ScGeom(IGeomFunctor):
    _attrs = {'interactionDetectionFactor': 1.0}
    _live = ('interactionDetectionFactor',)


class Ig2_Box_Sphere_ScGeom6D(Ig2_Box_Sphere_ScGeom):
    pass


class Bo1_GridConnection_Aabb(BoundFunctor):
    _attrs = {'aabbEnlargeFactor': -1.0}


class Ig2_Sphere_Sphere_ScGeom6D(Ig2_Sphere_Sphere_ScGeom):
    _attrs = {'updateRotations': True, 'creep': False}


class Ig2_GridNode_GridNode_GridNodeGeom6D(Ig2_Sphere_Sphere_ScGeom):
    _attrs = {'updateRotations': True, 'creep': False}


class Ig2_Sphere_GridConnection_ScGridCoGeom(IGeomFunctor):
    _attrs = {'interactionDetectionFactor': 1.0}


class Ig2_GridConnection_GridConnection_GridCoGridCoGeom(IGeomFunctor):
    pass


class IPhysFunctor(Functor):
    pass


class Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(IPhysFunctor):
    _attrs = {'setCohesionNow': False, 'setCohesionOnNewContacts': False, 'normalCohesion': None,
              'shearCohesion': None, 'frictAngle': None}

    def _json(self):
        for k in ('normalCohesion', 'shearCohesion', 'frictAngle'):
            if self._values[k] is not None:
                unsupported('Ip2_CohFrictMat_CohFrictMat_CohFrictPhys.%s (MatchMaker)' % k)
        return {'class': 'Ip2_CohFrictMat_CohFrictMat_CohFrictPhys', 'setCohesionNow': bool(self._values['setCohesionNow']),
                'setCohesionOnNewContacts': bool(self._values['setCohesionOnNewContacts'])}


class Ip2_FrictMat_FrictMat_FrictPhys(IPhysFunctor):
    _attrs = {'frictAngle': None, 'kn': None, 'ks': None}

    def _json(self):
        for k in ('frictAngle', 'kn', 'ks'):
            if self._values[k] is not None:
                unsupported('Ip2_FrictMat_FrictMat_FrictPhys.%s (MatchMaker)' % k)
        return {'class': 'Ip2_FrictMat_FrictMat_FrictPhys'}


class MatchMaker(Serializable):
    """YADE's MatchMaker (pkg/common/MatchMaker.cpp): a value per pair of material ids (`matches`, either
    order), else the fallback `algo` of two values ('avg', 'min', 'max', 'harmAvg') or without them
    ('val': `val`, 'zero'). A number given where a functor takes a MatchMaker becomes algo 'val'."""
    _attrs = {'matches': [], 'algo': 'avg', 'val': float('nan')}
    _ALGOS = ('val', 'zero', 'avg', 'min', 'max', 'harmAvg')

    def _convert(self, k, v):
        if k == 'matches':
            out = []
            for m in v:
                m = tuple(m)
                if len(m) != 3:
                    raise TypeError('MatchMaker.matches takes (id1, id2, value) items, got %r' % (m,))
                out.append((float(m[0]), float(m[1]), float(m[2])))
            return out
        if k == 'algo':
            if v not in self._ALGOS:
                raise ValueError("MatchMaker:: algo '%s' not recognized (possible values: val, avg, min, max, harmAvg)." % v)
            return v
        if k == 'val':
            return float(v)
        return v

    def _read(self, k):
        if k == 'matches':
            from .minieigen import Vector3
            return [Vector3(*m) for m in self._values['matches']]
        return self._values[k]

    def computeFallback(self, v1, v2):
        a = self._values['algo']
        if a == 'val':
            return self._values['val']
        if a == 'zero':
            return 0.
        if a == 'avg':
            return (v1 + v2) / 2.
        if a == 'min':
            return v2 if v2 < v1 else v1
        if a == 'max':
            return v2 if v1 < v2 else v1
        return 2 * v1 * v2 / (v1 + v2)

    def __call__(self, id1, id2, val1=float('nan'), val2=float('nan')):
        lo, hi = min(int(id1), int(id2)), max(int(id1), int(id2))
        for m in self._values['matches']:
            if (min(int(m[0]), int(m[1])), max(int(m[0]), int(m[1]))) == (lo, hi):
                return m[2]
        if self._values['algo'] not in ('val', 'zero') and (val1 != val1 or val2 != val2):
            raise ValueError("MatchMaker: no match for (%d,%d), and values required for algo computation '%s' not "
                             "specified." % (int(id1), int(id2), self._values['algo']))
        return self.computeFallback(val1, val2)

    def _json(self):
        return {'matches': [list(m) for m in self._values['matches']], 'algo': self._values['algo'],
                'val': _float_json(self._values['val'])}


def _match_maker(cls, k, v):
    """A functor's MatchMaker attribute: None, a MatchMaker, or a number (algo 'val', as YADE converts)."""
    if v is None or isinstance(v, MatchMaker):
        return v
    if isinstance(v, (int, float)) and not isinstance(v, bool):
        return MatchMaker(algo='val', val=float(v))
    raise TypeError('%s.%s takes a MatchMaker or a number, got %s' % (cls, k, type(v).__name__))


class Ip2_ViscElMat_ViscElMat_ViscElPhys(IPhysFunctor):
    _attrs = {'tc': None, 'en': None, 'et': None, 'frictAngle': None}

    def _convert(self, k, v):
        if k in ('tc', 'en', 'et', 'frictAngle'):
            return _match_maker('Ip2_ViscElMat_ViscElMat_ViscElPhys', k, v)
        return v

    def _json(self):
        d = {'class': 'Ip2_ViscElMat_ViscElMat_ViscElPhys'}
        for k in ('tc', 'en', 'et', 'frictAngle'):
            if self._values[k] is not None:
                d[k] = self._values[k]._json()
        return d


class Ip2_FrictMat_FrictMat_MindlinPhys(IPhysFunctor):
    """Hertz-Mindlin contact physics (HertzMindlin.cpp; Rust core `phys::ip2_mindlin`). en, es, betan,
    betas, frictAngle are MatchMakers (a number becomes a constant one, as in YADE)."""
    _attrs = {'gamma': 0.0, 'eta': 0.0, 'krot': 0.0, 'ktwist': 0.0, 'en': None, 'es': None, 'betan': None,
              'betas': None, 'frictAngle': None}
    _live = ('gamma', 'eta', 'krot', 'ktwist', 'en', 'es', 'betan', 'betas', 'frictAngle')
    _mm = ('en', 'es', 'betan', 'betas', 'frictAngle')

    def _convert(self, k, v):
        if k in self._mm:
            return _match_maker('Ip2_FrictMat_FrictMat_MindlinPhys', k, v)
        if k in ('gamma', 'eta', 'krot', 'ktwist'):
            return float(v)
        return v

    def _changed(self, k):
        if k in self._mm and self._owner is not None and getattr(self._owner, '_owner', None) is not None:
            omega, index = self._owner._owner
            v = self._values[k]
            omega._sim.engine_set(index, 'Ip2_FrictMat_FrictMat_MindlinPhys.%s' % k,
                                  json.dumps(None if v is None else v._json()))
            return
        IPhysFunctor._changed(self, k)

    def _json(self):
        d = {'class': 'Ip2_FrictMat_FrictMat_MindlinPhys'}
        for k in self._live:
            v = self._values[k]
            d[k] = v._json() if isinstance(v, MatchMaker) else v
        return d


class Ip2_BubbleMat_BubbleMat_BubblePhys(IPhysFunctor):
    def _json(self):
        return {'class': 'Ip2_BubbleMat_BubbleMat_BubblePhys'}


class Ip2_LudingMat_LudingMat_LudingPhys(IPhysFunctor):
    def _json(self):
        return {'class': 'Ip2_LudingMat_LudingMat_LudingPhys'}


class Ip2_CpmMat_CpmMat_CpmPhys(IPhysFunctor):
    """CpmPhys from two CpmMat (ConcretePM.cpp; Rust core `phys::ip2_cpm`)."""
    _attrs = {'cohesiveThresholdIter': 10, 'E': None}

    def _json(self):
        if self._values['E'] is not None:
            unsupported('Ip2_CpmMat_CpmMat_CpmPhys.E (MatchMaker)')
        return {'class': 'Ip2_CpmMat_CpmMat_CpmPhys', 'cohesiveThresholdIter': int(self._values['cohesiveThresholdIter'])}


class Ip2_FrictMat_CpmMat_FrictPhys(IPhysFunctor):
    """FrictPhys for a FrictMat against a CpmMat (Ip2_FrictMat_FrictMat_FrictPhys's formulas)."""
    _attrs = {'frictAngle': None}

    def _json(self):
        if self._values['frictAngle'] is not None:
            unsupported('Ip2_FrictMat_CpmMat_FrictPhys.frictAngle (MatchMaker)')
        return {'class': 'Ip2_FrictMat_CpmMat_FrictPhys'}


class LawFunctor(Functor):
    pass


class Law2_ScGeom_CpmPhys_Cpm(LawFunctor):
    """The concrete particle model's law, public version (ConcretePM.cpp; Rust core `law::cpm`)."""
    _attrs = {'yieldSurfType': 2, 'yieldLogSpeed': 0.1, 'yieldEllipseShift': float('nan'), 'omegaThreshold': 1.0,
              'epsSoft': 1.0, 'relKnSoft': 0.3}

    def _json(self):
        v = self._values
        ys = float(v['yieldEllipseShift'])
        return {'class': 'Law2_ScGeom_CpmPhys_Cpm', 'yieldSurfType': int(v['yieldSurfType']),
                'yieldLogSpeed': float(v['yieldLogSpeed']), 'yieldEllipseShift': None if ys != ys else ys,
                'omegaThreshold': float(v['omegaThreshold']), 'epsSoft': float(v['epsSoft']),
                'relKnSoft': float(v['relKnSoft'])}

    def elasticEnergy(self):
        """Σ over real CpmPhys contacts of ½|Fn|²/((1-ω⁺)kn) + ½|Fs|²/ks (Rust core `utils::cpm_elastic_energy`)."""
        from ._core import Omega
        return Omega()._sim.cpm_elastic_energy()

    def yieldSigmaTMagnitude(self, *a, **kw):
        raise RuntimeError('Full CPM model not available in this build')  # as Debian's YADE


class Law2_ScGeom_BubblePhys_Bubble(LawFunctor):
    """Chan's bubble-bubble law (BubbleMat.cpp; Rust core `law::bubble`); its own surfaceTension is used."""
    _attrs = {'pctMaxForce': 0.1, 'surfaceTension': 0.07197}

    def _json(self):
        return {'class': 'Law2_ScGeom_BubblePhys_Bubble', 'pctMaxForce': float(self._values['pctMaxForce']),
                'surfaceTension': float(self._values['surfaceTension'])}


class Law2_ScGeom_LudingPhys_Basic(LawFunctor):
    def _json(self):
        return {'class': 'Law2_ScGeom_LudingPhys_Basic'}


class Law2_ScGeom_MindlinPhys_Mindlin(LawFunctor):
    """Hertz-Mindlin contact law (HertzMindlin.cpp; Rust core `law::mindlin`)."""
    _attrs = {'includeAdhesion': False, 'calcEnergy': False, 'includeMoment': False, 'neverErase': False,
              'nothing': False}
    _live = ('includeAdhesion', 'includeMoment', 'neverErase')

    @property
    def preventGranularRatcheting(self):
        return self.nothing

    @preventGranularRatcheting.setter
    def preventGranularRatcheting(self, v):
        # YADE's deprecated attribute: a warning, then it sets `nothing` (unused)
        print("WARN: Law2_ScGeom_MindlinPhys_Mindlin.preventGranularRatcheting is deprecated, use "
              "Law2_ScGeom_MindlinPhys_Mindlin.nothing instead. (this value is no longer used, don't define it.)")
        self.nothing = v

    def _json(self):
        if self._values['calcEnergy']:
            unsupported('Law2_ScGeom_MindlinPhys_Mindlin.calcEnergy=True')
        return {'class': 'Law2_ScGeom_MindlinPhys_Mindlin', 'includeAdhesion': bool(self._values['includeAdhesion']),
                'includeMoment': bool(self._values['includeMoment']), 'neverErase': bool(self._values['neverErase'])}


class Law2_ScGeom_ViscElPhys_Basic(LawFunctor):
    def _json(self):
        return {'class': 'Law2_ScGeom_ViscElPhys_Basic'}


class Law2_ScGeom_FrictPhys_CundallStrack(LawFunctor):
    _attrs = {'neverErase': False, 'sphericalBodies': True, 'traceEnergy': False}

    def _json(self):
        if self._values['traceEnergy']:
            unsupported('Law2_ScGeom_FrictPhys_CundallStrack.traceEnergy', 'use O.trackEnergy=True')
        return {'class': 'Law2_ScGeom_FrictPhys_CundallStrack', 'neverErase': self._values['neverErase'],
                'sphericalBodies': self._values['sphericalBodies']}


class Law2_ScGeom6D_CohFrictPhys_CohesionMoment(LawFunctor):
    _attrs = {'neverErase': False, 'always_use_moment_law': False, 'shear_creep': False, 'twist_creep': False,
              'creep_viscosity': 1.0, 'traceEnergy': False, 'useIncrementalForm': False}

    def normElastEnergy(self):
        """Σ ½|Fn|²/kn over the real interactions (the Rust core's `utils::cohesion_moment_elastic_energy`)."""
        from ._core import Omega
        return Omega()._sim.cohesion_moment_elastic_energy(False)

    def shearElastEnergy(self):
        """Σ ½|Fs|²/ks over the real interactions."""
        from ._core import Omega
        return Omega()._sim.cohesion_moment_elastic_energy(True)


class Law2_ScGridCoGeom_FrictPhys_CundallStrack(LawFunctor):
    _attrs = {'neverErase': False}


class Law2_ScGridCoGeom_CohFrictPhys_CundallStrack(LawFunctor):
    _attrs = {'neverErase': False}


class Law2_GridCoGridCoGeom_FrictPhys_CundallStrack(LawFunctor):
    _attrs = {'neverErase': False, 'sphericalBodies': True, 'traceEnergy': False}


class Engine(Serializable):
    _attrs = {'label': '', 'dead': False, 'ompThreads': -1}
    #: attributes the Rust core can change on a live engine
    _live = ()

    def _bind(self, omega, index):
        object.__setattr__(self, '_owner', (omega, index))

    def _changed(self, k):
        if self._owner is None:
            return
        omega, index = self._owner
        if k == 'dead':
            omega._sim.set_engine_dead(index, bool(self._values['dead']))
        elif k in ('label', 'ompThreads'):
            pass
        elif k in self._live:
            omega._sim.engine_set(index, k, bridge_json(_jsonable(self._values[k]), '%s.%s' % (type(self).__name__, k)))
        elif self._is_builtin():
            unsupported('changing %s.%s after O.engines was assigned' % (type(self).__name__, k))

    def _is_builtin(self):
        return True

    def _json(self):
        raise NotImplementedError

    # ---- YADE's TimingInfo (`O.timingEnabled`): execTime in ns, execCount. An engine run by the Rust
    # core reads its slot there (`_tslot`) on top of what it collected in earlier engine lists
    # (`_exec`); a Python engine is timed by the step loop into `_exec`.
    def _timing_read(self):
        """(ns, runs, [[checkpoint, ns, runs], ...]) collected so far."""
        ns, n, deltas = self.__dict__.get('_exec', (0, 0, ()))
        deltas = [list(d) for d in deltas]
        slot = self.__dict__.get('_tslot')
        if slot is not None:
            dns, dn = slot[0].engine_timing(slot[1])
            ns, n = ns + dns, n + dn
            for k, (name, dt, c) in enumerate(slot[0].engine_timing_deltas(slot[1])):
                if k < len(deltas):
                    deltas[k][1] += dt
                    deltas[k][2] += c
                else:
                    deltas.append([name, dt, c])
        return ns, n, deltas

    def _timing_write(self, ns=None, n=None, zero_deltas=False):
        """Set execTime (`ns`) and/or execCount (`n`), or zero the checkpoints; the Rust slot's share
        moves into `_exec` first, so the rest is kept."""
        cur_ns, cur_n, deltas = self._timing_read()
        if zero_deltas:
            deltas = [[d[0], 0, 0] for d in deltas]
        slot = self.__dict__.get('_tslot')
        if slot is not None:
            slot[0].engine_timing_reset(slot[1])
        object.__setattr__(self, '_exec', (cur_ns if ns is None else int(ns), cur_n if n is None else int(n), deltas))

    def _timing_attach(self, sim, k):
        object.__setattr__(self, '_tslot', (sim, k))

    def _timing_detach(self):
        object.__setattr__(self, '_exec', self._timing_read())
        object.__setattr__(self, '_tslot', None)

    def _timing_add(self, ns):
        t, n, deltas = self.__dict__.get('_exec', (0, 0, ()))
        object.__setattr__(self, '_exec', (t + ns, n + 1, deltas))

    execTime = property(lambda self: self._timing_read()[0], lambda self, v: self._timing_write(ns=v),
                        doc='Nanoseconds spent in this engine while O.timingEnabled (YADE TimingInfo.nsec)')
    execCount = property(lambda self: self._timing_read()[1], lambda self, v: self._timing_write(n=v),
                         doc='Runs of this engine while O.timingEnabled (YADE TimingInfo.nExec)')

    @property
    def timingDeltas(self):
        """YADE's checkpoints inside an engine; Debian's build has them for NewtonIntegrator only."""
        return None


class GlobalEngine(Engine):
    pass


class TimingDeltas(object):
    """`Engine.timingDeltas` (YADE's TimingDeltas): `data` is [(checkpoint, ns, runs), ...]."""

    def __init__(self, engine):
        object.__setattr__(self, '_engine', engine)

    @property
    def data(self):
        return [tuple(d) for d in self._engine._timing_read()[2]]

    def reset(self):
        self._engine._timing_write(zero_deltas=True)


class ForceResetter(GlobalEngine):
    def _json(self):
        return {'class': 'ForceResetter'}


class BoundDispatcher(GlobalEngine):
    """`BoundDispatcher([Bo1 functors])` on its own in O.engines: every bounded body's axis-aligned box
    each step (BoundDispatcher::action), without the collider's sweep (YADE's defaults sweepDist=0,
    targetInterv=-1; other values are refused)."""
    _attrs = {'functors': [], 'sweepDist': 0.0, 'minSweepDistFactor': 0.2, 'targetInterv': -1,
              'updatingDispFactor': -1.0}
    _positional = ('functors',)

    def _convert(self, k, v):
        return list(v) if k == 'functors' else v

    def _json(self):
        v = self._values
        for k, d in (('sweepDist', 0.0), ('targetInterv', -1), ('updatingDispFactor', -1.0)):
            if v[k] != d:
                unsupported('BoundDispatcher.%s=%r on its own (the collider sets the sweep)' % (k, v[k]))
        return {'class': 'BoundDispatcher', 'bounds': [b._json() for b in v['functors']]}


class InsertionSortCollider(GlobalEngine):
    _attrs = {'verletDist': -0.5, 'allowBiggerThanPeriod': False, 'targetInterv': 100, 'minSweepDistFactor': 0.1,
              'sortAxis': 0, 'sortThenCollide': False, 'overlapTolerance': 1e-7, 'avoidSelfInteractionMask': 0,
              'doSort': False, 'smartInsertErase': False, 'keepListsShort': False}
    _positional = ('_bounds',)
    _live = ('verletDist', 'allowBiggerThanPeriod', 'doSort', 'targetInterv')

    def __init__(self, *args, **kw):
        object.__setattr__(self, '_bounds_list', [Bo1_Sphere_Aabb(), Bo1_Facet_Aabb(), Bo1_Box_Aabb()] if not args else None)
        Serializable.__init__(self, *args, **kw)

    def __setattr__(self, k, v):
        if k == '_bounds':
            object.__setattr__(self, '_bounds_list', list(v))
            return
        Serializable.__setattr__(self, k, v)

    def _convert(self, k, v):
        if k in ('avoidSelfInteractionMask', 'targetInterv', 'sortAxis'):
            return int(v)  # int attributes in YADE (a bool such as avoidSelfInteractionMask=True is 1)
        return v

    @property
    def boundDispatcher(self):
        return _Dispatcher(self._bounds_list)

    def _json(self):
        for k in ('smartInsertErase', 'keepListsShort'):
            if self._values[k]:
                unsupported('InsertionSortCollider.%s=True' % k)
        d = {'class': 'InsertionSortCollider', 'bounds': [b._json() for b in self._bounds_list]}
        for k in ('verletDist', 'allowBiggerThanPeriod', 'targetInterv', 'minSweepDistFactor', 'sortAxis',
                  'sortThenCollide', 'overlapTolerance', 'avoidSelfInteractionMask'):
            d[k] = self._values[k]
        return d

    def _read(self, k):
        if k == 'verletDist' and self._owner is not None:
            omega, index = self._owner
            return json.loads(omega._sim.engine_get(index, 'verletDist'))
        return self._values[k]

    def _functors(self):
        return list(self._bounds_list)


class InteractionLoop(GlobalEngine):
    _attrs = {'loopOnSortedInteractions': False, 'callbacks': []}
    _positional = ('_geom', '_phys', '_law')

    def __init__(self, *args, **kw):
        if args and len(args) != 3:
            raise TypeError('InteractionLoop takes exactly 3 lists of functors (geometry, physics, law)')
        object.__setattr__(self, '_lists', [list(a) for a in args] if args else [[], [], []])
        if not args:
            object.__setattr__(self, '_lists', [[Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()],
                                                [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]])
        Serializable.__init__(self, **kw)

    @property
    def geomDispatcher(self):
        return _Dispatcher(self._lists[0])

    @property
    def physDispatcher(self):
        return _Dispatcher(self._lists[1])

    @property
    def lawDispatcher(self):
        return _Dispatcher(self._lists[2])

    def _callbacks_json(self):
        out = []
        for cb in self._values['callbacks']:
            if not isinstance(cb, SumIntrForcesCb):
                unsupported('InteractionLoop.callbacks with %s' % type(cb).__name__)
            out.append(cb._json())
        return out

    def _changed(self, k):
        if k == 'callbacks':
            self._values['callbacks'] = list(self._values['callbacks'])
            if self._owner is not None:
                omega, index = self._owner
                omega._sim.engine_set(index, 'callbacks', json.dumps(self._callbacks_json()))
            return
        GlobalEngine._changed(self, k)

    def _json(self):
        if self._values['loopOnSortedInteractions']:
            unsupported('InteractionLoop.loopOnSortedInteractions')
        d = {'class': 'InteractionLoop', 'geom': [f._json() for f in self._lists[0]],
             'phys': [f._json() for f in self._lists[1]], 'law': [f._json() for f in self._lists[2]]}
        if self._values['callbacks']:
            d['callbacks'] = self._callbacks_json()
        return d

    def _functors(self):
        return self._lists[0] + self._lists[1] + self._lists[2]


class _Dispatcher(object):
    def __init__(self, functors):
        self.functors = functors

    def dispMatrix(self, names=True):
        """YADE's dispatch matrix as a dict: the classes each functor declares (a geometry functor of two
        different shapes both ways round) -> the functor's name. Entries YADE adds for derived classes
        once they were dispatched are not listed."""
        if not names:
            unsupported('dispMatrix(names=False) (YADE class indices)')
        out = {}
        for f in self.functors:
            n = type(f).__name__
            parts = n.split('_')
            if parts[0] == 'Bo1' and len(parts) >= 3:
                out[(parts[1],)] = n
            elif parts[0] in ('Ig2', 'Ip2', 'Law2') and len(parts) >= 4:
                a, b = parts[1], parts[2]
                out[(a, b)] = n
                if parts[0] == 'Ig2' and a != b:
                    out[(b, a)] = n
        return out


class IntrCallback(Serializable):
    pass


class SumIntrForcesCb(IntrCallback):
    """Prints the summed |normalForce + shearForce| of the previous InteractionLoop and the number of
    interactions counted, as `(force,numIntr)` on stderr at each loop (the Rust core's
    `scene::SumIntrForcesCb`)."""

    def _json(self):
        return {'class': 'SumIntrForcesCb'}


class NewtonIntegrator(GlobalEngine):
    _attrs = {'damping': 0.2, 'gravity': (0.0, 0.0, 0.0), 'dampGravity': True, 'exactAsphericalRot': True,
              'kinSplit': False, 'mask': -1, 'warnNoForceReset': True, 'densityScaling': False}
    _live = ('damping', 'gravity', 'dampGravity')

    @property
    def timingDeltas(self):
        return TimingDeltas(self)

    def _convert(self, k, v):
        if k == 'gravity':
            from .minieigen import to_vec3
            return to_vec3(v, 'NewtonIntegrator.gravity')
        return v

    @property
    def prevVelGrad(self):
        """The cell's velGrad of the previous step (zero until a periodic step ran), read from the
        integrator in O.engines; a copy, as YADE returns."""
        from .minieigen import Matrix3
        if self._owner is None:
            return Matrix3.Zero
        omega, index = self._owner
        m = json.loads(omega._sim.engine_get(index, 'prevVelGrad'))
        return Matrix3(*[x for row in m for x in row])

    def _read(self, k):
        if k == 'gravity':
            from .minieigen import Vector3
            return Vector3(*self._values['gravity'])
        if k == 'maxVelocitySq' and self._owner is not None:
            omega, index = self._owner
            return json.loads(omega._sim.engine_get(index, 'maxVelocitySq'))
        return self._values[k]

    def _json(self):
        if self._values['densityScaling']:
            unsupported('NewtonIntegrator.densityScaling')
        return {'class': 'NewtonIntegrator', 'damping': self._values['damping'], 'gravity': list(self._values['gravity']),
                'dampGravity': self._values['dampGravity'], 'mask': self._values['mask'],
                'kinSplit': bool(self._values['kinSplit'])}


class TimeStepper(GlobalEngine):
    _attrs = {'active': True, 'timeStepUpdateInterval': 1}


class GlobalStiffnessTimeStepper(TimeStepper):
    """dt from the stiffest eigen-period of each body (the Rust core's `timestepper`)."""
    _attrs = {'defaultDt': -1.0, 'maxDt': 1.7976931348623157e308, 'previousDt': 1.7976931348623157e308,
              'timestepSafetyCoefficient': 0.8, 'densityScaling': False, 'viscEl': False, 'targetDt': 1.0,
              'parallelMode': False}
    _live = ('active', 'timeStepUpdateInterval', 'defaultDt', 'maxDt', 'timestepSafetyCoefficient', 'previousDt')

    def _read(self, k):
        if k in ('previousDt', 'defaultDt', 'active') and self._owner is not None:
            omega, index = self._owner
            return json.loads(omega._sim.engine_get(index, k))
        return self._values[k]

    def _json(self):
        v = self._values
        for k in ('densityScaling', 'viscEl', 'parallelMode'):
            if v[k]:
                unsupported('GlobalStiffnessTimeStepper.%s=True' % k)
        return {'class': 'GlobalStiffnessTimeStepper', 'active': bool(v['active']),
                'timeStepUpdateInterval': int(v['timeStepUpdateInterval']), 'defaultDt': float(v['defaultDt']),
                'maxDt': float(v['maxDt']), 'timestepSafetyCoefficient': float(v['timestepSafetyCoefficient'])}


class PartialEngine(Engine):
    _attrs = {'ids': []}

    def _convert(self, k, v):
        if k == 'ids':
            try:
                out = [int(i) for i in v]
            except TypeError:
                raise TypeError('%s.ids must be a list of body ids' % type(self).__name__)
            if any(i < 0 for i in out):
                raise ValueError('%s.ids: negative body id in %r' % (type(self).__name__, out))
            return out
        return v


class KinematicEngine(PartialEngine):
    def __add__(self, other):
        # YADE CombinedKinematicEngine::fromTwo: a new combination with the first engine's ids
        return CombinedKinematicEngine._from_two(self, other)


def _eigen_normalized(v):
    """Eigen's normalize() on a 3-vector: divide by sqrt(x*x + (y*y + z*z)); a zero vector stays."""
    z = v[0] * v[0] + (v[1] * v[1] + v[2] * v[2])
    if z > 0:
        n = math.sqrt(z)
        return (v[0] / n, v[1] / n, v[2] / n)
    return tuple(v)


def _vec3_attr(cls, k, v):
    from .minieigen import to_vec3
    return to_vec3(v, '%s.%s' % (cls, k))


class _AxisEngine(KinematicEngine):
    """A kinematic engine whose postLoad normalizes its axis attribute `_axis` (Rust core: `kinematic`)."""
    _axis = None
    _vectors = ()
    _state = ()

    def __init__(self, *args, **kw):
        Serializable.__init__(self, *args, **kw)
        if self._axis in kw:
            # YADE quirk: constructing with the axis=... runs postLoad's normalize() twice (once per
            # attribute update and once at the end of the constructor); an assignment runs it once. The
            # second pass can move the last bit: (1, 1, 0) -> 0.7071067811865476 instead of ...475.
            self._values[self._axis] = _eigen_normalized(self._values[self._axis])

    def _convert(self, k, v):
        if k in self._vectors:
            v = tuple(_vec3_attr(type(self).__name__, k, v))
            # postLoad: axis.normalize()
            return _eigen_normalized(v) if k == self._axis else v
        return PartialEngine._convert(self, k, v)

    def _read(self, k):
        if self._owner is not None and (k in self._state or k in self._vectors):
            omega, index = self._owner
            v = json.loads(omega._sim.engine_get(index, k))
        else:
            v = self._values[k]
        if k in self._vectors:
            from .minieigen import Vector3
            return Vector3(*v)
        return v

    def _json(self):
        d = {'class': type(self).__name__}
        for k in self._all_attrs():
            if k not in Engine._attrs:
                d[k] = _jsonable(self._values[k])
        return d


class TranslationEngine(_AxisEngine):
    """Constant velocity along translationAxis for the listed bodies."""
    _attrs = {'velocity': 0.0, 'translationAxis': (0.0, 0.0, 0.0)}
    _live = ('ids', 'velocity', 'translationAxis')
    _axis = 'translationAxis'
    _vectors = ('translationAxis',)


class RotationEngine(_AxisEngine):
    """Constant angular velocity about rotationAxis for the listed bodies, carried round zeroPoint when
    rotateAroundZero."""
    _attrs = {'angularVelocity': 0.0, 'rotationAxis': (1.0, 0.0, 0.0), 'rotateAroundZero': False,
              'zeroPoint': (0.0, 0.0, 0.0)}
    _live = ('ids', 'angularVelocity', 'rotationAxis', 'rotateAroundZero', 'zeroPoint')
    _axis = 'rotationAxis'
    _vectors = ('rotationAxis', 'zeroPoint')


class ServoPIDController(TranslationEngine):
    """YADE's PID force servo (KinematicEngines.cpp), run in the Rust core (`kinematic::ServoPid`)."""
    _attrs = {'maxVelocity': 0.0, 'axis': (0.0, 0.0, 0.0), 'target': 0.0, 'current': (0.0, 0.0, 0.0), 'kP': 0.0,
              'kI': 0.0, 'kD': 0.0, 'iTerm': 0.0, 'curVel': 0.0, 'errorCur': 0.0, 'errorPrev': 0.0, 'iterPeriod': 100,
              'iterPrevStart': -1}
    _live = ('ids', 'velocity', 'translationAxis', 'maxVelocity', 'axis', 'target', 'current', 'kP', 'kI', 'kD',
             'iTerm', 'curVel', 'errorCur', 'errorPrev', 'iterPeriod', 'iterPrevStart')
    _vectors = ('translationAxis', 'axis', 'current')
    _state = ('iTerm', 'curVel', 'errorCur', 'errorPrev', 'iterPrevStart', 'velocity')


class HelixEngine(RotationEngine):
    """RotationEngine plus a velocity linearVelocity along the axis, always about zeroPoint (its apply sets
    rotateAroundZero); angleTurned counts the angle. Run in the Rust core (`kinematic::HelixEngine`)."""
    _attrs = {'linearVelocity': 0.0, 'angleTurned': 0.0}
    _live = RotationEngine._live + ('linearVelocity', 'angleTurned')
    _state = ('angleTurned', 'rotateAroundZero')


class ForceEngine(PartialEngine):
    """A constant force added to the listed bodies every step (ForceEngine.cpp; Rust core
    `force_engine::ForceEngine`)."""
    _attrs = {'force': (0.0, 0.0, 0.0)}
    _live = ('ids', 'force')
    _axis = None
    _vectors = ('force',)
    _state = ()
    _convert = _AxisEngine._convert
    _read = _AxisEngine._read
    _json = _AxisEngine._json


class HydroForceEngine(PartialEngine):
    """YADE's HydroForceEngine (pkg/common/HydroForceEngine.cpp): drag, lift, buoyancy and convective
    acceleration on the listed spheres from the 1-D fluid profile (Rust core `hydro`). The fluid
    resolution, the averaging and the turbulent-fluctuation models are not in ryade: those methods say
    so. Profiles are plain lists here, as YADE returns copies."""
    _core = {'gravity': (0.0, 0.0, -9.81), 'densFluid': 1000.0, 'viscoDyn': 1e-3, 'zRef': 0.0, 'deltaZ': float('nan'),
             'nCell': 1, 'expoRZ': 3.1, 'lift': False, 'Cl': 0.2, 'convAccOption': False, 'steadyFlow': True,
             'vxFluid': [], 'phiPart': [], 'convAcc': [], 'vFluctX': [], 'vFluctY': [], 'vFluctZ': []}
    #: the other attributes only the refused methods read (kept as given)
    _other = {'radiusParts': [], 'compatibilityOldVersion': False, 'vCell': float('nan'), 'radiusPart': 0.0, 'dpdx': 0.0,
              'turbulentViscosity': [], 'phiMax': 0.64, 'irheolf': 0, 'iturbu': 1, 'ilm': 2, 'iusl': 1, 'uTop': 1.0,
              'kappa': 0.41, 'viscousSubLayer': 0, 'fluidWallFriction': False, 'fluidFrictionCoef': 1.0,
              'channelWidth': 1.0, 'phiBed': 0.08, 'taufsi': [], 'lubrication': False, 'roughnessPartScale': 1e-3,
              'vPart': [], 'nbAverageT': 0, 'pointParticleAverage': False, 'enableMultiClassAverage': False,
              'velFluct': False, 'ReynoldStresses': [], 'bedElevation': 0.0, 'fluctTime': [], 'dtFluct': float('nan'),
              'unCorrelatedFluctuations': False, 'twoSize': False, 'radiusPart1': 0.0, 'radiusPart2': 0.0,
              'vxPart': [], 'vyPart': [], 'vzPart': [], 'averageDrag': []}
    _attrs = dict(_core, **_other)
    _live = ('ids',) + tuple(_core)

    def _convert(self, k, v):
        if k == 'gravity':
            return tuple(_vec3_attr('HydroForceEngine', k, v))
        if k in ('vxFluid', 'phiPart', 'convAcc', 'vFluctX', 'vFluctY', 'vFluctZ'):
            return [float(x) for x in v]
        if k == 'nCell':
            return int(v)
        if k == 'lubrication' and v:
            unsupported('HydroForceEngine.lubrication')
        return PartialEngine._convert(self, k, v)

    def _read(self, k):
        if k == 'gravity':
            from .minieigen import Vector3
            return Vector3(*self._values[k])
        v = self._values[k]
        return list(v) if isinstance(v, list) else v

    def _changed(self, k):
        if k in self._other:
            return
        PartialEngine._changed(self, k)

    def _json(self):
        d = {'class': 'HydroForceEngine', 'ids': list(self._values['ids'])}
        for k in self._core:
            v = self._values[k]
            d[k] = list(v) if isinstance(v, (list, tuple)) else v
        if d['deltaZ'] != d['deltaZ']:
            d['deltaZ'] = None
        return d

    def computeRadiusParts(self):
        """The distinct radii of the listed spheres, in list order (clumps skipped)."""
        from ._core import Omega, Sphere
        out = []
        bodies = Omega().bodies
        for i in self._values['ids']:
            if 0 <= i < len(bodies):
                b = bodies[i]
                if b is not None and not b.isClump and isinstance(b.shape, Sphere) and b.shape.radius not in out:
                    out.append(b.shape.radius)
        self._values['radiusParts'] = out

    def initialization(self):
        """`HydroForceEngine::initialization`: zero profiles (nCell cells, nCell + 1 fluid velocities) and
        per-body fluctuations, then computeRadiusParts."""
        from ._core import Omega
        n = int(self._values['nCell'])
        nb = len(Omega().bodies)
        for k in ('vxPart', 'phiPart', 'averageDrag', 'ReynoldStresses', 'turbulentViscosity', 'taufsi'):
            setattr(self, k, [0.0] * n)
        from .minieigen import Vector3
        self._values['vPart'] = [Vector3(0, 0, 0) for _ in range(n)]
        self.vxFluid = [0.0] * (n + 1)
        if not self._values['convAccOption']:
            self.convAcc = [0.0] * n
        for k in ('vFluctX', 'vFluctY', 'vFluctZ'):
            setattr(self, k, [0.0] * nb)
        self.computeRadiusParts()


class HarmonicForceEngine(PartialEngine):
    """A force A_i sin(2 pi f_i t + fi_i) per axis added to the listed bodies every step (ForceEngine.cpp;
    Rust core `force_engine::HarmonicForceEngine`)."""
    _attrs = {'A': (0.0, 0.0, 0.0), 'f': (0.0, 0.0, 0.0), 'fi': (0.0, 0.0, 0.0)}
    _live = ('ids', 'A', 'f', 'fi')
    _axis = None
    _vectors = ('A', 'f', 'fi')
    _state = ()
    _convert = _AxisEngine._convert
    _read = _AxisEngine._read
    _json = _AxisEngine._json


def _float_list(cls, k, v):
    try:
        return [float(x) for x in v]
    except TypeError:
        raise TypeError('%s.%s must be a list of numbers' % (cls, k))


class InterpolatingHelixEngine(HelixEngine):
    """HelixEngine with the angular velocity interpolated in `times`/`angularVelocities` (wrapped with
    `wrap`) and the axial velocity `slope` times it (KinematicEngines.cpp; Rust core
    `kinematic::InterpolatingHelixEngine`)."""
    _attrs = {'times': [], 'angularVelocities': [], 'wrap': False, 'slope': 0.0}
    _live = HelixEngine._live + ('times', 'angularVelocities', 'wrap', 'slope')
    _state = ('angleTurned', 'rotateAroundZero', 'angularVelocity', 'linearVelocity')

    def _convert(self, k, v):
        if k in ('times', 'angularVelocities'):
            return _float_list('InterpolatingHelixEngine', k, v)
        return HelixEngine._convert(self, k, v)


class BicyclePedalEngine(_AxisEngine):
    """Bodies carried round a circle of `radius` about `rotationAxis` without turning, at
    `angularVelocity`, phase `fi` (KinematicEngines.cpp; Rust core `kinematic::BicyclePedalEngine`)."""
    _attrs = {'angularVelocity': 0.0, 'rotationAxis': (1.0, 0.0, 0.0), 'radius': -1.0, 'fi': math.pi / 2.0}
    _live = ('ids', 'angularVelocity', 'rotationAxis', 'radius', 'fi')
    _axis = 'rotationAxis'
    _vectors = ('rotationAxis',)
    _state = ('fi',)


class InterpolatingDirectedForceEngine(ForceEngine):
    """ForceEngine with the magnitude interpolated in `times`/`magnitudes` (wrapped with `wrap`) along
    `direction`, normalised at every step (ForceEngine.cpp; Rust core
    `force_engine::InterpolatingDirectedForceEngine`)."""
    _attrs = {'times': [], 'magnitudes': [], 'direction': (1.0, 0.0, 0.0), 'wrap': False}
    _live = ('ids', 'force', 'times', 'magnitudes', 'direction', 'wrap')
    _vectors = ('force', 'direction')
    _state = ('force', 'direction')

    def _convert(self, k, v):
        if k in ('times', 'magnitudes'):
            return _float_list('InterpolatingDirectedForceEngine', k, v)
        return ForceEngine._convert(self, k, v)


class _MemberSim(object):
    """The Rust engine slot of a CombinedKinematicEngine seen from one of its members: attribute
    `k` of member `n` is `comb.n.k` of the combination."""

    def __init__(self, sim, n):
        self._sim, self._n = sim, n

    def engine_set(self, index, k, v):
        self._sim.engine_set(index, 'comb.%d.%s' % (self._n, k), v)

    def engine_get(self, index, k):
        return self._sim.engine_get(index, 'comb.%d.%s' % (self._n, k))

    def set_engine_dead(self, index, dead):
        self._sim.engine_set(index, 'comb.%d.dead' % self._n, json.dumps(bool(dead)))


class _MemberOwner(object):
    def __init__(self, omega, n):
        self._sim = _MemberSim(omega._sim, n)


class CombinedKinematicEngine(PartialEngine):
    """YADE's combination of kinematic engines (`a + b + c`, KinematicEngines.cpp): the listed bodies'
    velocities are reset once, then every member that is not dead adds its motion, in order, on the
    combination's ids (the first engine's). Members stay live: `comb[k].attr = v` reaches the run."""
    _attrs = {'comb': []}
    _live = ('ids',)

    @classmethod
    def _from_two(cls, first, second):
        c = cls()
        c._values['ids'] = list(first._values['ids'])
        c._values['comb'] = [first, second]
        return c

    def __add__(self, other):
        # YADE appendOne: this object, one member more
        if not isinstance(other, KinematicEngine):
            raise TypeError('only a KinematicEngine can be added to a CombinedKinematicEngine, got %s' % type(other).__name__)
        if self._owner is not None:
            unsupported('adding to a CombinedKinematicEngine after O.engines was assigned')
        self._values['comb'].append(other)
        return self

    def _convert(self, k, v):
        if k == 'comb':
            out = list(v)
            for e in out:
                if not isinstance(e, KinematicEngine):
                    raise TypeError('CombinedKinematicEngine.comb takes KinematicEngines, got %s' % type(e).__name__)
            return out
        return PartialEngine._convert(self, k, v)

    def _changed(self, k):
        if k == 'comb' and self._owner is not None:
            unsupported('changing CombinedKinematicEngine.comb after O.engines was assigned')
        PartialEngine._changed(self, k)

    def _bind(self, omega, index):
        Engine._bind(self, omega, index)
        for n, e in enumerate(self._values['comb']):
            object.__setattr__(e, '_owner', (_MemberOwner(omega, n), index))

    def _json(self):
        comb = []
        for e in self._values['comb']:
            if not isinstance(e, (TranslationEngine, RotationEngine, BicyclePedalEngine)):
                unsupported('%s in a CombinedKinematicEngine' % type(e).__name__)
            d = e._json()
            d['dead'] = bool(e._values['dead'])
            comb.append(d)
        return {'class': 'CombinedKinematicEngine', 'ids': list(self._values['ids']), 'comb': comb}


def _float_json(v):
    """A float for the Rust core's JSON: non-finite values as the strings 'inf', '-inf', 'nan'."""
    v = float(v)
    if v != v:
        return 'nan'
    if v in (float('inf'), float('-inf')):
        return 'inf' if v > 0 else '-inf'
    return v


class RyadePistonController(PartialEngine):
    """**A ryade extension, not a YADE class** (YADE stops a script that uses it with a NameError naming
    it): the geogrid study's piston law (yade_ref/study/study.py `Study.tick` in the phases approach,
    seat and cycle) run in the Rust core every step (`src/piston.rs`), with the same bits as the
    script's PyRunner. Put it where the PyRunner was (after NewtonIntegrator). Pressures in Pa.

    It runs by PeriodicEngine's rule with `iterPeriod` (default 1), `nDo`, `initRun`, `firstIterRun`,
    `nDone`, `iterLast`, as the PyRunner it replaces (a fresh one skips its first step): the study hands
    the PyRunner's `nDone` and `iterLast` over. Parameters: `ids` (piston bodies; forces summed in this order, the first one's z and vz stand for
    the piston), `area`, `alpha` (filter), `Kp`, `Ki`, `vmax`, `dt`, `pSeat`, `pPeak`, `freq`, `wave`
    ('haversine' or 'triangle'), `vApproach`, `iterSeatEnd`, `phase` ('idle', 'approach', 'seat',
    'cycle'), `stopRut`, `zRef`, `pistonOff`, `Z0`, `stepsEvery`, `neumaierSum` (sum the forces as this
    Python's builtin `sum` does; set from the interpreter). State: `pf`, `I`; per-cycle statistics
    `n`, `peak`, `peakRaw`, `se`, `seRaw`, `maxRut` (`resetCycle()`), `stopped`; the last step's `p`,
    `target`, `v`. The study's spring-bed subgrade (its `--subgrade-k`, `tick_subgrade`): `subId` (the
    bottom plate, -1: none), `subM`, `subKA`, `subC`, `subP0`, state `subU`, `subV`; stepped every time the
    engine runs, in every phase, before the piston law. The approach stops the run at p >= pSeat, a cycle once the rut passes `stopRut`
    (as `O.stopAtIter = O.iter + 1` from a PyRunner). `takeSteps()` returns and clears the steps.csv
    samples `[iter, phase, p_kPa, pf_kPa, target_kPa, pistonBottom - Z0, v]`."""
    _attrs = {'iterPeriod': 1, 'nDo': -1, 'initRun': False, 'firstIterRun': 0, 'nDone': 0, 'iterLast': 0,
              'area': 1.0, 'alpha': 1.0, 'Kp': 0.0, 'Ki': 0.0, 'vmax': 1.0, 'dt': 0.0, 'pSeat': 0.0, 'pPeak': 0.0,
              'freq': 0.0, 'wave': 'haversine', 'vApproach': -0.1, 'iterSeatEnd': 10**12, 'phase': 'idle',
              'stopRut': float('inf'), 'zRef': 0.0, 'pistonOff': 0.0, 'Z0': 0.0, 'stepsEvery': 0,
              'neumaierSum': sys.version_info >= (3, 12), 'pf': 0.0, 'I': 0.0, 'n': 0, 'peak': -1e300,
              'peakRaw': -1e300, 'se': 0.0, 'seRaw': 0.0, 'maxRut': -1e300, 'stopped': False, 'p': 0.0,
              'target': 0.0, 'v': 0.0, 'subId': -1, 'subM': 1.0, 'subKA': 0.0, 'subC': 0.0, 'subP0': 0.0,
              'subU': 0.0, 'subV': 0.0}
    _live = ('ids',) + tuple(_attrs)
    _ints = ('iterPeriod', 'nDo', 'firstIterRun', 'nDone', 'iterLast', 'iterSeatEnd', 'stepsEvery', 'n', 'subId')
    _bools = ('initRun', 'neumaierSum', 'stopped')
    _choices = {'wave': ('haversine', 'triangle'), 'phase': ('idle', 'approach', 'seat', 'cycle')}
    #: study.py load()'s per-cycle accumulators at the start of a cycle
    _CYCLE_START = (('n', 0), ('peak', -1e300), ('peakRaw', -1e300), ('se', 0.0), ('seRaw', 0.0), ('maxRut', -1e300))

    def _convert(self, k, v):
        if k in self._ints:
            return int(v)
        if k in self._bools:
            return bool(v)
        if k in self._choices:
            if v not in self._choices[k]:
                raise ValueError('RyadePistonController.%s must be one of %s, got %r' % (k, ', '.join(self._choices[k]), v))
            return v
        if k in RyadePistonController._attrs:
            return float(v)
        return PartialEngine._convert(self, k, v)

    def _encode(self, k):
        v = self._values[k]
        if k in RyadePistonController._attrs and not (k in self._ints or k in self._bools or k in self._choices):
            return _float_json(v)
        return v

    def _changed(self, k):
        if self._owner is not None and k in self._live:
            omega, index = self._owner
            omega._sim.engine_set(index, k, json.dumps(self._encode(k)))
            return
        PartialEngine._changed(self, k)

    def _read(self, k):
        if self._owner is None or k not in self._live:
            return self._values[k]
        omega, index = self._owner
        v = json.loads(omega._sim.engine_get(index, k))
        return float(v) if isinstance(v, str) and k not in self._choices else v

    def _json(self):
        d = {'class': 'RyadePistonController', 'ids': list(self._values['ids'])}
        for k in RyadePistonController._attrs:
            d[k] = self._encode(k)
        return d

    def takeSteps(self):
        """The steps.csv samples since the last call (and clears them): lists
        [iter, phase, p_kPa, pf_kPa, target_kPa, pistonBottom - Z0, v]."""
        if self._owner is None:
            return []
        omega, index = self._owner
        return [list(r) for r in omega._sim.piston_take_rows(index)]

    def boxPorosity(self, ids, lo, hi, Lx, Ly, nodes, weights):
        """The study script's porosity of the box [lo, hi] (study.py `box_porosity`: spheres `ids` as they
        are now and their periodic images in x and y, the sphere-box volumes integrated with the
        Gauss-Legendre `nodes` and `weights`), in the Rust core with the same bits as the script
        (`ryade::porosity::study_box_porosity`), without reading the spheres into Python."""
        if self._owner is None:
            raise RuntimeError('RyadePistonController.boxPorosity: put the engine in O.engines first (it reads that scene)')
        omega, _ = self._owner
        return omega._sim.study_box_porosity([int(i) for i in ids], tuple(lo), tuple(hi), float(Lx), float(Ly),
                                             [float(x) for x in nodes], [float(w) for w in weights])

    def resetCycle(self):
        """The per-cycle statistics back to their start values (study.py load(): n 0, peak, peakRaw and
        maxRut -1e300, se and seRaw 0)."""
        for k, v in self._CYCLE_START:
            setattr(self, k, v)
class BoundaryController(GlobalEngine):
    """Base of YADE's boundary controllers (not usable directly, as in YADE)."""


def _nan_none(v):
    """JSON for the Rust core: NaN (YADE's unset mass / currUnbalanced) as null."""
    if isinstance(v, float) and v != v:
        return None
    if isinstance(v, (list, tuple)):
        return [_nan_none(x) for x in v]
    return v


class PeriTriaxController(BoundaryController):
    """YADE's stress/strain controller of the periodic cell (pkg/dem/PeriIsoCompressor.cpp), run in the
    Rust core (`ryade::peri_triax`). Vector attributes are live views, as in YADE (`triax.goal[2] = -0.1`
    changes the goal); `doneHook` runs in the script's globals right after the controller, inside the step."""
    _attrs = {'dynCell': False, 'goal': (0.0, 0.0, 0.0), 'stressMask': 0, 'maxStrainRate': (1.0, 1.0, 1.0),
              'maxUnbalanced': 1e-4, 'absStressTol': 1e3, 'relStressTol': 3e-5, 'growDamping': 0.25, 'globUpdate': 5,
              'doneHook': '', 'maxBodySpan': (0.0, 0.0, 0.0), 'stressTensor': (0.0,) * 9, 'stress': (0.0, 0.0, 0.0),
              'strain': (0.0, 0.0, 0.0), 'strainRate': (0.0, 0.0, 0.0), 'stiff': (0.0, 0.0, 0.0),
              'currUnbalanced': float('nan'), 'prevGrow': (0.0, 0.0, 0.0), 'mass': float('nan'), 'externalWork': 0.0}
    _vectors = ('goal', 'maxStrainRate', 'maxBodySpan', 'stress', 'strain', 'strainRate', 'stiff', 'prevGrow')
    _ints = ('stressMask', 'globUpdate')
    _own = tuple(k for k in _attrs)

    def _convert(self, k, v):
        if k in self._vectors:
            return tuple(float(x) for x in _vec3_attr('PeriTriaxController', k, v))
        if k == 'stressTensor':
            try:
                vals = tuple(float(v[i, j]) for i in range(3) for j in range(3))
            except (TypeError, IndexError):
                vals = tuple(float(x) for row in v for x in row)
            if len(vals) != 9:
                raise TypeError('PeriTriaxController.stressTensor must be a 3x3 matrix')
            return vals
        if k in self._ints:
            return int(v)
        if k == 'dynCell':
            return bool(v)
        if k == 'doneHook':
            if not isinstance(v, str):
                raise TypeError('PeriTriaxController.doneHook must be a string (Python code)')
            return v
        if k in self._own:
            return float(v)
        return v

    def _raw(self, k):
        """The current value: from the Rust core while in O.engines, else the stored one."""
        if self._owner is not None and k in self._own:
            omega, index = self._owner
            v = json.loads(omega._sim.engine_get(index, k))
            if k == 'stressTensor':
                return tuple(x for row in v for x in row)
            if v is None:
                return float('nan')
            return tuple(v) if isinstance(v, list) else v
        return self._values[k]

    def _read(self, k):
        from .minieigen import Matrix3, Vector3
        if k in self._vectors:
            return Vector3._view(lambda: self._raw(k), lambda t: self._assign(k, t))
        if k == 'stressTensor':
            return Matrix3._view(lambda: self._raw(k), lambda t: self._assign(k, t))
        return self._raw(k)

    def _changed(self, k):
        if self._owner is not None and k in self._own:
            omega, index = self._owner
            v = self._values[k]
            if k == 'stressTensor':
                v = [list(v[0:3]), list(v[3:6]), list(v[6:9])]
            omega._sim.engine_set(index, k, json.dumps(_nan_none(v)))
            return
        BoundaryController._changed(self, k)

    def _timing_detach(self):
        # the object leaves this engine list: keep the state the Rust core reached (YADE keeps the object)
        if self._owner is not None:
            for k in self._own:
                self._values[k] = self._raw(k)
        BoundaryController._timing_detach(self)

    def _json(self):
        d = {'class': 'PeriTriaxController'}
        for k in self._own:
            v = self._values[k]
            if k == 'stressTensor':
                v = [list(v[0:3]), list(v[3:6]), list(v[6:9])]
            elif isinstance(v, tuple):
                v = list(v)
            d[k] = _nan_none(v)
        return d

    def _run_done_hook(self):
        """`pyRunString(doneHook)`: the hook in the script's globals (`__main__`)."""
        hook = self._raw('doneHook')
        if hook:
            exec(compile(hook, '<PeriTriaxController.doneHook>', 'exec'), sys.modules['__main__'].__dict__)


class TriaxialStressController(BoundaryController):
    """YADE's stress/strain controller of six walls around a packing, or internal compaction by growing
    the spheres (pkg/dem/TriaxialStressController.cpp), run in the Rust core (`ryade::triax`). Values the
    engine updates (height, meanStress, ...) are read from the run."""
    _attrs = {'stiffnessUpdateInterval': 10, 'radiusControlInterval': 10, 'computeStressStrainInterval': 10,
              'stressDamping': 0.25, 'strainDamping': 0.99, 'thickness': -1.0, 'wall_bottom_id': 2, 'wall_top_id': 3,
              'wall_left_id': 0, 'wall_right_id': 1, 'wall_front_id': 5, 'wall_back_id': 4,
              'wall_bottom_activated': True, 'wall_top_activated': True, 'wall_left_activated': True,
              'wall_right_activated': True, 'wall_front_activated': True, 'wall_back_activated': True,
              'height': 0.0, 'width': 0.0, 'depth': 0.0, 'height0': 0.0, 'width0': 0.0, 'depth0': 0.0,
              'goal1': 0.0, 'goal2': 0.0, 'goal3': 0.0, 'stressMask': 7, 'maxMultiplier': 1.001,
              'finalMaxMultiplier': 1.00001, 'max_vel': 1.0, 'previousStress': 0.0, 'previousMultiplier': 1.0,
              'internalCompaction': True, 'meanStress': 0.0, 'volumetricStrain': 0.0, 'externalWork': 0.0,
              'updatePorosity': False}
    _ints = ('stiffnessUpdateInterval', 'radiusControlInterval', 'computeStressStrainInterval', 'wall_bottom_id',
             'wall_top_id', 'wall_left_id', 'wall_right_id', 'wall_front_id', 'wall_back_id', 'stressMask')
    _bools = ('wall_bottom_activated', 'wall_top_activated', 'wall_left_activated', 'wall_right_activated',
              'wall_front_activated', 'wall_back_activated', 'internalCompaction', 'updatePorosity')
    _own = tuple(_attrs)
    _class = 'TriaxialStressController'

    def _convert(self, k, v):
        if k in self._ints:
            return int(v)
        if k in self._bools:
            return bool(v)
        if k in self._own:
            return float(v)
        return v

    def _get(self, k):
        omega, index = self._owner
        return json.loads(omega._sim.engine_get(index, k))

    def _read(self, k):
        if self._owner is not None and k in self._own:
            return self._get(k)
        return self._values[k]

    def _changed(self, k):
        if self._owner is not None and k in self._own:
            omega, index = self._owner
            omega._sim.engine_set(index, k, json.dumps(self._values[k]))
            return
        BoundaryController._changed(self, k)

    def _timing_detach(self):
        if self._owner is not None:
            for k in self._own:
                self._values[k] = self._get(k)
        BoundaryController._timing_detach(self)

    def _json(self):
        d = {'class': self._class}
        for k in self._own:
            d[k] = self._values[k]
        return d

    def _state(self, k, default):
        return self._get(k) if self._owner is not None else default

    @property
    def strain(self):
        from .minieigen import Vector3
        return Vector3(*self._state('strain', (0.0, 0.0, 0.0)))

    porosity = property(lambda self: self._state('porosity', 1.0))
    boxVolume = property(lambda self: self._state('boxVolume', 0.0))
    particlesVolume = property(lambda self: self._state('particlesVolume', 0.0))
    spheresVolume = property(lambda self: self._state('spheresVolume', 0.0))
    max_vel1 = property(lambda self: self._state('max_vel1', 0.0))
    max_vel2 = property(lambda self: self._state('max_vel2', 0.0))
    max_vel3 = property(lambda self: self._state('max_vel3', 0.0))

    def stress(self, id):
        """The average stress on boundary `id` (0..5: left, right, bottom, top, back, front)."""
        from .minieigen import Vector3
        id = int(id)
        if not 0 <= id <= 5:
            raise IndexError('TriaxialStressController.stress: boundary id must be 0..5, got %d' % id)
        return Vector3(*self._state('stress.%d' % id, (0.0, 0.0, 0.0)))

    def strainRate(self):
        from .minieigen import Vector3
        if self._owner is None:
            return Vector3(0, 0, 0)
        omega, index = self._owner
        return Vector3(*json.loads(omega._sim.triax_strain_rate(index)))

    def _compute_stress_strain(self):
        omega, index = self._owner
        omega._sim.triax_compute_stress_strain(index)


class TriaxialCompressionEngine(TriaxialStressController):
    """YADE's TriaxialCompressionEngine (pkg/dem/TriaxialCompressionEngine.cpp): the controller driven by
    its state machine (compaction, unloading, confined loading), run in the Rust core
    (`ryade::triax_compression`). Its snapshot files (noFiles=False) are refused when they would be
    written (YADE's .xml cannot be written by ryade)."""
    _attrs = {'strainRate': 0.0, 'currentStrainRate': 0.0, 'UnbalancedForce': 1.0, 'StabilityCriterion': 0.001,
              'translationAxis': (0.0, 1.0, 0.0), 'autoCompressionActivation': True, 'autoUnload': True,
              'autoStopSimulation': False, 'testEquilibriumInterval': 20, 'currentState': 0, 'previousState': 0,
              'sigmaIsoCompaction': 1.0, 'previousSigmaIso': 0.0, 'sigmaLateralConfinement': 1.0, 'noFiles': False,
              'frictionAngleDegree': -1.0, 'epsilonMax': 0.5, 'fixedPoroCompaction': False, 'fixedPorosity': 0.0,
              'maxStress': 0.0, 'sigma_iso': 0.0, 'isAxisymetric': True, 'Key': '',
              # kept on the Python side: a counter and a value YADE never updates
              'warn': 0, 'uniaxialEpsilonCurr': 1.0}
    _local = ('warn', 'uniaxialEpsilonCurr')
    _own = TriaxialStressController._own + tuple(k for k in _attrs if k not in ('warn', 'uniaxialEpsilonCurr'))
    _ints = TriaxialStressController._ints + ('testEquilibriumInterval', 'currentState', 'previousState', 'warn')
    _bools = TriaxialStressController._bools + ('autoCompressionActivation', 'autoUnload', 'autoStopSimulation',
                                                'noFiles', 'fixedPoroCompaction', 'isAxisymetric')
    _class = 'TriaxialCompressionEngine'
    # YADE's attribute strainRate shadows the controller's strainRate() method in this class
    strainRate = property(lambda self: self._read('strainRate'), lambda self, v: self._assign('strainRate', v))

    def _convert(self, k, v):
        if k == 'translationAxis':
            return tuple(_vec3_attr('TriaxialCompressionEngine', k, v))
        if k == 'Key':
            return str(v)
        return TriaxialStressController._convert(self, k, v)

    def _read(self, k):
        v = TriaxialStressController._read(self, k)
        if k == 'translationAxis':
            from .minieigen import Vector3
            return Vector3(*v)
        return v

    def _changed(self, k):
        if k in self._local:
            return
        TriaxialStressController._changed(self, k)

    def _json(self):
        d = TriaxialStressController._json(self)
        d['translationAxis'] = list(d['translationAxis'])
        return d

    def _run_done_hook(self):
        """The snapshot files YADE writes during this step (noFiles=False): `.spheres` as
        Shop::saveSpheresToFile (x y z r of each dynamic sphere, C++ stream format), `.xml` through
        O.save (ryade's own format, as O.save writes for any name: YADE's XML cannot be written)."""
        from ._core import Omega, Sphere
        omega, index = self._owner
        names = json.loads(omega._sim.engine_get(index, '_pendingFiles'))
        omega._sim.engine_set(index, '_pendingFiles', '[]')
        for name in names:
            if name.endswith('.spheres'):
                with open(name, 'w') as f:
                    for b in Omega().bodies:
                        if b is None or not b.dynamic or not isinstance(b.shape, Sphere):
                            continue
                        p = b.state.pos
                        f.write('%g %g %g %g\n' % (p[0], p[1], p[2], b.shape.radius))
            else:
                Omega().save(name)

    def setContactProperties(self, frictionDegree):
        """`Shop::setContactFriction`: dynamic bodies' materials and the real contacts get the angle."""
        from ._core import Omega
        Omega()._sim.set_contact_friction_degrees(float(frictionDegree), True)


class ThreeDTriaxialEngine(TriaxialStressController):
    """YADE's ThreeDTriaxialEngine (pkg/dem/ThreeDTriaxialEngine.cpp): per axis stress control (the
    controller's servo) or strain control at strainRate_i, run in the Rust core
    (`ryade::triax_compression::ThreeD`). Its strainDamping (0.9997) is its own, as in YADE (the
    controller keeps 0.99)."""
    _attrs = {'strainRate1': 0.0, 'currentStrainRate1': 0.0, 'strainRate2': 0.0, 'currentStrainRate2': 0.0,
              'strainRate3': 0.0, 'currentStrainRate3': 0.0, 'UnbalancedForce': 1.0, 'frictionAngleDegree': -1.0,
              'updateFrictionAngle': False, 'stressControl_1': True, 'stressControl_2': True, 'stressControl_3': True,
              'strainDamping': 0.9997, 'Key': ''}
    _own = TriaxialStressController._own + tuple(k for k in _attrs if k != 'strainDamping')
    _bools = TriaxialStressController._bools + ('updateFrictionAngle', 'stressControl_1', 'stressControl_2',
                                                'stressControl_3')
    _class = 'ThreeDTriaxialEngine'

    def _convert(self, k, v):
        if k == 'Key':
            return str(v)
        return TriaxialStressController._convert(self, k, v)

    def setContactProperties(self, frictionDegree):
        """Dynamic bodies' materials and the real contacts get the angle (clumps not skipped, as YADE's)."""
        from ._core import Omega
        Omega()._sim.set_contact_friction_degrees(float(frictionDegree), False)


class PeriodicEngine(GlobalEngine):
    """Run every `iterPeriod` steps / `virtPeriod` s of simulated time / `realPeriod` s of wall time
    (pkg/common/PeriodicEngines.hpp, isActivated, including its counting of the first call in nDone)."""
    _attrs = {'iterPeriod': 0, 'virtPeriod': 0.0, 'realPeriod': 0.0, 'nDo': -1, 'initRun': False, 'firstIterRun': 0,
              'nDone': 0, 'iterLast': 0, 'virtLast': 0.0, 'realLast': 0.0}

    def _is_builtin(self):
        return False

    def _is_activated(self, omega):
        v = self._values
        virt_now, real_now, iter_now = omega.time, _time.time(), omega.iter
        if v['firstIterRun'] > 0 and v['nDone'] == 0:
            if v['firstIterRun'] == iter_now:
                v['realLast'], v['virtLast'], v['iterLast'] = real_now, virt_now, iter_now
                v['nDone'] += 1
                return True
            return False
        if iter_now < v['iterLast']:
            v['nDone'] = 0
        if (v['nDo'] < 0 or v['nDone'] < v['nDo']) and (
                (v['virtPeriod'] > 0 and virt_now - v['virtLast'] >= v['virtPeriod'])
                or (v['realPeriod'] > 0 and real_now - v['realLast'] >= v['realPeriod'])
                or (v['iterPeriod'] > 0 and iter_now - v['iterLast'] >= v['iterPeriod'])):
            v['realLast'], v['virtLast'], v['iterLast'] = real_now, virt_now, iter_now
            v['nDone'] += 1
            return True
        if v['nDone'] == 0:
            v['realLast'], v['virtLast'], v['iterLast'] = real_now, virt_now, iter_now
            v['nDone'] += 1
            return bool(v['initRun'])
        return False

    def _json(self):
        return {'class': 'External'}


class DomainLimiter(PeriodicEngine):
    """YADE's DomainLimiter (pkg/dem/DomainLimiter.cpp): every period, spheres and clumps whose position
    is outside [lo, hi] (and whose groupMask shares a bit with `mask` when mask > 0) are deleted. ryade
    cannot erase bodies yet: the engine runs its check as YADE does and, when a body is to go, stops
    the run with the "does not support" error naming it; otherwise nothing changes."""
    _attrs = {'lo': (0.0, 0.0, 0.0), 'hi': (0.0, 0.0, 0.0), 'nDeleted': 0, 'mDeleted': 0.0, 'vDeleted': 0.0, 'mask': -1}

    def _convert(self, k, v):
        if k in ('lo', 'hi'):
            return tuple(_vec3_attr('DomainLimiter', k, v))
        return v

    def _read(self, k):
        if k in ('lo', 'hi'):
            from .minieigen import Vector3
            return Vector3(*self._values[k])
        return self._values[k]

    def _action(self, omega):
        from ._core import Sphere
        lo, hi, mask = self._values['lo'], self._values['hi'], self._values['mask']
        out = []
        for b in omega.bodies:
            if b is None or (mask > 0 and (b.groupMask & mask) == 0) or b.isClumpMember:
                continue
            if isinstance(b.shape, Sphere) or b.isClump:
                p = b.state.pos
                if any(p[k] < lo[k] or p[k] > hi[k] for k in range(3)):
                    out.append(b.id)
        if out:
            unsupported('DomainLimiter deleting bodies (#%s: O.bodies.erase)' % ', #'.join(str(i) for i in out[:10]))


class CpmStateUpdater(PeriodicEngine):
    """YADE's CpmStateUpdater (ConcretePM.cpp) writes only post-processing values: each body's CpmState
    (normDmg, stress, damageTensor, from its contacts' damage and the broken ones) and colour, and its
    own avgRelResidual/maxOmega; none of them feeds the simulation. ryade keeps none of them: the
    engine runs on YADE's schedule and changes nothing, and reading any of those values says that
    ryade does not support it."""
    _attrs = {'initRun': True}

    def _action(self, omega):
        pass


class PyRunner(PeriodicEngine):
    """`PyRunner(command, iterPeriod, ...)`: `command` runs in the script's `__main__` globals."""
    _attrs = {'command': '', 'ignoreErrors': False, 'updateGlobals': True}
    _positional = ('iterPeriod', 'command')

    def __init__(self, *args, **kw):
        # YADE accepts PyRunner(command) and PyRunner(iterPeriod, command)
        if len(args) == 1 and isinstance(args[0], str):
            kw['command'] = args[0]
            args = ()
        Serializable.__init__(self, *args, **kw)

    def _action(self, omega):
        cmd = self._values['command']
        if not cmd:
            return
        code = self.__dict__.get('_code')
        if code is None or code[0] != cmd:  # compiled once per command string
            code = (cmd, compile(cmd, '<PyRunner %s>' % (self._values['label'] or 'command'), 'exec'))
            object.__setattr__(self, '_code', code)
        try:
            exec(code[1], sys.modules['__main__'].__dict__)  # what `import __main__` gives, without the import machinery
        except Exception:
            if not self._values['ignoreErrors']:
                raise


# ---------------------------------------------------------------- materials

class Material(Serializable):
    _attrs = {'label': '', 'id': -1, 'density': 1000.0}

    def _bind(self, omega, rust_index):
        object.__setattr__(self, '_owner', (omega, rust_index))

    def _changed(self, k):
        if self._owner is None or k in ('label', 'id'):
            return
        omega, idx = self._owner
        omega._sim.material_set(idx, k, float(self._values[k]))


class ElastMat(Material):
    _attrs = {'young': 1e9, 'poisson': 0.25}


class FrictMat(ElastMat):
    _attrs = {'frictionAngle': 0.5}

    def _read(self, k):
        # engines (TriaxialCompressionEngine, ThreeDTriaxialEngine.setContactProperties) change it in
        # the core
        if k == 'frictionAngle' and self._owner is not None:
            omega, idx = self._owner
            return omega._sim.material_friction_angle(idx)
        return ElastMat._read(self, k)

    def _json(self):
        v = self._values
        return {'class': 'FrictMat', 'id': v['id'], 'label': v['label'], 'young': float(v['young']),
                'poisson': float(v['poisson']), 'frictionAngle': float(v['frictionAngle']), 'density': float(v['density'])}


class CpmMat(FrictMat):
    """The concrete particle model's material (pkg/dem/ConcretePM.hpp): a FrictMat, density 4800 by
    default; NaN (not given) travels as null."""
    _attrs = {'density': 4800.0, 'sigmaT': float('nan'), 'neverDamage': False, 'epsCrackOnset': float('nan'),
              'relDuctility': float('nan'), 'equivStrainShearContrib': 0.0, 'damLaw': 1, 'dmgTau': -1.0,
              'dmgRateExp': 0.0, 'plTau': -1.0, 'plRateExp': 0.0, 'isoPrestress': 0.0}
    _OWN = ('sigmaT', 'neverDamage', 'epsCrackOnset', 'relDuctility', 'equivStrainShearContrib', 'damLaw', 'dmgTau',
            'dmgRateExp', 'plTau', 'plRateExp', 'isoPrestress')

    def _json(self):
        d = FrictMat._json(self)
        d['class'] = 'CpmMat'
        for k in CpmMat._OWN:
            v = self._values[k]
            if k == 'neverDamage':
                d[k] = bool(v)
            elif k == 'damLaw':
                d[k] = int(v)
            else:
                x = float(v)
                d[k] = None if x != x else x
        return d

    def _changed(self, k):
        if self._owner is not None and k in CpmMat._OWN:
            unsupported('changing CpmMat.%s after the material is in use' % k)
        FrictMat._changed(self, k)


class CohFrictMat(FrictMat):
    _attrs = {'isCohesive': True, 'alphaKr': 2.0, 'alphaKtw': 2.0, 'etaRoll': -1.0, 'etaTwist': -1.0,
              'normalCohesion': -1.0, 'shearCohesion': -1.0, 'fragile': True, 'momentRotationLaw': False}

    def _json(self):
        d = FrictMat._json(self)
        d['class'] = 'CohFrictMat'
        for k in CohFrictMat._attrs:
            v = self._values[k]
            d[k] = bool(v) if isinstance(CohFrictMat._attrs[k], bool) else float(v)
        return d

    def _changed(self, k):
        if self._owner is not None and k in CohFrictMat._attrs:
            unsupported('changing CohFrictMat.%s after the material is in use' % k)
        FrictMat._changed(self, k)


class ViscElMat(FrictMat):
    _attrs = {'tc': float('nan'), 'en': float('nan'), 'et': float('nan'), 'kn': float('nan'), 'cn': float('nan'),
              'ks': float('nan'), 'cs': float('nan'), 'mR': 0.0, 'mRtype': 1, 'lubrication': False,
              'viscoDyn': 1e-3, 'roughnessScale': 1e-3}

    def _json(self):
        v = self._values
        if v['lubrication']:
            unsupported('ViscElMat.lubrication=True')
        d = FrictMat._json(self)
        d['class'] = 'ViscElMat'
        for k in ('tc', 'en', 'et', 'kn', 'cn', 'ks', 'cs'):
            x = float(v[k])
            d[k] = None if x != x else x  # NaN (not given) as null
        d['mR'], d['mRtype'] = float(v['mR']), int(v['mRtype'])
        return d

    def _changed(self, k):
        if self._owner is not None and k in ViscElMat._attrs:
            unsupported('changing ViscElMat.%s after the material is in use' % k)
        FrictMat._changed(self, k)


class LudingMat(Material):
    """YADE's LudingMat (pkg/dem/LudingPM.hpp): a Material (not an ElastMat) with Luding's hysteretic
    contact parameters; NaN (YADE's default) for a value not given."""
    _attrs = {'k1': float('nan'), 'kp': float('nan'), 'kc': float('nan'), 'ks': float('nan'), 'PhiF': float('nan'),
              'G0': float('nan'), 'frictionAngle': float('nan')}

    def _json(self):
        v = self._values
        d = {'class': 'LudingMat', 'id': v['id'], 'label': v['label'], 'density': float(v['density'])}
        for k in LudingMat._attrs:
            x = float(v[k])
            d[k] = None if x != x else x  # NaN (not given) as null
        return d

    def _changed(self, k):
        if self._owner is not None and k in LudingMat._attrs:
            unsupported('changing LudingMat.%s after the material is in use' % k)
        Material._changed(self, k)


class BubbleMat(Material):
    """YADE's BubbleMat (pkg/dem/BubbleMat.hpp): a Material for bubbles in a liquid of `surfaceTension`."""
    _attrs = {'surfaceTension': 0.07197}

    def _json(self):
        v = self._values
        return {'class': 'BubbleMat', 'id': v['id'], 'label': v['label'], 'density': float(v['density']),
                'surfaceTension': float(v['surfaceTension'])}

    def _changed(self, k):
        if self._owner is not None and k == 'surfaceTension':
            unsupported('changing BubbleMat.surfaceTension after the material is in use')
        Material._changed(self, k)


# ---------------------------------------------------------------- GUI stubs (harmless)

class _GlStub(Serializable):
    """OpenGL functor stubs: scripts set their static attributes for the GUI; nothing to do headless."""

    def __setattr__(self, k, v):
        object.__setattr__(self, k, v)

    def __getattr__(self, k):
        if k.startswith('_'):
            raise AttributeError(k)
        return None


def _jsonable(v):
    if isinstance(v, (list, tuple)):
        return [_jsonable(x) for x in v]
    if hasattr(v, '__len__') and hasattr(v, '__getitem__') and not isinstance(v, (str, dict)):
        return [float(x) for x in v]
    return v


class Recorder(PeriodicEngine):
    """YADE's Recorder: a periodic engine writing lines to `file` (opened in append mode, or truncated
    first with `truncate`; `addIterNum` appends the iteration to the file name). It runs at its first
    step too (YADE's constructor sets initRun)."""
    _attrs = {'file': '', 'truncate': False, 'addIterNum': False, 'initRun': True}

    def _out(self, omega):
        f = self.__dict__.get('_fh')
        if f is None:
            name = self._values['file']
            if not name:
                raise IOError('%s.file must be set' % type(self).__name__)
            if self._values['addIterNum']:
                name = '%s-%d' % (name, omega.iter)
            f = open(name, 'w' if self._values['truncate'] else 'a')
            object.__setattr__(self, '_fh', f)
        return f


def _lexical(x):
    """boost::lexical_cast<std::string>(double): 17 significant digits; a NaN keeps its sign (-nan)."""
    if x != x:
        return '-nan' if math.copysign(1.0, x) < 0 else 'nan'
    return '%.17g' % x


class TriaxialStateRecorder(Recorder):
    """YADE's TriaxialStateRecorder (pkg/dem/TriaxialStateRecorder.cpp): every period a line with the
    iteration, the stresses on the right, top and front walls, the strains, the unbalanced force, the
    porosity of the dynamic spheres in the box and the kinetic energy, from the first triaxial controller
    in O.engines."""
    _attrs = {'porosity': 1.0}

    def _action(self, omega):
        from . import utils
        f = self._out(omega)
        if f.tell() == 0:
            f.write('iteration s11 s22 s33 e11 e22 e33 unb_force porosity kineticE\n')
        tsc = self.__dict__.get('_tsc')
        if tsc is None:
            for e in omega.engines:
                if type(e).__name__ in ('TriaxialCompressionEngine', 'ThreeDTriaxialEngine', 'TriaxialStressController'):
                    tsc = e
            if tsc is None:
                unsupported('TriaxialStateRecorder without a triaxial controller in O.engines (YADE crashes)')
            object.__setattr__(self, '_tsc', tsc)
        if omega.iter % tsc.computeStressStrainInterval != 0:
            tsc._compute_stress_strain()
        vs = 0.0
        for b in omega.bodies:
            if b is None or b.isClump:
                continue
            if b.dynamic:
                vs += 1.3333333 * math.pi * math.pow(b.shape.radius, 3)
        v = tsc.height * tsc.width * tsc.depth
        self._values['porosity'] = (v - vs) / v
        st = [tsc.stress(1)[0], tsc.stress(3)[1], tsc.stress(5)[2]]
        e = tsc.strain
        f.write(' '.join([str(omega.iter)] + [_lexical(x) for x in st + [e[0], e[1], e[2], utils.unbalancedForce(),
                                                                          self._values['porosity'], utils.kineticEnergy()]]) + '\n')
        f.flush()



# ---------------------------------------------------------------- every other YADE class

def _make_unsupported(name):
    def __init__(self, *args, **kw):
        unsupported('class %s' % name)
    return type(name, (Serializable,), {'__init__': __init__, '__doc__': 'YADE class not implemented by ryade.',
                                        '_ryade_unsupported': 'class %s' % name})


_IMPLEMENTED = {c.__name__: c for c in [
    Serializable, Functor, BoundFunctor, Bo1_Sphere_Aabb, Bo1_Facet_Aabb, Bo1_Box_Aabb, Bo1_Wall_Aabb, IGeomFunctor,
    Ig2_Sphere_Sphere_ScGeom, Ig2_Facet_Sphere_ScGeom, Ig2_Wall_Sphere_ScGeom, Ig2_Box_Sphere_ScGeom, Ig2_Box_Sphere_ScGeom6D, IPhysFunctor,
    Ip2_FrictMat_FrictMat_FrictPhys, LawFunctor, Law2_ScGeom_FrictPhys_CundallStrack, Engine, GlobalEngine,
    ForceResetter, BoundDispatcher, InsertionSortCollider, InteractionLoop, IntrCallback, SumIntrForcesCb, NewtonIntegrator, PeriodicEngine, PyRunner, Material,
    TimeStepper, GlobalStiffnessTimeStepper, PartialEngine, KinematicEngine, TranslationEngine, RotationEngine, ServoPIDController,
    HelixEngine, CombinedKinematicEngine, ForceEngine, HarmonicForceEngine, DomainLimiter, RyadePistonController,
    InterpolatingHelixEngine, BicyclePedalEngine, InterpolatingDirectedForceEngine,
    BoundaryController, PeriTriaxController, TriaxialStressController, TriaxialCompressionEngine, ThreeDTriaxialEngine, HydroForceEngine, Recorder, TriaxialStateRecorder,
    CohFrictMat, Bo1_GridConnection_Aabb, Ig2_Sphere_Sphere_ScGeom6D,
    Ig2_GridNode_GridNode_GridNodeGeom6D, Ig2_Sphere_GridConnection_ScGridCoGeom,
    Ig2_GridConnection_GridConnection_GridCoGridCoGeom, Ip2_CohFrictMat_CohFrictMat_CohFrictPhys,
    Law2_ScGeom6D_CohFrictPhys_CohesionMoment, Law2_ScGridCoGeom_FrictPhys_CundallStrack,
    Law2_ScGridCoGeom_CohFrictPhys_CundallStrack, Law2_GridCoGridCoGeom_FrictPhys_CundallStrack,
    ElastMat, FrictMat, ViscElMat, Ip2_ViscElMat_ViscElMat_ViscElPhys, Law2_ScGeom_ViscElPhys_Basic,
    Ip2_FrictMat_FrictMat_MindlinPhys, Law2_ScGeom_MindlinPhys_Mindlin, MatchMaker, LudingMat,
    Ip2_LudingMat_LudingMat_LudingPhys, Law2_ScGeom_LudingPhys_Basic, BubbleMat, Ip2_BubbleMat_BubbleMat_BubblePhys,
    Law2_ScGeom_BubblePhys_Bubble, CpmMat, Ip2_CpmMat_CpmMat_CpmPhys, Ip2_FrictMat_CpmMat_FrictPhys,
    Law2_ScGeom_CpmPhys_Cpm, CpmStateUpdater]}


#: ryade's own engine classes (no YADE class of that name: a script using them runs under ryade only)
RYADE_EXTENSIONS = ('RyadePistonController',)

_ALL = {}


def all_classes():
    """name -> class for every YADE class: ours where implemented, an UnsupportedError stub otherwise
    (OpenGL `Gl1_*`/`GlExtra*` classes are harmless stubs for headless runs). Stubs get YADE's base
    class, so `isinstance(i.phys, FrictPhys)` holds for a CohFrictPhys as in YADE."""
    if _ALL:
        return dict(_ALL)
    out = dict(_IMPLEMENTED)

    def make(name):
        if name in out:
            return out[name]
        parents = [b for b in YADE_CLASSES.get(name, {}).get('bases', ()) if b in YADE_CLASSES]
        base = make(parents[0]) if parents else Serializable
        if name.startswith(('Gl1_', 'GlBound', 'GlShape', 'GlIGeom', 'GlIPhys', 'GlState', 'GlExtra', 'OpenGLRenderer')):
            cls = type(name, (_GlStub,), {})
        else:
            def __init__(self, *args, **kw):
                unsupported('class %s' % name)
            cls = type(name, (base,), {'__init__': __init__, '__doc__': 'YADE class not implemented by ryade.',
                                       '_ryade_unsupported': 'class %s' % name})
        out[name] = cls
        return cls

    for name in YADE_CLASSES:
        make(name)
    _ALL.update(out)
    return dict(out)


def class_by_name(name):
    """The class object scripts see under `name` (for geometry/physics views' `__class__`)."""
    return all_classes().get(name) or type(name, (object,), {})
