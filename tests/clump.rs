//! Clumps against YADE 2023.02a (golden/micro/clump.*, written by yade_ref/micro/clump.py).
//!
//! * ryade's own `Clump::updateProperties` (mass, centroid, principal inertia from Eigen's
//!   SelfAdjointEigenSolver, orientation, members' poses) rebuilds every clump of the golden scene
//!   from its member spheres bit for bit;
//! * the clump run itself (every body and contact, every step) is in micro_goldens.rs; here we also
//!   check that the comparison sees the aspherical integrator (switching it off must diverge).
use ryade::body::{Bodies, BodySpec};
use ryade::clump;
use ryade::harness::micro;
use ryade::io::scene_json;
use ryade::material::FrictMat;
use ryade::math::{Quat, Vec3};
use ryade::shape::Shape;
use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn golden_scene() -> serde_json::Value {
    serde_json::from_str(
        &std::fs::read_to_string(root().join("golden/micro/clump.scene.json")).unwrap(),
    )
    .unwrap()
}

fn bits3(v: &Vec3) -> [u64; 3] {
    [v[0].to_bits(), v[1].to_bits(), v[2].to_bits()]
}

fn bitsq(q: &Quat) -> [u64; 4] {
    [q.w.to_bits(), q.x.to_bits(), q.y.to_bits(), q.z.to_bits()]
}

/// Every clump of the golden scene (2- and 3-sphere, overlapping, made by appendClumped and by
/// O.bodies.clump) rebuilt by `clump::make_clump` from its members as YADE held them at creation:
/// mass, position, orientation, principal inertia, aspherical flag and member poses bit-identical.
#[test]
fn update_properties_reproduces_yade_bit_for_bit() {
    let v = golden_scene();
    let sf = scene_json::load(&root().join("golden/micro/clump.scene.json")).unwrap();
    let yade = &sf.scene.bodies;
    let mut n_clumps = 0;
    let mut n_aspherical = 0;
    for cid in 0..yade.len() {
        let Shape::Clump(yc) = &yade.shape[cid] else {
            continue;
        };
        n_clumps += 1;
        // a fresh scene with just the members, in id order
        let mut bodies = Bodies::default();
        let mats: Vec<FrictMat> = sf.scene.materials.clone();
        let mut ids = Vec::new();
        for m in &yc.members {
            let id = m.id as usize;
            ids.push(bodies.push(BodySpec {
                shape: yade.shape[id].clone(),
                material: yade.material[id],
                mask: 1,
                bounded: true,
                pos: yade.pos[id],
                vel: Vec3::zeros(),
                ang_vel: Vec3::zeros(),
                ori: yade.ori[id],
                mass: yade.mass[id],
                inertia: yade.inertia[id],
                blocked: 0,
                is_damped: true,
            }));
        }
        let ours = clump::make_clump(&mut bodies, &mats, &ids, 0).unwrap();
        assert_eq!(ours, ids.len(), "the clump is appended after its members");
        let checks = [
            (
                "mass",
                vec![bodies.mass[ours].to_bits()],
                vec![yade.mass[cid].to_bits()],
            ),
            (
                "pos",
                bits3(&bodies.pos[ours]).to_vec(),
                bits3(&yade.pos[cid]).to_vec(),
            ),
            (
                "inertia",
                bits3(&bodies.inertia[ours]).to_vec(),
                bits3(&yade.inertia[cid]).to_vec(),
            ),
            (
                "ori",
                bitsq(&bodies.ori[ours]).to_vec(),
                bitsq(&yade.ori[cid]).to_vec(),
            ),
            (
                "aspherical",
                vec![bodies.aspherical[ours] as u64],
                vec![yade.aspherical[cid] as u64],
            ),
        ];
        for (what, ours_bits, yade_bits) in checks {
            assert_eq!(ours_bits, yade_bits, "clump #{} {}", cid, what);
        }
        n_aspherical += yade.aspherical[cid] as usize;
        let Shape::Clump(oc) = &bodies.shape[ours] else {
            panic!("not a clump")
        };
        for (a, b) in oc.members.iter().zip(yc.members.iter()) {
            let ours_pose = (bits3(&a.rel_pos), bitsq(&a.rel_ori));
            let yade_pose = (bits3(&b.rel_pos), bitsq(&b.rel_ori));
            assert_eq!(ours_pose, yade_pose, "clump #{} member {} pose", cid, b.id);
        }
        for &m in &ids {
            assert!(bodies.is_clump_member(m));
            assert_eq!(bodies.clump_id[m], Some(ours as u32));
        }
        assert!(bodies.is_clump(ours) && !bodies.bounded[ours]);
    }
    assert!(
        n_clumps >= 7,
        "only {} clumps in the golden scene",
        n_clumps
    );
    assert_eq!(n_aspherical, n_clumps);
    // YADE's own numbers for the first clump (printed by the recorder script): mass of two
    // overlapping spheres r=0.02 and r=0.015 of density 2600 = 2600*(4/3)π(0.02³+0.015³)
    let m = v["bodies"][5]["mass"].as_f64().unwrap();
    let expect = 2600.0 * (4.0 / 3.0) * std::f64::consts::PI * (0.02f64.powi(3) + 0.015f64.powi(3));
    assert!((m - expect).abs() < 1e-15 * expect, "{} vs {}", m, expect);
}

/// Unsupported clump requests fail with errors naming them, and leave the bodies untouched.
#[test]
fn unsupported_clumps_are_refused_clearly() {
    let mats = vec![FrictMat {
        id: 0,
        label: String::new(),
        young: 1e7,
        poisson: 0.3,
        friction_angle: 0.5,
        density: 2600.0,
        coh: None,
        viscel: None,
        luding: None,
        bubble: None,
        cpm: None,
    }];
    let mut b = Bodies::default();
    for x in [0.0, 0.015, 0.5] {
        b.push(ryade::utils::sphere(
            Vec3::new(x, 0.0, 0.0),
            0.01,
            0,
            2600.0,
            false,
        ));
    }
    let e = clump::make_clump(&mut b, &mats, &[0, 1], 4).unwrap_err();
    assert!(e.contains("discretization=4"), "{}", e);
    let e = clump::make_clump(&mut b, &mats, &[], 0).unwrap_err();
    assert!(e.contains("zero members"), "{}", e);
    let e = clump::make_clump(&mut b, &mats, &[0, 7], 0).unwrap_err();
    assert!(e.contains("No body #7"), "{}", e);
    let e = clump::make_clump(&mut b, &mats, &[1, 1], 0).unwrap_err();
    assert!(e.contains("already part of this clump"), "{}", e);
    assert_eq!(b.len(), 3);
    let c = clump::make_clump(&mut b, &mats, &[0, 1], 0).unwrap();
    assert_eq!(c, 3);
    let e = clump::make_clump(&mut b, &mats, &[1, 2], 0).unwrap_err();
    assert!(e.contains("already a member of clump #3"), "{}", e);
    let e = clump::make_clump(&mut b, &mats, &[3, 2], 0).unwrap_err();
    assert!(e.contains("is a clump"), "{}", e);
    assert_eq!(b.len(), 4);
    assert_eq!(b.clump_id[2], None);
    // two equal spheres: the centroid halfway, mass twice a sphere's (exact here)
    assert!((b.pos[3][0] - 0.0075).abs() < 1e-18);
    assert_eq!(
        b.mass[3],
        2.0 * ((4.0 / 3.0) * std::f64::consts::PI * 0.01f64.powf(3.0) * 2600.0)
    );
}

/// The golden run sees the clump integrator: YADE's spherical rotation update instead of the
/// aspherical one (exactAsphericalRot=False) diverges at step 1.
#[test]
fn the_clump_golden_needs_the_aspherical_integrator() {
    let p = root().join("golden/micro/clump.scene.json");
    let mut sf = scene_json::load(&p).unwrap();
    for e in sf.scene.engines.iter_mut() {
        if let ryade::scene::Engine::Newton(n) = e {
            n.exact_aspherical_rot = false;
        }
    }
    let r = micro::diff_scene(sf, &p).unwrap();
    assert!(r.mismatches > 0);
    assert_eq!(r.first.unwrap().step, 1);
}
