#!/usr/bin/env python3
"""An unchanged YADE script timed in Debian YADE (`yade -n -x`, one thread) and under `compat run --fast`
(and `compat run`, the YADE-order path), alternating inside every repetition so that all see the same
machine load (issue 16: ">= 10x yade -n -x on the same script").

    python3 yade_ref/bench/fast_script_bench.py [--scene bench/scenes/dense8000.scene.json] [--steps 2000] [--reps 3]
    python3 yade_ref/bench/fast_script_bench.py --deposit 4000 [--roll] [--steps 2000] [--warmup 8000]

The script is yade_ref/bench/run_scene.py: it builds the scene from the file with plain YADE calls and
prints the seconds of its one O.run(steps, True) (warm-up steps first); that phase is what is compared.
With --deposit NUM it is yade_ref/bench/deposit_script.py instead: NUM spheres fallen into an open facet
box (makeCloud, geom.facetBox, gravity), the timed steps taken once the pile has formed.
Prints per variant the seconds (min/median/max) and the ratio to YADE paired by repetition.
"""
import argparse, os, re, statistics, subprocess, sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
SCRIPT = os.path.join(HERE, 'run_scene.py')


def timed(cmd, env=None):
    out = subprocess.run(cmd, capture_output=True, text=True, env=env)
    m = re.search(r'BENCH steps=(\d+) bodies=(\d+) contacts=(\d+) seconds=([0-9.e+-]+)', out.stdout + out.stderr)
    if not m:
        raise SystemExit('no BENCH line from %s:\n%s' % (' '.join(cmd), (out.stdout + out.stderr)[-2000:]))
    notes = [l for l in (out.stdout + out.stderr).splitlines() if l.startswith('[ryade] --fast')]
    return float(m.group(4)), int(m.group(3)), notes


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('--scene', default=os.path.join(ROOT, 'bench/scenes/dense8000.scene.json'))
    ap.add_argument('--steps', type=int, default=2000)
    ap.add_argument('--warmup', type=int, default=None, help='steps before the timed run (default 50; 8000 with --deposit)')
    ap.add_argument('--deposit', type=int, metavar='NUM', help='time deposit_script.py with NUM spheres instead of a scene')
    ap.add_argument('--roll', action='store_true', help='with --deposit: the study\'s rolling-resistance aggregate (CohFrictMat, ScGeom6D)')
    ap.add_argument('--reps', type=int, default=3)
    ap.add_argument('--no-yade-order', action='store_true', help='skip the plain `compat run` variant')
    a = ap.parse_args(argv)
    env = dict(os.environ, OMP_NUM_THREADS='1', OMP_WAIT_POLICY='PASSIVE')
    if a.deposit:
        script = os.path.join(HERE, 'deposit_script.py')
        args = [script, str(a.deposit), str(a.steps), str(8000 if a.warmup is None else a.warmup), '1'] + (['roll'] if a.roll else [])
        what = '%d spheres%s' % (a.deposit, ', rolling resistance' if a.roll else '')
    else:
        script = SCRIPT
        args = [script, a.scene, str(a.steps), str(50 if a.warmup is None else a.warmup)]
        what = 'scene %s' % os.path.relpath(a.scene, ROOT)
    variants = [('yade', ['yade', '-n', '-x'] + args), ('ryade --fast', ['compat', 'run', '--fast'] + args)]
    if not a.no_yade_order:
        variants.append(('ryade (YADE-order)', ['compat', 'run'] + args))
    res = {n: [] for n, _ in variants}
    for r in range(a.reps):
        for n, cmd in variants:
            s, nc, notes = timed(cmd, env)
            res[n].append(s)
            for l in notes:
                print('   ', l)
            print('rep %d %-20s %8.3f s  (%d contacts at the end)' % (r + 1, n, s, nc), flush=True)
    print('\nscript %s, %s, %d steps (load average %s)' % (os.path.relpath(script, ROOT), what, a.steps,
                                                                 ' '.join('%.2f' % x for x in os.getloadavg())))
    print('| variant | seconds min / median / max | ratio to YADE min / median / max |\n|---|---|---|')
    for n, _ in variants:
        t = res[n]
        ratios = [y / x for x, y in zip(t, res['yade'])]
        print('| %s | %.3f / %.3f / %.3f | %.2f / %.2f / %.2f |' % (n, min(t), statistics.median(t), max(t), min(ratios),
                                                                 statistics.median(ratios), max(ratios)))


if __name__ == '__main__':
    main(sys.argv[1:])
