# ForceEngine and HarmonicForceEngine (pkg/common/ForceEngine.cpp): spheres on a wall, two pushed sideways by
# a constant ForceEngine into a third, one shaken by a HarmonicForceEngine (different frequency and phase
# per axis) against its neighbours; an engine with an id past the container (skipped). The engines'
# forces are summed after the contacts' (one thread), as YADE's ForceContainer does. Gravity, damping 0.1.
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2600, frictionAngle=math.radians(25)))
O.bodies.append(utils.wall((0, 0, 0), axis=2, material=mat))
r = 0.01
ids = [O.bodies.append(utils.sphere((x, y, r * 0.999), r, material=mat)) for x, y in
       [(0, 0), (0.0199, 0.001), (0.04, -0.0005), (0.0595, 0.0003), (0.0205, 0.0195), (0.0, 0.0198)]]
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    ForceEngine(ids=[ids[0], ids[5]], force=(0.02, -0.003, 0.001)),
    HarmonicForceEngine(ids=[ids[2]], A=(0.05, 0.03, 0.02), f=(40, 65.5, 120), fi=(0.3, 0, 1.1)),
    ForceEngine(ids=[ids[3], 99], force=(-0.01, 0, 0)),
    NewtonIntegrator(damping=0.1, gravity=(0, 0, -9.81)),
]
O.dt = 2e-5

ryade_record.record('force_engines', steps=3000)
ryade_record.finish()
