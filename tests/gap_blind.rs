//! The gap diagnosis on a blind case made by Debian YADE (results/gap/blind_r07_G_tiny_c6/case04: one
//! hidden effect, rolling resistance etaRoll = 0.435, truth stored apart) against the committed ryade
//! library (results/gap/library_r07_G_tiny_c6): the effect must be named, its strength land inside the
//! library range near the truth, and the held-out rut gap must shrink by more than half.
//! The full validation score (12 cases) is in results/gap/blind_r07_G_tiny_c6/validation.md.

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
