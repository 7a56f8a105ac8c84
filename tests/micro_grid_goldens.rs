//! ryade against YADE 2023.02a's grid goldens (golden/micro_grid, FORMAT_GRID.md; written by
//! yade_ref/micro_grid): every double of every body, contact and 6-D/grid contact record at every step
//! must be bit-identical; the comparison must notice a one-ulp change in the 6-D records; and the
//! Rust `gridpfacet` builders must reproduce the masses, inertias and bond states YADE recorded.
use ryade::body::DOF_ALL;
use ryade::harness::micro;
use ryade::io::{golden, scene_json};
use ryade::scene::Scene;
use ryade::shape::Shape;
use ryade::utils;
use serde_json::Value;
use std::path::PathBuf;

fn dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("golden/micro_grid")
}

#[test]
fn every_micro_grid_scene_is_bit_identical_to_yade() {
    let reps = micro::diff_dir(&dir()).unwrap();
    let names: Vec<&str> = reps.iter().map(|r| r.scene.as_str()).collect();
    for must in [
        "cantilever",
        "net",
        "sphere_rope",
        "periodic_rib",
        "rolling",
    ] {
        assert!(names.contains(&must), "missing grid scene {}", must);
    }
    for r in &reps {
        assert!(
            r.values > 10000,
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

/// One ulp on one twist angle of the golden 6-D records must be reported (the intrs6d file is
/// really compared), at that step and quantity.
#[test]
fn a_one_ulp_change_in_the_6d_records_is_detected() {
    let p = dir().join("cantilever.scene.json");
    let (bp, ip) = micro::golden_paths(&p);
    let bodies = golden::read_bodies(&bp).unwrap();
    let intrs = golden::read_intrs(&ip).unwrap();
    let mut six = golden::read_intrs6d(&micro::golden_path6d(&p)).unwrap();
    let row = six
        .iter_mut()
        .find(|r| r.step == 700 && r.v[0] != 0.0)
        .unwrap();
    row.v[0] = f64::from_bits(row.v[0].to_bits() + 1);
    let (a, b) = (row.id1, row.id2);
    let sf = scene_json::load(&p).unwrap();
    let r = micro::diff_against_6d(sf, &bodies, &intrs, Some(&six));
    assert_eq!(r.mismatches, 1);
    assert_eq!(r.max_ulp, 1);
    let f = r.first.unwrap();
    assert_eq!(f.step, 700);
    assert_eq!(f.what, format!("contact {}-{} twist", a, b));
}

/// Numbers equal as doubles (bit for bit, so -0 and 0 differ); other JSON values equal.
fn same(a: &Value, b: &Value, path: &str) -> Result<(), String> {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            if x.to_bits() != y.to_bits() {
                return Err(format!("{}: ryade {:e}, yade {:e}", path, x, y));
            }
            Ok(())
        }
        (Value::Array(x), Value::Array(y)) => {
            if x.len() != y.len() {
                return Err(format!("{}: lengths {} and {}", path, x.len(), y.len()));
            }
            for (k, (p, q)) in x.iter().zip(y).enumerate() {
                same(p, q, &format!("{}[{}]", path, k))?;
            }
            Ok(())
        }
        (Value::Object(x), Value::Object(y)) => {
            for (k, q) in y {
                let p = x
                    .get(k)
                    .ok_or_else(|| format!("{}.{}: missing in ryade", path, k))?;
                same(p, q, &format!("{}.{}", path, k))?;
            }
            Ok(())
        }
        _ if a == b => Ok(()),
        _ => Err(format!("{}: ryade {}, yade {}", path, a, b)),
    }
}

/// Rebuild each grid scene with `utils::grid_node` / `utils::grid_connection` in body-id order (as
/// the reference scripts do with gridpfacet) and compare with the scene YADE recorded before step 1:
/// node masses and inertias (accumulated half-rib volumes), connection bodies, connection lists,
/// and every bond's geometry and physics (unp, kn, ks, kr, ktw, cohesion, connectionBody...).
#[test]
fn gridpfacet_builders_match_yade() {
    let mut checked_bonds = 0;
    for name in ["cantilever", "net", "sphere_rope", "periodic_rib"] {
        let p = dir().join(format!("{}.scene.json", name));
        let golden: Value = serde_json::from_str(&std::fs::read_to_string(&p).unwrap()).unwrap();
        let g = scene_json::load(&p).unwrap().scene;
        let mut s = Scene {
            materials: g.materials.clone(),
            engines: g.engines.clone(),
            cell: g.cell.clone(),
            dt: g.dt,
            ..Default::default()
        };
        for id in 0..g.bodies.len() {
            match &g.bodies.shape[id] {
                Shape::GridNode(n) => {
                    let fixed = g.bodies.blocked[id] == DOF_ALL;
                    let b =
                        utils::grid_node(g.bodies.pos[id], n.radius, g.bodies.material[id], fixed);
                    assert_eq!(s.bodies.push(b), id);
                }
                Shape::GridConnection(c) => {
                    let cid = utils::grid_connection(
                        &mut s,
                        c.node1 as usize,
                        c.node2 as usize,
                        c.radius,
                        g.bodies.material[id],
                        g.bodies.mask[id],
                        c.periodic.then_some(c.cell_dist),
                    )
                    .unwrap();
                    assert_eq!(cid, id);
                }
                _ => {
                    let spec =
                        scene_json::body(&golden["bodies"][id], &mut s.materials.clone()).unwrap();
                    s.bodies.push(spec);
                }
            }
        }
        let b = &s.bodies;
        for id in 0..g.bodies.len() {
            let what = format!("{} body {}", name, id);
            assert_eq!(b.shape[id], g.bodies.shape[id], "{} shape", what);
            assert_eq!(
                b.mass[id].to_bits(),
                g.bodies.mass[id].to_bits(),
                "{} mass",
                what
            );
            for k in 0..3 {
                assert_eq!(
                    b.inertia[id][k].to_bits(),
                    g.bodies.inertia[id][k].to_bits(),
                    "{} inertia",
                    what
                );
            }
            assert_eq!(b.pos[id], g.bodies.pos[id], "{} pos", what);
            assert_eq!(b.mask[id], g.bodies.mask[id], "{} mask", what);
            assert_eq!(b.bounded[id], g.bodies.bounded[id], "{} bounded", what);
            if matches!(b.shape[id], Shape::GridConnection(_)) {
                assert_eq!(b.blocked[id], DOF_ALL, "{} is fixed", what);
            }
        }
        let ours = &s.interactions.list;
        let theirs = golden["interactions"].as_array().unwrap();
        assert_eq!(ours.len(), theirs.len(), "{}: interaction count", name);
        for (k, (a, t)) in ours.iter().zip(theirs).enumerate() {
            same(
                &scene_json::interaction_to_value(a),
                t,
                &format!("{} interaction {}", name, k),
            )
            .unwrap();
            checked_bonds += 1;
        }
    }
    assert!(checked_bonds >= 20);
}
