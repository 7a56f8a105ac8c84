"""Clumps in the compatibility layer (O.bodies.appendClumped / O.bodies.clump, Body clump flags,
Clump.members, errors), checked against the values YADE 2023.02a printed for the same statements
(yade_ref/compat/clump_api.py, run with `yade -n -x`)."""
import pytest

from yade import O, utils, FrictMat, Clump, ForceResetter, InsertionSortCollider, InteractionLoop, NewtonIntegrator
from yade import (Bo1_Sphere_Aabb, Bo1_Facet_Aabb, Ig2_Sphere_Sphere_ScGeom, Ig2_Facet_Sphere_ScGeom,
                  Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack, UnsupportedError)


def _scene():
    O.reset()
    mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=0.5))
    O.bodies.append(utils.facet([(0, 0, 0), (1, 0, 0), (0, 1, 0)], material=mat))
    r = O.bodies.appendClumped([utils.sphere((0, 0, 0.1), 0.02, material=mat),
                                utils.sphere((0.025, 0.01, 0.11), 0.015, material=mat)])
    return mat, r


def test_append_clumped_returns_ids_and_sets_flags():
    mat, r = _scene()
    # YADE: ret (3, [1, 2]) tuple list
    assert r == (3, [1, 2]) and type(r) is tuple and type(r[1]) is list
    # YADE: id isClump isClumpMember isStandalone clumpId bounded aspherical
    expect = [(0, False, False, True, -1, True, False),
              (1, False, True, False, 3, True, False),
              (2, False, True, False, 3, True, False),
              (3, True, False, False, 3, False, True)]
    got = [(b.id, b.isClump, b.isClumpMember, b.isStandalone, b.clumpId, b.bounded, b.aspherical) for b in O.bodies]
    assert got == expect
    c = O.bodies[3]
    assert isinstance(c.shape, Clump) and c.material is None
    with pytest.raises(AttributeError):
        c.clumpId = 5


def test_clump_properties_are_yade_bit_for_bit():
    _scene()
    c = O.bodies[3]
    # YADE's Clump::updateProperties (discretization 0)
    assert repr(c.state.mass) == '0.12388347030655751'
    assert [repr(x) for x in c.state.pos] == ['0.0074175824175824155', '0.002967032967032966', '0.10296703296703295']
    assert [repr(x) for x in c.state.inertia] == ['1.724839086575941e-05', '3.857531699412874e-05', '3.857531699412913e-05']
    q = c.state.ori
    assert [repr(x) for x in (q[3], q[0], q[1], q[2])] == [
        '0.6743820136134884', '0.6931111307747562', '0.003486250260225655', '0.25454607867708157']
    m = c.shape.members
    assert sorted(m.keys()) == [1, 2] and c.shape.ids == [1, 2]
    assert [repr(x) for x in m[1][0]] == ['-0.008522153376732232', '6.461844948013606e-17', '2.2551405187698492e-17']
    assert [repr(x) for x in m[2][0]] == ['0.02020065985595791', '-1.0321604682062002e-16', '-5.193328406205566e-17']
    o = m[2][1]
    assert [repr(x) for x in (o[3], o[0], o[1], o[2])] == [
        '0.6743820136134884', '-0.6931111307747562', '-0.003486250260225655', '-0.25454607867708157']


def test_clump_of_appended_bodies_and_free_fall():
    mat, r = _scene()
    ids = O.bodies.append([utils.sphere((1, 1, 1), 0.01, material=mat), utils.sphere((1.01, 1, 1), 0.01, material=mat),
                           utils.sphere((1.5, 1, 1), 0.01, material=mat)])
    cid = O.bodies.clump(ids[:2])
    # YADE: clump ret 7 0.021781709064889236 (1.0050000000000001, 1.0, 1.0) True
    assert cid == 7 and repr(O.bodies[cid].state.mass) == '0.021781709064889236'
    assert tuple(O.bodies[cid].state.pos) == (1.0050000000000001, 1.0, 1.0) and O.bodies[cid].aspherical
    O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()],
                                 [Ip2_FrictMat_FrictMat_FrictPhys()], [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 NewtonIntegrator(damping=0.2, gravity=(0, 0, -9.81))]
    O.dt = 1e-5
    O.run(100, True)
    c = O.bodies[3]
    # YADE after 100 steps: the clump fell (damped gravity), its members follow it, and the two
    # overlapping members of one clump never formed an interaction
    assert [repr(x) for x in c.state.pos] == ['0.0074175824175824155', '0.002967032967032966', '0.10296306972703302']
    assert [repr(x) for x in c.state.vel] == ['0.0', '0.0', '-0.007847999999999987']
    assert [repr(x) for x in O.bodies[2].state.pos] == ['0.024999999999999998', '0.010000000000000007', '0.10999603676000007']
    assert len(O.interactions) == 0


def test_bad_and_unsupported_clumps_fail_clearly():
    mat, r = _scene()
    # YADE: RuntimeError "Clump::updateProperties: clump has zero members." (YADE also leaves an empty
    # clump body behind; ryade leaves the scene unchanged)
    with pytest.raises(RuntimeError, match='zero members'):
        O.bodies.clump([])
    i = O.bodies.append(utils.sphere((1.5, 1, 1), 0.01, material=mat))
    # YADE: ValueError "Body #6 is already part of this clump #9" (ids differ here: no leftover)
    with pytest.raises(ValueError, match='Body #%d is already part of this clump #%d' % (i, i + 1)):
        O.bodies.clump([i, i])
    assert len(O.bodies) == i + 1
    for call in (lambda: O.bodies.appendClumped([utils.sphere((2, 0, 0), 0.01)], discretization=5),
                 lambda: O.bodies.clump([i], discretization=3)):
        with pytest.raises(UnsupportedError, match='discretization'):
            call()
    for name in ('replaceByClumps', 'addToClump', 'releaseFromClump', 'deleteClumpMember', 'deleteClumpBody',
                 'updateClumpProperties'):
        with pytest.raises(UnsupportedError, match=name):
            getattr(O.bodies, name)([], [])
    with pytest.raises(RuntimeError, match='already a member of clump #3'):
        O.bodies.clump([1, i])
    with pytest.raises(RuntimeError, match='Sphere members only'):
        O.bodies.clump([0, i])
