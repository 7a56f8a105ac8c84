# Stand-in for yade_ref/calibration/cantilever.py (tests/calibrate.rs): Lo45(k) = 817.6 mm * k^0.3 with a
# small lattice-like ripple, in cantilever.py's output format, without any simulation. The exponent differs
# from the beam scaling's 1/3 on purpose (the fit must not rely on it).
import json, math, sys
p = {"kr_scale": 1.0}
for a in sys.argv[1:]:
    k, v = a.split("=", 1)
    try:
        v = json.loads(v)
    except ValueError:
        pass
    p[k] = v
k = p["kr_scale"]
lo = 0.8176 * k ** 0.3 * (1 + 2e-4 * math.sin(40 * math.log(k)))
pts = [{"Lo": L, "angle_deg": 45 * (L / lo) ** 1.5} for L in (lo - 0.03, lo + 0.03)]
out = {"result": {"overhang_m": lo, "overhang_mm": lo * 1e3, "overhang_loglog_m": lo + 1e-3,
                  "overhang_linear_m": lo + 8e-4, "all_converged": True}, "points": pts}
with open(p["out"], "w") as f:
    json.dump(out, f)
print("Lo45 = %.6f m at kr_scale %r" % (lo, k))
