"""Figures for ryade's study tools (called by the `compat` binary; headless matplotlib).

    python3 -m yade._ryade_figures diff DIFF.csv OUT.png          # compat diff rXX: YADE band vs ryade
    python3 -m yade._ryade_figures profile PROFILE.csv OUT.png TITLE   # paper Fig 7 for one run
    python3 -m yade._ryade_figures study HISTORIES.csv SDR.csv OUTDIR  # paper Figs 3-6
    python3 -m yade._ryade_figures profiles INDEX.csv OUT.png      # paper Fig 7 for a whole study
    python3 -m yade._ryade_figures gap PLOT.csv OUT.png              # compat gap: one diagnosis
"""
import csv
import math
import sys


def _plt():
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    return plt


def _rows(path):
    with open(path, newline='') as f:
        return list(csv.DictReader(f))


def _f(x):
    try:
        return float(x)
    except (TypeError, ValueError):
        return math.nan


CASE_STYLE = {'N': ('tab:red', 'N non-stabilized'), 'G': ('tab:green', 'G geogrid'),
              'F': ('tab:blue', 'F full lateral confinement')}
LABELS = {'rut_mm': 'rut [mm]', 'porosity_box': 'porosity under the piston'}


def diff(csv_path, png):
    plt = _plt()
    rows = _rows(csv_path)
    cases = sorted({r['case'] for r in rows}, key='NGF'.index)
    metrics = ['rut_mm', 'porosity_box']
    fig, axes = plt.subplots(len(metrics), max(1, len(cases)), figsize=(4.2 * max(1, len(cases)), 6.5), squeeze=False)
    for j, c in enumerate(cases):
        for i, m in enumerate(metrics):
            ax = axes[i][j]
            rr = [r for r in rows if r['case'] == c and r['metric'] == m]
            cyc = [int(r['cycle']) for r in rr]
            lo = [_f(r['band_lo']) for r in rr]
            hi = [_f(r['band_hi']) for r in rr]
            ax.fill_between(cyc, lo, hi, color='0.85', label='YADE band (mean +- k sd)')
            ys = [[_f(x) for x in r['yade_values'].split()] for r in rr]
            rs = [[_f(x) for x in r['ryade_values'].split()] for r in rr]
            for s in range(len(ys[0]) if ys else 0):
                ax.plot(cyc, [y[s] for y in ys], '-', color='0.45', lw=1, label='YADE seeds' if s == 0 else None)
            for s in range(len(rs[0]) if rs else 0):
                ax.plot(cyc, [y[s] for y in rs], 'o', ms=4, mfc='none', color=CASE_STYLE[c][0],
                        label='ryade seeds' if s == 0 else None)
            bad = [k for k, r in zip(cyc, rr) if r['inside'] != '1']
            if bad:
                ax.plot(bad, [_f(r['ryade_mean']) for r in rr if r['inside'] != '1'], 'kx', ms=8, label='outside')
            ax.set_xlabel('cycle')
            ax.set_ylabel(LABELS[m])
            ax.set_title('case %s' % c)
            ax.grid(alpha=0.3)
            if i == 0 and j == 0:
                ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def profile(csv_path, png, title):
    plt = _plt()
    rows = _rows(csv_path)
    mid = [-(0.5 * (_f(r['depth_top_m']) + _f(r['depth_bot_m']))) for r in rows]
    fig, ax = plt.subplots(1, 2, figsize=(8, 4.5), sharey=True)
    for k, (col, lab) in enumerate([('uz', 'vertical displacement uz [mm]'), ('ur', 'radial displacement ur [mm]')]):
        ax[k].plot([_f(r[col + '_under_mm']) for r in rows], mid, 'o-', label='under the piston')
        ax[k].plot([_f(r[col + '_outside_mm']) for r in rows], mid, 's--', label='beside the piston')
        ax[k].axvline(0, color='0.6', lw=0.8)
        ax[k].set_xlabel(lab)
        ax[k].grid(alpha=0.3)
    ax[0].set_ylabel('depth below the piston at the end of seating [m]')
    ax[0].legend(fontsize=8)
    fig.suptitle('%s: displacement since the end of seating (paper Fig 7)' % title)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def study(hist_csv, sdr_csv, outdir):
    import os
    plt = _plt()
    rows = _rows(hist_csv)
    ratios = sorted({r['ratio'] for r in rows}, key=float)
    for m, fname in [('rut_mm', 'fig_rutting.png'), ('porosity_box', 'fig_porosity.png')]:
        fig, axes = plt.subplots(1, len(ratios), figsize=(4.5 * len(ratios), 4), squeeze=False)
        for j, ra in enumerate(ratios):
            ax = axes[0][j]
            for c in 'NGF':
                for eng, ls in (('ryade', '-'), ('yade', ':')):
                    runs = sorted({r['seed'] for r in rows if r['ratio'] == ra and r['case'] == c and r['engine'] == eng})
                    per = {}
                    for s in runs:
                        for r in rows:
                            if r['ratio'] == ra and r['case'] == c and r['engine'] == eng and r['seed'] == s:
                                per.setdefault(int(r['cycle']), []).append(_f(r[m]))
                    if len(runs) > 1:  # seed band (min-max) around the seed mean, over the cycles every seed ran
                        cyc = [k for k in sorted(per) if len(per[k]) == len(runs)]
                        ax.fill_between(cyc, [min(per[k]) for k in cyc], [max(per[k]) for k in cyc], color=CASE_STYLE[c][0],
                                        alpha=0.18, lw=0)
                        ax.plot(cyc, [sum(per[k]) / len(per[k]) for k in cyc], ls, color=CASE_STYLE[c][0],
                                label='%s (%s, mean and range of %d seeds)' % (CASE_STYLE[c][1], eng, len(runs)))
                    elif runs:
                        cyc = sorted(per)
                        ax.plot(cyc, [per[k][0] for k in cyc], ls, color=CASE_STYLE[c][0], label='%s (%s)' % (CASE_STYLE[c][1], eng))
            ax.set_title('d/a = %s' % ra)
            ax.set_xlabel('cycle')
            ax.set_ylabel(LABELS[m])
            ax.grid(alpha=0.3)
            if j == 0:
                ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(outdir, fname), dpi=110)
        plt.close(fig)
    sd = _rows(sdr_csv)
    fig, ax = plt.subplots(figsize=(6, 4))
    # Eq 1 is undefined where F and N rut alike: such points (|F-N| under 5 % of N's rut) are masked, not
    # drawn off-scale, and the figure says how many; the axis spans the defined values (at least [-0.5, 1.5],
    # the paper's [0, 1] shaded), with values beyond +-15 (F within a few % of N) masked as well
    lo, hi, tol = -15.0, 15.0, 0.05
    mean_rut = {}
    for r in rows:
        mean_rut.setdefault((r['engine'], r['ratio'], r['case'], int(r['cycle'])), []).append(_f(r['rut_mm']))
    info = {'points': 0, 'masked': 0}
    shown = []
    for ra in sorted({r['ratio'] for r in sd}, key=float):
        for eng, ls in (('ryade', 'o-'), ('yade', 's:')):
            rr = [r for r in sd if r['ratio'] == ra and r['engine'] == eng]
            if not rr:
                continue
            cyc = [int(r['cycle']) for r in rr]
            several = int(rr[0]['n_seeds']) > 1
            # several seeds: Eq 1 on the seed-mean ruts, bars = sd of the per-seed ratios
            mean = [_f(r['sdr_of_mean_ruts'] if several else r['sdr_mean']) for r in rr]
            err = [_f(r['sdr_sd']) for r in rr] if several else None
            for k, c in enumerate(cyc):
                ruts = [mean_rut.get((eng, ra, x, c)) for x in 'NF']
                n, f = [sum(v) / len(v) if v else None for v in ruts]
                undefined = n is not None and f is not None and abs(f - n) < tol * abs(n)
                info['points'] += 1
                if undefined or not (lo <= mean[k] <= hi):
                    mean[k] = float('nan')
                    if err:
                        err[k] = float('nan')
                    info['masked'] += 1
            for c, v, e in zip(cyc, mean, err or [0.0] * len(cyc)):
                if v == v:  # the drawn span of a point: its bar, none where the sd is missing
                    e = e if e == e else 0.0
                    shown.append((c, v - e, v + e))
            every = max(1, len(cyc) // 40)
            ax.errorbar(cyc, mean, yerr=err, fmt=ls, capsize=2, markevery=every, errorevery=every, ms=4,
                        label='d/a = %s (%s%s)' % (ra, eng, ', %s seeds' % rr[0]['n_seeds'] if several else ''))
    ax.axhline(0, color='0.6', lw=0.8)
    ax.axhline(1, color='0.6', lw=0.8)
    ax.axhspan(0, 1, color='tab:green', alpha=0.08, lw=0, label="the paper's range [0, 1]")
    last = max([int(r['cycle']) for r in sd] or [0])
    first = 100 if last >= 150 else 0  # the paper reads the ratio over cycles 100-200
    y0 = min([a for c, a, _ in shown if c >= first] + [-0.5])
    y1 = max([b for c, _, b in shown if c >= first] + [1.5])
    pad = 0.05 * (y1 - y0)
    info['ylim'] = (y0 - pad, y1 + pad)
    ax.set_ylim(*info['ylim'])
    if not sd:
        cases = ''.join(sorted({r['case'] for r in rows}, key='NGF'.index))
        info['note'] = ('no surface displacement ratio: Eq 1 needs the N, G and F runs of one ratio and seed '
                        '(this study ran case%s %s)' % ('s' if len(cases) > 1 else '', ', '.join(cases)))
        ax.text(0.5, 0.5, info['note'].replace(': ', ':\n', 1), transform=ax.transAxes, ha='center', va='center',
                fontsize=9, wrap=True)
    else:
        info['note'] = ('%d of %d points masked: undefined where F and N rut alike (|F-N| < %g %% of N)\nor '
                        'beyond +-%g; every value in sdr.csv' % (info['masked'], info['points'], tol * 100, hi))
        ax.text(0.0, -0.17, info['note'], transform=ax.transAxes, fontsize=6.5, color='0.3', va='top')
    if first:
        ax.set_xlim(first, last)
    ax.set_xlabel('cycle')
    ax.set_ylabel('surface displacement ratio (G-N)/(F-N)')
    ax.set_title('Surface displacement ratio (paper Eq 1, Fig 6)')
    ax.grid(alpha=0.3)
    if sd:
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(outdir, 'fig_sdr.png'), dpi=110)
    plt.close(fig)
    return info


def profiles(index_csv, png):
    """Paper Fig 7 for a whole study: vertical displacement by depth under (solid) and beside (dashed) the
    piston, one panel per ratio (rows) and case (columns), one line per seed. index_csv lists
    ratio,case,seed,cycle,file."""
    plt = _plt()
    idx = _rows(index_csv)
    ratios = sorted({r['ratio'] for r in idx}, key=float)
    cases = [c for c in 'NGF' if any(r['case'] == c for r in idx)]
    fig, axes = plt.subplots(len(ratios), len(cases), figsize=(3.6 * len(cases), 3.2 * len(ratios)), squeeze=False, sharex=True)
    for i, ra in enumerate(ratios):
        for j, c in enumerate(cases):
            ax = axes[i][j]
            for r in [r for r in idx if r['ratio'] == ra and r['case'] == c]:
                pr = _rows(r['file'])
                mid = [-(0.5 * (_f(p['depth_top_m']) + _f(p['depth_bot_m']))) for p in pr]
                ax.plot([_f(p['uz_under_mm']) for p in pr], mid, '-', color=CASE_STYLE[c][0], lw=1.2)
                ax.plot([_f(p['uz_outside_mm']) for p in pr], mid, '--', color=CASE_STYLE[c][0], lw=1.0)
            cyc = sorted({r['cycle'] for r in idx if r['ratio'] == ra and r['case'] == c})
            ax.axvline(0, color='0.6', lw=0.8)
            ax.set_title('d/a = %s, %s, cycle %s' % (ra, CASE_STYLE[c][1], '/'.join(cyc)), fontsize=9)
            ax.grid(alpha=0.3)
            if j == 0:
                ax.set_ylabel('depth [m]')
            if i == len(ratios) - 1:
                ax.set_xlabel('uz [mm] (solid: under, dashed: beside)')
    fig.suptitle('Vertical displacement since the end of seating, by depth (paper Fig 7; one line per seed)')
    fig.tight_layout()
    fig.savefig(png, dpi=110)


GAP_NAMES = {'rut_mm': 'rut [mm]', 'porosity': 'porosity under the piston', 'rebound_mm': 'resilient rebound [mm]',
             'grid_settlement_mm': 'grid settlement [mm]', 'tracking_kpa': 'pressure tracking error [kPa]'}


def gap(plot_csv, png):
    """One gap diagnosis (`compat gap --observed ... --out DIR`: DIR/plot.csv): per observable, today's
    model (library baseline mean +- the noise of one run), the observation and the chosen model at its
    fitted strengths, with the fit | held-out split."""
    plt = _plt()
    rows = _rows(plot_csv)
    obs = [o for o in GAP_NAMES if any(r['observable'] == o for r in rows)]
    if not obs:
        sys.exit('%s: no known observable' % plot_csv)
    fig, axes = plt.subplots(1, len(obs), figsize=(4.2 * len(obs), 3.8), squeeze=False)
    for j, o in enumerate(obs):
        ax = axes[0][j]
        rr = [r for r in rows if r['observable'] == o]
        c = [int(r['cycle']) for r in rr]
        m = [_f(r['model_mean']) for r in rr]
        sd = [_f(r['model_sd']) for r in rr]
        ax.fill_between(c, [a - b for a, b in zip(m, sd)], [a + b for a, b in zip(m, sd)], color='0.85',
                        label="today's model (mean +- noise of one run)")
        ax.plot(c, m, '-', color='0.4')
        ax.plot(c, [_f(r['observed']) for r in rr], 'ko', label='observed')
        w = [_f(r['winner']) for r in rr]
        if any(x == x for x in w):
            ax.plot(c, w, 'r--', label='with the chosen effect(s), fitted')
        ax.axvline(float(rr[0]['fit_cycles']) + 0.5, color='tab:blue', ls=':', label='fit | held out')
        ax.set_xlabel('cycle')
        ax.set_ylabel(GAP_NAMES[o])
        ax.grid(alpha=0.3)
        if j == 0:
            ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def main(argv):
    if not argv or argv[0] not in ('diff', 'profile', 'profiles', 'study', 'gap'):
        sys.stderr.write(__doc__)
        return 2
    {'diff': diff, 'profile': profile, 'profiles': profiles, 'study': study, 'gap': gap}[argv[0]](*argv[1:])
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
