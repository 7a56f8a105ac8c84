"""Intra-cycle observables of a gap library (issue 20, deliverable 2; an exploration, not used by
`compat gap`):

    python3 yade_ref/gap/intra_cycle.py LIBRARY_DIR     # a library built by compat gap --make-library

Per load cycle, from each run's steps.csv (every 10 steps: filtered pressure, target, piston height):
  area  : hysteresis loop area, the integral of p d(settlement) over the cycle [kPa mm]
  resil : resilient (recovered) settlement, largest settlement - settlement at the cycle's end [mm]
  perm  : permanent settlement of the cycle (the rut increment) [mm]
  track : rms of (filtered - target) pressure [kPa]
Signal of an effect at a strength: mean over seeds of (effect run - baseline run of the same seed), over
the baseline seed-to-seed sd (12 seeds), per cycle 1-4, combined as sqrt(sum z^2). Grading has
specimens of its own: its shift is against the baseline mean. The recovered settlement is small and
skewed in the baseline (sd about its mean), so its Gaussian signal overstates."""
import csv, glob, os, re, statistics as st, sys, math


D = sys.argv[1]
PER = 910 // 10  # samples per cycle: 910 steps at 50 Hz, steps.csv every 10 steps (study.py defaults)

def obs(path):
    rows = [r for r in csv.DictReader(open(path)) if r['phase'] == 'cycle']
    out = []
    for c in range(len(rows) // PER):
        cy = rows[c * PER:(c + 1) * PER]
        p = [float(r['p_filtered_kPa']) for r in cy]
        pt = [float(r['p_target_kPa']) for r in cy]
        z = [float(r['piston_z_m']) for r in cy]
        s = [(z[0] - zz) * 1000 for zz in z]
        area = sum(0.5 * (p[k] + p[k - 1]) * (s[k] - s[k - 1]) for k in range(1, len(p)))
        ks = max(range(len(s)), key=lambda k: s[k])
        resil = s[ks] - s[-1]
        perm = s[-1]
        track = math.sqrt(sum((a - b) ** 2 for a, b in zip(p, pt)) / len(p))
        out.append(dict(area=area, resil=resil, track=track, perm=perm))
    return out

runs = {}
for d in sorted(glob.glob(D + '/*/steps.csv')):
    name = os.path.basename(os.path.dirname(d))
    runs[name] = obs(d)
base = {int(n.split('_s')[1]): o for n, o in runs.items() if n.startswith('base_')}
KEYS = ['perm', 'area', 'resil', 'track']
ncyc = 4
sd = {k: [st.stdev([base[s][c][k] for s in base]) for c in range(ncyc)] for k in KEYS}
mean = {k: [st.mean([base[s][c][k] for s in base]) for c in range(ncyc)] for k in KEYS}
print('baseline (12 seeds), cycles 1-4: mean (sd)')
for k in KEYS:
    print('  %-6s' % k, '  '.join('%.3g (%.2g)' % (mean[k][c], sd[k][c]) for c in range(ncyc)))
groups = {}
for n in runs:
    m = re.match(r'(.+)_(\d+)_s(\d+)$', n)
    if m and not n.startswith('base_'):
        groups.setdefault((m.group(1), int(m.group(2))), {})[int(m.group(3))] = runs[n]
print('\nsignal over one run\'s noise (paired with the baseline of the same seed), cycles 1-4 combined; sign of the cycle-4 shift')
print('%-12s %s' % ('effect_k', '  '.join('%14s' % k for k in KEYS)))
for (e, k), seeds in sorted(groups.items()):
    row = []
    for key in KEYS:
        z2 = 0.0
        last = 0.0
        for c in range(ncyc):
            if e == 'grading':
                d = st.mean([seeds[s][c][key] for s in seeds]) - mean[key][c]
            else:
                d = st.mean([seeds[s][c][key] - base[s][c][key] for s in seeds])
            z2 += (d / sd[key][c]) ** 2
            last = d / sd[key][c]
        row.append('%7.1f (%+5.1f)' % (math.sqrt(z2), last))
    print('%-12s %s' % ('%s_%d' % (e, k), '  '.join(row)))
