# Meso settle: >= 500 polydisperse spheres (makeCloud rMean=0.005, rRelFuzz=0.3, seed=7) in a
# fixed container of Boxes (floor + 4 side walls), thrown down at 1.5 m/s, gravity -9.81, NewtonIntegrator damping 0.2,
# dt = 0.5*PWaveTimeStep(), 2000 steps, default collider (verletDist=-0.5, striding).
# Writes golden/meso/settle.{scene.json,digest.csv,bodies.csv.gz} (bodies at steps 0,100,1000,2000;
# digest = SHA-256 per step over 19 little-endian doubles per body).
# Run: yade -n -x yade_ref/meso/settle.py [OUTDIR]
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *
from yade import pack

O.reset()
mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=math.radians(30)))
L = 0.05        # inner half width
H = 0.09        # half height of the side walls
t = 0.005       # half thickness of floor and walls
O.bodies.append([
    utils.box((0, 0, -t), (L + 2 * t, L + 2 * t, t), fixed=True, material=mat),          # floor, top z=0
    utils.box((-L - t, 0, H), (t, L + 2 * t, H), fixed=True, material=mat),              # x-
    utils.box((L + t, 0, H), (t, L + 2 * t, H), fixed=True, material=mat),               # x+
    utils.box((0, -L - t, H), (L, t, H), fixed=True, material=mat),                      # y-
    utils.box((0, L + t, H), (L, t, H), fixed=True, material=mat),                       # y+
])
sp = pack.SpherePack()
n = sp.makeCloud((-L, -L, 0.0), (L, L, 0.16), rMean=0.005, rRelFuzz=0.3, num=520, seed=7)
for c, r in sp:
    O.bodies.append(utils.sphere(c, r, material=mat))
for b in O.bodies:
    if isinstance(b.shape, Sphere):
        b.state.vel = (0, 0, -1.5)    # thrown down, so the cloud collapses within the 2000 steps
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=0.2, gravity=(0, 0, -9.81)),
]
O.dt = 0.5 * utils.PWaveTimeStep()
print('settle: %d spheres, dt=%.17g' % (n, O.dt), flush=True)
if n < 500:
    raise RuntimeError('settle: makeCloud placed only %d spheres (need >= 500)' % n)

ryade_record.record('settle', steps=2000, default_sub='golden/meso', intrs=False, digest=True,
                    keep_steps=(0, 100, 1000, 2000))
ryade_record.finish()
