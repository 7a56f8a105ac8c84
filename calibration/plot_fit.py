# Plots of a `compat calibrate` result (embedded in the compat binary; also runs standalone):
#   python3 calibration/plot_fit.py OUTDIR/calibration.json
# Writes next to the result file:
#   tensile_fit.png     force vs strain of the single-rib test at kn_scale = 1 and at the fitted kn_scale,
#                       with the target points F_i = T_i * eps_i
#   cantilever_fit.png  tip angle vs overhang of every cantilever evaluation (one curve per k), the target
#                       angle line and the target overhang
# Prints "wrote NAME" per file.
import csv, json, os, sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

res_path = sys.argv[1]
d = os.path.dirname(os.path.abspath(res_path))
with open(res_path) as f:
    res = json.load(f)
tg = res["targets"]


def curve(name):
    eps, F = [], []
    with open(os.path.join(d, name)) as f:
        for row in csv.DictReader(f):
            eps.append(float(row["strain"]) * 100)
            F.append(float(row["force_N"]) / 1e3)
    return eps, F


s1 = res.get("step1", {})
if "fitted_files" in s1:
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    e, F = curve(s1["baseline_files"][0])
    ax.plot(e, F, "-", color="0.5", label="model, kn_scale = 1")
    e, F = curve(s1["fitted_files"][0])
    ax.plot(e, F, "-", color="C0", label="model, fitted kn_scale = %.6g" % s1["kn_scale"])
    ax.plot([x * 100 for x in tg["strains"]], [t * x for t, x in zip(tg["secant_kN"], tg["strains"])],
            "o", color="C3", mfc="none", ms=9, label="targets (secant x strain)")
    ax.set_xlabel("strain [%]")
    ax.set_ylabel("force per rib [kN]")
    ax.set_title("single-rib tensile test (ASTM D6637), engine %s" % res["engine"])
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(d, "tensile_fit.png"), dpi=110)
    print("wrote tensile_fit.png")

s2 = res.get("step2", {})
ev = s2.get("evaluations", [])
if ev:
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    target_deg = tg["target_angle_deg"]
    for i, e in enumerate(ev):
        with open(os.path.join(d, e["file"])) as f:
            cj = json.load(f)
        pts = sorted((p["Lo"] * 1e3, p["angle_deg"]) for p in cj["points"])
        c = "C%d" % (i % 10)
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", color=c, ms=4,
                label="k = %.5g: Lo45 = %.1f mm" % (e["k"], e["lo45_mm"]))
        ax.plot([e["lo45_mm"]], [target_deg], "x", color=c, ms=9)
    ax.axhline(target_deg, color="k", lw=0.8, ls="--", label="%g deg" % target_deg)
    ax.axvline(tg["overhang_45deg_mm"], color="C3", lw=0.8, ls=":",
               label="target overhang %.1f mm" % tg["overhang_45deg_mm"])
    ax.set_xlabel("overhang Lo [mm]")
    ax.set_ylabel("tip angle below horizontal [deg]")
    ax.set_title("cantilever test (ASTM D7748), kr_scale = k, engine %s" % res["engine"])
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(d, "cantilever_fit.png"), dpi=110)
    print("wrote cantilever_fit.png")
