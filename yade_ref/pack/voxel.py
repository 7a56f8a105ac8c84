# Records utils.voxelPorosity (Shop::getVoxelPorosity) values from YADE 2023.02a for ryade's
# bit-for-bit test (tests/porosity.rs).  Run (from anywhere):
#     yade -n -x yade_ref/pack/voxel.py
# Writes golden/pack/voxel.json: a list of cases, each with the dynamic spheres ([x, y, z, r],
# floats written with repr, which round-trips), the fixed spheres that were also in the scene
# (YADE ignores them), the resolution, start, end and YADE's result.
import json, os, sys
import yade
from yade import pack, utils, Vector3

# repository root = three levels above this script (yade passes the script path as sys.argv[0])
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(sys.argv[0]))))
# output directory: first script argument if given, else golden/pack
OUT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, 'golden', 'pack')
os.makedirs(OUT, exist_ok=True)


def cloud(mn, mx, rMean, rRelFuzz, seed):
    sp = pack.SpherePack()
    sp.makeCloud(Vector3(*mn), Vector3(*mx), rMean=rMean, rRelFuzz=rRelFuzz, seed=seed)
    return [(tuple(c), r) for c, r in sp.toList()]


def run_case(name, dyn, fixed, probes):
    O.reset()
    for c, r in dyn:
        O.bodies.append(utils.sphere(c, r, fixed=False))
    for c, r in fixed:
        O.bodies.append(utils.sphere(c, r, fixed=True))
    out = []
    for res, start, end in probes:
        v = utils.voxelPorosity(res, Vector3(*start), Vector3(*end))
        out.append({'resolution': res, 'start': list(start), 'end': list(end), 'porosity': v})
        print('%-14s res=%4d start=%s end=%s porosity=%.17g' % (name, res, start, end, v))
    return {
        'name': name,
        'spheres': [[float(c[0]), float(c[1]), float(c[2]), float(r)] for c, r in dyn],
        'fixed_ignored': [[float(c[0]), float(c[1]), float(c[2]), float(r)] for c, r in fixed],
        'probes': out,
    }


cases = []
# a loose cloud, the whole box and a sub-box, plus a fixed sphere that YADE must ignore
c1 = cloud((0, 0, 0), (1, 1, 1), 0.08, 0.3, 3)
cases.append(run_case('cloud', c1, [((0.5, 0.5, 0.5), 0.3)], [
    (50, (0, 0, 0), (1, 1, 1)),
    (80, (0.2, 0.1, 0.3), (0.8, 0.7, 0.9)),
    (123, (-0.1, -0.05, 0.0), (1.1, 1.0, 0.75)),
]))
# a denser cloud in an unequal box, fine grid
c2 = cloud((-0.3, 0, 0.1), (0.3, 0.4, 0.5), 0.03, 0.2, 8)
cases.append(run_case('fine', c2, [], [
    (200, (-0.3, 0, 0.1), (0.3, 0.4, 0.5)),
    (97, (-0.2, 0.05, 0.2), (0.25, 0.33, 0.45)),
]))
# one sphere whose surface passes exactly through grid corners (strict '<' test)
cases.append(run_case('grid_sphere', [((0.5, 0.5, 0.5), 0.25)], [], [
    (100, (0, 0, 0), (1, 1, 1)),
    (64, (0, 0, 0), (1, 1, 1)),
]))

with open(os.path.join(OUT, 'voxel.json'), 'w') as f:
    json.dump({'source': 'yade 2023.02a', 'script': 'yade_ref/pack/voxel.py', 'cases': cases}, f, indent=1)
    f.write('\n')
