# Figure of one gap diagnosis (`compat gap --observed ... --out DIR` writes DIR/plot.csv and calls this):
# per observable, today's model (library baseline mean +- the noise of one run), the observation and the
# chosen model at its fitted strengths, with the fit | held-out split.
#   python3 yade_ref/gap/report_figure.py DIR/plot.csv DIR/report.png
import csv, math, sys

import matplotlib

matplotlib.use('Agg')
import matplotlib.pyplot as plt

NAMES = {'rut_mm': 'rut [mm]', 'porosity': 'porosity under the piston', 'rebound_mm': 'resilient rebound [mm]',
         'grid_settlement_mm': 'grid settlement [mm]'}


def f(x):
    try:
        return float(x)
    except (TypeError, ValueError):
        return math.nan


def main(plot_csv, png):
    rows = list(csv.DictReader(open(plot_csv, newline='')))
    obs = [o for o in NAMES if any(r['observable'] == o for r in rows)]
    if not obs:
        sys.exit('%s: no known observable' % plot_csv)
    fig, axes = plt.subplots(1, len(obs), figsize=(4.2 * len(obs), 3.8), squeeze=False)
    for j, o in enumerate(obs):
        ax = axes[0][j]
        rr = [r for r in rows if r['observable'] == o]
        c = [int(r['cycle']) for r in rr]
        m = [f(r['model_mean']) for r in rr]
        sd = [f(r['model_sd']) for r in rr]
        ax.fill_between(c, [a - b for a, b in zip(m, sd)], [a + b for a, b in zip(m, sd)], color='0.85',
                        label="today's model (mean +- noise of one run)")
        ax.plot(c, m, '-', color='0.4')
        ax.plot(c, [f(r['observed']) for r in rr], 'ko', label='observed')
        w = [f(r['winner']) for r in rr]
        if any(x == x for x in w):
            ax.plot(c, w, 'r--', label='with the chosen effect(s), fitted')
        ax.axvline(float(rr[0]['fit_cycles']) + 0.5, color='tab:blue', ls=':', label='fit | held out')
        ax.set_xlabel('cycle')
        ax.set_ylabel(NAMES[o])
        ax.grid(alpha=0.3)
        if j == 0:
            ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


if __name__ == '__main__':
    if len(sys.argv) != 3:
        sys.exit('usage: report_figure.py PLOT_CSV PNG')
    main(sys.argv[1], sys.argv[2])
