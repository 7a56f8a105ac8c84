//! Bad input must stop a run with a message that names the body, the step and the likely cause, and
//! keep everything recorded before the failure.
mod common;

use ryade::integrator::Newton;
use ryade::io::scene_json;
use ryade::math::Vec3;
use ryade::scene::Scene;
use ryade::utils;
use std::process::Command;

/// Three spheres resting on each other under gravity, with the given dt.
fn column(dt: f64) -> Scene {
    let mut s = common::scene_with_material(dt, 0.5);
    for k in 0..3 {
        s.bodies.push(utils::sphere(
            Vec3::new(0.0, 0.0, 0.0199 * k as f64),
            0.01,
            0,
            2600.0,
            k == 0,
        ));
    }
    s.engines = common::engines(Vec3::new(0.0, 0.0, -9.81), Newton::default().damping);
    s
}

fn write_scene(s: &Scene, name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("ryade-bad-{}-{}", name, std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(format!("{}.scene.json", name));
    std::fs::write(
        &p,
        serde_json::to_string(&scene_json::to_value(s, 50)).unwrap(),
    )
    .unwrap();
    p
}

#[test]
fn time_step_above_critical_is_refused_with_the_numbers() {
    // PWave dt = r/sqrt(E/rho) = 1.6e-4 s; the contact's critical dt is about 2.9x that
    let s = column(2e-3);
    let err = utils::check_time_step(&s).unwrap_err();
    assert!(err.contains("critical time step"), "{}", err);
    assert!(err.contains("PWaveTimeStep"), "{}", err);
    let ok = column(0.5 * utils::pwave_time_step(&s).unwrap());
    utils::check_time_step(&ok).unwrap();
    // the CLI refuses too, with a non-zero exit code
    let p = write_scene(&s, "bigdt");
    let out = Command::new(env!("CARGO_BIN_EXE_compat"))
        .arg("scene")
        .arg(&p)
        .arg("--out")
        .arg(p.parent().unwrap())
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("critical time step"));
}

#[test]
fn nan_in_a_state_stops_the_run_naming_body_and_step_and_keeps_records() {
    let mut s = column(1e-5);
    s.bodies.vel[2] = Vec3::new(0.0, f64::NAN, 0.0);
    let p = write_scene(&s, "nan");
    let outdir = p.parent().unwrap().join("out");
    // JSON cannot carry NaN: the scene file must be rejected with a message naming the value
    let text = std::fs::read_to_string(&p).unwrap();
    assert!(text.contains("null"), "serde writes NaN as null");
    let out = Command::new(env!("CARGO_BIN_EXE_compat"))
        .arg("scene")
        .arg(&p)
        .arg("--out")
        .arg(&outdir)
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("body #2") && err.contains("vel"), "{}", err);

    // a NaN that appears during the run: the integrator stops at the step it appears
    s.step().unwrap_err();
    let mut s = column(1e-5);
    for _ in 0..5 {
        s.step().unwrap();
    }
    s.bodies.vel[1][2] = f64::NAN;
    let e = s.step().unwrap_err().to_string();
    assert!(e.contains("step 5") && e.contains("body #1"), "{}", e);
    assert!(e.contains("time step"), "names the likely cause: {}", e);
}

#[test]
fn non_finite_report_says_what_was_found_not_always_the_time_step() {
    // issue 18: a NaN velocity at 1/16 of the critical step used to be blamed on "the time step
    // above the critical one"; the report now gives the quantity, dt against the critical step, the
    // body's contacts, and the cause those point to
    let mut s = column(1e-5);
    for _ in 0..5 {
        s.step().unwrap();
    }
    s.bodies.vel[1][2] = f64::NAN;
    let e = s.step().unwrap_err().to_string();
    let crit = utils::pwave_time_step(&s).unwrap();
    assert!(e.contains("body #1 (Sphere of radius 1e-2 m"), "{}", e);
    assert!(
        e.contains("its force (NaN, NaN, NaN) N is not finite"),
        "{}",
        e
    );
    assert!(
        e.contains(&format!("{:.3} x the critical time step", 1e-5 / crit)),
        "{}",
        e
    );
    assert!(e.contains("Its contacts now (2): #"), "{}", e);
    assert!(e.contains("already not finite"), "{}", e);
    assert!(!e.contains("above the critical"), "{}", e);

    // the same NaN with a time step above the critical one (set without the check): then the time
    // step is named as the cause
    let mut s = column(1e-5);
    s.dt = 6.0 * utils::pwave_time_step(&s).unwrap();
    s.bodies.vel[1][2] = f64::NAN;
    let e = s.step().unwrap_err().to_string();
    assert!(e.contains("above the critical one"), "{}", e);
    assert!(e.contains("6.000 x the critical time step"), "{}", e);
}

#[test]
fn records_before_a_failure_are_kept_on_disk() {
    let mut s = column(1e-5);
    let dir = std::env::temp_dir().join(format!("ryade-keep-{}", std::process::id()));
    let mut rec = ryade::io::golden::Recorder::create(&dir, "col").unwrap();
    rec.record(&s).unwrap();
    for _ in 0..3 {
        s.step().unwrap();
        rec.record(&s).unwrap();
    }
    s.bodies.pos[2][0] = f64::INFINITY;
    assert!(s.step().is_err());
    drop(rec);
    let rows = ryade::io::golden::read_bodies(&dir.join("col.bodies.csv")).unwrap();
    assert_eq!(rows.len(), 4 * 3, "steps 0..3 of 3 bodies are on disk");
    assert_eq!(rows.last().unwrap().step, 3);
}
