# ASTM D6637 single-rib tensile test, replicated numerically (seed-paper.txt 2.1: "a series of
# simulations in which a single rib was axially strained ... adjusting the axial stiffness").
#
# One rib of length a between two junction nodes J1 (x=0) and J2 (x=a) with the articulated mid-rib node M
# (x=a/2): J1-M-J2, two gridConnections (half ribs of length a/2). J1 is fixed (all DOFs), J2 is fixed
# and moved along the rib axis (+x) at the constant speed v = rate * a, M is free. No gravity.
# Recorded every step, in a PyRunner placed before NewtonIntegrator (forces and positions of the same step):
#   strain = (x_J2 - x_J1 - a) / a,  force = O.forces.f(J1) . x  (reaction on the fixed J1, tension > 0).
# Secant stiffness S(eps) = F(eps) / eps, F linearly interpolated between the two steps around eps.
#
# Strain rate: the standard's 10 %/min (1.7e-3 /s) would need ~6e6 steps to reach 10 %. The default
# 1 /s reaches 2 % after 0.02 s, i.e. ~150 periods of the mid-node's axial mode (1.3e-4 s at the defaults).
# Start-up: with affine_start (default) M starts with the velocity of the homogeneous strain field (v/2),
# so no oscillation is excited and the response is quasi-static at any rate (inertia of M: zero net force).
# With affine_start=false (M at rest while J2 jumps to v) M oscillates about the static solution for ever:
# NewtonIntegrator's local damping does NOT damp it, because M's velocity never changes sign (the Cundall
# damping is not Galilean invariant); the force then carries a +-0.25 N ripple at rate 1 /s (1e-3 of the
# force at 2 %), proportional to the rate. The script checks quasi-staticity by re-running at rate/2
# (check_half_rate) and reports the relative change of both secants.
#
# Bonds: normalCohesion = shearCohesion = 1e100, so -Fn never exceeds normalAdhesion: no normal plasticity,
# hence no erase through the default unpMax = 0 (grid-pid-api.md 1.8 step 4). The script checks that both
# bonds still exist at the end.
#
# Run:  yade -n -x yade_ref/calibration/tensile.py [params.json] [key=value ...]
# Defaults write golden/calibration/tensile.csv and golden/calibration/tensile.summary.json.
import json, math, os, sys, time
sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))
import calib_common as cc
from yade import *
from yade.gridpfacet import gridNode
import builtins

HERE = os.path.dirname(os.path.abspath(sys.argv[0]))
GOLDEN = os.path.normpath(os.path.join(HERE, '..', '..', 'golden', 'calibration'))

DEFAULTS = dict(cc.COMMON_DEFAULTS)
DEFAULTS.update({
    "damping": 0.0,          # local damping (acts on M only; J1, J2 are fixed; ineffective here, see above)
    "affine_start": True,    # M starts at v/2 (homogeneous strain rate), no start-up oscillation
    "rate": 1.0,             # strain rate [1/s]
    "max_strain": 0.10,      # stop when this strain is reached
    "csv_dstrain": 0.0005,   # strain increment between CSV rows (every step is used for the secants)
    "secant_strains": [0.02, 0.05],
    "check_half_rate": True, # re-run at rate/2 and report the relative change of the secants
    "out": os.path.join(GOLDEN, 'tensile.csv'),
    "summary": os.path.join(GOLDEN, 'tensile.summary.json'),
})


def run(p, rate):
    mat = cc.setup_scene(p, gravity=(0, 0, 0), extra_engines=[PyRunner(command='tensile_rec()', iterPeriod=1, label='rec')])
    a = p["a"]
    j1 = O.bodies.append(gridNode((0, 0, 0), p["r"], fixed=True, material=mat))
    m = O.bodies.append(gridNode((a / 2, 0, 0), p["r"], fixed=False, material=mat))
    j2 = O.bodies.append(gridNode((a, 0, 0), p["r"], fixed=True, material=mat))
    cc.connect(j1, m, p, mat)
    cc.connect(m, j2, p, mat)
    dtc = cc.critical_dt()
    O.dt = p["dt_factor"] * dtc
    v = rate * a
    O.bodies[j2].state.vel = (v, 0, 0)
    if p["affine_start"]:
        O.bodies[m].state.vel = (v / 2, 0, 0)
    rows = []

    def rec():
        x1 = O.bodies[j1].state.pos[0]
        x2 = O.bodies[j2].state.pos[0]
        rows.append((O.iter, O.time, x2 - x1 - a, (x2 - x1 - a) / a, O.forces.f(j1)[0]))
    builtins.tensile_rec = rec
    nsteps = int(math.ceil(p["max_strain"] / (rate * O.dt))) + 1
    O.run(nsteps, True)
    assert cc.count_bonds() == 2, 'a bond broke'
    ph = O.interactions[j1, m].phys
    info = {"dt": O.dt, "dt_crit_estimate": dtc, "steps": nsteps, "velocity": v,
            "kn_half_rib": ph.kn, "ks_half_rib": ph.ks, "kr_half_rib": ph.kr, "ktw_half_rib": ph.ktw,
            "mass_mid_node": O.bodies[m].state.mass, "bonds_at_end": cc.count_bonds(),
            "unp_at_end": ph.unp, "cohesionBroken": ph.cohesionBroken}
    return rows, info


def force_at(rows, eps):
    for k in range(1, len(rows)):
        e0, f0 = rows[k - 1][3], rows[k - 1][4]
        e1, f1 = rows[k][3], rows[k][4]
        if e0 <= eps <= e1 and e1 > e0:
            return f0 + (f1 - f0) * (eps - e0) / (e1 - e0)
    raise ValueError('strain %g not reached' % eps)


def secants(rows, strains):
    return {"%g" % e: force_at(rows, e) / e for e in strains}


p = cc.parse_params(DEFAULTS)
t0 = time.time()
rows, info = run(p, p["rate"])
sec = secants(rows, p["secant_strains"])
t1 = time.time()

os.makedirs(os.path.dirname(os.path.abspath(p["out"])), exist_ok=True)
with open(p["out"], 'w') as f:
    f.write('strain,force_N,step,time_s,elongation_m\n')
    nxt = 0.0
    for k, (it, t, du, eps, F) in enumerate(rows):
        if eps >= nxt - 1e-15 or k == len(rows) - 1:
            f.write('%.17g,%.17g,%d,%.17g,%.17g\n' % (eps, F, it, t, du))
            while nxt <= eps + 1e-15:
                nxt += p["csv_dstrain"]

L = p["a"]
Ls = L / 2
d = cc.bond_defaults(p, Ls)
EA = p["E"] * math.pi * p["r"] ** 2
summary = {
    "test": "ASTM D6637 single rib (J1-M-J2), YADE 2023.02a",
    "script": "yade_ref/calibration/tensile.py",
    "params": {k: v for k, v in p.items() if k not in ("out", "summary")},
    "rib_area_m2": math.pi * p["r"] ** 2,
    "secant_stiffness_N": {e: s for e, s in sec.items()},
    "secant_stiffness_kN": {e: s / 1e3 for e, s in sec.items()},
    "force_N": {e: s * float(e) for e, s in sec.items()},
    "expected_secant_N": EA * p["kn_scale"],   # series of two half ribs: (E pi r^2/(a/2)/2) * a = E A
    "gridConnection_defaults_half_rib": d,
    "run": info,
}
if p["check_half_rate"]:
    rows2, info2 = run(p, p["rate"] / 2)
    sec2 = secants(rows2, p["secant_strains"])
    summary["half_rate_check"] = {
        "rate": p["rate"] / 2, "steps": info2["steps"],
        "secant_stiffness_N": sec2,
        "relative_change": {e: (sec2[e] - sec[e]) / sec[e] for e in sec},
    }
cc.write_json(p["summary"], summary)
for e, s in sec.items():
    print('secant stiffness at %s strain: %.6f kN  (force %.6f N)' % (e, s / 1e3, s * float(e)))
if p["check_half_rate"]:
    for e, c in summary["half_rate_check"]["relative_change"].items():
        print('  rate/2 relative change at %s: %.3e' % (e, c))
print('expected E*A*kn_scale = %.6f kN' % (EA * p["kn_scale"] / 1e3))
print('wrote', p["out"], p["summary"])
print('wall time %.2f s (main run %.2f s)' % (time.time() - t0, t1 - t0))
