# Pile: ~25 polydisperse spheres (makeCloud, seed=1) thrown down (vz0=-1 m/s) into a container
# made of fixed Boxes (floor + 4 side walls), gravity -9.81, damping 0.2, default collider
# verletDist (-0.5: the collider strides), dt = 0.3*PWaveTimeStep().
# Exercises multi-contact force summation order (YADE container order: initial sweep, appends on
# insertion-sort inversions, swap-with-last on erase), Box-sphere contacts (floor and side
# walls), Box-Box potential pairs that never get a functor, bouncing and piling up.
# The spheres are large (r ~ 5 cm): with dt = 0.3*r_min/sqrt(E/rho) the number of steps a fall
# takes grows as 1/sqrt(r), so big spheres land within ~1000 steps at E=1e7.
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *
from yade import pack

O.reset()
mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=math.radians(30)))
L = 0.15        # inner half width of the container
H = 0.35        # half height of the side walls
t = 0.01        # half thickness of floor and walls
O.bodies.append([
    utils.box((0, 0, -t), (L + 2 * t, L + 2 * t, t), fixed=True, material=mat),          # floor, top face z=0
    utils.box((-L - t, 0, H), (t, L + 2 * t, H), fixed=True, material=mat),              # x-
    utils.box((L + t, 0, H), (t, L + 2 * t, H), fixed=True, material=mat),               # x+
    utils.box((0, -L - t, H), (L, t, H), fixed=True, material=mat),                      # y-
    utils.box((0, L + t, H), (L, t, H), fixed=True, material=mat),                       # y+
])
sp = pack.SpherePack()
n = sp.makeCloud((-L, -L, 0.0), (L, L, 0.55), rMean=0.05, rRelFuzz=0.3, num=25, seed=1)
for c, r in sp:
    O.bodies.append(utils.sphere(c, r, material=mat))
for b in O.bodies:
    if isinstance(b.shape, Sphere):
        b.state.vel = (0, 0, -1.0)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=0.2, gravity=(0, 0, -9.81)),
]
O.dt = 0.3 * utils.PWaveTimeStep()
print('pile: %d spheres, dt=%.17g' % (n, O.dt), flush=True)

ryade_record.record('pile', steps=1200, min_contacts_check=(3, 4))
ryade_record.finish()
