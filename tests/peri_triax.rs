//! PeriTriaxController (pkg/dem/PeriIsoCompressor.cpp) and the moving periodic cell: the golden scene
//! `peri_triax` (YADE 2023.02a, digest scene) must be bit-identical, and the checks must notice a
//! change of the controller's parameters, of its doneHook timing and of the Love-Weber stress.
mod common;

use ryade::cell::Cell;
use ryade::harness::micro;
use ryade::io::scene_json;
use ryade::math::{Mat3, Vec3};
use ryade::peri_triax::{get_stress, PeriTriax};
use ryade::scene::Engine;
use ryade::utils;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A copy of the golden `peri_triax` with the scene JSON edited.
fn edited_copy(tmp: &Path, edit: impl Fn(&mut serde_json::Value)) -> PathBuf {
    std::fs::create_dir_all(tmp).unwrap();
    let src = root().join("golden/micro");
    for suffix in [
        "bodies.csv.gz",
        "intrs.csv.gz",
        "digest.csv.gz",
        "peri.csv.gz",
    ] {
        std::fs::copy(
            src.join(format!("peri_triax.{}", suffix)),
            tmp.join(format!("peri_triax.{}", suffix)),
        )
        .unwrap();
    }
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(src.join("peri_triax.scene.json")).unwrap())
            .unwrap();
    edit(&mut v);
    let p = tmp.join("peri_triax.scene.json");
    std::fs::write(&p, serde_json::to_string(&v).unwrap()).unwrap();
    p
}

fn controller(v: &mut serde_json::Value) -> &mut serde_json::Value {
    v["engines"]
        .as_array_mut()
        .unwrap()
        .iter_mut()
        .find(|e| e["class"] == "PeriTriaxController")
        .unwrap()
}

#[test]
fn golden_peri_triax_is_bit_identical_and_both_hooks_fire() {
    let p = root().join("golden/micro/peri_triax.scene.json");
    let sf = scene_json::load(&p).unwrap();
    assert!(sf.scene.cell.is_some());
    let r = micro::diff_scene(sf, &p).unwrap();
    assert_eq!(
        r.mismatches,
        0,
        "{}",
        micro::format_table(std::slice::from_ref(&r))
    );
    assert!(r.values > 4_000_000, "{} values", r.values);

    // every recorded doneHook firing was consumed, and the engine ends in the dynCell stage
    let mut s = scene_json::load(&p).unwrap();
    for _ in 0..s.steps {
        s.scene.step().unwrap();
    }
    let Some(Engine::PeriTriax(t)) = s
        .scene
        .engines
        .iter()
        .find(|e| matches!(e, Engine::PeriTriax(_)))
    else {
        panic!("no controller")
    };
    assert!(t.hook_events.is_empty(), "{:?}", t.hook_events);
    assert!(t.dyn_cell && t.stress_mask == 7 && t.done_hook.is_empty());
    assert!(t.mass > 0.0, "the cell mass was set from the bodies");
}

/// A 1e-9 relative change of growDamping (it acts only when the servo is not saturated) must be
/// seen by the per-step digests.
#[test]
fn a_changed_grow_damping_is_detected() {
    let tmp = std::env::temp_dir().join(format!("ryade-peritriax-gd-{}", std::process::id()));
    let p = edited_copy(&tmp, |v| {
        controller(v)["growDamping"] = serde_json::json!(0.25 * (1.0 + 1e-9));
    });
    let r = micro::diff_scene(scene_json::load(&p).unwrap(), &p).unwrap();
    assert!(r.mismatches > 0);
    let first = r.first.unwrap();
    assert!(first.what.contains("digest"), "{}", first.what);
}

/// A doneHook that fires at another iteration than in YADE stops the run with both iterations.
#[test]
fn a_done_hook_at_another_iteration_is_an_error() {
    let tmp = std::env::temp_dir().join(format!("ryade-peritriax-hook-{}", std::process::id()));
    let p = edited_copy(&tmp, |v| {
        controller(v)["doneHookEvents"][0]["iter"] = serde_json::json!(689);
    });
    let r = micro::diff_scene(scene_json::load(&p).unwrap(), &p).unwrap();
    let e = r.error.expect("the replay must fail");
    assert!(e.contains("690") && e.contains("689"), "{}", e);
}

/// Without recorded effects a doneHook needs Python: `Scene::step` says so instead of skipping it.
#[test]
fn a_python_done_hook_without_runner_is_an_error() {
    let p = root().join("golden/micro/peri_triax.scene.json");
    let mut s = scene_json::load(&p).unwrap().scene;
    for e in s.engines.iter_mut() {
        if let Engine::PeriTriax(t) = e {
            t.hook_events.clear();
            t.replay_hooks = false;
        }
    }
    let mut err = None;
    for _ in 0..800 {
        if let Err(e) = s.step() {
            err = Some(e.to_string());
            break;
        }
    }
    let e = err.expect("the hook fires at iteration 690");
    assert!(e.contains("stage2()") && e.contains("690"), "{}", e);
}

/// A strain-controlled cell with no particles: `strain = log(trsf)` reaches the goal, and the strain
/// rate never exceeds maxStrainRate.
#[test]
fn strain_control_reaches_the_goal_at_the_capped_rate() {
    let mut s = common::scene_with_material(1e-3, 0.5);
    s.cell = Some(Cell::set_box(Vec3::new(1.0, 1.0, 1.0)).unwrap());
    // two distant spheres, so the stress is zero and the cell may shrink freely
    s.bodies.push(utils::sphere(
        Vec3::new(0.1, 0.1, 0.1),
        0.01,
        0,
        2600.0,
        false,
    ));
    s.bodies.push(utils::sphere(
        Vec3::new(0.6, 0.6, 0.6),
        0.01,
        0,
        2600.0,
        false,
    ));
    let mut engines = common::engines(Vec3::zeros(), 0.0);
    engines.insert(
        3,
        Engine::PeriTriax(Box::new(PeriTriax {
            goal: Vec3::new(-0.05, 0.0, 0.02),
            stress_mask: 0,
            max_strain_rate: Vec3::new(2.0, 2.0, 2.0),
            ..Default::default()
        })),
    );
    s.engines = engines;
    let mut max_rate: f64 = 0.0;
    for _ in 0..400 {
        s.step().unwrap();
        let c = s.cell.as_ref().unwrap();
        for i in 0..3 {
            max_rate = max_rate.max(c.vel_grad[(i, i)].abs());
        }
    }
    assert!(max_rate <= 2.0);
    let c = s.cell.as_ref().unwrap();
    let strain: Vec<f64> = (0..3).map(|i| c.trsf[(i, i)].ln()).collect();
    assert!((strain[0] + 0.05).abs() < 1e-6, "{:?}", strain);
    assert!(strain[1].abs() < 1e-9, "{:?}", strain);
    assert!((strain[2] - 0.02).abs() < 1e-6, "{:?}", strain);
    // the cell size follows trsf
    assert!((c.size()[0] - (-0.05f64).exp()).abs() < 1e-6);
}

/// `Shop::getStress` on two overlapping spheres across the periodic boundary: σ = f ⊗ branch / V.
#[test]
fn love_weber_stress_of_one_contact_across_the_boundary() {
    let mut s = common::scene_with_material(1e-6, 0.5);
    s.cell = Some(Cell::new(Mat3::from_diagonal(&Vec3::new(0.1, 0.2, 0.3))).unwrap());
    s.bodies.push(utils::sphere(
        Vec3::new(0.005, 0.1, 0.1),
        0.01,
        0,
        2600.0,
        false,
    ));
    s.bodies.push(utils::sphere(
        Vec3::new(0.0865, 0.1, 0.1),
        0.01,
        0,
        2600.0,
        false,
    ));
    s.engines = common::engines(Vec3::zeros(), 0.0);
    s.step().unwrap();
    assert_eq!(s.interactions.count_real(), 1);
    let it = &s.interactions.list[0];
    assert_eq!(
        it.cell_dist,
        [-1, 0, 0],
        "body 2 is seen one period to the left"
    );
    let st = get_stress(&s, 0.0).unwrap();
    let ph = it.phys.unwrap();
    let f = ph.normal_force + ph.shear_force;
    let branch = s.bodies.pos[0] - (s.bodies.pos[1] - Vec3::new(0.1, 0.0, 0.0));
    let v = 0.1 * (0.2 * 0.3);
    assert!(((st[(0, 0)] - f[0] * branch[0] / v) / st[(0, 0)]).abs() < 1e-12);
    assert!(
        st[(0, 0)] < 0.0,
        "compression is negative in YADE: {}",
        st[(0, 0)]
    );
    assert_eq!(st[(1, 1)], 0.0);
}
