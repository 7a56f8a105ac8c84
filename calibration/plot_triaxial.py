# Plot of a `compat calibrate --triaxial` run (embedded in the compat binary; also runs standalone):
#   python3 calibration/plot_triaxial.py OUTDIR
# Reads OUTDIR/triaxial.csv (one curve per variant) and writes OUTDIR/triaxial.png: stress ratio q/p (top) and
# volumetric strain (bottom, compression positive) against axial strain, one line per variant, with the peak
# marked. Prints "wrote NAME".
import csv, json, os, sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

d = sys.argv[1]
curves = {}
with open(os.path.join(d, "triaxial.csv")) as f:
    for row in csv.DictReader(f):
        c = curves.setdefault(row["variant"], {"ea": [], "qp": [], "ev": []})
        c["ea"].append(float(row["eps_a"]) * 100)
        c["qp"].append(float(row["q_over_p"]))
        c["ev"].append(float(row["eps_v"]) * 100)

fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7.0, 8.0), sharex=True)
for k, (v, c) in enumerate(curves.items()):
    col = "C%d" % (k % 10)
    label = v
    sp = os.path.join(d, "runs", "%s.summary.json" % v)
    if os.path.exists(sp):
        with open(sp) as f:
            s = json.load(f)
        label = "%s: phi_peak %.1f, phi_cv %.1f, psi_max %.1f deg, n0 %.3f" % (
            v, s["phi_peak_deg"], s["phi_cv_deg"], s["psi_max_deg"], s["porosity_0"])
        ax1.plot([s["eps_a_peak"] * 100], [s["q_over_p_peak"]], "o", color=col, mfc="none")
    ax1.plot(c["ea"], c["qp"], "-", color=col, lw=1.2, label=label)
    ax2.plot(c["ea"], c["ev"], "-", color=col, lw=1.2)
ax1.set_ylabel("stress ratio q/p")
ax1.set_title("periodic drained triaxial test (PeriTriaxController), p0 = lateral stress")
ax1.legend(fontsize=7, loc="lower right")
ax1.grid(alpha=0.3)
ax2.set_xlabel("axial strain [%] (logarithmic)")
ax2.set_ylabel("volumetric strain [%] (compression > 0)")
ax2.axhline(0, color="0.6", lw=0.8)
ax2.grid(alpha=0.3)
fig.tight_layout()
out = os.path.join(d, "triaxial.png")
fig.savefig(out, dpi=110)
print("wrote triaxial.png")
