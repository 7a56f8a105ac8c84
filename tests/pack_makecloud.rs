//! `SpherePack::make_cloud` against YADE 2023.02a `SpherePack.makeCloud`, bit for bit.
//!
//! The goldens `golden/pack/<config>.{json,txt}` are written by `yade -n -x yade_ref/pack/clouds.py`:
//! the `.json` holds the arguments (ryade's `CloudParams` field names) and YADE's returned count,
//! `len(sp)`, `cellSize`, `isPeriodic` and `appliedPsdScaling`; the `.txt` holds one sphere per
//! line, `x y z r` with '%.17g'.

use ryade::math::{Mat3, Vec3};
use ryade::pack::{CloudParams, SpherePack};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::time::Instant;

fn golden_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("golden")
        .join("pack")
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

fn vec3(v: &Value) -> Vec3 {
    let a = v.as_array().expect("3-vector");
    assert_eq!(a.len(), 3);
    Vec3::new(f(&a[0]), f(&a[1]), f(&a[2]))
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array().expect("array").iter().map(f).collect()
}

fn params(p: &Value) -> CloudParams {
    let h_size = match &p["h_size"] {
        Value::Null => None,
        rows => {
            let r = rows.as_array().expect("hSize rows");
            let (a, b, c) = (vec3(&r[0]), vec3(&r[1]), vec3(&r[2]));
            Some(Mat3::new(
                a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2],
            ))
        }
    };
    CloudParams {
        min_corner: vec3(&p["min_corner"]),
        max_corner: vec3(&p["max_corner"]),
        r_mean: f(&p["r_mean"]),
        r_rel_fuzz: f(&p["r_rel_fuzz"]),
        num: p["num"].as_i64().expect("num") as i32,
        periodic: p["periodic"].as_bool().expect("periodic"),
        porosity: f(&p["porosity"]),
        psd_sizes: floats(&p["psd_sizes"]),
        psd_cumm: floats(&p["psd_cumm"]),
        distribute_mass: p["distribute_mass"].as_bool().expect("distribute_mass"),
        seed: p["seed"].as_i64().expect("seed") as i32,
        h_size,
    }
}

fn read_spheres(path: &Path) -> Vec<[f64; 4]> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text.lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let v: Vec<f64> = l
                .split_whitespace()
                .map(|x| x.parse().expect("float"))
                .collect();
            assert_eq!(v.len(), 4, "bad line {l:?} in {}", path.display());
            [v[0], v[1], v[2], v[3]]
        })
        .collect()
}

fn bits(a: &[f64; 4]) -> [u64; 4] {
    [
        a[0].to_bits(),
        a[1].to_bits(),
        a[2].to_bits(),
        a[3].to_bits(),
    ]
}

/// Compare one configuration; returns a description of the first difference.
fn check(name: &str) -> Result<(usize, f64), String> {
    let dir = golden_dir();
    let doc: Value = serde_json::from_str(
        &std::fs::read_to_string(dir.join(format!("{name}.json"))).map_err(|e| e.to_string())?,
    )
    .map_err(|e| e.to_string())?;
    let want = read_spheres(&dir.join(format!("{name}.txt")));
    let p = params(&doc["params"]);

    let mut sp = SpherePack::new();
    let t0 = Instant::now();
    let n = sp
        .make_cloud(&p)
        .map_err(|e| format!("{name}: make_cloud failed: {e:#}"))?;
    let dt = t0.elapsed().as_secs_f64();

    let got: Vec<[f64; 4]> = sp
        .spheres
        .iter()
        .map(|(c, r)| [c[0], c[1], c[2], *r])
        .collect();
    for (i, (g, w)) in got.iter().zip(want.iter()).enumerate() {
        if bits(g) != bits(w) {
            return Err(format!(
                "{name}: first differing sphere #{i}: ryade {g:?} vs YADE {w:?} (bits {:x?} vs {:x?})",
                bits(g),
                bits(w)
            ));
        }
    }
    if got.len() != want.len() {
        return Err(format!(
            "{name}: ryade made {} spheres, YADE {} (first {} equal)",
            got.len(),
            want.len(),
            got.len().min(want.len())
        ));
    }
    let returned = doc["returned"].as_u64().expect("returned") as usize;
    if n != returned {
        return Err(format!("{name}: ryade returned {n}, YADE {returned}"));
    }
    let cell = vec3(&doc["cell_size"]);
    let got_cell = sp.cell_size.unwrap_or_else(Vec3::zeros);
    if got_cell
        .iter()
        .zip(cell.iter())
        .any(|(a, b)| a.to_bits() != b.to_bits())
    {
        return Err(format!("{name}: cell_size {got_cell:?} vs YADE {cell:?}"));
    }
    if sp.is_periodic != doc["is_periodic"].as_bool().expect("is_periodic") {
        return Err(format!("{name}: is_periodic differs"));
    }
    let scaling = f(&doc["applied_psd_scaling"]);
    if sp.applied_psd_scaling.to_bits() != scaling.to_bits() {
        return Err(format!(
            "{name}: applied_psd_scaling {} vs YADE {scaling}",
            sp.applied_psd_scaling
        ));
    }
    Ok((n, dt))
}

fn config_names() -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(golden_dir())
        .expect("golden/pack exists (run yade -n -x yade_ref/pack/clouds.py)")
        .filter_map(|e| {
            let p = e.ok()?.path();
            if p.extension()? == "txt" {
                Some(p.file_stem()?.to_str()?.to_string())
            } else {
                None
            }
        })
        .collect();
    names.sort();
    names
}

#[test]
fn make_cloud_matches_yade_bit_for_bit() {
    let names = config_names();
    assert!(
        names.len() >= 5,
        "expected >= 5 golden clouds, found {names:?}"
    );
    let mut failures = Vec::new();
    for name in &names {
        match check(name) {
            Ok((n, dt)) => eprintln!(
                "{name:<18} {n:>4} spheres  bit-identical  {:.1} ms",
                dt * 1e3
            ),
            Err(e) => failures.push(e),
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} clouds differ:\n{}",
        failures.len(),
        names.len(),
        failures.join("\n")
    );
}

/// The same seed gives the same cloud; a cloud with seed < 0 still works.
#[test]
fn seeds() {
    let p = CloudParams {
        max_corner: Vec3::new(1.0, 1.0, 1.0),
        r_mean: 0.1,
        seed: 42,
        ..Default::default()
    };
    let (mut a, mut b) = (SpherePack::new(), SpherePack::new());
    a.make_cloud(&p).unwrap();
    b.make_cloud(&p).unwrap();
    assert_eq!(a.spheres, b.spheres);
    let mut c = SpherePack::new();
    let n = c.make_cloud(&CloudParams { seed: -1, ..p }).unwrap();
    assert!(n > 0 && n == c.len());
}

/// Restarts (num mode) are reported as warnings and the final count is the requested one.
#[test]
fn restart_reaches_num() {
    let p = CloudParams {
        max_corner: Vec3::new(1.0, 1.0, 1.0),
        num: 40,
        porosity: 0.2,
        seed: 4,
        ..Default::default()
    };
    let mut sp = SpherePack::new();
    assert_eq!(sp.make_cloud(&p).unwrap(), 40);
    assert_eq!(sp.len(), 40);
    assert!(sp
        .warnings
        .iter()
        .any(|w| w.contains("Trying again with porosity")));
}

#[test]
fn bad_arguments_are_errors() {
    let base = CloudParams {
        max_corner: Vec3::new(1.0, 1.0, 1.0),
        seed: 1,
        ..Default::default()
    };
    let err = |p: CloudParams| SpherePack::new().make_cloud(&p).unwrap_err().to_string();
    // an empty box (maxCorner below minCorner is accepted, as YADE does: funnel.py)
    assert!(err(CloudParams {
        r_mean: 0.1,
        max_corner: Vec3::zeros(),
        ..base.clone()
    })
    .contains("zero volume and zero area"));
    // psd arrays of different lengths
    assert!(err(CloudParams {
        psd_sizes: vec![0.1, 0.2, 0.3],
        psd_cumm: vec![0.0, 1.0],
        ..base.clone()
    })
    .contains("same dimensions"));
    assert!(err(CloudParams {
        psd_sizes: vec![0.1],
        psd_cumm: vec![1.0],
        ..base.clone()
    })
    .contains("at least 2 items"));
    assert!(err(CloudParams {
        psd_sizes: vec![0.2, 0.1],
        psd_cumm: vec![0.0, 1.0],
        ..base.clone()
    })
    .contains("non-decreasing"));
    // rMean with a PSD
    assert!(err(CloudParams {
        r_mean: 0.1,
        psd_sizes: vec![0.1, 0.2],
        psd_cumm: vec![0.0, 1.0],
        ..base.clone()
    })
    .contains("rMean can't be combined"));
    // nothing to size spheres by (no rMean, no num, no psd)
    assert!(err(base.clone()).contains("at least one of rMean"));
    // flat hSize
    assert!(err(CloudParams {
        num: 10,
        periodic: true,
        h_size: Some(Mat3::new(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0)),
        ..base.clone()
    })
    .contains("hSize has null length"));
    assert!(err(CloudParams {
        r_mean: 0.1,
        r_rel_fuzz: 1.5,
        ..base.clone()
    })
    .contains("rRelFuzz"));
}

/// maxCorner below minCorner on an axis (YADE's examples/funnel.py): YADE fills the same box walked
/// the other way. `yade -n -x` printed, for `makeCloud(Vector3(-1, -9, 30), Vector3(1, -13, 32), .2,
/// rRelFuzz=.3, seed=3)`: 122 spheres, the first at (0.57894206775246371, -9.3728587617011048,
/// 31.118038991903653) with radius 0.1484869856541268, the last at (-0.17597846877631751,
/// -13.175185226552859, 31.350154231091793).
#[test]
#[allow(clippy::excessive_precision)] // YADE's 17-digit prints, verbatim
fn inverted_box_fills_as_yade() {
    let p = CloudParams {
        min_corner: Vec3::new(-1.0, -9.0, 30.0),
        max_corner: Vec3::new(1.0, -13.0, 32.0),
        r_mean: 0.2,
        r_rel_fuzz: 0.3,
        seed: 3,
        ..Default::default()
    };
    let mut sp = SpherePack::new();
    assert_eq!(sp.make_cloud(&p).unwrap(), 122);
    let (c0, r0) = sp.spheres[0];
    assert_eq!(
        [c0[0], c0[1], c0[2], r0],
        [
            0.57894206775246371,
            -9.3728587617011048,
            31.118038991903653,
            0.1484869856541268
        ]
    );
    let (cl, _) = sp.spheres[121];
    assert_eq!(
        [cl[0], cl[1], cl[2]],
        [
            -0.17597846877631751,
            -13.175185226552859,
            31.350154231091793
        ]
    );
}
