# the statements of compat/tests/test_fastpaths.py, printed by YADE 2023.02a: yade -n -x fastpaths_yade_ref.py (or compat run)
from yade import utils
O.reset()
mat = O.materials.append(FrictMat(young=1e8, poisson=0.25, density=2650, frictionAngle=0.5))
f = O.bodies.append(utils.facet([(-0.1, -0.1, 0), (0.1, -0.1, 0), (0, 0.1, 0)], material=mat))
s = O.bodies.append(utils.sphere((0, 0, 0.0099), 0.01, material=mat))
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
             InteractionLoop([Ig2_Facet_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                             [Law2_ScGeom_FrictPhys_CundallStrack()]),
             NewtonIntegrator(damping=0.2, gravity=(0, 0, -9.81))]
O.dt = 1e-5
fb = O.bodies[f]
fb.state.vel = Vector3(0, 0, -0.1)
O.step()
print('A', repr(O.forces.f(f)[2]), repr(O.forces.f(s)[2]), repr(O.forces.t(s)), repr(O.forces.f(s, sync=True)))
print('B', repr(O.bodies[f].state.pos), repr(O.bodies[f].state.vel[2]), repr(O.bodies[s].state.pos[2]), repr(O.bodies[s].state.vel[2]))
v = O.forces.f(f)
print('C', type(v).__name__, repr(v), repr(v * 2), repr(v.norm()))
fb.state.vel = Vector3(0, 0, 0.5)
O.step()
print('D', repr(O.bodies[f].state.pos[2]), repr(O.forces.f(f)[2]), repr(O.forces.f(s)))
sv = O.bodies[s].state.vel
sv[0] = 0.25
O.step()
print('E', repr(O.bodies[s].state.vel), repr(O.bodies[s].state.pos), repr(O.iter), repr(O.time))
st = State()
st.vel = Vector3(1, 2, 3)
print('F', repr(st.vel), repr(st.pos))
b = O.bodies[s]
b.state.vel = (0.0, 0.0, 1.0)
b.state.angVel = Vector3(0, 0, 2)
b.state.pos = Vector3(0.01, 0, 0.02)
print('G', repr(b.state.vel), repr(b.state.angVel), repr(b.state.pos))
b.state.vel = b.state.angVel
print('H', repr(b.state.vel))
try:
    b.state.vel = 3
except Exception as e:
    print('I', type(e).__name__)
try:
    b.state.foo = 3
except Exception as e:
    print('J', type(e).__name__, e)
try:
    O.forces.f(99)
except Exception as e:
    print('K', type(e).__name__, e)
