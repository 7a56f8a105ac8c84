"""The Rust fast paths behind a PyRunner controller's hot statements (`O.forces.f(i)`, `b.state.vel = v`
on a cached Body, `O.bodies[i].state.vel[2]`, `state.pos[2]`, `O.iter`): the values are the ones YADE
2023.02a printed for the same statements (`yade -n -x data/scripts/fastpaths_yade_ref.py`: a sphere
resting on a facet, the facet moved by setting its velocity), and everything the generic paths did
(conversions, live views, errors naming the class, attribute and script line) still holds. The costs per
operation in both engines: data/scripts/controller_ops_bench.py."""
import pytest

from yade import (O, utils, FrictMat, State, Body, Sphere, Vector3, ForceResetter, InsertionSortCollider, InteractionLoop,
                  NewtonIntegrator, Bo1_Sphere_Aabb, Bo1_Facet_Aabb, Ig2_Facet_Sphere_ScGeom, Ip2_FrictMat_FrictMat_FrictPhys,
                  Law2_ScGeom_FrictPhys_CundallStrack, UnsupportedError)
from yade import _ryade


def _scene():
    O.reset()
    mat = O.materials.append(FrictMat(young=1e8, poisson=0.25, density=2650, frictionAngle=0.5))
    f = O.bodies.append(utils.facet([(-0.1, -0.1, 0), (0.1, -0.1, 0), (0, 0.1, 0)], material=mat))
    s = O.bodies.append(utils.sphere((0, 0, 0.0099), 0.01, material=mat))
    O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
                 InteractionLoop([Ig2_Facet_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                                 [Law2_ScGeom_FrictPhys_CundallStrack()]),
                 NewtonIntegrator(damping=0.2, gravity=(0, 0, -9.81))]
    O.dt = 1e-5
    return f, s


def test_the_fast_paths_are_in_use():
    _scene()
    # the Vector3 slots were found, so values are built and read without getattr/setattr
    assert O._sim._vector3_slots_found()
    assert type(State.__dict__['__setattr__']).__name__ == 'method_descriptor' and isinstance(State(), _ryade.StateBase)
    assert O.forces.f.__self__ is O._sim and O.forces.f.__name__ == 'f' and O.forces.t.__name__ == 't'


def test_forces_and_cached_body_velocity_match_yade():
    f, s = _scene()
    fb = O.bodies[f]                       # cached, as the study's pistonBodies
    fb.state.vel = Vector3(0, 0, -0.1)
    O.step()
    # YADE: -133.33333333333252 133.33333333333252 Vector3(0,0,0) Vector3(0,0,133.3333333333325186)
    assert repr(O.forces.f(f)[2]) == '-133.33333333333252' and repr(O.forces.f(s)[2]) == '133.33333333333252'
    assert repr(O.forces.t(s)) == 'Vector3(0,0,0)' and repr(O.forces.f(s, sync=True)) == 'Vector3(0,0,133.3333333333325186)'
    assert repr(O.forces.m(s)) == 'Vector3(0,0,0)'
    # YADE: Vector3(0,-0.03819660112501051946,-1.000000000000000167e-06) -0.1 0.00990096015070546 0.09601507054604945
    assert repr(O.bodies[f].state.pos) == 'Vector3(0,-0.03819660112501051946,-1.000000000000000167e-06)'
    assert repr(O.bodies[f].state.vel[2]) == '-0.1'
    assert repr(O.bodies[s].state.pos[2]) == '0.00990096015070546' and repr(O.bodies[s].state.vel[2]) == '0.09601507054604945'
    # a force is a plain Vector3 (YADE: Vector3 Vector3(0,0,-133.3333333333325186) Vector3(0,0,-266.6666666666650372)
    # 133.33333333333252)
    v = O.forces.f(f)
    assert type(v) is Vector3 and repr(v) == 'Vector3(0,0,-133.3333333333325186)'
    assert repr(v * 2) == 'Vector3(0,0,-266.6666666666650372)' and repr(v.norm()) == '133.33333333333252'
    v[2] = 1.0                             # a copy: the force container is not changed
    assert O.forces.f(f)[2] == -133.33333333333252
    # the velocity set through the cached body is what the next step's NewtonIntegrator uses
    fb.state.vel = Vector3(0, 0, 0.5)
    O.step()
    # YADE: 4.000000000000001e-06 -130.71979905938716 Vector3(0,0,130.7197990593871566)
    assert repr(O.bodies[f].state.pos[2]) == '4.000000000000001e-06'
    assert repr(O.forces.f(f)[2]) == '-130.71979905938716' and repr(O.forces.f(s)) == 'Vector3(0,0,130.7197990593871566)'
    # a live view: item assignment moves the body (YADE's return_internal_reference)
    sv = O.bodies[s].state.vel
    sv[0] = 0.25
    O.step()
    # YADE: Vector3(0.2490991229636307924,0,0.2872555465143564746)
    #       Vector3(2.490991229636308307e-06,0,0.00990573417179743676) 3 3.0000000000000004e-05
    assert repr(O.bodies[s].state.vel) == 'Vector3(0.2490991229636307924,0,0.2872555465143564746)'
    assert repr(sv) == 'Vector3(0.2490991229636307924,0,0.2872555465143564746)'   # still live
    assert repr(O.bodies[s].state.pos) == 'Vector3(2.490991229636308307e-06,0,0.00990573417179743676)'
    assert O.iter == 3 and repr(O.time) == '3.0000000000000004e-05'


def test_assignments_other_than_a_plain_vector3_take_the_generic_path():
    f, s = _scene()
    b = O.bodies[s]
    # YADE: Vector3(0,0,1) Vector3(0,0,2) Vector3(0.01000000000000000021,0,0.02000000000000000042)
    b.state.vel = (0.0, 0.0, 1.0)
    b.state.angVel = Vector3(0, 0, 2)
    b.state.pos = Vector3(0.01, 0, 0.02)
    assert repr(b.state.vel) == 'Vector3(0,0,1)' and repr(b.state.angVel) == 'Vector3(0,0,2)'
    assert repr(b.state.pos) == 'Vector3(0.01000000000000000021,0,0.02000000000000000042)'
    b.state.vel = b.state.angVel           # a view as the value (YADE: Vector3(0,0,2))
    assert repr(b.state.vel) == 'Vector3(0,0,2)'
    b.state.vel = [1, 2, 3]                # ints in a list are converted
    assert tuple(b.state.vel) == (1.0, 2.0, 3.0) and all(type(x) is float for x in b.state.vel)
    b.state.inertia = Vector3(1e-3, 2e-3, 3e-3)
    assert tuple(O.bodies[s].state.inertia) == (1e-3, 2e-3, 3e-3)
    b.state.mass = 2
    assert b.state.mass == 2.0
    with pytest.raises(TypeError, match='State.vel'):
        b.state.vel = 3
    # a name YADE does not have: kept as the script's own attribute, as YADE's objects do
    b.state.foo = 3
    assert b.state.foo == 3
    # a YADE attribute ryade lacks: UnsupportedError naming it and this file's line
    with pytest.raises(UnsupportedError, match=r'State\.se3.*test_fastpaths\.py, line'):
        b.state.se3 = 3
    with pytest.raises(UnsupportedError, match=r'State\.se3'):
        b.state.se3
    with pytest.raises(IndexError):
        O.forces.f(99)
    with pytest.raises(IndexError):
        O.forces.t(99, sync=True)
    with pytest.raises(OverflowError):
        O.forces.f(-1)
    with pytest.raises(TypeError):
        O.forces.f(1.0)
    with pytest.raises(TypeError):
        O.forces.f(s, bogus=1)
    with pytest.raises(TypeError):
        O.forces.f()
    assert O.forces.f(s, True) == O.forces.f(s) == O.forces.f(id=s, sync=False) and O.forces.t(id=s) == Vector3(0, 0, 0)
    assert O.forces.f(True) == O.forces.f(1)   # a bool is an int (the generic path)


def test_unbound_state_and_body_state_attribute():
    _scene()
    st = State()
    st.vel = Vector3(1, 2, 3)              # YADE: Vector3(1,2,3) Vector3(0,0,0)
    assert repr(st.vel) == 'Vector3(1,2,3)' and repr(st.pos) == 'Vector3(0,0,0)'
    st.pos = Vector3(0, 0, 0.5)
    b = Body(shape=Sphere(radius=0.01), state=st, material=O.materials[0])
    assert b.state is st and b._values['state'] is st
    st2 = State()
    st2.pos = Vector3(0, 0, 0.7)
    b.state = st2                          # before O.bodies.append: replaces the state
    assert b.state is st2 and b._values['state'] is st2
    bid = O.bodies.append(b)
    assert O.bodies[bid].state is st2 and tuple(O.bodies[bid].state.pos) == (0.0, 0.0, 0.7)
    st2.vel = Vector3(0, 0, -1.0)          # the bound state is a view onto the scene
    assert O._sim.get_vec3(bid, 'vel') == (0.0, 0.0, -1.0)
    with pytest.raises(UnsupportedError, match=r'Body\.state of a body already in O\.bodies'):
        O.bodies[bid].state = State()
    assert Body().state is not None and type(Body().state) is State


def test_vector3_getitem_in_c_keeps_minieigen_semantics():
    from yade.minieigen import ArgumentError
    assert type(Vector3.__dict__['__getitem__']).__name__ == 'method_descriptor' and callable(Vector3._py_getitem)
    v = Vector3(1, 2, 3.5)
    assert (v[0], v[1], v[2]) == (1.0, 2.0, 3.5) and type(v[0]) is float
    assert v[True] == 2.0 and v.__getitem__(2) == 3.5          # bool index: the Python definition
    # minieigen: negative indices raise IndexError, as do indices past the end; other types ArgumentError
    for bad in (-1, 3, 10**30):
        with pytest.raises(IndexError):
            v[bad]
    for bad in (1.0, 'a', slice(0, 2), None):
        with pytest.raises(ArgumentError):
            v[bad]
    with pytest.raises(TypeError):
        v.__getitem__()
    # a view reads the scene every time
    f, s = _scene()
    sv = O.bodies[s].state.vel
    assert sv[2] == 0.0
    O.bodies[s].state.vel = Vector3(0, 0, 0.75)
    assert sv[2] == 0.75 and O.bodies[s].state.vel[2] == 0.75
    # a subclass goes through the Python definition
    class W(Vector3):
        pass
    w = W(4, 5, 6)
    assert w[1] == 5.0 and list(w) == [4.0, 5.0, 6.0]
    with pytest.raises(IndexError):
        w[3]
    # in-place modification is seen
    v[1] = 7
    assert v[1] == 7.0
    v += Vector3(1, 1, 1)
    assert (v[0], v[1], v[2]) == (2.0, 8.0, 4.5)


def test_direct_state_store_edge_cases():
    f, s = _scene()
    st = O.bodies[s].state
    v = Vector3(0, 0, 1.0)
    v._v[2] = 2                            # not a float: the generic path converts it
    st.vel = v
    assert O._sim.get_vec3(s, 'vel') == (0.0, 0.0, 2.0) and type(st.vel[2]) is float
    setattr(st, 'v' + 'el', Vector3(0, 0, 3.0))   # a name built at run time
    assert st.vel[2] == 3.0
    st.__setattr__('angVel', Vector3(1.0, 0, 0))
    assert tuple(O.bodies[s].state.angVel) == (1.0, 0.0, 0.0)
    with pytest.raises(TypeError):
        State.__setattr__(st, 'vel')
    O.reset()                              # the old body's state now points past the (empty) scene
    with pytest.raises(IndexError):
        st.vel = Vector3(0, 0, 1.0)
    with pytest.raises(IndexError):
        st.vel


def test_state_copy_and_pickle():
    import copy
    import pickle
    st = State()
    st.vel = Vector3(1, 2, 3)
    assert repr(pickle.loads(pickle.dumps(st)).vel) == 'Vector3(1,2,3)'
    assert repr(copy.deepcopy(st).vel) == 'Vector3(1,2,3)'
    f, s = _scene()
    c = copy.copy(O.bodies[s].state)       # a bound state's copy is a view of the same body
    c.vel = Vector3(0, 0, 5.0)
    assert O.bodies[s].state.vel[2] == 5.0 and c.pos[2] == O.bodies[s].state.pos[2]
