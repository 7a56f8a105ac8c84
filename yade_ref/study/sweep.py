#!/usr/bin/env python3
"""The sweep behind preset paper200 (issue 17): why the study's model punches and what stops it.

Each variant is one study.py run (seed 1). `g_*` variants generate a specimen and load it; `l_*` variants
load a specimen a `g_*` variant exported (same packing, one loading option changed), so their differences
are the option's, not a new packing's. Runs that finished earlier (history.csv present) are reused.

    python3 yade_ref/study/sweep.py --out sweep_out [-j 2] [--engine ryade|yade] [--only r07G]

Writes OUT/sweep.csv and OUT/sweep.md: per variant the layer height and porosity after generation, the rut
at cycles 1, 5, 10, 30, 60 (where run), the filtered peak pressure range and the tracking error.
The results of the session that chose the preset are in results/paper200/sweep.{csv,md}.
"""
import argparse, csv, json, os, subprocess, sys
from concurrent.futures import ThreadPoolExecutor

HERE = os.path.dirname(os.path.abspath(__file__))
STUDY = os.path.join(HERE, 'study.py')

FULL = ['--size', 'full', '--seed', '1']
ROLL = ['--load-friction', '30', '--eta-roll', '0.5']  # the first trial's loading (study.md findings)
# (name, what it tests, arguments); l_* variants name their specimen as 'spec:<g_* name>'
VARIANTS = [
    # generation: compaction friction (lower = denser), grading, the paper's mid-rib grid
    ('g_r07G_f30', 'study model (friction 30 in generation and loading), rolling resistance 0.5',
     ['--ratio', '0.7', '--case', 'G'] + FULL + ['--cycles', '3', '--eta-roll', '0.5']),
    ('g_r07N_f10', 'generation friction 10', ['--ratio', '0.7', '--case', 'N'] + FULL + ['--cycles', '10', '--friction', '10'] + ROLL),
    ('g_r07G_f10', 'generation friction 10', ['--ratio', '0.7', '--case', 'G'] + FULL + ['--cycles', '10', '--friction', '10'] + ROLL),
    ('g_r07F_f10', 'generation friction 10', ['--ratio', '0.7', '--case', 'F'] + FULL + ['--cycles', '10', '--friction', '10'] + ROLL),
    ('g_r07G_f0', 'frictionless generation (densest)', ['--ratio', '0.7', '--case', 'G'] + FULL + ['--cycles', '10', '--friction', '0'] + ROLL),
    ('g_r07N_psd04', 'graded layer, radii r(1 +- 0.4)',
     ['--ratio', '0.7', '--case', 'N'] + FULL + ['--cycles', '10', '--psd-fuzz', '0.4', '--friction', '10'] + ROLL),
    ('g_r07G_psd04', 'graded layer, radii r(1 +- 0.4)',
     ['--ratio', '0.7', '--case', 'G'] + FULL + ['--cycles', '10', '--psd-fuzz', '0.4', '--friction', '10'] + ROLL),
    ('g_r07G_midrib', "the paper's ribs (articulated mid node; 2228 steps a cycle)",
     ['--ratio', '0.7', '--case', 'G'] + FULL + ['--cycles', '10', '--mid-rib', '--friction', '10'] + ROLL),
    ('g_r05N_f10', 'generation friction 10', ['--ratio', '0.5', '--case', 'N'] + FULL + ['--cycles', '10', '--friction', '10'] + ROLL),
    ('g_r05G_f10', 'generation friction 10', ['--ratio', '0.5', '--case', 'G'] + FULL + ['--cycles', '10', '--friction', '10'] + ROLL),
    ('g_r03N_medium_f10', 'generation friction 10 (medium)',
     ['--ratio', '0.3', '--case', 'N', '--size', 'medium', '--seed', '1', '--cycles', '10', '--friction', '10'] + ROLL),
    ('g_r03G_medium_f10', 'generation friction 10 (medium)',
     ['--ratio', '0.3', '--case', 'G', '--size', 'medium', '--seed', '1', '--cycles', '10', '--friction', '10'] + ROLL),
    ('g_r03N_medium_f20', 'generation friction 20 (medium, generation only)',
     ['--ratio', '0.3', '--case', 'N', '--size', 'medium', '--seed', '1', '--friction', '20', '--generate-only']),
    ('g_r03N_medium_f25', 'generation friction 25 (medium, generation only)',
     ['--ratio', '0.3', '--case', 'N', '--size', 'medium', '--seed', '1', '--friction', '25', '--generate-only']),
    # loading on the same r07 / r05 specimens
    ('l_r07N_eta1', 'rolling resistance 1.0', ['spec:g_r07N_f10', '--cycles', '5', '--load-friction', '30', '--eta-roll', '1.0']),
    ('l_r07G_eta1', 'rolling resistance 1.0', ['spec:g_r07G_f10', '--cycles', '5', '--load-friction', '30', '--eta-roll', '1.0']),
    ('l_r07N_blockrot', 'sphere rotations blocked (no rolling at all), no etaRoll',
     ['spec:g_r07N_f10', '--cycles', '10', '--load-friction', '30', '--block-rotations']),
    ('l_r07G_blockrot', 'sphere rotations blocked (no rolling at all), no etaRoll',
     ['spec:g_r07G_f10', '--cycles', '10', '--load-friction', '30', '--block-rotations']),
    ('l_r07G_gridblock_all', 'diagnostic: grid nodes held in place', ['spec:g_r07G_f10', '--cycles', '5'] + ROLL + ['--grid-block', 'xyzXYZ']),
    ('l_r07G_gridblock_z', 'diagnostic: grid nodes held vertically', ['spec:g_r07G_f10', '--cycles', '5'] + ROLL + ['--grid-block', 'z']),
    ('l_r07G_gridblock_xy', 'diagnostic: grid nodes held horizontally', ['spec:g_r07G_f10', '--cycles', '5'] + ROLL + ['--grid-block', 'xy']),
    ('l_r07G_gridblock_rot', 'diagnostic: grid node rotations held (ribs cannot roll)',
     ['spec:g_r07G_f10', '--cycles', '5'] + ROLL + ['--grid-block', 'XYZ']),
    ('l_r05G_gridblock_z', 'diagnostic: grid nodes held vertically', ['spec:g_r05G_f10', '--cycles', '5'] + ROLL + ['--grid-block', 'z']),
    ('l_r07G_kn10', 'grid bonds kn, ks x 10', ['spec:g_r07G_f10', '--cycles', '5'] + ROLL + ['--grid-kn-scale', '10']),
    ('l_r07G_kr10', 'grid bonds kr, ktw x 10', ['spec:g_r07G_f10', '--cycles', '5'] + ROLL + ['--grid-kr-scale', '10']),
    ('l_r07N_lf40', 'loading friction 40', ['spec:g_r07N_f10', '--cycles', '10', '--load-friction', '40', '--eta-roll', '0.5']),
    ('l_r07G_lf40', 'loading friction 40', ['spec:g_r07G_f10', '--cycles', '10', '--load-friction', '40', '--eta-roll', '0.5']),
    ('l_r07G_c60', 'friction 30, rolling 0.5: 60 cycles', ['spec:g_r07G_f10', '--cycles', '60'] + ROLL),
    ('l_r07G_lf35_c30', 'loading friction 35, rolling 0.5 (the preset): 30 cycles',
     ['spec:g_r07G_f10', '--cycles', '30', '--load-friction', '35', '--eta-roll', '0.5']),
    ('l_r07G_lf35_eta1_c30', 'loading friction 35, rolling 1.0: 30 cycles',
     ['spec:g_r07G_f10', '--cycles', '30', '--load-friction', '35', '--eta-roll', '1.0']),
]


def command(engine, name, args, out):
    a = []
    for x in args:
        if x.startswith('spec:'):
            a += ['--import-specimen', os.path.join(out, x[5:], 'specimen.json')]
        else:
            a.append(x)
    d = os.path.join(out, name)
    a += ['--out', d]
    if name.startswith('g_'):
        a += ['--export-specimen', os.path.join(d, 'specimen.json')]
    if engine == 'yade':
        return ['yade', '-n', '-x', STUDY, '--'] + a, d
    return ['compat', 'run', STUDY, '--'] + a, d


def run(engine, name, args, out):
    cmd, d = command(engine, name, args, out)
    done = os.path.isfile(os.path.join(d, 'summary.json'))
    if done:
        return name, 'reused'
    os.makedirs(d, exist_ok=True)
    env = dict(os.environ, OMP_NUM_THREADS='1')
    with open(os.path.join(d, engine + '.log'), 'w') as log:
        rc = subprocess.call(cmd, stdout=log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL, env=env)
    print('[sweep] %-24s %s' % (name, 'ok' if rc == 0 else 'FAILED (rc %d, see %s/%s.log)' % (rc, d, engine)), flush=True)
    return name, rc


def row(out, name, what, args):
    d = os.path.join(out, name)
    r = {'name': name, 'what': what, 'args': ' '.join(args)}
    try:
        s = json.load(open(os.path.join(d, 'summary.json')))
    except (OSError, ValueError):
        return r
    spec = args[0][5:] if args and args[0].startswith('spec:') else name
    try:
        g = json.load(open(os.path.join(out, spec, 'summary.json')))['generation']
        r['layer_m'] = '%.4f' % g['layerHeight']
        r['porosity'] = '%.4f' % g['layerPorosity']
    except (OSError, ValueError, KeyError):
        pass
    hp = os.path.join(d, 'history.csv')
    if os.path.isfile(hp):
        h = list(csv.DictReader(open(hp)))
        for k in (1, 5, 10, 30, 60):
            if len(h) > k:
                r['rut%d_mm' % k] = '%.2f' % float(h[k]['rut_mm'])
        pk = [float(x['peak_kPa']) for x in h[1:]]
        if pk:
            r['peak_kPa'] = '%.0f-%.0f' % (min(pk), max(pk))
        r['stopped'] = s.get('loading', {}).get('stopped', '')
    return r


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0], formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--out', default='sweep_out', help='run directory (finished runs in it are reused)')
    ap.add_argument('-j', type=int, default=2, help='parallel runs (each one thread)')
    ap.add_argument('--engine', choices=['ryade', 'yade'], default='ryade')
    ap.add_argument('--only', default='', help='run only variants whose name contains this text (and their specimens)')
    ap.add_argument('--collect', action='store_true', help='only write the tables from runs that exist')
    a = ap.parse_args(argv)
    out = os.path.abspath(a.out)
    sel = [v for v in VARIANTS if a.only in v[0]]
    need = {x[5:] for _, _, args in sel for x in args if x.startswith('spec:')}
    gen = [v for v in VARIANTS if v[0].startswith('g_') and (v in sel or v[0] in need)]
    load = [v for v in sel if v[0].startswith('l_')]
    if not a.collect:
        for stage in (gen, load):
            with ThreadPoolExecutor(max_workers=max(1, a.j)) as ex:
                list(ex.map(lambda v: run(a.engine, v[0], v[2], out), stage))
    rows = [row(out, n, w, args) for n, w, args in VARIANTS]
    cols = ['name', 'what', 'layer_m', 'porosity', 'rut1_mm', 'rut5_mm', 'rut10_mm', 'rut30_mm', 'rut60_mm', 'peak_kPa', 'stopped', 'args']
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, 'sweep.csv'), 'w', newline='') as f:
        w = csv.DictWriter(f, cols)
        w.writeheader()
        for r in rows:
            w.writerow({k: r.get(k, '') for k in cols})
    with open(os.path.join(out, 'sweep.md'), 'w') as f:
        f.write('| ' + ' | '.join(cols[:-1]) + ' |\n|' + '---|' * (len(cols) - 1) + '\n')
        for r in rows:
            f.write('| ' + ' | '.join(str(r.get(k, '')) for k in cols[:-1]) + ' |\n')
    print('[sweep] tables: %s/sweep.{csv,md}' % out)


if __name__ == '__main__':
    main(sys.argv[1:])
