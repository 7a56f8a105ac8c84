//! `compat diff micro` / `compat diff micro_grid`: run each golden scene in ryade and compare every
//! recorded double, every step (bodies, interactions and, for grid scenes, the `intrs6d` file).

use crate::io::golden::{self, BODY_COLS, INTR6D_COLS, INTR_COLS};
use crate::io::scene_json::{self, SceneFile};
use crate::scene::Scene;
use anyhow::{Context, Result};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Distance in units in the last place between two doubles (0 when bit-identical or both NaN; NaN
/// vs number counts as u64::MAX).
pub fn ulp_distance(a: f64, b: f64) -> u64 {
    // NaN == NaN: the golden text ('nan') keeps neither the sign nor the payload of a NaN
    if a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan()) {
        return 0;
    }
    if a.is_nan() || b.is_nan() {
        return u64::MAX;
    }
    let key = |x: f64| -> i128 {
        let bits = x.to_bits() as i64;
        (if bits < 0 { i64::MIN - bits } else { bits }) as i128
    };
    // +0 and -0 are one step apart: their bits differ, so they are a mismatch
    ((key(a) - key(b)).unsigned_abs().min(u64::MAX as u128) as u64).max(1)
}

#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct FirstDiff {
    pub step: u64,
    pub what: String,
    pub ryade: f64,
    pub yade: f64,
}

#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct DiffReport {
    pub scene: String,
    pub steps: u64,
    pub values: u64,
    pub mismatches: u64,
    pub max_ulp: u64,
    /// Real interactions present in one engine and not the other (counted in `mismatches` too).
    pub missing_contacts: u64,
    /// Steps where the container order of real interactions differs (informative).
    pub order_differs_steps: u64,
    pub first: Option<FirstDiff>,
    pub error: Option<String>,
}

impl DiffReport {
    fn note(&mut self, step: u64, what: impl FnOnce() -> String, ours: f64, theirs: f64) {
        self.values += 1;
        let d = ulp_distance(ours, theirs);
        if d != 0 {
            self.mismatches += 1;
            self.max_ulp = self.max_ulp.max(d);
            if self.first.is_none() {
                self.first = Some(FirstDiff {
                    step,
                    what: what(),
                    ryade: ours,
                    yade: theirs,
                });
            }
        }
    }
}

/// Golden file paths of a scene `<dir>/<name>.scene.json`.
pub fn golden_paths(scene_json: &Path) -> (PathBuf, PathBuf) {
    let s = scene_json.to_string_lossy();
    let base = s.trim_end_matches(".scene.json");
    (
        PathBuf::from(format!("{}.bodies.csv.gz", base)),
        PathBuf::from(format!("{}.intrs.csv.gz", base)),
    )
}

/// The `intrs6d` golden file of a scene (grid extension; absent for FORMAT.md scenes).
pub fn golden_path6d(scene_json: &Path) -> PathBuf {
    let s = scene_json.to_string_lossy();
    PathBuf::from(format!(
        "{}.intrs6d.csv.gz",
        s.trim_end_matches(".scene.json")
    ))
}

/// The per-step digest file of a digest scene (FORMAT.md, "Digest scenes"), if the scene has one.
pub fn golden_digest_path(scene_json: &Path) -> PathBuf {
    let s = scene_json.to_string_lossy();
    PathBuf::from(format!(
        "{}.digest.csv.gz",
        s.trim_end_matches(".scene.json")
    ))
}

/// Compare a ryade run of `sf` with the golden records next to `scene_json`.
pub fn diff_scene(sf: SceneFile, scene_json: &Path) -> Result<DiffReport> {
    let dp = golden_digest_path(scene_json);
    if dp.exists() {
        return diff_digest_scene(sf, scene_json, &dp);
    }
    let (bp, ip) = golden_paths(scene_json);
    let bodies = golden::read_bodies(&bp)?;
    let intrs = golden::read_intrs(&ip)?;
    let p6 = golden_path6d(scene_json);
    let intrs6d = if p6.exists() {
        Some(golden::read_intrs6d(&p6)?)
    } else {
        None
    };
    Ok(diff_against_6d(sf, &bodies, &intrs, intrs6d.as_deref()))
}

pub fn diff_against(
    sf: SceneFile,
    bodies: &[golden::BodyRow],
    intrs: &[golden::IntrRow],
) -> DiffReport {
    diff_against_6d(sf, bodies, intrs, None)
}

/// As `diff_against`, also comparing the `intrs6d` rows when given.
pub fn diff_against_6d(
    sf: SceneFile,
    bodies: &[golden::BodyRow],
    intrs: &[golden::IntrRow],
    intrs6d: Option<&[golden::Intr6dRow]>,
) -> DiffReport {
    let (mut scene, steps, mut rep) = start(sf);
    let by_step_b = by_step(bodies, |r| r.step);
    let by_step_i = by_step(intrs, |r| r.step);
    let by_step_6 = by_step(intrs6d.unwrap_or(&[]), |r| r.step);
    for step in 0..=steps {
        if !advance(&mut scene, step, &mut rep) {
            break;
        }
        compare_step(
            &scene,
            step,
            by_step_b.get(&step),
            by_step_i.get(&step),
            &mut rep,
        );
        if intrs6d.is_some() {
            compare_step_6d(&scene, step, by_step_6.get(&step), &mut rep);
        }
    }
    rep
}

/// The scene to run, its step count and an empty report named after it.
fn start(sf: SceneFile) -> (Scene, u64, DiffReport) {
    let SceneFile { scene, steps, name } = sf;
    let rep = DiffReport {
        scene: name,
        steps,
        ..Default::default()
    };
    (scene, steps, rep)
}

/// Run step `step` of the scene (nothing for step 0, the state before the first step); a failed step is
/// a mismatch and the report's error. Returns whether the comparison goes on.
fn advance(scene: &mut Scene, step: u64, rep: &mut DiffReport) -> bool {
    if step > 0 {
        if let Err(e) = scene.step() {
            rep.error = Some(e.to_string());
            rep.mismatches += 1;
            return false;
        }
    }
    true
}

/// Golden rows grouped by step.
fn by_step<T>(rows: &[T], step: impl Fn(&T) -> u64) -> HashMap<u64, Vec<&T>> {
    let mut m: HashMap<u64, Vec<&T>> = HashMap::new();
    for r in rows {
        m.entry(step(r)).or_default().push(r);
    }
    m
}

/// A digest scene: every step's three digests (bodies, interactions, cell and controllers), the full
/// body and interaction rows at the steps the bodies file keeps, and the `peri` rows (cell diagonal
/// and controller) where the scene has them. Values behind a matching digest count as compared; a
/// differing digest counts one mismatch per group and step.
pub fn diff_digest_scene(sf: SceneFile, scene_json: &Path, digest: &Path) -> Result<DiffReport> {
    let digests = golden::read_step_digests(digest)?;
    let (bp, ip) = golden_paths(scene_json);
    let bodies = golden::read_bodies(&bp)?;
    let intrs = golden::read_intrs(&ip)?;
    let s = scene_json.to_string_lossy();
    let pp = PathBuf::from(format!("{}.peri.csv.gz", s.trim_end_matches(".scene.json")));
    let peri: HashMap<u64, [f64; 17]> = if pp.exists() {
        golden::read_peri(&pp)?.into_iter().collect()
    } else {
        HashMap::new()
    };
    let (mut scene, steps, mut rep) = start(sf);
    let by_step_b = by_step(&bodies, |r| r.step);
    let by_step_i = by_step(&intrs, |r| r.step);
    const GROUPS: [&str; 3] = ["bodies", "interactions", "cell and controller"];
    for step in 0..=steps {
        if !advance(&mut scene, step, &mut rep) {
            break;
        }
        match digests.get(&step) {
            None => {
                rep.mismatches += 1;
                rep.error
                    .get_or_insert(format!("no digest for step {}", step));
            }
            Some(theirs) => {
                let (ours, n) = golden::step_digests(&scene);
                rep.values += n;
                for g in 0..3 {
                    if ours[g] != theirs[g] {
                        rep.mismatches += 1;
                        if rep.first.is_none() {
                            rep.first = Some(FirstDiff {
                                step,
                                what: format!("digest of the {}", GROUPS[g]),
                                ryade: f64::NAN,
                                yade: f64::NAN,
                            });
                        }
                    }
                }
            }
        }
        if by_step_b.contains_key(&step) {
            compare_step(
                &scene,
                step,
                by_step_b.get(&step),
                by_step_i.get(&step),
                &mut rep,
            );
        }
        if let Some(row) = peri.get(&step) {
            match golden::peri_values(&scene) {
                None => {
                    rep.mismatches += 1;
                    rep.error.get_or_insert(
                        "the golden has peri rows but ryade no PeriTriaxController".into(),
                    );
                }
                Some(v) => {
                    for (k, (o, t)) in v.iter().zip(row.iter()).enumerate() {
                        rep.note(
                            step,
                            || format!("cell/controller {}", golden::PERI_COLS[k]),
                            *o,
                            *t,
                        );
                    }
                }
            }
        }
    }
    Ok(rep)
}

/// The `intrs6d` rows of one step, matched by pair (the pair set itself is checked by
/// `compare_step`; here a missing pair only counts once more as a mismatch).
fn compare_step_6d(
    scene: &Scene,
    step: u64,
    g6: Option<&Vec<&golden::Intr6dRow>>,
    rep: &mut DiffReport,
) {
    let key = |a: u32, b: u32| if a < b { (a, b) } else { (b, a) };
    let ours: HashMap<(u32, u32), [f64; 15]> = golden::intr6d_values(scene)
        .into_iter()
        .map(|(a, b, v)| (key(a, b), v))
        .collect();
    let empty = Vec::new();
    for row in g6.unwrap_or(&empty) {
        match ours.get(&key(row.id1, row.id2)) {
            None => {
                rep.values += 1;
                rep.mismatches += 1;
                if rep.first.is_none() {
                    rep.first = Some(FirstDiff {
                        step,
                        what: format!(
                            "intrs6d: contact {}-{} exists in YADE only",
                            row.id1, row.id2
                        ),
                        ..Default::default()
                    });
                }
            }
            Some(v) => {
                for (k, (o, t)) in v.iter().zip(row.v.iter()).enumerate() {
                    rep.note(
                        step,
                        || format!("contact {}-{} {}", row.id1, row.id2, INTR6D_COLS[k]),
                        *o,
                        *t,
                    );
                }
            }
        }
    }
}

fn compare_step(
    scene: &Scene,
    step: u64,
    gb: Option<&Vec<&golden::BodyRow>>,
    gi: Option<&Vec<&golden::IntrRow>>,
    rep: &mut DiffReport,
) {
    let empty_b = Vec::new();
    let gb = gb.unwrap_or(&empty_b);
    if gb.len() != scene.bodies.len() {
        rep.mismatches += 1;
        if rep.first.is_none() {
            rep.first = Some(FirstDiff {
                step,
                what: format!(
                    "body count: golden has {} rows, ryade {} bodies",
                    gb.len(),
                    scene.bodies.len()
                ),
                ..Default::default()
            });
        }
    }
    for row in gb {
        let id = row.id as usize;
        if id >= scene.bodies.len() {
            continue;
        }
        let ours = golden::body_values(scene, id);
        for (k, (o, t)) in ours.iter().zip(row.v.iter()).enumerate() {
            rep.note(step, || format!("body {} {}", id, BODY_COLS[k]), *o, *t);
        }
    }
    let ours = golden::intr_values(scene);
    let empty_i = Vec::new();
    let gi = gi.unwrap_or(&empty_i);
    let key = |a: u32, b: u32| if a < b { (a, b) } else { (b, a) };
    type Entry<'a> = (usize, u32, u32, &'a [f64; 18]);
    let mut ours_map: HashMap<(u32, u32), Entry> = HashMap::new();
    for (ord, (a, b, v)) in ours.iter().enumerate() {
        ours_map.insert(key(*a, *b), (ord, *a, *b, v));
    }
    let mut order_same = ours.len() == gi.len();
    for row in gi {
        match ours_map.remove(&key(row.id1, row.id2)) {
            None => {
                rep.values += 1;
                rep.mismatches += 1;
                rep.missing_contacts += 1;
                if rep.first.is_none() {
                    rep.first = Some(FirstDiff {
                        step,
                        what: format!("contact {}-{} exists in YADE only", row.id1, row.id2),
                        ..Default::default()
                    });
                }
            }
            Some((ord, a, b, v)) => {
                if ord as u32 != row.ord {
                    order_same = false;
                }
                if (a, b) != (row.id1, row.id2) {
                    rep.values += 1;
                    rep.mismatches += 1;
                    if rep.first.is_none() {
                        rep.first = Some(FirstDiff {
                            step,
                            what: format!(
                                "contact {}-{} has ids in order {}-{} in ryade",
                                row.id1, row.id2, a, b
                            ),
                            ..Default::default()
                        });
                    }
                }
                for (k, (o, t)) in v.iter().zip(row.v.iter()).enumerate() {
                    rep.note(
                        step,
                        || format!("contact {}-{} {}", row.id1, row.id2, INTR_COLS[k]),
                        *o,
                        *t,
                    );
                }
            }
        }
    }
    for (_, (_, a, b, _)) in ours_map {
        rep.values += 1;
        rep.mismatches += 1;
        rep.missing_contacts += 1;
        if rep.first.is_none() {
            rep.first = Some(FirstDiff {
                step,
                what: format!("contact {}-{} exists in ryade only", a, b),
                ..Default::default()
            });
        }
    }
    if !order_same {
        rep.order_differs_steps += 1;
    }
}

/// All `*.scene.json` files of a golden directory, sorted by name.
pub fn scene_files(dir: &Path) -> Result<Vec<PathBuf>> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .with_context(|| format!("reading golden directory {}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.to_string_lossy().ends_with(".scene.json"))
        .collect();
    v.sort();
    Ok(v)
}

/// Diff every scene of `dir`.
pub fn diff_dir(dir: &Path) -> Result<Vec<DiffReport>> {
    let mut out = Vec::new();
    for p in scene_files(dir)? {
        let sf = scene_json::load(&p)?;
        out.push(diff_scene(sf, &p)?);
    }
    Ok(out)
}

/// The table `compat diff micro` prints.
pub fn format_table(reps: &[DiffReport]) -> String {
    let mut s = format!(
        "{:<14} {:>6} {:>10} {:>10} {:>8} {:>7}  {}\n",
        "scene", "steps", "values", "mismatch", "maxULP", "order≠", "first divergence"
    );
    for r in reps {
        let first = match (&r.error, &r.first) {
            (Some(e), _) => format!("ERROR: {}", e),
            (None, Some(f)) if f.ryade.is_nan() && f.yade.is_nan() => {
                format!("step {}: {}", f.step, f.what)
            }
            (None, Some(f)) => format!(
                "step {}: {} (ryade {:e}, yade {:e})",
                f.step, f.what, f.ryade, f.yade
            ),
            (None, None) => "-".into(),
        };
        let ulp = if r.max_ulp == u64::MAX {
            "NaN".to_string()
        } else {
            r.max_ulp.to_string()
        };
        s.push_str(&format!(
            "{:<14} {:>6} {:>10} {:>10} {:>8} {:>7}  {}\n",
            r.scene, r.steps, r.values, r.mismatches, ulp, r.order_differs_steps, first
        ));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::ulp_distance;
    #[test]
    fn ulp() {
        assert_eq!(ulp_distance(1.0, 1.0), 0);
        assert_eq!(ulp_distance(1.0, f64::from_bits(1.0f64.to_bits() + 3)), 3);
        assert_eq!(ulp_distance(0.0, -0.0), 1);
        assert_eq!(
            ulp_distance(-1.0, f64::from_bits((-1.0f64).to_bits() + 2)),
            2
        );
    }
}
