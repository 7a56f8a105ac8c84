# TriaxialCompressionEngine (pkg/dem/TriaxialCompressionEngine.cpp): the TriaxialStressController under its
# state machine. 48 spheres (makeCloud of 150 at porosity 0.95 fits 48, seed 7) in six aabbWalls: isotropic compaction by the walls to
# sigmaIsoCompaction -20 kPa until stable (StabilityCriterion 0.02 checked every testEquilibriumInterval 20),
# unloading to sigmaLateralConfinement -10 kPa, then confined loading: top and bottom walls driven at a
# strain rate converging to strainRate (0.5), lateral walls servoed to -10 kPa; frictionAngleDegree 20
# re-assigns the friction of the materials and live contacts at the transitions (Shop::setContactFriction).
# noFiles=True (ryade cannot write YADE's snapshot files). Run: yade -n -x yade_ref/micro/rs_triax_compression.py
import math, os, sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), '..', 'lib'))
import ryade_record
from yade import *

O.reset()
young = 5e6
O.materials.append(FrictMat(young=young, poisson=0.5, frictionAngle=math.radians(30), density=2600, label='spheres'))
O.materials.append(FrictMat(young=young, poisson=0.5, frictionAngle=0, density=0, label='walls'))
mn, mx = Vector3(0, 0, 0), Vector3(0.1, 0.1, 0.1)
walls = O.bodies.append(utils.aabbWalls([mn, mx], thickness=0.002, material='walls'))
sp = pack.SpherePack()
sp.makeCloud(mn, mx, 0.009, 0.3, 150, False, 0.95, seed=7)
O.bodies.append([utils.sphere(c, r, material='spheres') for c, r in sp])
triax = TriaxialCompressionEngine(wall_left_id=walls[0], wall_right_id=walls[1], wall_bottom_id=walls[2],
                                  wall_top_id=walls[3], wall_back_id=walls[4], wall_front_id=walls[5],
                                  thickness=0.002, internalCompaction=False, sigmaIsoCompaction=-20e3,
                                  sigmaLateralConfinement=-10e3, max_vel=1, strainRate=0.5, StabilityCriterion=0.02,
                                  frictionAngleDegree=20, noFiles=True)
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Box_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Box_Sphere_ScGeom()],
                    [Ip2_FrictMat_FrictMat_FrictPhys()],
                    [Law2_ScGeom_FrictPhys_CundallStrack()]),
    GlobalStiffnessTimeStepper(active=1, timeStepUpdateInterval=100, timestepSafetyCoefficient=0.8),
    triax,
    NewtonIntegrator(damping=0.4),
]
seen = {}


def hook(step):
    s = triax.currentState
    if s not in seen:
        seen[s] = step
        print('[rs_triax_compression] state %d at step %d' % (s, step))


def final():
    if 3 not in seen:
        return 'the loading state (3) was not reached'
    return None


# a digest scene (golden/FORMAT.md): every step's SHA-256 of all values, full rows at the transitions
ryade_record.record('rs_triax_compression', steps=6000, step_hook=hook, final_check=final, micro_digest=True,
                    keep_steps=[0, 1, 2, 300, 301, 302, 760, 761, 762, 6000])
ryade_record.finish()
