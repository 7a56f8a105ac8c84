//! Issue 16, item 5: the paired mean test (`study::mean_test`) for a chaotic engine, on YADE's own
//! rerun of the same five r05 N tiny specimens with two OpenMP threads
//! (results/fast_engine_band/yade_2threads, `yade -j 2`: only the summation order differs from the
//! one-thread goldens of golden/study), which is as good a YADE run as any: the test accepts it, with
//! the t YADE's two runs give (2.26 at cycle 3's rut, computed independently with Python/mpmath from
//! the same histories; critical value 8.83 = t(4) at 1 - 0.01/22, as tables give), and refuses the
//! same rerun shifted by 2 YADE sd. (This rerun also stays inside the 3-sd band, max 2.33 sd.)
use ryade::harness::study;
use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn histories(dir: &str) -> Vec<Vec<study::HistoryRow>> {
    case_histories(dir, "r05_N")
}

fn case_histories(dir: &str, case: &str) -> Vec<Vec<study::HistoryRow>> {
    (1..=5)
        .map(|s| {
            study::read_history(&root().join(format!("{dir}/{case}_tiny_s{s}/history.csv")))
                .unwrap()
        })
        .collect()
}

#[test]
fn yade_rerun_passes_the_paired_mean_test_and_a_biased_copy_fails_it() {
    let one = histories("golden/study");
    let two = histories("results/fast_engine_band/yade_2threads");
    let bands = study::compare_case(&one, &two, 3.0).unwrap();
    assert_eq!(bands.len(), 12, "cycles 0-5, rut and porosity");
    assert!(bands.iter().all(|b| b.inside));
    let t = study::mean_test(&bands, 0.01).unwrap();
    assert_eq!((t.n, t.m), (5, 11), "cycle 0's rut is 0 in every run");
    assert!((t.t_crit - 8.827).abs() < 2e-3, "{t:?}");
    assert!(
        (t.t_max - 2.26).abs() < 5e-3 && t.cycle == 3 && t.metric == "rut_mm",
        "{t:?}"
    );
    assert!(t.pass);
    // the same test on a biased copy of the rerun (+2 YADE sd of cycle 3's rut on every rut): BIASED
    let sd3 = bands
        .iter()
        .find(|b| b.cycle == 3 && b.metric == "rut_mm")
        .unwrap()
        .yade_sd;
    let mut biased = two.clone();
    for h in &mut biased {
        for r in h.iter_mut().skip(1) {
            r.rut_mm += 2.0 * sd3;
        }
    }
    let t = study::mean_test(&study::compare_case(&one, &biased, 3.0).unwrap(), 0.01).unwrap();
    assert!(!t.pass, "{t:?}");
}

/// YADE against itself on all nine tiny cases (5 seeds each): the two-thread rerun of every
/// golden specimen (results/fast_engine_band/yade_2threads, session 15) falls outside the issue's
/// 3-sd band in r03 N (3.30 sd, porosity at cycle 5) and r03 G (7.68 sd, porosity at cycle 3:
/// where the fast engine's r03 G run was 4.34 sd out), so that band rule refuses YADE itself; the
/// paired mean test accepts YADE's rerun in all nine (largest t 4.86, critical 8.83).
#[test]
fn yade_rerun_fails_the_3sd_band_in_two_cases_and_passes_the_mean_test_in_all() {
    let mut band_fails = Vec::new();
    for case in [
        "r03_N", "r03_G", "r03_F", "r05_N", "r05_G", "r05_F", "r07_N", "r07_G", "r07_F",
    ] {
        let one = case_histories("golden/study", case);
        let two = case_histories("results/fast_engine_band/yade_2threads", case);
        let bands = study::compare_case(&one, &two, 3.0).unwrap();
        let worst = bands.iter().map(|b| b.z_max_run).fold(0.0, f64::max);
        if !bands.iter().all(|b| b.inside) {
            band_fails.push((case, (worst * 100.0).round() / 100.0));
        }
        let t = study::mean_test(&bands, 0.01).unwrap();
        assert!(t.pass && t.t_max < 4.9, "{case}: {t:?}");
    }
    assert_eq!(band_fails, [("r03_N", 3.30), ("r03_G", 7.68)]);
}
