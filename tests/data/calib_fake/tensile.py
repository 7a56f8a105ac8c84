# Stand-in for yade_ref/calibration/tensile.py (tests/calibrate.rs): a linear rib, secant = kn_scale * 12.566 kN,
# written in tensile.py's output format (CSV + summary JSON), without any simulation.
import json, sys
p = {"kn_scale": 1.0, "secant_strains": [0.02, 0.05]}
for a in sys.argv[1:]:
    k, v = a.split("=", 1)
    try:
        v = json.loads(v)
    except ValueError:
        pass
    p[k] = v
S = p["kn_scale"] * 12.566370614359172
with open(p["out"], "w") as f:
    f.write("strain,force_N,step,time_s,elongation_m\n")
    for i in range(11):
        e = 0.01 * i
        f.write("%r,%r,%d,0,0\n" % (e, S * 1e3 * e, i))
with open(p["summary"], "w") as f:
    json.dump({"secant_stiffness_kN": {"%g" % e: S for e in p["secant_strains"]}, "params": p}, f)
