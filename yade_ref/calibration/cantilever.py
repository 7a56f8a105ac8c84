# ASTM D7748 flexural rigidity (cantilever) test, replicated numerically (seed-paper.txt 2.1: "A section
# of the geogrid spanning two triangular openings in width was hung from a surface ... bending and torsional
# stiffness were then adjusted until the tip of the geogrid strip formed a 45 deg angle with the horizontal").
#
# Strip (study.md lattice, shifted so that the support edge is x = 0): junction (i,j) at
#   x = (i + (j mod 2)/2) a,  y = j a sqrt(3)/2,  z = 0,   j = 0 .. rows-1 (rows = 3: two apertures wide,
# i.e. two bands of triangles across the width, width a sqrt(3) = 0.104 m), i such that 0 <= x <= Lo.
# Each junction is linked to (i+1, j) and to its two neighbours in row j+1; every rib gets its articulated
# mid-rib node (two gridConnections of length a/2; moments act at every node, the mid node included).
# Ribs are kept when both junctions lie in [0, Lo]; at the support edge the odd-row ribs that cross x = 0
# have their mid node exactly on x = 0, and their forward half rib is kept (clamped stub). The tip end is
# cut clean (no dangling half ribs).
#
# Support: every node on the edge line x = 0 (even-row junctions, odd-row mid-rib nodes) is fixed (all six
# DOFs): the part of the specimen on the platform is held flat up to the edge (as under the standard's
# slide) and is not modelled further. Facets cannot carry a grid (Facet-GridConnection contacts dispatch to
# Ig2_Facet_Sphere_ScGeom and the force is lost, grid-pid-api.md 1.13-2), hence the clamp. Because x = 0
# must be a clean cut of the lattice (a line through nodes only), the overhang takes discrete values
# Lo = m * lo_step, lo_step a multiple of a/2. Default lo_step = a: the tip is then always the even-row
# junction column (rows 0 and 2: the two corners of a square-cut strip). With lo_step = a/2 the odd
# multiples give a pointed tip (the odd-row junction alone), a slightly different structure: the angle
# sequence zigzags by ~0.3 deg between even and odd multiples, so mixing them is avoided by default.
#
# Loading: gravity g on the node masses (half-rib volumes * rho, from gridConnection()), applied at once.
# Settling: NewtonIntegrator local damping plus kinetic damping (a PyRunner every kd_period steps zeroes
# all velocities as soon as the kinetic energy drops, i.e. at each kinetic-energy peak: dynamic
# relaxation). Local damping alone (0.8) needs ~3x more steps (the strip swings like a pendulum).
# Converged when the largest kinetic energy seen in the last chunk of steps is below
# ke_rel * W * Lo (W = weight of the free nodes).
#
# Tip angle = angle below the horizontal of the chord from the support edge (x = 0, z = 0) to the mean
# position of the tip nodes (the junctions with the largest x).
#
# Modes: single (one Lo = lo), sweep (every Lo in lo_list), bisect (default): bracket [lo_min, lo_max],
# expanded if needed (lo_min halved / lo_max * 1.5), then bisection on m until the bracket is one lo_step
# wide. With split = "loglog" (default) the split point is the root of the (log Lo, log angle) line through
# the bracket ends, rounded to the lattice and kept strictly inside the bracket (regula falsi on the
# lattice; it falls back to the midpoint when it has not closed the bracket after ceil(log2(width))+1
# splits); split = "midpoint" is plain bisection. The 45 deg overhang is then interpolated: with
# interp = "quadratic" (default) one more lattice point is evaluated next to the bracket (on the side of
# the root) and Lo(angle) is the quadratic through the three adjacent points; "loglog" (linear in
# (log Lo, log angle)) and "linear" use the bracket only. All three are reported. On the scale-1 strip the
# bracket-only interpolations are ~1 mm off (angle(Lo) bends over towards 90 deg); the quadratic agrees
# with a cubic through four points to ~0.1 mm. Any lo_list points are evaluated first and reused.
#
# Run:  yade -n -x yade_ref/calibration/cantilever.py [params.json] [key=value ...]
# Default output: golden/calibration/cantilever.json
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
    "rows": 3,              # junction rows across the width (3 = two apertures)
    "lo_step": None,        # overhang resolution [m]; None = a (must be a multiple of a/2)
    "gravity": 9.81,
    "damping": 0.2,         # NewtonIntegrator local damping
    "kinetic_damping": True,
    "kd_period": 10,        # steps between kinetic-energy checks
    "ke_rel": 1e-10,        # convergence: max KE in the last chunk < ke_rel * W * Lo
    "chunk": 2000,          # steps between convergence checks
    "max_steps": 600000,    # per overhang
    "mode": "bisect",       # single | sweep | bisect
    "lo": 0.6,              # single
    "lo_list": [],          # sweep (also evaluated first in bisect mode)
    "lo_min": 0.6, "lo_max": 1.02,  # bisect: initial bracket (snapped inwards to the lattice)
    "split": "loglog",      # bisect: loglog (interpolated split point) | midpoint
    "interp": "quadratic",  # bisect: final interpolation: quadratic (3 adjacent points) | loglog | linear
    "lo_limit": 3.0,        # bisect: never go beyond this overhang when expanding the bracket
    "target_deg": 45.0,
    "out": os.path.join(GOLDEN, 'cantilever.json'),
})


def build(p, m):
    """Strip with overhang Lo = m * lo_step. Returns (node ids, fixed ids, tip ids, info)."""
    a, rows = p["a"], p["rows"]
    h = a * math.sqrt(3) / 2
    step = p["lo_step"]
    half = int(round(2 * step / a))             # lo_step in units of a/2
    n2 = m * half                                # Lo in units of a/2
    Lo = n2 * a / 2
    eps = 1e-9 * a
    # junctions: x = (i + (j%2)/2) a in [0, Lo]  <=>  2i + (j%2) in [0, n2]
    J = {}
    for j in range(rows):
        for i in range(0, n2 // 2 + 1):
            k2 = 2 * i + (j % 2)
            if 0 <= k2 <= n2:
                J[(i, j)] = ((k2 * a / 2), j * h, 0.0)
    ribs = []                                   # (junction key 1, junction key 2); key None = outside
    for (i, j) in sorted(J, key=lambda k: (k[1], k[0])):
        ribs.append(((i, j), (i + 1, j)))
        if j + 1 < rows:
            nb = [(i - 1, j + 1), (i, j + 1)] if j % 2 == 0 else [(i, j + 1), (i + 1, j + 1)]
            for k in nb:
                ribs.append(((i, j), k))
    # clamped stubs: odd-row x-ribs crossing x = 0 have their mid node on x = 0
    for j in range(1, rows, 2):
        if (0, j) in J:
            ribs.append(((-1, j), (0, j)))
    mat = cc.setup_scene(p, gravity=(0, 0, -p["gravity"]),
                         extra_engines=[PyRunner(command='cantilever_kd()', iterPeriod=p["kd_period"], label='kd')])
    ids = {}
    for key in sorted(J, key=lambda k: (J[k][0], k[1])):
        pos = J[key]
        ids[key] = O.bodies.append(gridNode(pos, p["r"], fixed=abs(pos[0]) < eps, material=mat))
    pending = []
    for k1, k2 in ribs:
        in1, in2 = k1 in J, k2 in J
        if not in2 and not in1:
            continue
        if in1 and in2:
            p1, p2 = J[k1], J[k2]
        elif in2 and not in1:
            # only the clamp stubs: the other junction is behind the edge
            if k1[0] >= 0 or k2 != (0, k1[1]):
                continue
            p2 = J[k2]
            p1 = (p2[0] - a, p2[1], p2[2])
        else:
            continue                            # partner beyond the tip: cut clean
        mid = ((p1[0] + p2[0]) / 2, (p1[1] + p2[1]) / 2, 0.0)
        pending.append((k1 if in1 else None, k2, mid))
    conns = []
    for k1, k2, mid in pending:
        mid_id = O.bodies.append(gridNode(mid, p["r"], fixed=abs(mid[0]) < eps, material=mat))
        if k1 is not None:
            conns.append((ids[k1], mid_id))
        conns.append((mid_id, ids[k2]))
    for i1, i2 in conns:
        cc.connect(i1, i2, p, mat)
    nodes = [b.id for b in O.bodies if isinstance(b.shape, GridNode)]
    fixed = [i for i in nodes if O.bodies[i].state.blockedDOFs == 'xyzXYZ']
    free = [i for i in nodes if i not in fixed]
    xmax = max(J[k][0] for k in J)
    tip = [ids[k] for k in sorted(J) if abs(J[k][0] - xmax) < eps]
    for i in nodes:
        assert len(O.bodies[i].shape.getConnections()) >= 1, 'orphan node %d' % i
    info = {"m": m, "Lo": Lo, "junctions": len(J), "nodes": len(nodes), "fixed_nodes": len(fixed),
            "connections": len(conns), "tip_nodes": len(tip),
            "mass_free_kg": sum(O.bodies[i].state.mass for i in free)}
    return nodes, fixed, free, tip, info


def evaluate(p, m):
    nodes, fixed, free, tip, info = build(p, m)
    Lo = info["Lo"]
    O.dt = p["dt_factor"] * cc.critical_dt()
    W = info["mass_free_kg"] * p["gravity"]
    ke_tol = p["ke_rel"] * W * Lo
    st = {"prev": 0.0, "resets": 0, "chunk_max": 0.0, "last_peak": None}
    bodies = [O.bodies[i] for i in free]

    def kd():
        ke = utils.kineticEnergy()
        st["chunk_max"] = max(st["chunk_max"], ke)
        if p["kinetic_damping"] and ke < st["prev"]:
            for b in bodies:
                b.state.vel = Vector3.Zero
                b.state.angVel = Vector3.Zero
            st["last_peak"] = st["prev"]
            st["resets"] += 1
            st["prev"] = 0.0
        else:
            st["prev"] = ke
    builtins.cantilever_kd = kd

    def tip_angle():
        x = sum(O.bodies[i].state.pos[0] for i in tip) / len(tip)
        y = sum(O.bodies[i].state.pos[1] for i in tip) / len(tip)
        z = sum(O.bodies[i].state.pos[2] for i in tip) / len(tip)
        return math.degrees(math.atan2(-z, x)), (x, y, z)

    t0 = time.time()
    converged = False
    history = []
    while O.iter < p["max_steps"]:
        st["chunk_max"] = 0.0
        O.run(p["chunk"], True)
        ang, _ = tip_angle()
        history.append(ang)
        if O.iter >= 2 * p["chunk"] and st["chunk_max"] < ke_tol:
            converged = True
            break
    ang, tpos = tip_angle()
    assert cc.count_bonds() == len(O.interactions), 'unexpected interactions'
    res = dict(info)
    res.update({"angle_deg": ang, "tip_pos": list(tpos), "converged": converged, "steps": O.iter,
                "sim_time_s": O.time, "dt": O.dt, "kinetic_resets": st["resets"],
                "ke_last_chunk_max_J": st["chunk_max"], "ke_tol_J": ke_tol,
                "angle_change_last_chunk_deg": (history[-1] - history[-2]) if len(history) > 1 else None,
                "bonds": cc.count_bonds()})
    wall = time.time() - t0
    print('Lo = %.4f m (m=%d, %d nodes): angle %.6f deg, %d steps, converged %s, %.1f s'
          % (Lo, m, info["nodes"], ang, O.iter, converged, wall))
    sys.stdout.flush()
    return res


p = cc.parse_params(DEFAULTS)
a = p["a"]
if p["lo_step"] is None:
    p["lo_step"] = a
assert abs(2 * p["lo_step"] / a - round(2 * p["lo_step"] / a)) < 1e-9 and p["lo_step"] > 0, 'lo_step must be a multiple of a/2'
step = p["lo_step"]
t_start = time.time()
cache = {}


def ev(m):
    if m not in cache:
        cache[m] = evaluate(p, m)
    return cache[m]["angle_deg"]


def snap(lo, up):
    x = lo / step
    return max(1, int(math.ceil(x - 1e-9)) if up else int(math.floor(x + 1e-9)))


out = {"test": "ASTM D7748 cantilever (strip two apertures wide, clamped at the edge), YADE 2023.02a",
       "script": "yade_ref/calibration/cantilever.py",
       "params": {k: v for k, v in p.items() if k != "out"}}
d = cc.bond_defaults(p, a / 2)
out["gridConnection_defaults_half_rib"] = d
out["scaled_half_rib"] = {"kn": d["kn"] * p["kn_scale"], "ks": d["ks"] * p["ks_scale"],
                          "kr": d["kr"] * p["kr_scale"], "ktw": d["ktw"] * p["ktw_scale"]}
# model mass per plan area of the infinite lattice: 3 ribs per junction, a^2 sqrt(3)/2 per junction
out["model_mass_per_area_kg_m2"] = 3 * a * math.pi * p["r"] ** 2 * p["rho"] / (a * a * math.sqrt(3) / 2)

for lo in p["lo_list"]:
    ev(snap(lo, False) if abs(lo / step - round(lo / step)) > 1e-9 else int(round(lo / step)))
if p["mode"] == "single":
    ev(int(round(p["lo"] / step)))
elif p["mode"] == "bisect":
    tgt = p["target_deg"]
    mlo, mhi = snap(p["lo_min"], True), snap(p["lo_max"], False)
    mlim = snap(p["lo_limit"], False)
    while ev(mlo) >= tgt and mlo > 1:
        mhi, mlo = mlo, max(1, mlo // 2)
    while ev(mhi) < tgt and mhi < mlim:
        mlo, mhi = mhi, min(mlim, int(math.ceil(mhi * 1.5)))
    ok = ev(mlo) < tgt <= ev(mhi)
    if ok:
        nsplit, maxsplit = 0, int(math.ceil(math.log2(max(2, mhi - mlo)))) + 1
        while mhi - mlo > 1:
            mid = (mlo + mhi) // 2
            if p["split"] == "loglog" and nsplit < maxsplit:
                L1, L2, a1, a2 = cache[mlo]["Lo"], cache[mhi]["Lo"], cache[mlo]["angle_deg"], cache[mhi]["angle_deg"]
                if a1 > 0:
                    lr = math.exp(math.log(L1) + (math.log(tgt) - math.log(a1)) * (math.log(L2) - math.log(L1))
                                  / (math.log(a2) - math.log(a1)))
                    mid = min(mhi - 1, max(mlo + 1, int(round(lr / step))))
            nsplit += 1
            if ev(mid) < tgt:
                mlo = mid
            else:
                mhi = mid
        # tighten with any cached points (from lo_list)
        for m in sorted(cache):
            if m > mlo and cache[m]["angle_deg"] < tgt:
                mlo = m
        for m in sorted(cache, reverse=True):
            if m < mhi and cache[m]["angle_deg"] >= tgt:
                mhi = m
        L1, L2 = cache[mlo]["Lo"], cache[mhi]["Lo"]
        a1, a2 = cache[mlo]["angle_deg"], cache[mhi]["angle_deg"]
        lo45_log = math.exp(math.log(L1) + (math.log(tgt) - math.log(a1)) * (math.log(L2) - math.log(L1))
                            / (math.log(a2) - math.log(a1)))
        lo45_lin = L1 + (tgt - a1) * (L2 - L1) / (a2 - a1)
        res = {"target_deg": tgt, "interp": p["interp"],
               "bracket": [{"Lo": L1, "angle_deg": a1}, {"Lo": L2, "angle_deg": a2}],
               "overhang_loglog_m": lo45_log, "overhang_linear_m": lo45_lin}
        lo45 = {"loglog": lo45_log, "linear": lo45_lin}.get(p["interp"])
        if p["interp"] == "quadratic":
            m3 = mlo - 1 if (lo45_log - L1 < L2 - lo45_log and mlo > 1) else mhi + 1
            ev(m3)
            pts = [(cache[m]["angle_deg"], cache[m]["Lo"]) for m in sorted((mlo, mhi, m3))]
            lo45 = 0.0
            for i, (xi, yi) in enumerate(pts):
                w = 1.0
                for j, (xj, yj) in enumerate(pts):
                    if j != i:
                        w *= (tgt - xj) / (xi - xj)
                lo45 += w * yi
            res["overhang_quadratic_m"] = lo45
            res["quadratic_points"] = [{"Lo": y, "angle_deg": x} for x, y in pts]
        res["overhang_m"] = lo45
        res["overhang_mm"] = lo45 * 1e3
        res["all_converged"] = all(c["converged"] for c in cache.values())
        out["result"] = res
        print('overhang at %g deg: %.6f m (%s; bracket %.4f-%.4f m, %.4f-%.4f deg; loglog %.6f, linear %.6f m)'
              % (tgt, lo45, p["interp"], L1, L2, a1, a2, lo45_log, lo45_lin))
    else:
        out["result"] = {"target_deg": tgt, "overhang_m": None,
                         "error": "target not bracketed within [step, lo_limit]"}
        print('target not bracketed')
out["points"] = [cache[m] for m in sorted(cache)]
cc.write_json(p["out"], out)
print('wrote', p["out"], '(%d overhangs, wall %.1f s)' % (len(cache), time.time() - t_start))
