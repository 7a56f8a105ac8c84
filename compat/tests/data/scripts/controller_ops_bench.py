"""Per-operation cost of a PyRunner controller's hot statements (the study's piston controller: 72 facet
forces read, 72 cached bodies' velocities set every step), in microseconds per operation. Runs unchanged in
both engines: `OMP_NUM_THREADS=1 yade -n -x controller_ops_bench.py` and `compat run controller_ops_bench.py`."""
import time, sys
from yade import geom
O.reset()
mat = O.materials.append(FrictMat(young=1e8, poisson=0.25, frictionAngle=0.5, density=2650))
ids = O.bodies.append(geom.facetCylinder((0, 0, 0.1), radius=0.045, height=0.05, segmentsNumber=24, wallMask=2 | 4, material=mat, mask=1))
for i in range(20):
    O.bodies.append(sphere((0.01 * i, 0, 0), 0.004, material=mat))
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Facet_Aabb()]),
             InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                             [Law2_ScGeom_FrictPhys_CundallStrack()]), NewtonIntegrator(damping=0.2)]
O.dt = 1e-6
O.run(2, True)
bodies = [O.bodies[i] for i in ids]
N = len(ids)
R = 2000
def timeit(name, fn):
    fn(10)
    best = 1e9
    for _ in range(5):
        t0 = time.perf_counter(); fn(R); t = time.perf_counter() - t0
        best = min(best, t)
    print('%-28s %7.3f us/op' % (name, best / (R * N) * 1e6))
def f_force(r):
    f = O.forces.f
    for _ in range(r):
        s = sum(f(i)[2] for i in ids)
def f_force_only(r):
    f = O.forces.f
    for _ in range(r):
        for i in ids: f(i)
def f_setvel(r):
    for _ in range(r):
        vv = Vector3(0, 0, -0.1)
        for b in bodies:
            b.state.vel = vv
def f_getvel(r):
    for _ in range(r):
        for i in ids: O.bodies[i].state.vel[2]
def f_getpos(r):
    for _ in range(r):
        for i in ids: O.bodies[i].state.pos[2]
def f_vec(r):
    for _ in range(r):
        for i in ids: Vector3(0, 0, -0.1)
def f_iter(r):
    for _ in range(r):
        for i in ids: O.iter
def f_bodyget(r):
    for _ in range(r):
        for i in ids: O.bodies[i]
timeit('sum(f(i)[2])', f_force)
timeit('O.forces.f(i)', f_force_only)
timeit('b.state.vel = v', f_setvel)
timeit('O.bodies[i].state.vel[2]', f_getvel)
timeit('O.bodies[i].state.pos[2]', f_getpos)
timeit('Vector3(0,0,v)', f_vec)
timeit('O.iter', f_iter)
timeit('O.bodies[i]', f_bodyget)
O.bodies[ids[0]].state.vel = Vector3(0, 0, -0.5)
O.step()
print('vel after', O.bodies[ids[0]].state.vel, O.bodies[ids[0]].state.pos[2])
