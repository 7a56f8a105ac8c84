# Grid case G5b (rolling resistance, incremental form; the recipe of grid-pid-api.md 2.1): two
# CohFrictMat spheres (r = 1.5 cm, isCohesive=False,
# momentRotationLaw=True, alphaKr = alphaKtw = 0.5, etaRoll = etaTwist = 0.5): sphere A rests on a fixed
# Box floor (FrictMat), sphere B sits on top of A (1 mm off-axis) and starts spinning with
# angVel (0, 15, 10) rad/s (bending about y, twist about the vertical contact normal); gravity, no damping.
# Ig2_Sphere_Sphere_ScGeom6D + Ip2_CohFrictMat_CohFrictMat_CohFrictPhys +
# Law2_ScGeom6D_CohFrictPhys_CohesionMoment(always_use_moment_law=True, useIncrementalForm=True):
# moment_bending and moment_twist updated incrementally from (angVel2 - angVel1) * dt (rotated with
# the contact),
# scaled down to maxRollPl |Fn| and maxTwistPl |Fn| (maxRollPl = maxTwistPl = 0.5 * 0.015); no warning
# (the law warns only for the total form). Same scene as rolling.py otherwise.
# Sphere A - floor: Ig2_Box_Sphere_ScGeom + Ip2_FrictMat_FrictMat_FrictPhys (FrictMat vs CohFrictMat
# falls back to the FrictMat functor) + Law2_ScGeom_FrictPhys_CundallStrack.
# Run: yade -n -x yade_ref/micro_grid/rolling_inc.py [OUTDIR]
import os, sys

RYADE_ROLLING_INCREMENTAL = True
exec(compile(open(os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), 'rolling.py')).read(), 'rolling.py', 'exec'))
