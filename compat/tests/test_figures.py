"""The study's SDR figure (issue 18): without an F run it says why it is empty; where F and N rut alike
the undefined ratio is masked (not drawn off-scale) and the figure says how many points."""
import csv
import os

from yade import _ryade_figures as figs

HEAD = ['engine', 'ratio', 'case', 'seed', 'cycle', 'complete', 'rut_mm', 'rut_max_mm', 'peak_kPa', 'tracking_rms_kPa',
        'porosity_box', 'piston_z_m', 'grid_z_m']


def write(path, head, rows):
    with open(path, 'w', newline='') as f:
        w = csv.writer(f)
        w.writerow(head)
        w.writerows(rows)


def hist(ruts):
    """histories.csv rows: ruts[case] = [rut at cycle 0, 1, ...] (ryade, ratio 0.7, seed 1)."""
    return [['ryade', '0.7', c, '1', k, '1', r, r, 0, 0, 0.4, 0.26, ''] for c, rr in ruts.items() for k, r in enumerate(rr)]


def test_sdr_figure_without_f_says_why(tmp_path):
    write(tmp_path / 'h.csv', HEAD, hist({'N': [0, 5, 6], 'G': [0, 4, 5]}))
    write(tmp_path / 's.csv', ['engine', 'ratio', 'cycle', 'n_seeds', 'sdr_mean', 'sdr_sd', 'sdr_of_mean_ruts', 'values'], [])
    info = figs.study(str(tmp_path / 'h.csv'), str(tmp_path / 's.csv'), str(tmp_path))
    assert info['points'] == 0
    assert info['note'].startswith('no surface displacement ratio: Eq 1 needs the N, G and F runs') and 'cases N, G' in info['note']
    assert os.path.getsize(tmp_path / 'fig_sdr.png') > 10000


def test_sdr_figure_masks_the_undefined_ratio(tmp_path):
    # cycle 1: F - N = 2 (defined, ratio 0.5); cycle 2: F and N rut alike (0.1 of 6): ratio 20, masked;
    # cycle 3: defined and outside [0, 1] (-3): drawn, the axis widened to show it (the r07 study's values)
    n, g, f = [0, 4, 6, 6], [0, 5, 7, 3], [0, 6, 6.1, 7]
    write(tmp_path / 'h.csv', HEAD, hist({'N': n, 'G': g, 'F': f}))
    sdr = [['ryade', '0.7', k, 1, (g[k] - n[k]) / (f[k] - n[k]), 0, (g[k] - n[k]) / (f[k] - n[k]), ''] for k in (1, 2, 3)]
    write(tmp_path / 's.csv', ['engine', 'ratio', 'cycle', 'n_seeds', 'sdr_mean', 'sdr_sd', 'sdr_of_mean_ruts', 'values'], sdr)
    info = figs.study(str(tmp_path / 'h.csv'), str(tmp_path / 's.csv'), str(tmp_path))
    assert (info['points'], info['masked']) == (3, 1)
    assert info['note'].startswith('1 of 3 points masked: undefined where F and N rut alike')
    assert info['ylim'][0] < -3 and 1.5 < info['ylim'][1] < 2
