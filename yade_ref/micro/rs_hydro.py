# HydroForceEngine.action (pkg/common/HydroForceEngine.cpp): drag (Dallavalle, Richardson-Zaki exponent
# expoRZ on the cell's phiPart), lift from the fluid velocity difference across the particle, buoyancy
# (streamwise gravity dropped with steadyFlow), convective acceleration. Six FrictMat spheres of three sizes
# in a 40-cell mesh (deltaZ 1 mm above zRef) with a log-like vxFluid profile, a phiPart profile, per-body
# fluctuations vFluctX/Y/Z and a convAcc profile; gravity tilted; they sediment onto a fixed floor sphere
# bed and one leaves the mesh from above (no force there). Run: yade -n -x yade_ref/micro/rs_hydro.py
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
O.materials.append(FrictMat(young=5e6, poisson=0.3, density=2500, frictionAngle=0.4, label='m'))
n, dz = 40, 1e-3
g = Vector3(0.5, 0, -9.81)
floor = [O.bodies.append(sphere((0.004 * i, 0, 0.001), 0.002, fixed=True)) for i in range(5)]
moving = []
for k, (x, z, r) in enumerate([(0.002, 0.010, 0.0015), (0.006, 0.020, 0.002), (0.010, 0.030, 0.0025),
                                (0.014, 0.015, 0.001), (0.004, 0.036, 0.002), (0.008, 0.0405, 0.001)]):
    b = O.bodies.append(sphere((x, 0.001 * k, z), r))
    O.bodies[b].state.vel = (0.01 * k, -0.005, 0.02 if k == 5 else 0)
    moving.append(b)
hydro = HydroForceEngine(densFluid=1000, viscoDyn=1e-3, zRef=0, gravity=g, deltaZ=dz, nCell=n, expoRZ=3.1, lift=True,
                         Cl=0.2, convAccOption=True, steadyFlow=True, ids=moving + [floor[0]], label='hydro')
hydro.initialization()
hydro.vxFluid = [0.05 * math.log(1 + i) for i in range(n + 1)]
hydro.phiPart = [0.5 * math.exp(-i / 8.0) for i in range(n)]
hydro.convAcc = [1e-4 * (i % 7) for i in range(n)]
nb = len(O.bodies)
hydro.vFluctX = [0.001 * ((3 * i) % 5) for i in range(nb)]
hydro.vFluctY = [-0.0005 * (i % 3) for i in range(nb)]
hydro.vFluctZ = [0.0007 * ((2 * i) % 3) for i in range(nb)]
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    hydro,
    NewtonIntegrator(damping=0.0, gravity=g),
]
O.dt = 1e-5

ryade_record.record('rs_hydro', steps=3000)
ryade_record.finish()
