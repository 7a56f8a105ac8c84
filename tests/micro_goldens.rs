//! ryade against YADE 2023.02a's golden records (golden/micro, golden/meso; written by the scripts in
//! yade_ref/ and re-checked against a fresh YADE run in CI): every double of every body and contact at
//! every step must be bit-identical, and the comparison must notice a one-ulp perturbation.
use ryade::harness::{meso, micro};
use ryade::io::scene_json;
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn every_micro_scene_is_bit_identical_to_yade() {
    let reps = micro::diff_dir(&root().join("golden/micro")).unwrap();
    assert!(
        reps.len() >= 9,
        "expected at least 9 micro scenes, found {}",
        reps.len()
    );
    for r in &reps {
        assert!(
            r.values > 1000,
            "{}: too few values compared ({})",
            r.scene,
            r.values
        );
        assert_eq!(
            r.mismatches,
            0,
            "{}",
            micro::format_table(std::slice::from_ref(r))
        );
        assert_eq!(
            r.order_differs_steps, 0,
            "{}: interaction order differs from YADE's",
            r.scene
        );
    }
}

#[test]
fn meso_packing_is_identical_for_all_steps() {
    let r = meso::diff_meso(&root().join("golden/meso")).unwrap();
    assert!(r.bodies >= 500);
    assert_eq!(r.steps, 2000);
    assert_eq!(r.first_diff_step, None, "{}", meso::format_report(&r));
    assert_eq!(r.identical_steps, 2001);
}

fn perturbed_copy(scene: &str, tmp: &Path, edit: impl Fn(&mut serde_json::Value)) -> PathBuf {
    std::fs::create_dir_all(tmp).unwrap();
    let src = root().join("golden/micro");
    for suffix in ["bodies.csv.gz", "intrs.csv.gz"] {
        std::fs::copy(
            src.join(format!("{}.{}", scene, suffix)),
            tmp.join(format!("{}.{}", scene, suffix)),
        )
        .unwrap();
    }
    let mut v: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(src.join(format!("{}.scene.json", scene))).unwrap(),
    )
    .unwrap();
    edit(&mut v);
    let p = tmp.join(format!("{}.scene.json", scene));
    std::fs::write(&p, serde_json::to_string(&v).unwrap()).unwrap();
    p
}

/// Moving one sphere of the pile by one ulp must be reported, and the CLI must exit non-zero.
#[test]
fn a_one_ulp_perturbation_is_detected() {
    let tmp = std::env::temp_dir().join(format!("ryade-perturb-{}", std::process::id()));
    let p = perturbed_copy("pile", &tmp, |v| {
        let bodies = v["bodies"].as_array_mut().unwrap();
        let b = bodies
            .iter_mut()
            .find(|b| b["shape"]["class"] == "Sphere")
            .unwrap();
        let x = b["pos"][0].as_f64().unwrap();
        b["pos"][0] = serde_json::json!(f64::from_bits(x.to_bits() + 1));
    });
    let r = micro::diff_scene(scene_json::load(&p).unwrap(), &p).unwrap();
    assert!(r.mismatches > 0);
    let first = r.first.unwrap();
    assert_eq!(
        first.step, 0,
        "the initial position already differs by one ulp"
    );
    assert!(first.what.contains("pos_x"), "{}", first.what);
    assert_eq!(r.max_ulp.min(1), 1);

    let out = Command::new(env!("CARGO_BIN_EXE_compat"))
        .args(["diff", "micro", "--golden"])
        .arg(&tmp)
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(1),
        "compat diff must exit 1 on a mismatch"
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("pile") && !text.contains(" 0 mismatches"),
        "{}",
        text
    );
}

/// A physics change that leaves the start state alone (damping 0.2 -> 0.2000000001) must show up as
/// a divergence after the first step.
#[test]
fn a_changed_parameter_is_detected_after_step_one() {
    let tmp = std::env::temp_dir().join(format!("ryade-perturb2-{}", std::process::id()));
    let p = perturbed_copy("facet_tilted", &tmp, |v| {
        for e in v["engines"].as_array_mut().unwrap() {
            if e["class"] == "NewtonIntegrator" {
                e["damping"] = serde_json::json!(0.2000000001);
            }
        }
    });
    let r = micro::diff_scene(scene_json::load(&p).unwrap(), &p).unwrap();
    assert!(r.mismatches > 0);
    assert_eq!(r.first.unwrap().step, 1);
}
