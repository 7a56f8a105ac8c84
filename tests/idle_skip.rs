//! Regression guard for `IdleSkip` (src/idle_skip.rs): the interaction loop skips YADE's distance
//! check of an idle sphere-sphere pair while an accumulated bound proves the spheres are still
//! apart. YADE checks every pair every step, so a skip that outlived the proof would create a
//! contact one step late and change every later bit. Here a sphere approaches another at constant
//! speed (no gravity, no damping), then, in a second run, is teleported into contact the way a
//! Python script writing `state.pos` would; at every step the contact must exist exactly when
//! YADE's check `(r1 + r2)² - |d|² >= 0` on the positions the loop saw says so.
mod common;

use ryade::math::{norm2, Vec3};
use ryade::scene::Scene;
use ryade::utils;

fn scene(gap: f64, speed: f64) -> Scene {
    let mut s = common::scene_with_material(1e-5, 0.5);
    s.bodies
        .push(utils::sphere(Vec3::zeros(), 0.01, 0, 2600.0, false));
    let mut b = utils::sphere(Vec3::new(0.02 + gap, 0.0, 0.0), 0.01, 0, 2600.0, false);
    b.vel = Vec3::new(-speed, 0.0, 0.0);
    s.bodies.push(b);
    s.engines = common::engines(Vec3::zeros(), 0.0);
    s
}

/// Steps `s` until `stop` says so (or `max` steps); asserts at each step that the pair is real
/// exactly when YADE's check on the positions before the step says it touches. Returns how many
/// steps the pair was idle with its check skipped.
fn run_checking(s: &mut Scene, max: usize, mut before: impl FnMut(&mut Scene, usize)) -> usize {
    let mut skipped = 0;
    let mut was_real = false;
    for step in 0..max {
        before(s, step);
        let d = s.bodies.pos[1] - s.bodies.pos[0];
        let touching = (0.02f64 * 0.02) - norm2(&d) >= 0.0;
        s.step().unwrap();
        let real = s
            .interactions
            .find(0, 1)
            .is_some_and(|k| s.interactions.list[k].is_real());
        if !was_real {
            assert_eq!(
                real, touching,
                "step {step}: contact {real}, YADE's check {touching}"
            );
        }
        if let Some(k) = s.interactions.find(0, 1) {
            let e = &s.interactions.scan[k];
            if e.idle && s.idle_skip.skips(e) {
                skipped += 1;
            }
        }
        was_real = real;
        if real {
            return skipped;
        }
    }
    panic!("no contact within {max} steps");
}

#[test]
fn an_approaching_sphere_touches_on_the_step_yades_check_says() {
    // 0.004 m apart at 0.5 m/s: 5 µm per step, contact after ~800 steps
    let mut s = scene(0.004, 0.5);
    let skipped = run_checking(&mut s, 2000, |_, _| {});
    assert!(skipped > 100, "the skip was exercised ({skipped} steps)");
}

#[test]
fn a_teleported_sphere_is_checked_at_once() {
    // slow approach, then the sphere is put in contact by hand at step 50
    let mut s = scene(0.004, 1e-3);
    let skipped = run_checking(&mut s, 100, |s, step| {
        if step == 50 {
            s.bodies.pos[1][0] = 0.0199;
        }
    });
    assert!(skipped > 10, "the skip was exercised ({skipped} steps)");
    assert!(
        s.iter <= 51,
        "contact on the step after the teleport (iter {})",
        s.iter
    );
}
