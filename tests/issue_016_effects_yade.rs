//! Issue 16 (the fast engine matches YADE statistically) for the study's unmodelled-effect knobs,
//! the runs `compat gap` libraries are built from: Debian YADE reran specimens of the r05 G medium
//! library (`results/fast_engine_band/effects_r05_G_medium/yade.table`, 6 cycles each) with a knob
//! at the library's extreme strengths, and each run is paired with the library's fast-engine run of
//! the same specimen and knob (results/gap/library_r05_G_medium_c6).

use ryade::gap::{self, Series};
use std::path::{Path, PathBuf};

/// Per cycle 1..=6: rut increment, porosity increment, rebound, grid-settlement increment, tracking
/// error (what a gap diagnosis compares).
fn quantities(s: &Series) -> Vec<[f64; 5]> {
    let v = |o: &str, c: usize| s.get(o).and_then(|x| x.get(c)).copied().unwrap_or(f64::NAN);
    (1..=6)
        .map(|c| {
            [
                v("rut_mm", c) - v("rut_mm", c - 1),
                v("porosity", c) - v("porosity", c - 1),
                v("rebound_mm", c),
                v("grid_settlement_mm", c) - v("grid_settlement_mm", c - 1),
                v("tracking_kpa", c),
            ]
        })
        .collect()
}

fn load(dir: &Path) -> Option<Vec<[f64; 5]>> {
    let h = dir.join("history.csv");
    h.is_file()
        .then(|| quantities(&gap::series_of_history(&h).unwrap()))
}

fn mean_sd(x: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let m = x.iter().sum::<f64>() / n;
    (
        m,
        (x.iter().map(|v| (v - m) * (v - m)).sum::<f64>() / (n - 1.0)).sqrt(),
    )
}

/// (largest |mean difference| in noise units, largest |t|) over the five observables of one
/// group: YADE's runs `yade_group` against the library's `fast_group`, paired by specimen.
fn paired(
    root: &Path,
    yade_group: &str,
    fast_group: &str,
    noise: &[[f64; 5]],
) -> (f64, f64, usize) {
    let (mut worst_m, mut worst_t, mut n) = (0.0f64, 0.0f64, 0);
    let mut per_obs: Vec<Vec<f64>> = vec![Vec::new(); 5];
    for s in 1..=15 {
        let ydir = root.join(format!(
            "results/fast_engine_band/effects_r05_G_medium/{yade_group}_s{s}"
        ));
        let Some(y) = load(&ydir) else { continue };
        // the library's run, or one of the fast engine's own runs kept next to YADE's
        let lib = root.join(format!(
            "results/gap/library_r05_G_medium_c6/{fast_group}_s{s}"
        ));
        let own = root.join(format!(
            "results/fast_engine_band/effects_r05_G_medium/{fast_group}_s{s}"
        ));
        let f = load(&lib).or_else(|| load(&own)).unwrap();
        n += 1;
        for (o, v) in per_obs.iter_mut().enumerate() {
            // the specimen's mean difference over the cycles, in units of one run's noise
            // (cycles both runs reached: a soft specimen may pass --stop-rut before cycle 6)
            let d: Vec<f64> = (0..6)
                .map(|c| (y[c][o] - f[c][o]) / noise[c][o])
                .filter(|x| x.is_finite())
                .collect();
            if !d.is_empty() {
                v.push(d.iter().sum::<f64>() / d.len() as f64);
            }
        }
    }
    for v in &per_obs {
        assert!(
            v.len() >= 2,
            "{yade_group}: fewer than 2 specimens with this observable"
        );
        let (m, sd) = mean_sd(v);
        assert!(
            m.is_finite() && sd.is_finite(),
            "{yade_group}: mean {m}, sd {sd}"
        );
        worst_m = worst_m.max(m.abs());
        // identical runs (sd 0) pass only with a zero mean
        let t = if sd > 0.0 {
            (m / (sd / (v.len() as f64).sqrt())).abs()
        } else if m == 0.0 {
            0.0
        } else {
            f64::INFINITY
        };
        worst_t = worst_t.max(t);
    }
    (worst_m, worst_t, n)
}

/// Every knob at the library's extreme strengths (damping -0.15 and +0.3, rolling 0.05 and 0.5,
/// friction -10 and +10 degrees, geogrid softness 1) and today's model: YADE's shifts and the fast
/// engine's agree within the seed noise, every paired t under 3 over the 40 tests (the two-sided
/// Bonferroni 5 % level is |t| 6.7 at 5 and 4.2 at 13 degrees of freedom, so 3 is stricter; the
/// largest mean difference, 0.52 of one run's noise, is friction +10's rebound over 6 specimens, t
/// 1.2). The library's subgrade runs took the YADE-order path (the study kept its PyRunner for the
/// spring bed until session 17) and equal YADE's byte for byte; the fast path's own subgrade runs
/// (the native piston engine steps the spring bed) pair with YADE's like the others. Pairing YADE's
/// damping +0.3 with the library's damping +0.15 instead gives t = 12.3 (checked below).
#[test]
fn fast_engine_effect_shifts_match_yade() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let lib = root.join("results/gap/library_r05_G_medium_c6");
    let base: Vec<Vec<[f64; 5]>> = (1..=15)
        .map(|s| load(&lib.join(format!("base_s{s}"))).unwrap())
        .collect();
    let noise: Vec<[f64; 5]> = (0..6)
        .map(|c| {
            std::array::from_fn(|o| {
                mean_sd(
                    &base
                        .iter()
                        .map(|b| b[c][o])
                        .filter(|x| x.is_finite())
                        .collect::<Vec<_>>(),
                )
                .1
            })
        })
        .collect();
    let groups = [
        ("base", 14),
        ("damping_0", 14),
        ("damping_3", 6),
        ("rolling_1", 6),
        ("rolling_3", 6),
        ("friction_0", 14),
        ("friction_3", 6),
        ("grid_soft_1", 14),
    ];
    for (g, n_expected) in groups {
        let (m, t, n) = paired(&root, g, g, &noise);
        eprintln!("{g}: {n} specimens, largest |mean| {m:.2} sd, largest |t| {t:.2}");
        assert_eq!(n, n_expected, "{g}");
        assert!(m < 0.6 && t < 3.0, "{g}: |mean| {m:.2} sd, |t| {t:.2}");
    }
    for s in 1..=6 {
        let read = |p: PathBuf| std::fs::read(p.join("history.csv")).unwrap();
        assert_eq!(
            read(root.join(format!(
                "results/fast_engine_band/effects_r05_G_medium/subgrade_2_s{s}"
            ))),
            read(lib.join(format!("subgrade_2_s{s}"))),
            "subgrade seed {s}"
        );
    }
    // the spring bed stepped by the native piston engine (session 17): the fast path takes the run,
    // and its 14 runs pair with YADE's as the other knobs' do
    let (m, t, n) = paired(&root, "subgrade_2", "fast_subgrade_2", &noise);
    eprintln!("subgrade (fast path): {n} specimens, largest |mean| {m:.2} sd, largest |t| {t:.2}");
    assert_eq!(n, 14);
    assert!(m < 0.6 && t < 3.0, "subgrade: |mean| {m:.2} sd, |t| {t:.2}");
    // the test sees a wrong strength: YADE's damping +0.3 against the library's +0.15
    let (_, t, _) = paired(&root, "damping_3", "damping_2", &noise);
    eprintln!("wrong strength: |t| {t:.2}");
    assert!(t > 5.0, "a wrong strength passed: |t| {t:.2}");
}
