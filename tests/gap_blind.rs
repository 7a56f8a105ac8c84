//! The gap diagnosis against blind cases made by Debian YADE (truth stored apart):
//! * the first tiny set (results/gap/blind_r07_G_tiny_c6/case04: rolling resistance etaRoll = 0.435)
//!   against the tiny library: the effect is named, its strength lands near the truth, and the
//!   held-out rut gap shrinks by more than half (that set's score: its validation.md);
//! * the medium library's validation design, fixed from the library alone;
//! * three cases of the final blind set results/gap/blind2028_r07_G_medium_c6 (13/14 named; its
//!   validation.md) against the medium library.

use ryade::{gap, gap_run};
use std::path::PathBuf;

#[test]
fn blind_case04_rolling_resistance_is_named() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("results/gap");
    let (_, lib) = gap_run::load_library(&root.join("library_r07_G_tiny_c6")).unwrap();
    let obs =
        gap::read_observed(&root.join("blind_r07_G_tiny_c6/cases/case04/observed.csv")).unwrap();
    let d = gap::diagnose(&lib, &obs, 4).unwrap();
    let truth: gap_run::Truth = serde_json::from_str(
        &std::fs::read_to_string(root.join("blind_r07_G_tiny_c6/truth/case04.json")).unwrap(),
    )
    .unwrap();
    assert_eq!(truth.effects[0].0, "rolling");
    assert_eq!(d.winner, "rolling");
    let s = d.candidates[0].strength;
    assert!(
        (s - truth.effects[0].1).abs() / truth.effects[0].1 < 0.3,
        "fitted {}",
        s
    );
    assert!(d.gap_reduction > 0.5, "gap reduction {}", d.gap_reduction);
}

/// The validation design of the committed medium library (r07 G medium, 6 cycles, made by ryade;
/// YADE and ryade give byte-identical study histories for these knobs): fixed from the library alone,
/// the detectability floor admits rolling resistance, a compliant subgrade and lower damping at the
/// strengths below, and no strength of grading, geogrid softness or friction change in the library's
/// plausible range; the chance drops of today's model's own seeds raise the penalty above Bonferroni.
#[test]
fn medium_library_design_is_fixed_from_the_library() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("results/gap");
    let (idx, lib) = gap_run::load_library(&root.join("library_r07_G_medium_c6")).unwrap();
    assert_eq!(idx.baseline_seeds.len(), 12);
    assert_eq!(lib.baseline.len(), 12);
    // the design served observations of rut, porosity, rebound and grid settlement
    let full = lib;
    let four =
        gap::read_observed(&root.join("blind2028_r07_G_medium_c6/cases/case01/observed.csv"))
            .unwrap();
    assert!(four.tracking_kpa.is_none());
    let lib = full.restricted_to(&four);
    let r = gap_run::detectable_ranges(&lib, 4, gap_run::DETECTABILITY_FLOOR);
    let get = |k: &str| r.iter().find(|x| x.knob == k).unwrap();
    for k in ["grading", "grid_soft", "friction"] {
        assert!(get(k).intervals.is_empty(), "{} {:?}", k, get(k));
        assert!(get(k).max_signal < gap_run::DETECTABILITY_FLOOR);
    }
    // (values printed by `compat gap --detectability`)
    let roll = &get("rolling").intervals;
    assert_eq!(roll.len(), 1);
    assert!((roll[0].0 - 0.0875).abs() < 1e-9 && (roll[0].1 - 0.5).abs() < 1e-9);
    let sub = &get("subgrade").intervals;
    assert!((sub[0].0 - 0.25).abs() < 1e-9 && (sub[0].1 - 1.0).abs() < 1e-9);
    let damp = &get("damping").intervals;
    assert!((damp[0].0 + 0.117).abs() < 1e-9 && (damp[0].1 + 0.15).abs() < 1e-9);
    // only the three detectable effects are fitted (issue 20): Bonferroni over 3 (the 0.05/3
    // quantile of chi2(1), 5.73); the library's own seeds drop by more than Gaussian noise would
    // for the best of 3 (median 2.05 against 1.64): the first penalty is 5.73 x 1.25 = 7.16
    let fitted = gap::fitted_effects(&lib, 4);
    assert_eq!(
        fitted,
        vec![true, false, true, false, false, true],
        "rolling, subgrade, damping"
    );
    let pen = gap::calibrated_penalties(&lib, 4);
    assert!((pen.bonferroni.0 - 5.731).abs() < 0.01, "{:?}", pen);
    assert_eq!(pen.null_drops1.len(), 12);
    assert!((pen.p1 - 7.165).abs() < 0.01, "{:?}", pen);
    assert!((pen.p2 - pen.bonferroni.1).abs() < 1e-12, "{:?}", pen);
    // with the pressure tracking error as well (session 16), friction lowered by 9-10 degrees
    // reaches the floor too (signal 6.2), and rolling from 0.0825
    let r = gap_run::detectable_ranges(&full, 4, gap_run::DETECTABILITY_FLOOR);
    let get = |k: &str| r.iter().find(|x| x.knob == k).unwrap();
    let fr = &get("friction").intervals;
    assert!(
        fr.len() == 1 && (fr[0].0 + 9.0).abs() < 1e-9 && (fr[0].1 + 10.0).abs() < 1e-9,
        "{fr:?}"
    );
    assert!((get("rolling").intervals[0].0 - 0.0825).abs() < 1e-9);
}

/// The final blind set (results/gap/blind2028_r07_G_medium_c6: Debian YADE, seed 2028, made after the
/// method was frozen, validated once: 13/14 named). Three of its cases against the committed medium
/// library: rolling resistance etaRoll = 0.3744 (fitted 0.370), a compliant subgrade of compliance
/// 0.4105 (K = 2.4e7 N/m^3; seen in the grid settlement, fitted 0.565), and a case of today's model
/// whose answer must be "none".
#[test]
fn final_blind_set_cases_are_diagnosed() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("results/gap");
    let (_, lib) = gap_run::load_library(&root.join("library_r07_G_medium_c6")).unwrap();
    let set = root.join("blind2028_r07_G_medium_c6");
    let pen = gap::calibrated_penalties(&lib, 4);
    let diag = |c: &str| {
        let obs = gap::read_observed(&set.join("cases").join(c).join("observed.csv")).unwrap();
        let t: gap_run::Truth = serde_json::from_str(
            &std::fs::read_to_string(set.join("truth").join(format!("{}.json", c))).unwrap(),
        )
        .unwrap();
        (gap::diagnose_with(&lib, &obs, 4, &pen).unwrap(), t)
    };
    let (d, t) = diag("case01");
    assert_eq!(t.effects, vec![("rolling".to_string(), 0.3744)]);
    assert_eq!(d.winner, "rolling");
    assert_eq!(d.model.len(), 1);
    assert!(
        (d.model[0].1 - 0.3744).abs() / 0.3744 < 0.05,
        "{:?}",
        d.model
    );
    assert!(
        d.gap_reduction > 0.9 && d.norm_gap_reduction > 0.8,
        "{:?}",
        d
    );
    let (d, t) = diag("case04");
    assert_eq!(t.effects, vec![("subgrade".to_string(), 0.4105)]);
    assert_eq!(d.winner, "subgrade");
    assert!((d.model[0].1 - 0.565).abs() < 0.01, "{:?}", d.model);
    assert!(d.dominant_part.starts_with("grid_settlement_mm"));
    assert!(d.norm_gap_reduction > 0.7, "{}", d.norm_gap_reduction);
    let (d, t) = diag("case02");
    assert!(t.effects.is_empty());
    assert_eq!(d.winner, "none");
    assert!(d.confidence > 0.9, "{}", d.confidence);
}

/// Issue 20's scoring rule: the effect named is right, "none" is right only for today's model or an
/// effect under the detectability floor, any other effect is wrong, and an effect outside the
/// catalogue is scored apart.
#[test]
fn scoring_counts_none_right_only_under_the_floor() {
    use gap_run::answer_is_right as right;
    assert!(right("rolling", "rolling", true, false));
    assert!(!right("none", "rolling", true, false)); // detectable and missed
    assert!(right("none", "grading", false, false)); // under the floor: "none" is the honest answer
    assert!(!right("grading", "damping", false, false)); // a wrong effect is wrong at any strength
    assert!(right("none", "none", false, false)); // today's model
    assert!(!right("rolling", "none", false, false)); // a false positive
    assert!(!right("rolling", "none", false, true)); // clumps: outside the catalogue, apart
}

/// The committed blind set made with Debian YADE (results/gap/blind2028, filtered design) scored by
/// issue 20's rule with the method of issue 20 (only detectable effects fitted, an answer only at
/// the floor): all 12 detectable dominant effects named, no wrong effect (the method frozen before
/// this set gave 11/12: case06, lower damping, was read as friction), and the held-out gap per
/// observable of the named cases.
/// A committed blind set validated in a scratch copy (cases and truth only) against the committed
/// medium library: the validation table.
/// Every line is in the scores table `t`.
fn has_lines(t: &str, lines: &[&str]) {
    for line in lines {
        assert!(t.contains(line), "{}\n{}", line, t);
    }
}

fn score_set(set: &str) -> String {
    score_set_with(set, "library_r07_G_medium_c6")
}

/// A temporary copy of the committed blind set `set` (its observed files and truth only), so that
/// validating it writes no committed file.
fn copy_set(set: &str, tag: &str) -> PathBuf {
    let src = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("results/gap/{}", set));
    let tmp = std::env::temp_dir().join(format!("ryade_{}_{}_{}", tag, set, std::process::id()));
    let _ = std::fs::remove_dir_all(&tmp);
    for sub in ["cases", "truth"] {
        for e in std::fs::read_dir(src.join(sub)).unwrap() {
            let e = e.unwrap();
            let to = tmp.join(sub).join(e.file_name());
            if e.path().is_dir() {
                std::fs::create_dir_all(&to).unwrap();
                std::fs::copy(e.path().join("observed.csv"), to.join("observed.csv")).unwrap();
            } else {
                std::fs::create_dir_all(to.parent().unwrap()).unwrap();
                std::fs::copy(e.path(), &to).unwrap();
            }
        }
    }
    tmp
}

/// `score_set` against the committed library `library`.
fn score_set_with(set: &str, library: &str) -> String {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let tmp = copy_set(set, "gap");
    let (_, lib) = gap_run::load_library(&root.join("results/gap").join(library)).unwrap();
    let scores = gap_run::validate(&tmp, &lib, 4).unwrap();
    let t = gap_run::format_scores(&scores);
    let _ = std::fs::remove_dir_all(&tmp);
    t
}

#[test]
fn blind2028_scored_by_issue_20s_rule() {
    let t = score_set("blind2028_r07_G_medium_c6");
    assert!(
        t.contains("Detectable dominant effects named: 12/12 (100 %)"),
        "{}",
        t
    );
    assert!(
        t.contains("Wrong effect named: 0 of 12 cases with catalogue effects"),
        "{}",
        t
    );
    assert!(
        t.contains("Named cases whose held-out rut gets worse: 2, of which the report warns: 2"),
        "{}",
        t
    );
    assert!(
        t.contains(
            "Median held-out gap reduction per observable, named cases: rut 81 %, porosity 18 %"
        ),
        "{}",
        t
    );
}

/// What blind2030u's answers must be, whichever r07 library diagnoses it.
const BLIND2030_NAMING: [&str; 4] = [
    "Detectable dominant effects named: 2/2 (100 %)",
    "Dominant effects under the floor: 8 (answered none 8, named it 0, named another 0)",
    "Wrong effect named: 0 of 10 cases with catalogue effects",
    "Cases of today's model: 2; false positives (an effect named): 0",
];

/// The unfiltered blind set (results/gap/blind2030u: Debian YADE, seed 2030, effects and strengths
/// drawn over the whole library range, two-effect cases, two clump cases outside the catalogue; made
/// after the method was frozen at 7ea5b89, validated once): both detectable dominant effects named,
/// no wrong effect, every effect under the floor answered "none", no false positive, and the clump
/// cases read as rolling resistance (the catalogue's proxy for angularity).
#[test]
fn unfiltered_blind_set_2030() {
    let t = score_set("blind2030u_r07_G_medium_c6");
    has_lines(&t, &BLIND2030_NAMING);
    has_lines(
        &t,
        &[
            "Outside the catalogue: case03 (clump 4): named rolling",
            "Median held-out gap reduction per observable, named cases: rut 62 %, porosity 6 %, rebound -62 %, grid settlement 89 %",
        ],
    );
}

/// Issue 20's second scenario, r05 G medium (959 spheres): its library built by `compat gap
/// --make-library --scenario r05` on the fast engine (results/gap/library_r05_G_medium_c6), then an
/// unfiltered blind set in Debian YADE (results/gap/blind2031u: seed 2031, 14 cases, 2 of today's
/// model, 2 clump cases, two-effect cases). Scored once blind with the 4-seed library (session 15:
/// 5/5, 0 wrong, 0 false positives; rut 93 %, porosity 54 %, rebound 74 %, grid settlement 94 %); since
/// session 16 it is the dev set of two changes: the library completed to the 15 seeds its noise asks
/// for (`gap::seeds_needed`) and the pressure tracking error as a fifth observable (its observed.csv
/// files gained the column from the same YADE runs' history.csv). With both: the 5 detectable
/// dominant effects named, no false positive on YADE's own model, but one grading case under the
/// floor (signal 2.1) named damping -0.073 (at the floor; "none" with 14 seeds and without the
/// tracking error).
#[test]
fn second_scenario_r05_unfiltered_blind_set_2031() {
    let t = score_set_with("blind2031u_r05_G_medium_c6", "library_r05_G_medium_c6");
    has_lines(
        &t,
        &[
            "Detectable dominant effects named: 5/5 (100 %)",
            "Dominant effects under the floor: 5 (answered none 4, named it 0, named another 1)",
            "Wrong effect named: 1 of 10 cases with catalogue effects",
            "Cases of today's model: 2; false positives (an effect named): 0",
            "Named cases whose held-out rut gets worse: 0",
            "Median held-out gap reduction per observable, named cases: rut 89 %, porosity 28 %, rebound 62 %, grid settlement 74 %, tracking error 29 %",
            "(held-out normalised RMS > 1; cases): rut 89 % (6), porosity 83 % (1), rebound 88 % (4), grid settlement 86 % (5), tracking error 23 % (1)",
        ],
    );
}

/// Issue 20's blind set blind2032u_r05_G_medium_c6 (Debian YADE, seed 2032, 14 unfiltered cases with
/// the tracking error recorded; made after the method was frozen at be3f4da and scored once: 6/6,
/// 0 wrong, 0 false positives; held-out rut 36 %, porosity -1 %, rebound 58 %, grid settlement 84 %,
/// tracking 59 %). A review then found the frozen method compared the tracking error's increments,
/// not its levels; re-scored (seen) with the fix: the same answers, every detectable dominant
/// effect named (6/6), no wrong effect, no false positive on YADE's own model, the 4 effects under
/// the floor answered "none"; the two subgrade cases whose held-out rut gets worse (today's model
/// happens to hit it: 0.14-0.17 noise sd before, 0.36-0.59 after) are warned in their reports.
#[test]
fn second_scenario_fresh_blind_set_2032() {
    let t = score_set_with("blind2032u_r05_G_medium_c6", "library_r05_G_medium_c6");
    has_lines(
        &t,
        &[
            "Detectable dominant effects named: 6/6 (100 %)",
            "Dominant effects under the floor: 4 (answered none 4, named it 0, named another 0)",
            "Wrong effect named: 0 of 10 cases with catalogue effects",
            "Cases of today's model: 2; false positives (an effect named): 0",
            "Named cases whose held-out rut gets worse: 2, of which the report warns: 2",
            "Median held-out gap reduction per observable, named cases: rut 35 %, porosity 2 %, rebound 55 %, grid settlement 88 %, tracking error 69 %",
            "(held-out normalised RMS > 1; cases): rut 79 % (3), porosity 86 % (1), rebound 92 % (3), grid settlement 88 % (5), tracking error 69 % (4)",
        ],
    );
}

/// A library built from scratch by the seed rule on the fast engine (`compat gap --make-library
/// --scenario r07 --size medium --cycles 6`: a pilot of 10 baseline and 3 effect seeds measured the
/// paired scatter at 1.10 times one run's noise and asked for 13 seeds; 260 runs, 7.0 min on 2
/// cores): the full library's own noise asks for no more (the pilot's estimate held), and its 13
/// effect seeds keep the shifts' variance under `SHIFT_VAR` of the noise's. Diagnosing the r07
/// unfiltered blind set 2030u (Debian YADE, seen; scored before with the 4-seed YADE-order
/// library): both detectable effects named, the 8 under the floor answered none, no false positive.
#[test]
fn rule_built_fast_library_r07() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("results/gap");
    let (idx, lib) = gap_run::load_library(&root.join("library_r07_G_medium_c6_fast")).unwrap();
    assert_eq!((idx.baseline_seeds.len(), idx.effect_seeds.len()), (13, 13));
    assert_eq!(idx.engine, "fast");
    let pilot = idx.seed_choice.as_ref().unwrap();
    assert_eq!(pilot.effect, 13);
    let now = gap::seeds_needed(&lib, 4).unwrap();
    assert!(now.effect <= 13, "{now:?}");
    assert!(now.mean_ratio2 / 13.0 <= gap::SHIFT_VAR, "{now:?}");
    let t = score_set_with("blind2030u_r07_G_medium_c6", "library_r07_G_medium_c6_fast");
    has_lines(&t, &BLIND2030_NAMING);
}

/// Issue 20's fresh blind set after the tracking-level fix (results/gap/blind2033u_r05_G_medium_c6:
/// Debian YADE, seed 2033, 14 unfiltered cases; made after the method was frozen at 761fdd1 and
/// scored once). No false positive on YADE's own model and no unwarned worse held-out rut, but only
/// 3 of the 4 detectable dominant effects named: a higher damping (0.21, signal 6.9) was read as
/// rolling 0.039 + damping 0.12 (both lower the rut; rolling's larger signal makes it the dominant
/// one), and a soft subgrade under the floor (0.094, signal 2.8) as rolling 0.035. The same two
/// answers without the tracking column; with it, a lower damping under the floor is named right.
#[test]
fn second_scenario_fresh_blind_set_2033() {
    let t = score_set_with("blind2033u_r05_G_medium_c6", "library_r05_G_medium_c6");
    has_lines(
        &t,
        &[
            "Detectable dominant effects named: 3/4 (75 %)",
            "Dominant effects under the floor: 6 (answered none 4, named it 1, named another 1)",
            "Wrong effect named: 2 of 10 cases with catalogue effects",
            "Cases of today's model: 2; false positives (an effect named): 0",
            "Named cases whose held-out rut gets worse: 0",
            "| case01 | damping 0.2141 | damping | 6.9 | NO: rolling (0.73) | rolling 0.039 + damping 0.120 |",
            "Median held-out gap reduction per observable, named cases: rut 95 %, porosity 59 %, rebound 32 %, grid settlement 82 %, tracking error 49 %",
        ],
    );
}

/// Issue 20's fresh blind sets of session 17, made after the method was frozen (diagnoses unchanged
/// since 761fdd1; made at 5cc37ce) and scored once, each with its scenario's library:
/// * results/gap/blind2034u_r05_G_medium_c6 (Debian YADE, seed 2034, 14 unfiltered cases, 2 of
///   today's model, 2 of clumps): every detectable dominant effect named (4/4), no wrong effect, the
///   6 effects under the floor answered none, no false positive; the two named cases whose held-out
///   rut gets worse (subgrade cases where today's model happens to hit it) are warned. The held-out
///   medians per observable do not all reach 70 % (rut 24 %, tracking error 18 %).
#[test]
fn fresh_blind_set_2034_r05() {
    let t = score_set_with("blind2034u_r05_G_medium_c6", "library_r05_G_medium_c6");
    has_lines(
        &t,
        &[
            "Detectable dominant effects named: 4/4 (100 %)",
            "Dominant effects under the floor: 6 (answered none 6, named it 0, named another 0)",
            "Wrong effect named: 0 of 10 cases with catalogue effects",
            "Cases of today's model: 2; false positives (an effect named): 0",
            "Named cases whose held-out rut gets worse: 2, of which the report warns: 2",
            "Median held-out gap reduction per observable, named cases: rut 24 %, porosity 32 %, rebound 72 %, grid settlement 78 %, tracking error 18 %",
        ],
    );
}

/// * results/gap/blind2035u_r07_G_medium_c6 (Debian YADE, seed 2035, the same design, the
///   rule-built fast library): one detectable dominant effect in the draw (rolling 0.23), named;
///   the 9 under the floor answered none; no wrong effect, no false positive.
#[test]
fn fresh_blind_set_2035_r07() {
    let t = score_set_with("blind2035u_r07_G_medium_c6", "library_r07_G_medium_c6_fast");
    has_lines(
        &t,
        &[
            "Detectable dominant effects named: 1/1 (100 %)",
            "Dominant effects under the floor: 9 (answered none 9, named it 0, named another 0)",
            "Wrong effect named: 0 of 10 cases with catalogue effects",
            "Cases of today's model: 2; false positives (an effect named): 0",
            "Named cases whose held-out rut gets worse: 0",
        ],
    );
}

/// P(X <= k) and P(X >= k) for X ~ Binomial(n, p).
fn binomial_tails(n: usize, p: f64, k: usize) -> (f64, f64) {
    let pmf = |j: usize| -> f64 {
        let mut c = 1.0;
        for i in 0..j {
            c *= (n - i) as f64 / (i + 1) as f64;
        }
        c * p.powi(j as i32) * (1.0 - p).powi((n - j) as i32)
    };
    let le: f64 = (0..=k).map(pmf).sum();
    let ge: f64 = (k..=n).map(pmf).sum();
    (le, ge)
}

/// `compat gap --self-test` measures the method's error rates from the library alone (each of its
/// 300 runs diagnosed by the library without that specimen). On the r05 G medium library they are
/// consistent with what Debian YADE's four unfiltered blind sets of that scenario showed (2031u-2034u; 56
/// cases, the same scoring, today's method): each blind count lies inside the two-sided 5 %
/// binomial tails of the self-test's rate (self-test 121/135 detectable named and 16/285 wrong;
/// YADE 18/19 and 3/40). With 19 and 40 blind cases the check is weak (it admits a named rate from
/// about 0.75 and 0 to 6 wrong): it catches a grossly optimistic self-test, such as one that
/// diagnosed each group's mean run instead of its single runs (no run-to-run noise: 135/135 named,
/// 0 wrong; fails here, checked). The blind sets draw strengths at random, the self-test uses the
/// library's own.
#[test]
fn self_test_predicts_the_yade_blind_rates_r05() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("results/gap");
    let (_, lib) = gap_run::load_library(&root.join("library_r05_G_medium_c6")).unwrap();
    let st = gap_run::self_test(&lib, 4, 2).unwrap();
    assert_eq!(st.len(), 300);
    let rates = |s: &[gap_run::CaseScore]| {
        let k = gap_run::rule_counts(s, gap_run::DETECTABILITY_FLOOR);
        (k.named, k.detectable, k.wrong, k.catalogue, k.false_pos)
    };
    let (sn, sd, sw, sc, sfp) = rates(&st);
    eprintln!("self-test: named {sn}/{sd}, wrong {sw}/{sc}, false positives {sfp}");
    let (mut yn, mut yd, mut yw, mut yc, mut yfp) = (0, 0, 0, 0, 0);
    for set in [
        "blind2031u_r05_G_medium_c6",
        "blind2032u_r05_G_medium_c6",
        "blind2033u_r05_G_medium_c6",
        "blind2034u_r05_G_medium_c6",
    ] {
        let tmp = copy_set(set, "st");
        let s = gap_run::validate(&tmp, &lib, 4).unwrap();
        let _ = std::fs::remove_dir_all(&tmp);
        let (a, b, c, d, e) = rates(&s);
        (yn, yd, yw, yc, yfp) = (yn + a, yd + b, yw + c, yc + d, yfp + e);
    }
    eprintln!("YADE blind sets: named {yn}/{yd}, wrong {yw}/{yc}, false positives {yfp}");
    assert_eq!((yn, yd, yw, yc, yfp), (18, 19, 3, 40, 0));
    let inside = |k: usize, n: usize, p: f64| {
        let (le, ge) = binomial_tails(n, p, k);
        le > 0.025 && ge > 0.025
    };
    let p_named = sn as f64 / sd as f64;
    let p_wrong = sw as f64 / sc as f64;
    assert!(
        inside(yn, yd, p_named),
        "detectable named: YADE {yn}/{yd} against the self-test's {p_named:.3}"
    );
    assert!(
        inside(yw, yc, p_wrong),
        "wrong named: YADE {yw}/{yc} against the self-test's {p_wrong:.3}"
    );
    assert_eq!((sfp, yfp), (0, 0));
}

/// Issue 20's "median held-out gap reduction >= 70 % on every observable" against the oracle: the
/// true effects at their true strengths, predicted by the library (`gap::heldout_of`), on the same
/// cases. On the r05 library's self-test and on Debian YADE's four unfiltered r05 blind sets the
/// oracle closes most of the held-out rut gap (a model that knows the truth must: this fails,
/// checked, when the oracle is given today's model instead) but well under 70 % of the porosity
/// gap: one observed run's own noise, which no model removes, is most of what is left there, so the
/// target asks more than the true model itself gives with these observables (a reference, not a
/// strict bound: a fitted strength can do a little better by absorbing part of the specimen's own
/// departure). And the method's own reductions on the cases it names right are the oracle's to
/// within 15 points on the rut.
#[test]
fn the_true_model_falls_short_of_the_heldout_target_r05() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("results/gap");
    let (_, lib) = gap_run::load_library(&root.join("library_r05_G_medium_c6")).unwrap();
    let med = |s: &[&gap_run::CaseScore], o: &str, oracle: bool| -> f64 {
        gap_run::median(gap_run::heldout_reductions(s, o, oracle, false))
            .unwrap_or_else(|| panic!("no held-out {o}"))
    };
    let st = gap_run::self_test(&lib, 4, 2).unwrap();
    let mut yade = Vec::new();
    for set in [
        "blind2031u_r05_G_medium_c6",
        "blind2032u_r05_G_medium_c6",
        "blind2033u_r05_G_medium_c6",
        "blind2034u_r05_G_medium_c6",
    ] {
        let tmp = copy_set(set, "oracle");
        yade.extend(gap_run::validate(&tmp, &lib, 4).unwrap());
        let _ = std::fs::remove_dir_all(&tmp);
    }
    for (what, s) in [("self-test", &st), ("YADE blind sets", &yade)] {
        let det: Vec<&gap_run::CaseScore> = s.iter().filter(|c| c.detectable).collect();
        let right: Vec<&gap_run::CaseScore> = det.iter().filter(|c| c.correct).copied().collect();
        let (rut, por) = (med(&det, "rut_mm", true), med(&det, "porosity", true));
        eprintln!(
            "{what}: oracle on {} detectable cases: rut {rut:.2}, porosity {por:.2}; method on {} named right: rut {:.2} (oracle {:.2})",
            det.len(),
            right.len(),
            med(&right, "rut_mm", false),
            med(&right, "rut_mm", true)
        );
        assert!(rut > 0.6, "{what}: the oracle closes the rut gap: {rut}");
        assert!(por < 0.6, "{what}: the oracle's porosity reduction {por}");
        assert!(
            (med(&right, "rut_mm", false) - med(&right, "rut_mm", true)).abs() < 0.15,
            "{what}: method and oracle on the rut"
        );
    }
}
