# Records SpherePack.makeCloud results from YADE 2023.02a for ryade's bit-for-bit test
# (tests/pack_makecloud.rs).  Run (from anywhere):
#     yade -n -x yade_ref/pack/clouds.py
# For each configuration it writes
#   golden/pack/<name>.json  parameters (ryade CloudParams field names) + returned count, len, cellSize, ...
#   golden/pack/<name>.txt   one sphere per line: "x y z r" with '%.17g' (round-trips every double)
import json, os, sys, time
from yade import pack
import yade
from yade import Vector3, Matrix3

# repository root = three levels above this script (yade passes the script path as sys.argv[0])
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(sys.argv[0]))))
# output directory: first script argument if given, else golden/pack
OUT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, 'golden', 'pack')
os.makedirs(OUT, exist_ok=True)

# name -> keyword arguments of makeCloud (minCorner/maxCorner given as tuples)
CONFIGS = {
    # rMean mode, stochastic radii, stochastic count (ends after 1000 failed tries)
    'stoch_rmean_fuzz': dict(minCorner=(0, 0, 0), maxCorner=(1, 1, 1), rMean=0.08, rRelFuzz=0.2, seed=7),
    # rMean mode without fuzz, stochastic count, negative and unequal box
    'stoch_rmean': dict(minCorner=(-0.5, -0.25, 0.1), maxCorner=(0.5, 0.25, 0.9), rMean=0.06, seed=1),
    # periodic, num (rMean derived from porosity)
    'periodic_num': dict(minCorner=(0, 0, 0), maxCorner=(1, 1, 1), num=200, periodic=True, seed=3),
    # non-periodic, num and rMean (deterministic radii)
    'num_rmean': dict(minCorner=(0, 0, 0), maxCorner=(2, 1, 1), rMean=0.05, rRelFuzz=0.25, num=300, seed=11),
    # num mode with rRelFuzz (rMean from porosity with the (1+fuzz^2) term)
    'num_fuzz': dict(minCorner=(-1, -0.5, 0), maxCorner=(1, 0.5, 1.5), rRelFuzz=0.5, num=150, porosity=0.7, seed=5),
    # PSD, deterministic radii (num > 0)
    'psd_num': dict(minCorner=(0, 0, 0), maxCorner=(1, 1, 1), psdSizes=[0.04, 0.06, 0.1], psdCumm=[0, 0.3, 1], num=100, seed=2),
    # PSD with the num/porosity consistency scaling (appliedPsdScaling < 1)
    'psd_scaled': dict(minCorner=(0, 0, 0), maxCorner=(0.5, 0.5, 0.5), psdSizes=[0.05, 0.08, 0.12, 0.2], psdCumm=[0, 0.2, 0.7, 1], num=120, porosity=0.6, seed=13),
    # PSD, stochastic count
    'psd_stoch': dict(minCorner=(0, 0, 0), maxCorner=(0.6, 0.6, 0.6), psdSizes=[0.05, 0.08, 0.12], psdCumm=[0, 0.5, 1], seed=9),
    # PSD with distributeMass (pow3Interp on the mass-weighted cumulative curve)
    'psd_mass': dict(minCorner=(0, 0, 0), maxCorner=(1, 1, 1), psdSizes=[0.03, 0.05, 0.1], psdCumm=[0, 0.4, 1], num=150, distributeMass=True, seed=21),
    # rMean mode with distributeMass and fuzz, stochastic count
    'rmean_mass': dict(minCorner=(0, 0, 0), maxCorner=(0.7, 0.7, 0.7), rMean=0.05, rRelFuzz=0.4, distributeMass=True, seed=17),
    # num mode at low porosity: 1000-try failure -> restart with porosity += (1-porosity)/10, several times
    'num_restart': dict(minCorner=(0, 0, 0), maxCorner=(1, 1, 1), num=40, porosity=0.2, seed=4),
    # rMean mode with num too large: 1000-try failure -> stops early (returns the count placed)
    'rmean_num_fail': dict(minCorner=(0, 0, 0), maxCorner=(1, 1, 1), rMean=0.12, num=200, seed=8),
    # periodic, rMean, stochastic count
    'periodic_stoch': dict(minCorner=(0.1, -0.2, 0), maxCorner=(0.9, 0.6, 0.5), rMean=0.05, rRelFuzz=0.1, periodic=True, seed=12),
    # 2-D (zero z size): area-based rMean, no draw for the flat axis
    'flat_num': dict(minCorner=(0, 0, 0.25), maxCorner=(1, 1, 0.25), num=100, seed=6),
    # periodic with hSize (sheared cell)
    'periodic_hsize': dict(minCorner=(0, 0, 0), maxCorner=(0, 0, 0), num=80, periodic=True, seed=10,
                           hSize=((1.0, 0.2, 0.0), (0.0, 0.9, 0.15), (0.1, 0.0, 1.1))),
}

summary = []
for name, kw in sorted(CONFIGS.items()):
    args = dict(kw)
    args['minCorner'] = Vector3(*kw['minCorner'])
    args['maxCorner'] = Vector3(*kw['maxCorner'])
    if 'hSize' in kw:
        # Matrix3's 9-argument constructor is row-major (Matrix3(1,...,9)[0,1] == 2), so rows go in order
        args['hSize'] = Matrix3(*[x for row in kw['hSize'] for x in row])
    sp = pack.SpherePack()
    t0 = time.time()
    n = sp.makeCloud(**args)
    dt = time.time() - t0
    spheres = sp.toList()
    params = {
        'min_corner': list(kw['minCorner']), 'max_corner': list(kw['maxCorner']),
        'r_mean': kw.get('rMean', -1.0), 'r_rel_fuzz': kw.get('rRelFuzz', 0.0), 'num': kw.get('num', -1),
        'periodic': kw.get('periodic', False), 'porosity': kw.get('porosity', 0.65),
        'psd_sizes': kw.get('psdSizes', []), 'psd_cumm': kw.get('psdCumm', []),
        'distribute_mass': kw.get('distributeMass', False), 'seed': kw['seed'],
        'h_size': [list(r) for r in kw['hSize']] if 'hSize' in kw else None,
    }
    doc = {
        'source': 'yade %s' % yade.config.version if hasattr(yade, 'config') else 'yade',
        'script': 'yade_ref/pack/clouds.py',
        'name': name,
        'params': params,
        'returned': int(n),
        'len': len(spheres),
        'cell_size': [float(x) for x in sp.cellSize],
        'is_periodic': bool(sp.isPeriodic),
        'applied_psd_scaling': float(sp.appliedPsdScaling),
    }
    with open(os.path.join(OUT, name + '.json'), 'w') as f:
        json.dump(doc, f, indent=1, sort_keys=True)
        f.write('\n')
    with open(os.path.join(OUT, name + '.txt'), 'w') as f:
        for s in spheres:
            c, r = s[0], s[1]
            f.write('%.17g %.17g %.17g %.17g\n' % (c[0], c[1], c[2], r))
    summary.append('%-18s returned=%4d len=%4d scaling=%.6g  %.3fs' % (name, n, len(spheres), sp.appliedPsdScaling, dt))

print('\n'.join(summary))
sys.stdout.flush()
