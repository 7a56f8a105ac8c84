//! Regression guard for `IdleSkip` (src/idle_skip.rs): the interaction loop skips YADE's distance
//! check of an idle sphere-sphere pair while an accumulated bound proves the spheres are still
//! apart. YADE checks every pair every step, so a skip that outlived the proof would create a
//! contact one step late and change every later bit. Here a sphere approaches another at constant
//! speed (no gravity, no damping), then, in a second run, is teleported into contact the way a
//! Python script writing `state.pos` would; at every step the contact must exist exactly when
//! YADE's check `(r1 + r2)² - |d|² >= 0` on the positions the loop saw says so. The last test does
//! the same for potential sphere-`GridConnection` pairs, whose functor can also take over a
//! neighbouring rib's contact without any distance check.
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

/// The same scene with `Ig2_Sphere_Sphere_ScGeom6D` in place of `Ig2_Sphere_Sphere_ScGeom` (the study's
/// rolling-resistance loading): its potential pairs are skipped by the same proof.
fn scene_6d(gap: f64, speed: f64) -> Scene {
    let mut s = scene(gap, speed);
    for e in &mut s.engines {
        if let ryade::scene::Engine::InteractionLoop(il) = e {
            il.sphere_sphere = None;
            il.sphere_sphere_6d = Some(Default::default());
        }
    }
    s
}

#[test]
fn six_d_geometry_pairs_are_skipped_and_touch_on_the_step_yades_check_says() {
    // fails if the 6D functor's pairs are checked every step again (skipped = 0) or skipped too long
    let mut s = scene_6d(0.004, 0.5);
    let skipped = run_checking(&mut s, 2000, |_, _| {});
    assert!(skipped > 100, "the skip was exercised ({skipped} steps)");
    let mut s = scene_6d(0.004, 1e-3);
    let skipped = run_checking(&mut s, 100, |s, step| {
        if step == 50 {
            s.bodies.pos[1][0] = 0.0199;
        }
    });
    assert!(
        skipped > 10 && s.iter <= 51,
        "skipped {skipped}, contact at iter {}",
        s.iter
    );
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

/// The grid half of the skip, on YADE's inclined 3×3 net (golden/micro_grid/net, held fixed) with 9
/// spheres dropped on its ribs: they are thrown down the slope, land on the ribs and slide from rib
/// to rib, so potential sphere-connection pairs are skipped while the spheres fall and contacts are
/// handed over between neighbouring ribs. Before every step the decisions of the next interaction
/// loop (the skip's state cloned and advanced by the same `prepare`) are checked against the
/// geometry itself: every potential pair it would skip must be beyond contact on the positions the
/// loop will see (the distance from the sphere's centre to the segment above r + R) and its sphere
/// must not be behind any connection sharing a node with it that it has a real contact with (the
/// functor's take-over, which needs no distance check). Pairs are skipped beside real contacts too.
/// Fails when the distance bound is cut to 0.3 of itself (a pair skipped in contact; checked by
/// hand). On this net a take-over always comes within reach, so the take-over bound and the gains
/// are guarded by the next test, and the bound beyond an end by the one after.
#[test]
fn skipped_sphere_connection_pairs_are_apart_and_cannot_take_over() {
    use ryade::io::scene_json;
    use ryade::scene::Engine;
    use ryade::shape::Shape;
    let dir = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("golden/micro_grid");
    let mut s = scene_json::load(&dir.join("net.scene.json")).unwrap().scene;
    // the net held still (in the golden it is thrown down and hangs from one fixed node)
    for id in 0..s.bodies.len() {
        if matches!(s.bodies.shape[id], Shape::GridNode(_)) {
            s.bodies.blocked[id] = ryade::body::DOF_ALL;
            s.bodies.vel[id] = Vec3::zeros();
        }
    }
    let mat = s.bodies.material[0];
    // above the three ribs that run up the slope (x = 0, 0.06, 0.12), a little off their axes, one
    // of each three just above the middle node (y = 0.052); thrown down the slope, they pass nodes
    for (i, x) in [0.001, 0.059, 0.1205].into_iter().enumerate() {
        for (j, y) in [0.02, 0.055 + 0.002 * i as f64, 0.095]
            .into_iter()
            .enumerate()
        {
            let z = 0.577 * y + 0.008 + 0.003 + 0.002 * ((i + j) % 3) as f64;
            let mut b = utils::sphere(Vec3::new(x, y, z), 0.006, mat, 2600.0, false);
            // thrown down the slope
            b.vel = Vec3::new(0.0, -0.433, -0.25);
            s.bodies.push(b);
        }
    }
    let factor = s
        .engines
        .iter()
        .find_map(|e| match e {
            Engine::InteractionLoop(il) => Some(
                il.sphere_sphere
                    .map_or(1.0, |p| p.interaction_detection_factor),
            ),
            _ => None,
        })
        .unwrap();
    let (mut skipped, mut skipped_beside) = (0, 0);
    let mut ever = std::collections::BTreeSet::new();
    for step in 0..3000 {
        let (mut skip, mut scan) = (s.idle_skip.clone(), s.interactions.scan.clone());
        skip.prepare(&s.bodies, s.cell.as_ref(), factor, &mut scan);
        for (k, e) in scan.iter().enumerate() {
            if !(e.idle_gc && skip.skips_gridco(e)) {
                continue;
            }
            skipped += 1;
            assert!(
                !s.interactions.list[k].is_real(),
                "step {step}: a real pair is idle"
            );
            let Shape::GridConnection(_) = &s.bodies.shape[e.id2 as usize] else {
                panic!("step {step}: #{} is no connection", e.id2)
            };
            let r = s.bodies.shape[e.id1 as usize].sphere_radius().unwrap();
            let rc = ryade::geom::grid::sphere_gridco_reach(
                &s.bodies,
                None,
                e.id1,
                e.id2,
                r,
                &Vec3::zeros(),
            )
            .unwrap();
            assert!(
                norm2(&(rc.nearest - rc.sphere)).sqrt() > rc.reach,
                "step {step}: #{}+#{} skipped in contact",
                e.id1,
                e.id2
            );
            // no take-over: beyond an end of the connection (relPos <= 0 or >= 1, where the
            // functor looks at no neighbour), or behind no neighbour (at either node) it has a real
            // contact with
            let rel = ryade::geom::grid::sphere_gridco_rel_pos(
                &s.bodies,
                None,
                (e.id1, e.id2),
                &Vec3::zeros(),
            )
            .unwrap();
            let beyond = !(rel > 0.0 && rel < 1.0);
            let mut beside = 0;
            ryade::geom::grid::takeover_operands(
                &s.interactions,
                &s.bodies,
                (e.id1, e.id2),
                &Vec3::zeros(),
                None,
                |a, b| {
                    beside += 1;
                    assert!(
                        beyond || ryade::math::dot(a, b) > 0.0,
                        "step {step}: #{}+#{} skipped behind a real neighbour contact",
                        e.id1,
                        e.id2
                    );
                },
            )
            .unwrap();
            skipped_beside += (beside > 0) as usize;
        }
        s.step().unwrap();
        for it in &s.interactions.list {
            if it.is_real() && it.functor == ryade::interaction::GeomFunctor::SphereGridConnection {
                ever.insert((it.id1, it.id2));
            }
        }
    }
    assert!(
        skipped > 1000 && skipped_beside > 30,
        "the skip was exercised ({skipped} pair-steps, {skipped_beside} beside a real contact)"
    );
    // contacts made, and handed from rib to rib
    let spheres: std::collections::BTreeSet<u32> = ever.iter().map(|p| p.0).collect();
    assert!(spheres.len() >= 6, "spheres landed on the ribs: {ever:?}");
    assert!(
        ever.len() > spheres.len(),
        "a contact moved to a neighbouring rib: {ever:?}"
    );
}

/// The two bounds of a skipped sphere-connection pair that sits beside a real contact, on a corner
/// of two connections at node N, a thick one along +x (N-O, R = 0.01) and a thin one along +y (N-P,
/// R = 0.001): a sphere (r = 0.005, moved at constant speed by its blocked DOFs) passes above N
/// from over N-O to behind it, within reach of the thick one all the time and beyond reach of the
/// thin one, whose potential pair must take the contact over (`sphere_gridco`: inside the thin
/// connection, behind the real neighbour) at the first step that starts with the sphere behind.
/// Run twice: the neighbour contact made before the pair's first check (the take-over test's
/// deadline holds the skip) and after it (the gained contact ends the skip). Fails, checked by
/// hand, when `skips_gridco` ignores the gains, or when `behind_deadline` allows 3 times its bound.
#[test]
fn skipped_pair_beside_a_real_contact_takes_it_over_on_time() {
    for thin_first in [false, true] {
        // 0.003 in 60 steps: behind (x < 0) from step 41 on
        let (x0, dx) = (
            Vec3::new(0.00202, 0.005, 0.0125),
            Vec3::new(-0.003, 0.0, 0.0),
        );
        let (taken, _) = take_over_on_the_corner(x0, dx, thin_first, |x| x[0] < 0.0);
        assert!(taken.is_some_and(|k| k > 30), "{thin_first}: {taken:?}");
    }
}

/// On the `corner`, a sphere (r = 0.005, blocked DOFs) from `x0`, moved by `dx` in 60 steps at
/// constant speed, its pairs with the thin and the thick connection listed in either order: the
/// thick contact must be real after the first step, and the thin connection must take it over
/// exactly at the first step that starts with `ready` true of the sphere's position. Returns that
/// step and how many steps the next loop would have skipped the thin pair (the thick contact real
/// at each).
fn take_over_on_the_corner(
    x0: Vec3,
    dx: Vec3,
    thin_first: bool,
    ready: impl Fn(&Vec3) -> bool,
) -> (Option<usize>, usize) {
    use ryade::interaction::Interaction;
    let (mut s, mat) = hand_listed_scene();
    let (thick, thin) = corner(&mut s, mat);
    let mut b = utils::sphere(x0, 0.005, mat, 2600.0, false);
    b.blocked = ryade::body::DOF_ALL;
    b.vel = dx / (60.0 * s.dt);
    let sid = s.bodies.push(b) as u32;
    let order = if thin_first {
        [thin, thick]
    } else {
        [thick, thin]
    };
    for c in order {
        s.interactions.insert(Interaction::new(sid, c, [0; 3], 0));
    }
    let real = |s: &Scene, c: u32| {
        s.interactions
            .find(sid, c)
            .is_some_and(|j| s.interactions.list[j].is_real())
    };
    let mut skipped = 0;
    for step in 0..60 {
        let now = ready(&s.bodies.pos[sid as usize]);
        // the next loop's decision on the thin pair
        let (mut skip, mut scan) = (s.idle_skip.clone(), s.interactions.scan.clone());
        skip.prepare(&s.bodies, s.cell.as_ref(), 1.0, &mut scan);
        let j = s.interactions.find(sid, thin).unwrap();
        if scan[j].idle_gc && skip.skips_gridco(&scan[j]) {
            assert!(
                real(&s, thick),
                "step {step}: skipped without the neighbour"
            );
            skipped += 1;
        }
        s.step().unwrap();
        if step == 0 {
            assert!(
                real(&s, thick) && !real(&s, thin),
                "the thick contact first"
            );
        }
        if real(&s, thin) {
            assert!(now, "step {step}: taken over before the sphere is there");
            return (Some(step), skipped);
        }
        assert!(
            !now,
            "step {step}: there, behind the real neighbour, not taken over"
        );
    }
    (None, skipped)
}

/// An empty scene with the net golden's materials and engines but no collider (the pairs are
/// listed by hand and stay listed), dt 1e-5; and the net's material.
fn hand_listed_scene() -> (Scene, usize) {
    use ryade::io::scene_json;
    use ryade::scene::Engine;
    let dir = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("golden/micro_grid");
    let net = scene_json::load(&dir.join("net.scene.json")).unwrap().scene;
    let mut s = Scene {
        materials: net.materials.clone(),
        engines: net.engines.clone(),
        dt: 1e-5,
        ..Default::default()
    };
    s.engines.retain(|e| !matches!(e, Engine::Collider(_)));
    (s, net.bodies.material[0])
}

/// The corner of node N at the origin: a thick connection N-O along +x (R = 0.01) and a thin one
/// N-P along +y (R = 0.001), nodes fixed; (thick, thin).
fn corner(s: &mut Scene, mat: usize) -> (u32, u32) {
    let node = |s: &mut Scene, x: f64, y: f64| {
        s.bodies
            .push(utils::grid_node(Vec3::new(x, y, 0.0), 0.001, mat, true))
    };
    let (n, o, p) = (node(s, 0.0, 0.0), node(s, 0.05, 0.0), node(s, 0.0, 0.05));
    let thick = utils::grid_connection(s, n, o, 0.01, mat, 1, None).unwrap() as u32;
    let thin = utils::grid_connection(s, n, p, 0.001, mat, 1, None).unwrap() as u32;
    (thick, thin)
}

/// A skipped pair whose sphere lies beyond an end of its connection, behind a real neighbour
/// contact: on the corner of the previous test, the sphere (blocked DOFs, constant speed) sits
/// behind the thick connection N-O (x < 0) in contact with it and beyond the thin one's end at N
/// (y < 0), then moves along +y into the thin one, which must take the contact over at the first
/// step that starts with the sphere inside it (relPos > 0). Before that the thin pair is skipped
/// (`IdleSkip::beyond_deadline`, free of the sphere's gains), though its take-over test is true
/// all along. Run with the thick contact made before and after the pair's first check. Fails,
/// checked by hand, when `beyond_deadline` allows 3 times its bound (taken over late), and
/// without the beyond bound (nothing skipped).
#[test]
fn skipped_pair_beyond_an_end_takes_over_on_time() {
    for thin_first in [false, true] {
        // 0.006 in 60 steps: inside the thin connection (y > 0) from step 31 on
        let (x0, dx) = (
            Vec3::new(-0.002, -0.003, 0.0125),
            Vec3::new(0.0, 0.006, 0.0),
        );
        let (taken, skipped) = take_over_on_the_corner(x0, dx, thin_first, |x| x[1] > 0.0);
        assert!(
            taken.is_some_and(|k| k > 25) && skipped > 15,
            "{thin_first}: taken {taken:?}, skipped {skipped}"
        );
    }
}

/// A sphere coming straight at a connection's end along its axis stays beyond that end all the
/// way, so the bound beyond the end never runs out: the pair's skip must still end by its distance,
/// and the contact be made on the step YADE's distance check says (the first that starts within
/// r + R of the end node). Fails, checked by hand, with the beyond-end deadline not capped by the
/// distance's (the contact made late, skipped in contact).
#[test]
fn a_sphere_along_the_axis_touches_the_end_on_time() {
    use ryade::interaction::Interaction;
    let (mut s, mat) = hand_listed_scene();
    let n = s
        .bodies
        .push(utils::grid_node(Vec3::zeros(), 0.001, mat, true));
    let o = s.bodies.push(utils::grid_node(
        Vec3::new(0.05, 0.0, 0.0),
        0.001,
        mat,
        true,
    ));
    let c = utils::grid_connection(&mut s, n, o, 0.002, mat, 1, None).unwrap() as u32;
    let mut b = utils::sphere(Vec3::new(-0.03, 0.0, 0.0), 0.005, mat, 2600.0, false);
    b.blocked = ryade::body::DOF_ALL;
    // 0.03 in 100 steps along +x: within r + R = 0.007 of node N from step 77 on
    b.vel = Vec3::new(0.03 / (100.0 * s.dt), 0.0, 0.0);
    let sid = s.bodies.push(b) as u32;
    s.interactions.insert(Interaction::new(sid, c, [0; 3], 0));
    let (mut skipped, mut touched) = (0, None);
    for step in 0..100 {
        let within = norm2(&s.bodies.pos[sid as usize]).sqrt() <= 0.007;
        let (mut skip, mut scan) = (s.idle_skip.clone(), s.interactions.scan.clone());
        skip.prepare(&s.bodies, s.cell.as_ref(), 1.0, &mut scan);
        let j = s.interactions.find(sid, c).unwrap();
        if scan[j].idle_gc && skip.skips_gridco(&scan[j]) {
            assert!(!within, "step {step}: skipped within reach");
            skipped += 1;
        }
        s.step().unwrap();
        let real = s.interactions.list[j].is_real();
        assert_eq!(
            real, within,
            "step {step}: contact {real}, within reach {within}"
        );
        if real {
            touched = Some(step);
            break;
        }
    }
    assert!(
        touched.is_some_and(|k| k > 70) && skipped > 40,
        "touched {touched:?}, skipped {skipped}"
    );
}
