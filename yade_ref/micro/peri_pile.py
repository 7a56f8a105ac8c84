# Periodic pile (the study's setup in miniature): periodic cell 0.1 x 0.1 x 0.5 m, 32 spheres
# (r in [0.009, 0.011]) drifting at (0.3, 0.2, 0) m/s so they cross the x/y boundaries, falling
# a few mm under gravity onto a fixed Box floor much larger than the cell (half-extents
# 50 x 50 x 0.01, top face at z=0.05, away from the z=0 cell boundary, as in the study),
# InsertionSortCollider(allowBiggerThanPeriod=True), damping 0.2, dt = 0.5*PWaveTimeStep().
# The spheres start as two jittered 4x4 layers, the upper one nested 0.2-0.5 mm above the
# pockets of the lower one, 2-5 mm above the floor (seeded Python RNG; the positions are
# written to the scene file anyway) rather than a makeCloud cloud: a cloud would need ~0.1 s
# just to fall and thousands of steps to settle, too long for a per-step golden file.
# verletDist=-0.1 (not the default): the floor pairs are created by the z insertion sort when
# a sphere's bound first crosses the floor's. Observed: spheres whose enlarged bound already
# overlapped the floor at the first collider run got a floor pair only if their x bound range
# contained the floor's wrapped x bound (0.05); the others fell through. So the start gap must
# exceed the two sweep enlargements (2 * 0.1 * r_min here).
# Exercises the periodic collider with a body bigger than the period (period 0 on x/y for the
# floor pairs), cellDist shifts for sphere pairs across boundaries, unwrapped positions,
# up to 3 contacts per sphere (upper layer falling into the pockets of the lower one).
import math, os, random, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
O.periodic = True
O.cell.setBox(0.1, 0.1, 0.5)
mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=math.radians(30)))
Z0 = 0.05
floor = O.bodies.append(utils.box((0.05, 0.05, Z0 - 0.01), (50, 50, 0.01), fixed=True, material=mat))   # id 0
rng = random.Random(1)
Lc = 0.1
lower = []
for i in range(4):
    for j in range(4):
        r = 0.009 + 0.002 * rng.random()
        x = 0.025 * i + 0.0125 + rng.uniform(-0.001, 0.001)
        y = 0.025 * j + 0.0125 + rng.uniform(-0.001, 0.001)
        z = Z0 + r + rng.uniform(0.002, 0.005)
        lower.append((x, y, z, r))
upper = []
for i in range(4):
    for j in range(4):
        r = 0.009 + 0.002 * rng.random()
        x = 0.025 * i + 0.025 + rng.uniform(-0.001, 0.001)
        y = 0.025 * j + 0.025 + rng.uniform(-0.001, 0.001)
        # rest it 0.2-0.5 mm above the highest touching point of the lower layer (periodic images)
        z = 0.0
        for (xl, yl, zl, rl) in lower:
            dx = x - xl - Lc * round((x - xl) / Lc)
            dy = y - yl - Lc * round((y - yl) / Lc)
            h2 = (r + rl) ** 2 - dx * dx - dy * dy
            if h2 > 0:
                z = max(z, zl + math.sqrt(h2))
        upper.append((x, y, z + rng.uniform(0.0002, 0.0005), r))
n = 0
for (x, y, z, r) in lower + upper:
    O.bodies.append(utils.sphere((x, y, z), r, material=mat))
    n += 1
for b in O.bodies:
    if isinstance(b.shape, Sphere):
        b.state.vel = (0.3, 0.2, 0.0)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb()], allowBiggerThanPeriod=True, verletDist=-0.1),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    NewtonIntegrator(damping=0.2, gravity=(0, 0, -9.81)),
]
O.dt = 0.5 * utils.PWaveTimeStep()
print('peri_pile: %d spheres, dt=%.17g' % (n, O.dt), flush=True)

def landed():
    # every sphere must end on the floor or on other spheres (none fell through), and the floor
    # must carry at least 6 of them
    low = [b.id for b in O.bodies if isinstance(b.shape, Sphere) and b.state.pos[2] - b.shape.radius < Z0 - 1e-3]
    if low:
        return 'spheres fell through the floor: %s' % low
    nfloor = sum(1 for i in O.interactions if i.id1 == floor)
    if nfloor < 6:
        return 'only %d spheres on the floor at the end' % nfloor
    return None

ryade_record.record('peri_pile', steps=1500, final_check=landed)
ryade_record.finish()
