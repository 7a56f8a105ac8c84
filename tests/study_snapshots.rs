//! insta snapshots of ryade's own study histories (r07 tiny seed 1, N/G/F, 2 load cycles from the
//! committed YADE specimens): they catch unintended changes of ryade's output. The YADE comparison
//! itself is `compat diff r05/r03/r07` (band rule and exact-match horizon); these snapshots were
//! accepted only after that diff showed them byte-identical to YADE's own histories for the same
//! specimens (golden/study/r07_*_tiny_s1/history.csv, first 3 rows).
//!
//! Needs the `yade` compat package in `python3` (test.sh installs it before `cargo test`).

use std::path::PathBuf;
use std::process::Command;

fn run_case(case: &str) -> String {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let out = std::env::temp_dir().join(format!("ryade_snap_{}_{}", case, std::process::id()));
    let spec = root.join(format!("golden/study/r07_{}_tiny_s1/specimen.json", case));
    let st = Command::new(env!("CARGO_BIN_EXE_compat"))
        .arg("run")
        .arg(root.join("yade_ref/study/study.py"))
        .args(["--", "--import-specimen"])
        .arg(&spec)
        .args(["--cycles", "2", "--out"])
        .arg(&out)
        .output()
        .expect("running compat run");
    assert!(
        st.status.success(),
        "compat run study.py failed (is the yade compat package installed? pip install ./compat):\n{}",
        String::from_utf8_lossy(&st.stderr)
    );
    let h = std::fs::read_to_string(out.join("history.csv")).unwrap();
    // the same rows as YADE's golden (which ran 5 cycles): header + cycles 0..2, except `complete`
    // is identical and the 5-cycle run's rows 0-2 match the 2-cycle run's exactly
    let golden = std::fs::read_to_string(
        root.join(format!("golden/study/r07_{}_tiny_s1/history.csv", case)),
    )
    .unwrap();
    let g3: Vec<&str> = golden.lines().take(4).collect();
    let h3: Vec<&str> = h.lines().take(4).collect();
    assert_eq!(
        h3, g3,
        "ryade's r07 {} history departs from YADE's golden",
        case
    );
    std::fs::remove_dir_all(&out).ok();
    h
}

#[test]
fn study_r07_tiny_histories() {
    for case in ["N", "G", "F"] {
        insta::assert_snapshot!(format!("r07_{}_tiny_s1_c2", case), run_case(case));
    }
}
