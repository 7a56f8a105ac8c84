"""Recorder for ryade golden files (see golden/FORMAT.md).

Used from plain YADE scripts run with ``yade -n -x script.py [OUTDIR]``:

    import os, sys
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
    import ryade_record
    ... build the scene (O.bodies, O.engines, O.dt) ...
    ryade_record.record('headon', steps=300)

Under ``yade -x`` the name ``__file__`` is /usr/bin/yade, so the script path is taken from
``sys.argv[0]`` (YADE does not change the working directory, so abspath() resolves it).

``record`` introspects the scene (raising on anything FORMAT.md cannot express), runs
``O.step()`` ``steps`` times and writes, atomically (temp file + rename, all files at the end):
  <name>.scene.json       always
  <name>.bodies.csv.gz    every step, or only ``keep_steps``
  <name>.intrs.csv.gz     if ``intrs`` (every step)
  <name>.digest.csv       if ``digest`` (SHA-256 per step)
  <name>.intrs6d.csv.gz   if ``grid`` (every step; golden/FORMAT_GRID.md)

``grid=True`` selects the grid extension (golden/FORMAT_GRID.md): the scene JSON gets the format id
``ryade-scene-grid-1``, the extra shape/material/functor classes and the top-level ``interactions`` array.
With ``grid=False`` (the default) the output is exactly golden/FORMAT.md.
"""

import gzip
import hashlib
import math
import os
import struct
import sys

from yade import O  # noqa: F401  (the YADE scene singleton)

FORMAT_ID = 'ryade-scene-1'
GRID_FORMAT_ID = 'ryade-scene-grid-1'
SOURCE = 'yade 2023.02a'

BODY_HEADER = ('step,id,pos_x,pos_y,pos_z,vel_x,vel_y,vel_z,angVel_x,angVel_y,angVel_z,'
               'ori_w,ori_x,ori_y,ori_z,f_x,f_y,f_z,t_x,t_y,t_z')
INTR_HEADER = ('step,ord,id1,id2,normal_x,normal_y,normal_z,pen,cp_x,cp_y,cp_z,'
               'shearInc_x,shearInc_y,shearInc_z,fn_x,fn_y,fn_z,fs_x,fs_y,fs_z,kn,ks')
BODY_FMT = '%d,%d,' + ','.join(['%.17g'] * 19) + '\n'
INTR_FMT = '%d,%d,%d,%d,' + ','.join(['%.17g'] * 18) + '\n'
INTR6D_HEADER = ('step,ord,id1,id2,twist,bending_x,bending_y,bending_z,mtw_x,mtw_y,mtw_z,mb_x,mb_y,mb_z,'
                 'unp,cohesionBroken,relPos,isDuplicate,trueInt')

# grid extension (golden/FORMAT_GRID.md): geometry / physics classes that may appear in interactions
GEOM6D_CLASSES = ('ScGeom6D', 'GridNodeGeom6D', 'ScGridCoGeom')
GEOM_CLASSES = ('ScGeom', 'GridCoGridCoGeom') + GEOM6D_CLASSES
PHYS_CLASSES = ('FrictPhys', 'CohFrictPhys', 'ViscElPhys')

DOF_BITS = {'x': 1, 'y': 2, 'z': 4, 'X': 8, 'Y': 16, 'Z': 32}


class UnsupportedScene(RuntimeError):
    """The scene holds something golden/FORMAT.md cannot describe."""


# ----------------------------------------------------------------------------------------
# paths

def script_path():
    """Absolute path of the running YADE script (``__file__`` is /usr/bin/yade under -x)."""
    return os.path.abspath(sys.argv[0])


def repo_root():
    """Repository root: scripts live in <root>/yade_ref/<kind>/<script>.py."""
    return os.path.normpath(os.path.join(os.path.dirname(script_path()), '..', '..'))


def output_dir(default_sub):
    """First script argument if given, else <root>/<default_sub> (e.g. 'golden/micro')."""
    if len(sys.argv) > 1 and sys.argv[1]:
        d = os.path.abspath(sys.argv[1])
    else:
        d = os.path.join(repo_root(), default_sub)
    os.makedirs(d, exist_ok=True)
    return d


def script_rel():
    return os.path.relpath(script_path(), repo_root()).replace(os.sep, '/')


# ----------------------------------------------------------------------------------------
# small helpers

def _cls(o):
    return type(o).__name__


def _v3(v):
    return [float(v[0]), float(v[1]), float(v[2])]


def _quat_wxyz(q):
    # YADE Python: q[0..2] = x, y, z and q[3] = w
    return [float(q[3]), float(q[0]), float(q[1]), float(q[2])]


def dof_bits(s):
    bits = 0
    for ch in s:
        if ch not in DOF_BITS:
            raise UnsupportedScene('unknown blockedDOFs letter %r in %r' % (ch, s))
        bits |= DOF_BITS[ch]
    return bits


def _require(cond, what):
    if not cond:
        raise UnsupportedScene(what)


def _is_zero_m3(m):
    return all(m[i][j] == 0 for i in range(3) for j in range(3))


# ----------------------------------------------------------------------------------------
# scene introspection

def _shape(b, grid=False):
    s = b.shape
    c = _cls(s)
    if grid and c == 'GridNode':
        _require(len(s.getPFacets()) == 0, 'body %d: GridNode with PFacets is not supported' % b.id)
        return {'class': c, 'radius': float(s.radius), 'connections': [int(x.id) for x in s.getConnections()]}
    if grid and c == 'GridConnection':
        _require(len(s.getPFacets()) == 0, 'body %d: GridConnection with PFacets is not supported' % b.id)
        _require(s.node1 is not None and s.node2 is not None, 'body %d: GridConnection without nodes' % b.id)
        cd = s.cellDist
        return {'class': c, 'radius': float(s.radius), 'node1': int(s.node1.id), 'node2': int(s.node2.id),
                'periodic': bool(s.periodic), 'cellDist': [int(cd[0]), int(cd[1]), int(cd[2])]}
    if c == 'Sphere':
        return {'class': 'Sphere', 'radius': float(s.radius)}
    if c == 'Facet':
        return {'class': 'Facet', 'vertices': [_v3(v) for v in s.vertices]}
    if c == 'Wall':
        return {'class': 'Wall', 'axis': int(s.axis), 'sense': int(s.sense)}
    if c == 'Box':
        return {'class': 'Box', 'extents': _v3(s.extents)}
    raise UnsupportedScene('body %d: shape class %s is not supported by golden/FORMAT.md' % (b.id, c))


def _material(b, grid=False):
    m = b.material
    c = _cls(m)
    if grid and c == 'CohFrictMat':
        return {'id': int(m.id), 'class': c, 'young': float(m.young), 'poisson': float(m.poisson),
                'frictionAngle': float(m.frictionAngle), 'density': float(m.density),
                'isCohesive': bool(m.isCohesive), 'alphaKr': float(m.alphaKr), 'alphaKtw': float(m.alphaKtw),
                'etaRoll': float(m.etaRoll), 'etaTwist': float(m.etaTwist),
                'normalCohesion': float(m.normalCohesion), 'shearCohesion': float(m.shearCohesion),
                'fragile': bool(m.fragile), 'momentRotationLaw': bool(m.momentRotationLaw), 'label': str(m.label)}
    if c == 'ViscElMat':
        _require(not m.lubrication, 'body %d: ViscElMat.lubrication=True is not supported' % b.id)
        d = {'id': int(m.id), 'class': c, 'young': float(m.young), 'poisson': float(m.poisson),
             'frictionAngle': float(m.frictionAngle), 'density': float(m.density), 'label': str(m.label)}
        for a in ('tc', 'en', 'et', 'kn', 'cn', 'ks', 'cs'):
            d[a] = _num_or_null(getattr(m, a))
        d['mR'], d['mRtype'] = float(m.mR), int(m.mRtype)
        return d
    if c == 'BubbleMat':
        return {'id': int(m.id), 'class': c, 'density': float(m.density), 'label': str(m.label),
                'surfaceTension': float(m.surfaceTension)}
    if c == 'CpmMat':
        d = {'id': int(m.id), 'class': c, 'young': float(m.young), 'poisson': float(m.poisson),
             'frictionAngle': float(m.frictionAngle), 'density': float(m.density), 'label': str(m.label),
             'neverDamage': bool(m.neverDamage), 'damLaw': int(m.damLaw)}
        for a in ('sigmaT', 'epsCrackOnset', 'relDuctility', 'equivStrainShearContrib', 'dmgTau', 'dmgRateExp', 'plTau',
                  'plRateExp', 'isoPrestress'):
            d[a] = _num_or_null(getattr(m, a))
        return d
    if c == 'LudingMat':
        d = {'id': int(m.id), 'class': c, 'density': float(m.density), 'label': str(m.label)}
        for a in ('k1', 'kp', 'kc', 'ks', 'PhiF', 'G0', 'frictionAngle'):
            d[a] = _num_or_null(getattr(m, a))
        return d
    if c != 'FrictMat':
        raise UnsupportedScene('body %d: material class %s is not supported (only FrictMat)' % (b.id, c))
    return {'id': int(m.id), 'class': 'FrictMat', 'young': float(m.young), 'poisson': float(m.poisson),
            'frictionAngle': float(m.frictionAngle), 'density': float(m.density), 'label': str(m.label)}


def _clump_body(b):
    """A clump (golden/FORMAT.md, clump extension): members with their pose in the clump frame as
    YADE stores it (Clump.members), no material, the aspherical flag and the angular momentum."""
    st = b.state
    _require(_cls(st) == 'State', 'body %d: state class %s is not supported' % (b.id, _cls(st)))
    mem = b.shape.members
    members = [{'id': int(i), 'relPos': _v3(mem[i][0]), 'relOri': _quat_wxyz(mem[i][1])} for i in sorted(mem.keys())]
    return {'id': int(b.id), 'shape': {'class': 'Clump', 'members': members}, 'material': None,
            'mask': int(b.mask), 'bounded': bool(b.bounded),
            'pos': _v3(st.pos), 'vel': _v3(st.vel), 'angVel': _v3(st.angVel), 'ori': _quat_wxyz(st.ori),
            'mass': float(st.mass), 'inertia': _v3(st.inertia), 'blockedDOFs': dof_bits(st.blockedDOFs),
            'isDamped': bool(st.isDamped), 'clumpId': int(b.clumpId), 'aspherical': bool(b.aspherical),
            'angMom': _v3(st.angMom)}


def _body(b, grid=False):
    _require(b is not None, 'erased body (None) in O.bodies: ids must be dense')
    if b.isClump:
        _require(not grid, 'body %d: clumps are not supported in grid scenes' % b.id)
        return _clump_body(b)
    st = b.state
    # a CpmMat body gets a CpmState (post-processing values only: not recorded)
    _require(_cls(st) == 'State' or (_cls(st) == 'CpmState' and _cls(b.material) == 'CpmMat'),
             'body %d: state class %s is not supported' % (b.id, _cls(st)))
    shape = _shape(b, grid)
    if shape['class'] in ('Sphere', 'GridNode', 'GridConnection'):
        _require(not b.aspherical, 'body %d: aspherical %s' % (b.id, shape['class'].lower()))
    d = {'id': int(b.id), 'shape': shape, 'material': _material(b, grid),
         'mask': int(b.mask), 'bounded': bool(b.bounded),
         'pos': _v3(st.pos), 'vel': _v3(st.vel), 'angVel': _v3(st.angVel), 'ori': _quat_wxyz(st.ori),
         'mass': float(st.mass), 'inertia': _v3(st.inertia), 'blockedDOFs': dof_bits(st.blockedDOFs),
         'isDamped': bool(st.isDamped)}
    if grid:
        d['aspherical'] = bool(b.aspherical)
    if b.isClumpMember:
        _require(not grid, 'body %d: clump members are not supported in grid scenes' % b.id)
        d['clumpId'] = int(b.clumpId)
    return d


def _bound_functor(f, grid=False):
    c = _cls(f)
    if grid and c == 'Bo1_GridConnection_Aabb':
        return {'class': c, 'aabbEnlargeFactor': float(f.aabbEnlargeFactor)}
    if c == 'Bo1_Sphere_Aabb':
        return {'class': c, 'aabbEnlargeFactor': float(f.aabbEnlargeFactor)}
    if c in ('Bo1_Facet_Aabb', 'Bo1_Wall_Aabb', 'Bo1_Box_Aabb'):
        return {'class': c}
    raise UnsupportedScene('bound functor class %s is not supported' % c)


def _geom_functor(f, grid=False):
    c = _cls(f)
    if grid and c in ('Ig2_GridNode_GridNode_GridNodeGeom6D', 'Ig2_Sphere_Sphere_ScGeom6D'):
        return {'class': c, 'interactionDetectionFactor': float(f.interactionDetectionFactor),
                'avoidGranularRatcheting': bool(f.avoidGranularRatcheting),
                'updateRotations': bool(f.updateRotations), 'creep': bool(f.creep)}
    if grid and c == 'Ig2_Sphere_GridConnection_ScGridCoGeom':
        return {'class': c, 'interactionDetectionFactor': float(f.interactionDetectionFactor)}
    if grid and c == 'Ig2_GridConnection_GridConnection_GridCoGridCoGeom':
        return {'class': c}
    if c == 'Ig2_Sphere_Sphere_ScGeom':
        return {'class': c, 'interactionDetectionFactor': float(f.interactionDetectionFactor),
                'avoidGranularRatcheting': bool(f.avoidGranularRatcheting)}
    if c == 'Ig2_Facet_Sphere_ScGeom':
        d = {'class': c, 'shrinkFactor': float(f.shrinkFactor)}
        if f.hertzian:
            d['hertzian'] = True
        return d
    if c == 'Ig2_Wall_Sphere_ScGeom':
        d = {'class': c, 'noRatch': bool(f.noRatch)}
        if f.hertzian:
            d['hertzian'] = True
        return d
    if c == 'Ig2_Box_Sphere_ScGeom' or (grid and c == 'Ig2_Box_Sphere_ScGeom6D'):
        return {'class': c, 'interactionDetectionFactor': float(f.interactionDetectionFactor)}
    raise UnsupportedScene('geometry functor class %s is not supported' % c)


def _match_maker(m):
    """A MatchMaker as golden/FORMAT.md describes it."""
    return {'matches': [[int(x[0]), int(x[1]), float(x[2])] for x in m.matches], 'algo': str(m.algo),
            'val': 'nan' if m.val != m.val else float(m.val)}


def _phys_functor(f, grid=False):
    c = _cls(f)
    if grid and c == 'Ip2_CohFrictMat_CohFrictMat_CohFrictPhys':
        for a in ('normalCohesion', 'shearCohesion', 'frictAngle'):
            _require(getattr(f, a) is None, '%s.%s (MatchMaker) is not supported' % (c, a))
        return {'class': c, 'setCohesionNow': bool(f.setCohesionNow),
                'setCohesionOnNewContacts': bool(f.setCohesionOnNewContacts)}
    if c == 'Ip2_ViscElMat_ViscElMat_ViscElPhys':
        d = {'class': c}
        for a in ('tc', 'en', 'et', 'frictAngle'):
            m = getattr(f, a)
            if m is not None:
                d[a] = _match_maker(m)
        return d
    if c == 'Ip2_BubbleMat_BubbleMat_BubblePhys':
        return {'class': c}
    if c == 'Ip2_LudingMat_LudingMat_LudingPhys':
        return {'class': c}
    if c == 'Ip2_CpmMat_CpmMat_CpmPhys':
        _require(f.E is None, '%s.E (MatchMaker) is not supported' % c)
        return {'class': c, 'cohesiveThresholdIter': int(f.cohesiveThresholdIter)}
    if c == 'Ip2_FrictMat_CpmMat_FrictPhys':
        _require(f.frictAngle is None, '%s.frictAngle (MatchMaker) is not supported' % c)
        return {'class': c}
    if c == 'Ip2_FrictMat_FrictMat_MindlinPhys':
        d = {'class': c, 'gamma': float(f.gamma), 'eta': float(f.eta), 'krot': float(f.krot),
             'ktwist': float(f.ktwist)}
        for a in ('en', 'es', 'betan', 'betas', 'frictAngle'):
            m = getattr(f, a)
            if m is None:
                if a != 'frictAngle':
                    d[a] = None
            elif len(m.matches) == 0 and m.algo == 'val':
                d[a] = float(m.val)  # a number given for it
            else:
                d[a] = _match_maker(m)
        return d
    if c == 'Ip2_FrictMat_FrictMat_FrictPhys':
        for a in ('kn', 'ks', 'frictAngle'):
            _require(getattr(f, a) is None, 'Ip2_FrictMat_FrictMat_FrictPhys.%s (MatchMaker) is not supported' % a)
        return {'class': c}
    raise UnsupportedScene('physics functor class %s is not supported' % c)


def _law_functor(f, grid=False):
    c = _cls(f)
    if grid and c == 'Law2_ScGeom6D_CohFrictPhys_CohesionMoment':
        return {'class': c, 'neverErase': bool(f.neverErase), 'always_use_moment_law': bool(f.always_use_moment_law),
                'shear_creep': bool(f.shear_creep), 'twist_creep': bool(f.twist_creep),
                'traceEnergy': bool(f.traceEnergy), 'useIncrementalForm': bool(f.useIncrementalForm),
                'creep_viscosity': float(f.creep_viscosity)}
    if grid and c == 'Law2_ScGridCoGeom_FrictPhys_CundallStrack':
        return {'class': c, 'neverErase': bool(f.neverErase)}
    if grid and c == 'Law2_GridCoGridCoGeom_FrictPhys_CundallStrack':
        return {'class': c, 'neverErase': bool(f.neverErase), 'sphericalBodies': bool(f.sphericalBodies),
                'traceEnergy': bool(f.traceEnergy)}
    if c == 'Law2_ScGeom_FrictPhys_CundallStrack':
        return {'class': c, 'neverErase': bool(f.neverErase), 'sphericalBodies': bool(f.sphericalBodies)}
    if c == 'Law2_ScGeom_ViscElPhys_Basic':
        return {'class': c}
    if c == 'Law2_ScGeom_BubblePhys_Bubble':
        return {'class': c, 'pctMaxForce': float(f.pctMaxForce), 'surfaceTension': float(f.surfaceTension)}
    if c == 'Law2_ScGeom_LudingPhys_Basic':
        return {'class': c}
    if c == 'Law2_ScGeom_CpmPhys_Cpm':
        return {'class': c, 'omegaThreshold': float(f.omegaThreshold), 'epsSoft': float(f.epsSoft),
                'relKnSoft': float(f.relKnSoft), 'yieldSurfType': int(f.yieldSurfType),
                'yieldLogSpeed': float(f.yieldLogSpeed), 'yieldEllipseShift': _num_or_null(f.yieldEllipseShift)}
    if c == 'Law2_ScGeom_MindlinPhys_Mindlin':
        _require(not f.calcEnergy, '%s.calcEnergy is not supported' % c)
        return {'class': c, 'includeAdhesion': bool(f.includeAdhesion), 'includeMoment': bool(f.includeMoment),
                'neverErase': bool(f.neverErase)}
    raise UnsupportedScene('law functor class %s is not supported' % c)


def _engine(e, grid=False):
    c = _cls(e)
    _require(not e.dead, 'engine %s is dead=True (not supported)' % c)
    if c == 'ForceResetter':
        return {'class': c}
    if c == 'InsertionSortCollider':
        if not grid:
            _require(e.avoidSelfInteractionMask == 0, 'InsertionSortCollider.avoidSelfInteractionMask != 0')
        _require(not e.smartInsertErase, 'InsertionSortCollider.smartInsertErase=True is not supported')
        _require(not e.keepListsShort, 'InsertionSortCollider.keepListsShort=True is not supported')
        d = {'class': c, 'bounds': [_bound_functor(f, grid) for f in e.boundDispatcher.functors],
             'verletDist': float(e.verletDist), 'allowBiggerThanPeriod': bool(e.allowBiggerThanPeriod),
             'targetInterv': int(e.targetInterv), 'minSweepDistFactor': float(e.minSweepDistFactor),
             'sortAxis': int(e.sortAxis), 'sortThenCollide': bool(e.sortThenCollide)}
        if grid:
            d['avoidSelfInteractionMask'] = int(e.avoidSelfInteractionMask)
        return d
    if c == 'InteractionLoop':
        _require(len(e.callbacks) == 0, 'InteractionLoop.callbacks are not supported')
        _require(not e.loopOnSortedInteractions, 'InteractionLoop.loopOnSortedInteractions=True is not supported')
        return {'class': c,
                'geom': [_geom_functor(f, grid) for f in e.geomDispatcher.functors],
                'phys': [_phys_functor(f, grid) for f in e.physDispatcher.functors],
                'law': [_law_functor(f, grid) for f in e.lawDispatcher.functors]}
    if c == 'NewtonIntegrator':
        _require(not e.densityScaling, 'NewtonIntegrator.densityScaling=True is not supported')
        _require(e.mask == -1, 'NewtonIntegrator.mask != -1 is not supported')
        _require(_is_zero_m3(e.prevVelGrad), 'NewtonIntegrator.prevVelGrad != 0 is not supported')
        _require(e.exactAsphericalRot, 'NewtonIntegrator.exactAsphericalRot=False is not supported')
        return {'class': c, 'damping': float(e.damping), 'gravity': _v3(e.gravity),
                'dampGravity': bool(e.dampGravity)}
    if c == 'TranslationEngine':
        return {'class': c, 'ids': [int(i) for i in e.ids], 'velocity': float(e.velocity),
                'translationAxis': _v3(e.translationAxis)}
    if c == 'RotationEngine':
        return {'class': c, 'ids': [int(i) for i in e.ids], 'angularVelocity': float(e.angularVelocity),
                'rotationAxis': _v3(e.rotationAxis), 'rotateAroundZero': bool(e.rotateAroundZero),
                'zeroPoint': _v3(e.zeroPoint)}
    if c == 'GlobalStiffnessTimeStepper':
        for k in ('densityScaling', 'viscEl'):
            _require(not getattr(e, k), 'GlobalStiffnessTimeStepper.%s is not supported' % k)
        return {'class': c, 'active': bool(e.active), 'timeStepUpdateInterval': int(e.timeStepUpdateInterval),
                'defaultDt': float(e.defaultDt), 'maxDt': float(e.maxDt),
                'timestepSafetyCoefficient': float(e.timestepSafetyCoefficient)}
    if c in ('TriaxialStressController', 'TriaxialCompressionEngine', 'ThreeDTriaxialEngine'):
        d = {'class': c}
        if c == 'ThreeDTriaxialEngine':
            for k in ('strainRate1', 'strainRate2', 'strainRate3', 'currentStrainRate1', 'currentStrainRate2',
                      'currentStrainRate3', 'UnbalancedForce', 'frictionAngleDegree'):
                d[k] = float(getattr(e, k))
            for k in ('updateFrictionAngle', 'stressControl_1', 'stressControl_2', 'stressControl_3'):
                d[k] = bool(getattr(e, k))
        if c == 'TriaxialCompressionEngine':
            _require(e.noFiles, 'TriaxialCompressionEngine.noFiles=False is not supported (snapshot files)')
            for k in ('strainRate', 'currentStrainRate', 'UnbalancedForce', 'StabilityCriterion', 'sigmaIsoCompaction',
                      'previousSigmaIso', 'sigmaLateralConfinement', 'frictionAngleDegree', 'epsilonMax', 'fixedPorosity',
                      'maxStress', 'sigma_iso'):
                d[k] = float(getattr(e, k))
            for k in ('autoCompressionActivation', 'autoUnload', 'autoStopSimulation', 'noFiles', 'isAxisymetric'):
                d[k] = bool(getattr(e, k))
            d['fixedPoroCompaction'] = bool(e.fixedPoroCompaction)
            for k in ('testEquilibriumInterval', 'currentState', 'previousState'):
                d[k] = int(getattr(e, k))
            d['translationAxis'] = _v3(e.translationAxis)
        for k in ('stiffnessUpdateInterval', 'radiusControlInterval', 'computeStressStrainInterval', 'stressMask'):
            d[k] = int(getattr(e, k))
        for k in ('internalCompaction', 'updatePorosity'):
            d[k] = bool(getattr(e, k))
        for k in ('stressDamping', 'strainDamping', 'thickness', 'height', 'width', 'depth', 'height0', 'width0',
                  'depth0', 'goal1', 'goal2', 'goal3', 'maxMultiplier', 'finalMaxMultiplier', 'max_vel',
                  'previousStress', 'previousMultiplier', 'meanStress', 'volumetricStrain', 'externalWork'):
            d[k] = float(getattr(e, k))
        for w in ('left', 'right', 'bottom', 'top', 'back', 'front'):
            d['wall_%s_id' % w] = int(getattr(e, 'wall_%s_id' % w))
            d['wall_%s_activated' % w] = bool(getattr(e, 'wall_%s_activated' % w))
        return d
    if c == 'HydroForceEngine':
        _require(not e.lubrication, 'HydroForceEngine.lubrication=True is not supported')
        d = {'class': c, 'ids': [int(i) for i in e.ids], 'gravity': _v3(e.gravity), 'nCell': int(e.nCell)}
        for k in ('densFluid', 'viscoDyn', 'zRef', 'deltaZ', 'expoRZ', 'Cl'):
            d[k] = float(getattr(e, k))
        for k in ('lift', 'convAccOption', 'steadyFlow'):
            d[k] = bool(getattr(e, k))
        for k in ('vxFluid', 'phiPart', 'convAcc', 'vFluctX', 'vFluctY', 'vFluctZ'):
            d[k] = [float(x) for x in getattr(e, k)]
        return d
    if c == 'ForceEngine':
        return {'class': c, 'ids': [int(i) for i in e.ids], 'force': _v3(e.force)}
    if c == 'HarmonicForceEngine':
        return {'class': c, 'ids': [int(i) for i in e.ids], 'A': _v3(e.A), 'f': _v3(e.f), 'fi': _v3(e.fi)}
    if c == 'InterpolatingHelixEngine':
        return {'class': c, 'ids': [int(i) for i in e.ids], 'angularVelocity': float(e.angularVelocity),
                'rotationAxis': _v3(e.rotationAxis), 'rotateAroundZero': bool(e.rotateAroundZero),
                'zeroPoint': _v3(e.zeroPoint), 'linearVelocity': float(e.linearVelocity),
                'angleTurned': float(e.angleTurned), 'times': [float(x) for x in e.times],
                'angularVelocities': [float(x) for x in e.angularVelocities], 'wrap': bool(e.wrap),
                'slope': float(e.slope)}
    if c == 'BicyclePedalEngine':
        return {'class': c, 'ids': [int(i) for i in e.ids], 'angularVelocity': float(e.angularVelocity),
                'rotationAxis': _v3(e.rotationAxis), 'radius': float(e.radius), 'fi': float(e.fi)}
    if c == 'InterpolatingDirectedForceEngine':
        return {'class': c, 'ids': [int(i) for i in e.ids], 'force': _v3(e.force),
                'times': [float(x) for x in e.times], 'magnitudes': [float(x) for x in e.magnitudes],
                'direction': _v3(e.direction), 'wrap': bool(e.wrap)}
    if c == 'HelixEngine':
        return {'class': c, 'ids': [int(i) for i in e.ids], 'angularVelocity': float(e.angularVelocity),
                'rotationAxis': _v3(e.rotationAxis), 'rotateAroundZero': bool(e.rotateAroundZero),
                'zeroPoint': _v3(e.zeroPoint), 'linearVelocity': float(e.linearVelocity),
                'angleTurned': float(e.angleTurned)}
    if c == 'CombinedKinematicEngine':
        comb = []
        for m in e.comb:
            dead = bool(m.dead)
            m.dead = False  # _engine refuses dead engines; a member's dead flag is recorded here
            d = _engine(m, grid)
            m.dead = dead
            d['dead'] = dead
            comb.append(d)
        return {'class': c, 'ids': [int(i) for i in e.ids], 'comb': comb}
    if c == 'ServoPIDController':
        return {'class': c, 'ids': [int(i) for i in e.ids], 'axis': _v3(e.axis), 'target': float(e.target),
                'kP': float(e.kP), 'kI': float(e.kI), 'kD': float(e.kD), 'iTerm': float(e.iTerm),
                'curVel': float(e.curVel), 'errorCur': float(e.errorCur), 'errorPrev': float(e.errorPrev),
                'maxVelocity': float(e.maxVelocity), 'iterPeriod': int(e.iterPeriod),
                'iterPrevStart': int(e.iterPrevStart)}
    if c == 'PeriTriaxController':
        return _peri_triax_dict(e)
    raise UnsupportedScene('engine class %s is not supported by golden/FORMAT.md' % c)


# PeriTriaxController attributes a doneHook may set (replayed by ryade in this order of names); any other
# change a hook makes is refused (_run_hook)
PERI_SETTABLE = ('goal', 'stressMask', 'maxStrainRate', 'maxUnbalanced', 'absStressTol', 'relStressTol',
                 'growDamping', 'globUpdate', 'doneHook', 'dynCell', 'mass', 'dead')
PERI_STATE = ('maxBodySpan', 'stressTensor', 'stress', 'strain', 'strainRate', 'stiff', 'currUnbalanced',
              'prevGrow', 'externalWork')


def _num_or_null(x):
    x = float(x)
    return None if x != x else x


def _m3(m):
    return [[float(m[i][j]) for j in range(3)] for i in range(3)]


def _peri_value(k, v):
    if k in ('goal', 'maxStrainRate', 'maxBodySpan', 'stress', 'strain', 'strainRate', 'stiff', 'prevGrow'):
        return _v3(v)
    if k == 'stressTensor':
        return _m3(v)
    if k in ('stressMask', 'globUpdate'):
        return int(v)
    if k in ('dynCell', 'dead'):
        return bool(v)
    if k == 'doneHook':
        return str(v)
    return _num_or_null(v)


def _peri_triax_dict(e):
    d = {'class': 'PeriTriaxController'}
    for k in PERI_SETTABLE + PERI_STATE:
        if k == 'dead':
            continue
        d[k] = _peri_value(k, getattr(e, k))
    # the hook as the script set it (the recorder wraps it while recording, see _wrap_hooks)
    d['doneHook'] = _HOOK_ORIG.get(id(e), d['doneHook'])
    return d


def _geom_dict(g):
    c = _cls(g)
    if c not in GEOM_CLASSES:
        raise UnsupportedScene('interaction geometry class %s is not supported by golden/FORMAT_GRID.md' % c)
    d = {'class': c, 'normal': _v3(g.normal), 'penetrationDepth': float(g.penetrationDepth),
         'contactPoint': _v3(g.contactPoint), 'shearInc': _v3(g.shearInc),
         'refR1': float(g.refR1), 'refR2': float(g.refR2)}
    if c in GEOM6D_CLASSES:
        d['initialOrientation1'] = _quat_wxyz(g.initialOrientation1)
        d['initialOrientation2'] = _quat_wxyz(g.initialOrientation2)
        d['twistCreep'] = _quat_wxyz(g.twistCreep)
        d['twist'] = float(g.twist)
        d['bending'] = _v3(g.bending)
    if c == 'GridNodeGeom6D':
        d['connectionBody'] = -1 if g.connectionBody is None else int(g.connectionBody.id)
    if c == 'ScGridCoGeom':
        d['isDuplicate'] = int(g.isDuplicate)
        d['trueInt'] = int(g.trueInt)
        d['id3'] = int(g.id3)
        d['id4'] = int(g.id4)
        d['id5'] = int(g.id5)
        d['weight'] = _v3(g.weight)
        d['relPos'] = float(g.relPos)
    if c == 'GridCoGridCoGeom':
        d['relPos1'] = float(g.relPos1)
        d['relPos2'] = float(g.relPos2)
    return d


def _phys_dict(p):
    c = _cls(p)
    if c not in PHYS_CLASSES:
        raise UnsupportedScene('interaction physics class %s is not supported by golden/FORMAT_GRID.md' % c)
    d = {'class': c, 'kn': float(p.kn), 'ks': float(p.ks)}
    if c == 'CohFrictPhys':
        d['kr'] = float(p.kr)
        d['ktw'] = float(p.ktw)
    d['tangensOfFrictionAngle'] = float(p.tangensOfFrictionAngle)
    d['normalForce'] = _v3(p.normalForce)
    d['shearForce'] = _v3(p.shearForce)
    if c == 'CohFrictPhys':
        for a in ('cohesionBroken', 'fragile', 'initCohesion'):
            d[a] = bool(getattr(p, a))
        for a in ('normalAdhesion', 'shearAdhesion', 'unp', 'unpMax'):
            d[a] = float(getattr(p, a))
        d['momentRotationLaw'] = bool(p.momentRotationLaw)
        d['maxRollPl'] = float(p.maxRollPl)
        d['maxTwistPl'] = float(p.maxTwistPl)
        d['moment_twist'] = _v3(p.moment_twist)
        d['moment_bending'] = _v3(p.moment_bending)
        d['cohesionDisablesFriction'] = bool(p.cohesionDisablesFriction)
        d['creep_viscosity'] = float(p.creep_viscosity)
    if c == 'ViscElPhys':
        for a in ('cn', 'cs', 'Fn', 'Fv', 'mR'):
            d[a] = float(getattr(p, a))
        d['mRtype'] = int(p.mRtype)
    return d


def _interaction_dict(I):
    cd = I.cellDist
    d = {'id1': int(I.id1), 'id2': int(I.id2), 'isReal': bool(I.isReal),
         'cellDist': [int(cd[0]), int(cd[1]), int(cd[2])],
         'iterMadeReal': int(I.iterMadeReal), 'iterBorn': int(I.iterBorn)}
    d['geom'] = None if I.geom is None else _geom_dict(I.geom)
    d['phys'] = None if I.phys is None else _phys_dict(I.phys)
    return d


def scene_dict(steps, script=None, grid=False):
    """The scene as YADE holds it now (call before the first step)."""
    d = {'format': GRID_FORMAT_ID if grid else FORMAT_ID, 'source': SOURCE,
         'script': script if script is not None else script_rel(),
         'steps': int(steps), 'dt': float(O.dt), 'periodic': bool(O.periodic)}
    if grid:
        _require(not O.trackEnergy, 'O.trackEnergy=True is not supported')
    if O.periodic:
        c = O.cell
        _require(_is_zero_m3(c.velGrad) and _is_zero_m3(c.nextVelGrad) and _is_zero_m3(c.prevVelGrad),
                 'periodic cell with velGrad != 0 is not supported')
        t = c.trsf
        _require(all(t[i][j] == (1 if i == j else 0) for i in range(3) for j in range(3)),
                 'periodic cell with trsf != identity is not supported')
        _require(c.homoDeform == 2, 'Cell.homoDeform != 2 is not supported')
        h = c.hSize
        d['cell_hsize'] = [[float(h[i][j]) for j in range(3)] for i in range(3)]
    bodies = [_body(b, grid) for b in O.bodies]
    for i, b in enumerate(bodies):
        _require(b['id'] == i, 'body ids are not dense 0..n-1')
    d['bodies'] = bodies
    d['engines'] = [_engine(e, grid) for e in O.engines]
    if grid:
        # every interaction in container order (O.interactions.all(False)), real and potential
        d['interactions'] = [_interaction_dict(I) for I in O.interactions.all(False)]
    return d


# ----------------------------------------------------------------------------------------
# JSON writer: floats as '%.17g' (FORMAT.md), one body / engine per line

def _js(v):
    if v is None:
        return 'null'
    if isinstance(v, bool):
        return 'true' if v else 'false'
    if isinstance(v, int):
        return '%d' % v
    if isinstance(v, float):
        if not math.isfinite(v):
            raise UnsupportedScene('non-finite float %r cannot be written to JSON' % v)
        return '%.17g' % v
    if isinstance(v, str):
        import json
        return json.dumps(v)
    if isinstance(v, (list, tuple)):
        return '[' + ', '.join(_js(x) for x in v) + ']'
    if isinstance(v, dict):
        return '{' + ', '.join('%s: %s' % (_js(str(k)), _js(x)) for k, x in v.items()) + '}'
    raise TypeError('cannot serialise %r' % (v,))


def scene_json(d):
    out = ['{']
    keys = list(d.keys())
    for k in keys:
        v = d[k]
        last = (k == keys[-1])
        if k in ('bodies', 'engines', 'interactions'):
            out.append('  %s: [' % _js(k))
            for i, x in enumerate(v):
                out.append('    ' + _js(x) + (',' if i + 1 < len(v) else ''))
            out.append('  ]' + ('' if last else ','))
        else:
            out.append('  %s: %s%s' % (_js(k), _js(v), '' if last else ','))
    out.append('}')
    return '\n'.join(out) + '\n'


# ----------------------------------------------------------------------------------------
# outputs

class _AtomicGz(object):
    """gzip text writer with mtime=0 and an empty file name (reproducible bytes)."""

    def __init__(self, path):
        self.path = path
        self.tmp = path + '.tmp%d' % os.getpid()
        self.raw = open(self.tmp, 'wb')
        self.gz = gzip.GzipFile(filename='', mode='wb', fileobj=self.raw, mtime=0, compresslevel=9)
        self.buf = []

    def write(self, s):
        self.buf.append(s)
        if len(self.buf) >= 4096:
            self.flush()

    def flush(self):
        if self.buf:
            self.gz.write(''.join(self.buf).encode('ascii'))
            self.buf = []

    def close_tmp(self):
        self.flush()
        self.gz.close()
        self.raw.flush()
        os.fsync(self.raw.fileno())
        self.raw.close()

    def commit(self):
        os.replace(self.tmp, self.path)

    def abort(self):
        try:
            self.gz.close()
            self.raw.close()
        except Exception:
            pass
        if os.path.exists(self.tmp):
            os.remove(self.tmp)


class _AtomicText(object):
    def __init__(self, path):
        self.path = path
        self.tmp = path + '.tmp%d' % os.getpid()
        self.f = open(self.tmp, 'w', encoding='ascii', newline='\n')

    def write(self, s):
        self.f.write(s)

    def close_tmp(self):
        self.f.flush()
        os.fsync(self.f.fileno())
        self.f.close()

    def commit(self):
        os.replace(self.tmp, self.path)

    def abort(self):
        try:
            self.f.close()
        except Exception:
            pass
        if os.path.exists(self.tmp):
            os.remove(self.tmp)


def _body_values(b, forces):
    s = b.state
    p = s.pos
    v = s.vel
    w = s.angVel
    q = s.ori
    f = forces.f(b.id)
    t = forces.t(b.id)
    return (p[0], p[1], p[2], v[0], v[1], v[2], w[0], w[1], w[2], q[3], q[0], q[1], q[2],
            f[0], f[1], f[2], t[0], t[1], t[2])


def _write_bodies(out, step, vals):
    for i, v in enumerate(vals):
        out.write(BODY_FMT % ((step, i) + v))


def _real_intrs():
    # container order (O.interactions.all(False) is the raw container; keep the real ones)
    return [i for i in O.interactions.all(False) if i.isReal]


def _write_intrs(out, step, intrs):
    for k, I in enumerate(intrs):
        g = I.geom
        ph = I.phys
        n = g.normal
        cp = g.contactPoint
        si = g.shearInc
        fn = ph.normalForce
        # a physics without shear force or stiffnesses (BubblePhys, an IPhys): zeros, as ryade keeps them
        fs = getattr(ph, 'shearForce', (0.0, 0.0, 0.0))
        out.write(INTR_FMT % (step, k, I.id1, I.id2, n[0], n[1], n[2], g.penetrationDepth,
                              cp[0], cp[1], cp[2], si[0], si[1], si[2],
                              fn[0], fn[1], fn[2], fs[0], fs[1], fs[2], getattr(ph, 'kn', 0.0), getattr(ph, 'ks', 0.0)))


def _write_intrs6d(out, step, intrs):
    for k, I in enumerate(intrs):
        g = I.geom
        ph = I.phys
        gc = _cls(g)
        pc = _cls(ph)
        _require(gc in GEOM_CLASSES, 'step %d: interaction %d+%d: geometry class %s is not supported'
                 % (step, I.id1, I.id2, gc))
        _require(pc in PHYS_CLASSES, 'step %d: interaction %d+%d: physics class %s is not supported'
                 % (step, I.id1, I.id2, pc))
        f = ['%d' % step, '%d' % k, '%d' % I.id1, '%d' % I.id2]
        if gc in GEOM6D_CLASSES:
            bb = g.bending
            f += ['%.17g' % g.twist, '%.17g' % bb[0], '%.17g' % bb[1], '%.17g' % bb[2]]
        else:
            f += ['nan'] * 4
        if pc == 'CohFrictPhys':
            mt = ph.moment_twist
            mb = ph.moment_bending
            f += ['%.17g' % x for x in (mt[0], mt[1], mt[2], mb[0], mb[1], mb[2], ph.unp)]
            f.append('%d' % (1 if ph.cohesionBroken else 0))
        else:
            f += ['nan'] * 8
        if gc == 'ScGridCoGeom':
            f += ['%.17g' % g.relPos, '%d' % g.isDuplicate, '%d' % g.trueInt]
        else:
            f += ['nan'] * 3
        out.write(','.join(f) + '\n')


# ----------------------------------------------------------------------------------------
# PeriTriaxController doneHooks (FORMAT.md, "doneHookEvents")

_HOOK_ORIG = {}     # id(engine) -> the hook string the script set
_HOOK_EVENTS = {}   # id(engine) -> [event, ...]


def _peri_engines():
    return [e for e in O.engines if _cls(e) == 'PeriTriaxController']


def _wrap_hook(e):
    """Replace the engine's doneHook by a call to _run_hook, which runs the original string and records
    what it changed."""
    h = e.doneHook
    if h:
        _HOOK_ORIG[id(e)] = h
        e.doneHook = 'import ryade_record; ryade_record._run_hook(%d)' % id(e)
    else:
        _HOOK_ORIG.pop(id(e), None)


def _wrap_hooks():
    for e in _peri_engines():
        _HOOK_EVENTS.setdefault(id(e), [])
        _wrap_hook(e)


def _unwrap_hooks():
    for e in _peri_engines():
        if id(e) in _HOOK_ORIG:
            e.doneHook = _HOOK_ORIG.pop(id(e))


def _world_snapshot():
    """What a doneHook must not change for ryade to replay it: bodies, time step, cell, engine list."""
    h = hashlib.sha256()
    pack = struct.Struct('<19d').pack
    for b in O.bodies:
        h.update(pack(*_body_values(b, O.forces)))
        h.update(str(b.state.blockedDOFs).encode())
    c = O.cell
    cell = (tuple(tuple(c.hSize[i]) for i in range(3)), tuple(tuple(c.velGrad[i]) for i in range(3)),
            tuple(tuple(c.nextVelGrad[i]) for i in range(3))) if O.periodic else None
    return (h.hexdigest(), float(O.dt), cell, tuple((_cls(e), bool(e.dead)) for e in O.engines),
            O.interactions.countReal())


def _run_hook(key):
    """Run the original doneHook of the engine whose id() is ``key`` in __main__ (as YADE's pyRunString
    does) and record the controller attributes it changed."""
    import __main__
    e = [x for x in _peri_engines() if id(x) == key][0]
    orig = _HOOK_ORIG[key]
    e.doneHook = orig  # the hook sees its own string, as in a plain run
    before = dict((k, _peri_value(k, getattr(e, k))) for k in PERI_SETTABLE + PERI_STATE)
    world = _world_snapshot()
    it = O.iter
    exec(orig, __main__.__dict__)
    after = dict((k, _peri_value(k, getattr(e, k))) for k in PERI_SETTABLE + PERI_STATE)
    for k in PERI_STATE:
        _require(after[k] == before[k], 'iteration %d: doneHook %r changed PeriTriaxController.%s, which ryade '
                 'cannot replay' % (it, orig, k))
    _require(_world_snapshot() == world, 'iteration %d: doneHook %r changed something besides the controller\'s '
             'attributes %s (bodies, O.dt, the cell or the engines), which ryade cannot replay'
             % (it, orig, ', '.join(PERI_SETTABLE)))
    _HOOK_EVENTS[key].append({'iter': it, 'hook': orig,
                              'set': dict((k, after[k]) for k in PERI_SETTABLE if after[k] != before[k])})
    _wrap_hook(e)


# ----------------------------------------------------------------------------------------
# per-step digests of the micro extension (FORMAT.md, "Digest scenes")

def _pack_doubles(vals):
    out = []
    for x in vals:
        x = float(x)
        out.append(b'\x00\x00\x00\x00\x00\x00\xf8\x7f' if x != x else struct.pack('<d', x))
    return b''.join(out)


def _digest16(data):
    return hashlib.sha256(data).hexdigest()[:16]


def _intrs_bytes(intrs):
    out = []
    for I in intrs:
        g = I.geom
        ph = I.phys
        out.append(struct.pack('<2q', I.id1, I.id2))
        out.append(_pack_doubles(tuple(g.normal) + (g.penetrationDepth,) + tuple(g.contactPoint) + tuple(g.shearInc)
                                 + tuple(ph.normalForce) + tuple(ph.shearForce) + (ph.kn, ph.ks)))
    return b''.join(out)


def _m3_rows(m):
    return [float(m[i][j]) for i in range(3) for j in range(3)]


def _peri_digest_values(e):
    """FORMAT.md order (ryade: PeriTriax::digest_values)."""
    v = _m3_rows(e.stressTensor)
    for k in ('stress', 'strain', 'strainRate', 'stiff'):
        v += _v3(getattr(e, k))
    v.append(float(e.currUnbalanced))
    v += _v3(e.prevGrow) + _v3(e.goal)
    v += [float(e.mass), float(e.externalWork)]
    v += _v3(e.maxBodySpan)
    v += [float(e.stressMask), 1.0 if e.dynCell else 0.0]
    return v


def _cell_bytes():
    if not O.periodic:
        return b''
    c = O.cell
    vals = _m3_rows(c.hSize) + _m3_rows(c.trsf) + _m3_rows(c.velGrad) + _m3_rows(c.prevVelGrad)
    for e in _peri_engines():
        vals += _peri_digest_values(e)
    return _pack_doubles(vals)


PERI_HEADER = ('step,hSize_xx,hSize_yy,hSize_zz,velGrad_xx,velGrad_yy,velGrad_zz,stress_x,stress_y,stress_z,'
               'strain_x,strain_y,strain_z,stiff_x,stiff_y,stiff_z,currUnbalanced,externalWork')


def _peri_row(step):
    c = O.cell
    e = _peri_engines()[0]
    h = c.hSize
    g = c.velGrad
    vals = [h[0][0], h[1][1], h[2][2], g[0][0], g[1][1], g[2][2]] + _v3(e.stress) + _v3(e.strain) + _v3(e.stiff)
    vals += [e.currUnbalanced, e.externalWork]
    return '%d,' % step + ','.join('%.17g' % float(x) for x in vals) + '\n'


def _say(msg):
    print('[ryade_record] ' + msg, flush=True)
    sys.stderr.flush()


def record(name, steps, outdir=None, default_sub='golden/micro', intrs=True, keep_steps=None, digest=False,
           min_contacts_check=None, final_check=None, grid=False, step_hook=None, micro_digest=False):
    """Record scene ``name`` for ``steps`` steps (see module docstring).

    keep_steps: None = every step 0..steps in the bodies file, else an iterable of steps to keep.
    digest:     also write <name>.digest.csv (SHA-256 of 19 little-endian doubles per body, id order).
    min_contacts_check: (k, n) -> fail unless at least n dynamic bodies have >= k real contacts at the end.
    final_check: callable run after the last step; returns None or an error message (-> failure).
    grid:       grid extension (golden/FORMAT_GRID.md): format id ryade-scene-grid-1, grid classes allowed,
                the ``interactions`` array in the scene JSON and <name>.intrs6d.csv.gz (needs ``intrs``).
    step_hook:  callable(step) run after every recorded step (step 0 included, after the rows are written);
                for script-side checks and statistics. It must not change the scene.
    micro_digest: digest scene of the micro format (FORMAT.md, "Digest scenes"): every step goes into
                <name>.digest.csv.gz (SHA-256 prefixes of the bodies, the real interactions and the cell with its
                PeriTriaxControllers), the bodies and interactions files keep only ``keep_steps``, and a periodic
                scene with a PeriTriaxController gets <name>.peri.csv.gz (cell and controller, every step).
    A PeriTriaxController's doneHook is run through _run_hook, which records what each firing changed
    (``doneHookEvents`` in the scene JSON, written after the last step).
    Returns a dict of statistics.
    """
    if outdir is None:
        outdir = output_dir(default_sub)
    os.makedirs(outdir, exist_ok=True)
    _require(O.iter == 0, 'record() must be called before the first step (O.iter=%d)' % O.iter)
    _require(O.numThreads == 1, 'YADE must run with one thread (O.numThreads=%d)' % O.numThreads)

    _require(not grid or intrs, 'grid=True needs intrs=True')
    scene = scene_dict(steps, grid=grid)
    nb = len(scene['bodies'])
    dynamic = [b['blockedDOFs'] != 63 for b in scene['bodies']]
    keep = None if keep_steps is None else set(int(s) for s in keep_steps)

    files = []
    try:
        fscene = _AtomicText(os.path.join(outdir, name + '.scene.json'))
        files.append(fscene)
        fb = _AtomicGz(os.path.join(outdir, name + '.bodies.csv.gz'))
        files.append(fb)
        fb.write(BODY_HEADER + '\n')
        fi = None
        if intrs:
            fi = _AtomicGz(os.path.join(outdir, name + '.intrs.csv.gz'))
            files.append(fi)
            fi.write(INTR_HEADER + '\n')
        fi6 = None
        if grid:
            fi6 = _AtomicGz(os.path.join(outdir, name + '.intrs6d.csv.gz'))
            files.append(fi6)
            fi6.write(INTR6D_HEADER + '\n')
        fd = None
        if digest:
            fd = _AtomicText(os.path.join(outdir, name + '.digest.csv'))
            files.append(fd)
            fd.write('step,sha256\n')
        fdm = fp = None
        if micro_digest:
            _require(not grid, 'micro_digest is for FORMAT.md scenes')
            fdm = _AtomicGz(os.path.join(outdir, name + '.digest.csv.gz'))
            files.append(fdm)
            fdm.write('step,bodies,intrs,cell\n')
            if O.periodic and _peri_engines():
                _require(len(_peri_engines()) == 1, 'at most one PeriTriaxController per digest scene')
                fp = _AtomicGz(os.path.join(outdir, name + '.peri.csv.gz'))
                files.append(fp)
                fp.write(PERI_HEADER + '\n')
        pack = struct.Struct('<19d').pack
        peri = [(k, e) for k, e in enumerate(O.engines) if _cls(e) == 'PeriTriaxController']
        _wrap_hooks()

        max_real = 0
        max_real_step = 0
        max_per_body = 0      # over dynamic bodies
        max_per_body_any = 0  # including fixed ones
        last_counts = [0] * nb
        forces = O.forces

        for step in range(0, steps + 1):
            if step > 0:
                O.step()
            bodies = list(O.bodies)
            vals = [_body_values(b, forces) for b in bodies]
            if keep is None or step in keep:
                _write_bodies(fb, step, vals)
            if fd is not None:
                h = hashlib.sha256()
                for v in vals:
                    h.update(pack(*v))
                fd.write('%d,%s\n' % (step, h.hexdigest()))
            real = _real_intrs()
            if fdm is not None:
                fdm.write('%d,%s,%s,%s\n' % (step, _digest16(b''.join(_pack_doubles(v) for v in vals)),
                                              _digest16(_intrs_bytes(real)), _digest16(_cell_bytes())))
            if fp is not None:
                fp.write(_peri_row(step))
            if fi is not None and (not micro_digest or keep is None or step in keep):
                _write_intrs(fi, step, real)
            if fi6 is not None:
                _write_intrs6d(fi6, step, real)
            if step_hook is not None:
                step_hook(step)
            counts = [0] * nb
            for I in real:
                counts[I.id1] += 1
                counts[I.id2] += 1
            if len(real) > max_real:
                max_real, max_real_step = len(real), step
            md = max([c for c, d in zip(counts, dynamic) if d] or [0])
            max_per_body = max(max_per_body, md)
            max_per_body_any = max(max_per_body_any, max(counts or [0]))
            last_counts = counts
            if step % 500 == 0 and step > 0:
                _say('%s: step %d/%d, real intrs %d' % (name, step, steps, len(real)))

        _require(O.iter == steps, 'O.iter=%d after %d steps' % (O.iter, steps))
        for k, e in peri:
            if _HOOK_EVENTS.get(id(e)):
                scene['engines'][k]['doneHookEvents'] = _HOOK_EVENTS[id(e)]
        _unwrap_hooks()
        fscene.write(scene_json(scene))
        end_ge3 = sum(1 for c, d in zip(last_counts, dynamic) if d and c >= 3)
        stats = {'name': name, 'bodies': nb, 'steps': steps, 'max_real': max_real, 'max_real_step': max_real_step,
                 'max_contacts_dynamic_body': max_per_body, 'max_contacts_any_body': max_per_body_any,
                 'end_real': len(_real_intrs()), 'end_dynamic_bodies_ge3': end_ge3}
        if min_contacts_check is not None:
            k, n = min_contacts_check
            got = sum(1 for c, d in zip(last_counts, dynamic) if d and c >= k)
            msg = '%s: only %d dynamic bodies end with >= %d contacts (need %d)' % (name, got, k, n)
            if got < n:
                if os.environ.get('RYADE_RECORD_NOCHECK'):
                    _say('WARNING (RYADE_RECORD_NOCHECK set): ' + msg)
                else:
                    raise UnsupportedScene(msg)

        if final_check is not None:
            msg = final_check()
            if msg:
                if os.environ.get('RYADE_RECORD_NOCHECK'):
                    _say('WARNING (RYADE_RECORD_NOCHECK set): %s: %s' % (name, msg))
                else:
                    raise UnsupportedScene('%s: %s' % (name, msg))
        for f in files:
            f.close_tmp()
        for f in files:
            f.commit()
    except BaseException:
        for f in files:
            f.abort()
        raise
    _say('%s: done %s' % (name, ' '.join('%s=%s' % (k, v) for k, v in stats.items() if k != 'name')))
    return stats


def finish():
    """End the script cleanly (flush, exit 0)."""
    sys.stdout.flush()
    sys.stderr.flush()
    sys.exit(0)
