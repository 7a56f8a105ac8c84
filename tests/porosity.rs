//! Exact sphere/box volumes (physics checks) and `voxel_porosity` against YADE's
//! `utils.voxelPorosity` (golden/pack/voxel.json from `yade -n -x yade_ref/pack/voxel.py`).

use rand_mt::Mt;
use ryade::math::Vec3;
use ryade::porosity::{box_porosity, sphere_box_volume, voxel_porosity};
use serde_json::Value;
use std::f64::consts::PI;
use std::path::Path;

fn ball(r: f64) -> f64 {
    4.0 / 3.0 * PI * r * r * r
}

fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

/// Uniform in [0,1) from MT19937 (53 bits).
fn uniform(mt: &mut Mt) -> f64 {
    (mt.next_u64() >> 11) as f64 / (1u64 << 53) as f64
}

#[test]
fn sphere_inside_box_is_whole() {
    let r = 0.37;
    let v = sphere_box_volume(
        &Vec3::new(0.5, 0.5, 0.5),
        r,
        &Vec3::zeros(),
        &Vec3::new(1.0, 1.0, 1.0),
    );
    assert!(rel(v, ball(r)) < 1e-12, "{v} vs {}", ball(r));
    // touching the faces from inside still whole
    let v = sphere_box_volume(
        &Vec3::new(0.5, 0.5, 0.5),
        0.5,
        &Vec3::zeros(),
        &Vec3::new(1.0, 1.0, 1.0),
    );
    assert!(rel(v, ball(0.5)) < 1e-12);
    // outside: nothing
    assert_eq!(
        sphere_box_volume(
            &Vec3::new(2.0, 0.5, 0.5),
            0.5,
            &Vec3::zeros(),
            &Vec3::new(1.0, 1.0, 1.0)
        ),
        0.0
    );
}

#[test]
fn sphere_on_face_edge_corner() {
    let (lo, hi) = (Vec3::new(-1.0, -2.0, -3.0), Vec3::new(4.0, 5.0, 6.0));
    let r = 0.8;
    let full = ball(r);
    // centred on each of the 6 faces: half
    for k in 0..3 {
        for bound in [lo, hi] {
            let mut c = Vec3::new(1.5, 1.5, 1.5);
            c[k] = bound[k];
            let v = sphere_box_volume(&c, r, &lo, &hi);
            assert!(
                rel(v, full / 2.0) < 1e-14,
                "face axis {k}: {v} vs {}",
                full / 2.0
            );
        }
    }
    // centred on edges: a quarter
    for (a, b) in [(0, 1), (1, 2), (0, 2)] {
        let mut c = Vec3::new(1.5, 1.5, 1.5);
        c[a] = lo[a];
        c[b] = hi[b];
        let v = sphere_box_volume(&c, r, &lo, &hi);
        assert!(
            rel(v, full / 4.0) < 1e-14,
            "edge {a}{b}: {v} vs {}",
            full / 4.0
        );
    }
    // centred on corners: an eighth
    for corner in 0..8 {
        let c = Vec3::from_fn(|k, _| if corner & (1 << k) == 0 { lo[k] } else { hi[k] });
        let v = sphere_box_volume(&c, r, &lo, &hi);
        assert!(
            rel(v, full / 8.0) < 1e-14,
            "corner {corner}: {v} vs {}",
            full / 8.0
        );
    }
    // spherical cap: centre at distance d below the face z = 0
    let (d, r) = (0.3, 1.0);
    let cap = PI * (r - d) * (r - d) * (2.0 * r + d) / 3.0;
    let v = sphere_box_volume(
        &Vec3::new(0.0, 0.0, -d),
        r,
        &Vec3::new(-5.0, -5.0, 0.0),
        &Vec3::new(5.0, 5.0, 5.0),
    );
    assert!(rel(v, cap) < 1e-14, "{v} vs {cap}");
}

/// Splitting space into boxes must add up: 27 boxes around an arbitrary sphere (cut by two
/// random planes per axis) sum to the whole ball; the error bounds the method's accuracy.
#[test]
fn additivity_gives_accuracy() {
    let mut mt = Mt::new(7);
    let mut worst: f64 = 0.0;
    for _ in 0..200 {
        let r = 0.1 + uniform(&mut mt);
        let c = Vec3::new(uniform(&mut mt), uniform(&mut mt), uniform(&mut mt));
        let cuts: Vec<[f64; 4]> = (0..3)
            .map(|k| {
                let mut a = c[k] + (2.0 * uniform(&mut mt) - 1.0) * r;
                let mut b = c[k] + (2.0 * uniform(&mut mt) - 1.0) * r;
                if a > b {
                    std::mem::swap(&mut a, &mut b);
                }
                [c[k] - 2.0 * r, a, b, c[k] + 2.0 * r]
            })
            .collect();
        let mut sum = 0.0;
        for i in 0..3 {
            for j in 0..3 {
                for k in 0..3 {
                    let lo = Vec3::new(cuts[0][i], cuts[1][j], cuts[2][k]);
                    let hi = Vec3::new(cuts[0][i + 1], cuts[1][j + 1], cuts[2][k + 1]);
                    sum += sphere_box_volume(&c, r, &lo, &hi);
                }
            }
        }
        worst = worst.max(((sum - ball(r)) / (r * r * r)).abs());
    }
    eprintln!("additivity: worst |sum - 4/3 pi r^3| / r^3 = {worst:e}");
    assert!(worst < 1e-13, "{worst}");
}

/// Random sphere/box overlaps against a 1e6-sample Monte Carlo estimate, within 3 sigma.
#[test]
fn monte_carlo() {
    let mut mt = Mt::new(2024);
    let cases = [
        (
            Vec3::new(0.3, 0.9, 0.05),
            0.4,
            Vec3::zeros(),
            Vec3::new(1.0, 1.0, 0.5),
        ),
        (
            Vec3::new(0.1, 0.12, 0.2),
            0.25,
            Vec3::new(0.0, 0.0, 0.1),
            Vec3::new(0.3, 0.2, 0.35),
        ),
        (
            Vec3::new(-0.05, 0.5, 1.02),
            0.3,
            Vec3::zeros(),
            Vec3::new(1.0, 1.0, 1.0),
        ),
    ];
    for (c, r, lo, hi) in cases {
        let v = sphere_box_volume(&c, r, &lo, &hi);
        let n = 1_000_000;
        let mut hits = 0u64;
        for _ in 0..n {
            let p = Vec3::new(
                c[0] + (2.0 * uniform(&mut mt) - 1.0) * r,
                c[1] + (2.0 * uniform(&mut mt) - 1.0) * r,
                c[2] + (2.0 * uniform(&mut mt) - 1.0) * r,
            );
            let d = p - c;
            if d.norm_squared() <= r * r && (0..3).all(|k| p[k] >= lo[k] && p[k] <= hi[k]) {
                hits += 1;
            }
        }
        let cube = 8.0 * r * r * r;
        let phat = hits as f64 / n as f64;
        let est = phat * cube;
        let sigma = (phat * (1.0 - phat) / n as f64).sqrt() * cube;
        eprintln!("MC: exact {v:.6e} estimate {est:.6e} +- {sigma:.1e}");
        assert!(
            v > 0.0 && (v - est).abs() < 3.0 * sigma,
            "exact {v} vs MC {est} +- {sigma}"
        );
    }
}

#[test]
fn periodic_images() {
    let (lx, ly) = (1.0, 0.8);
    let (lo, hi) = (Vec3::new(0.0, 0.0, 0.0), Vec3::new(lx, ly, 1.0));
    let r = 0.2;
    let box_vol = lx * ly * 1.0;
    // straddling x = 0: half in the box, half of it wraps in through x = Lx
    let s = [(Vec3::new(0.0, 0.4, 0.5), r)];
    let p = box_porosity(&s, &lo, &hi, Some((lx, ly)));
    assert!(rel(1.0 - p, ball(r) / box_vol) < 1e-13, "{p}");
    let p_np = box_porosity(&s, &lo, &hi, None);
    assert!(rel(1.0 - p_np, ball(r) / 2.0 / box_vol) < 1e-13, "{p_np}");
    // straddling the x-y corner: four images each contribute a quarter
    let s = [(Vec3::new(lx, 0.0, 0.5), r)];
    let p = box_porosity(&s, &lo, &hi, Some((lx, ly)));
    assert!(rel(1.0 - p, ball(r) / box_vol) < 1e-13, "{p}");
    // a centre given outside the period (x = Lx + 0.1) is counted through its image too
    let s = [(Vec3::new(lx + 0.1, 0.4, 0.5), r)];
    let p = box_porosity(&s, &lo, &hi, Some((lx, ly)));
    assert!(rel(1.0 - p, ball(r) / box_vol) < 1e-13, "{p}");
    // z is not periodic: sticking out of the top counts only the part inside
    let s = [(Vec3::new(0.5, 0.4, 1.0), r)];
    let p = box_porosity(&s, &lo, &hi, Some((lx, ly)));
    assert!(rel(1.0 - p, ball(r) / 2.0 / box_vol) < 1e-13, "{p}");
}

fn vec3(v: &Value) -> Vec3 {
    let a = v.as_array().expect("3-vector");
    Vec3::new(
        a[0].as_f64().unwrap(),
        a[1].as_f64().unwrap(),
        a[2].as_f64().unwrap(),
    )
}

fn spheres(v: &Value) -> Vec<(Vec3, f64)> {
    v.as_array()
        .expect("sphere list")
        .iter()
        .map(|s| {
            let a: Vec<f64> = s
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect();
            (Vec3::new(a[0], a[1], a[2]), a[3])
        })
        .collect()
}

#[test]
fn voxel_porosity_matches_yade() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("golden/pack/voxel.json");
    let doc: Value =
        serde_json::from_str(&std::fs::read_to_string(&path).expect("golden/pack/voxel.json"))
            .unwrap();
    let mut checked = 0;
    for case in doc["cases"].as_array().unwrap() {
        let name = case["name"].as_str().unwrap();
        let dynamic = spheres(&case["spheres"]);
        let fixed = spheres(&case["fixed_ignored"]);
        for probe in case["probes"].as_array().unwrap() {
            let res = probe["resolution"].as_i64().unwrap() as i32;
            let (start, end) = (vec3(&probe["start"]), vec3(&probe["end"]));
            let want = probe["porosity"].as_f64().unwrap();
            let got = voxel_porosity(&dynamic, res, &start, &end).unwrap();
            assert_eq!(
                got.to_bits(),
                want.to_bits(),
                "{name} res={res}: ryade {got:?} vs YADE {want:?}"
            );
            if !fixed.is_empty() {
                // YADE left the fixed spheres out: counting them changes the value
                let all: Vec<_> = dynamic.iter().chain(fixed.iter()).copied().collect();
                assert_ne!(voxel_porosity(&all, res, &start, &end).unwrap(), want);
            }
            checked += 1;
        }
    }
    assert!(checked >= 5, "only {checked} voxel probes");
}

#[test]
fn voxel_porosity_errors() {
    let s = [(Vec3::new(0.5, 0.5, 0.5), 0.2)];
    let one = Vec3::new(1.0, 1.0, 1.0);
    assert!(voxel_porosity(&s, 100, &one, &one).is_err());
    assert!(voxel_porosity(&s, 49, &Vec3::zeros(), &one).is_err());
    assert!(voxel_porosity(&s, 50, &Vec3::zeros(), &Vec3::new(1.0, 0.0, 1.0)).is_err());
}

/// Voxel porosity converges to the exact box porosity.
#[test]
fn voxel_close_to_exact() {
    let s = [
        (Vec3::new(0.5, 0.45, 0.55), 0.3),
        (Vec3::new(0.1, 0.1, 0.1), 0.2),
    ];
    let (lo, hi) = (Vec3::zeros(), Vec3::new(1.0, 1.0, 1.0));
    let exact = box_porosity(&s, &lo, &hi, None);
    let vox = voxel_porosity(&s, 200, &lo, &hi).unwrap();
    assert!((exact - vox).abs() < 2e-3, "exact {exact} voxel {vox}");
}
