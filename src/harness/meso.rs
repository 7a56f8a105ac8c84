//! `compat diff meso`: a YADE-made packing of >= 500 spheres settling on a box for 2000 steps.
//! Per step a SHA-256 digest of every body's 19 recorded doubles tells the first step where the
//! engines differ; full states at a few steps give the size of the difference.

use crate::io::golden::{self, BODY_COLS};
use crate::io::scene_json;
use anyhow::{anyhow, bail, Context, Result};
use sha2::{Digest, Sha256};
use std::collections::BTreeMap;
use std::path::Path;

/// The digest the YADE recorder writes: SHA-256 of little-endian doubles, 19 per body in id order.
pub fn state_digest(scene: &crate::scene::Scene) -> String {
    let mut h = Sha256::new();
    for id in 0..scene.bodies.len() {
        for x in golden::body_values(scene, id) {
            h.update(x.to_le_bytes());
        }
    }
    h.finalize().iter().map(|b| format!("{:02x}", b)).collect()
}

#[derive(Clone, Debug, serde::Serialize)]
pub struct StepDiff {
    pub step: u64,
    /// max over columns of max_i |ryade - yade| / max_i |yade| (per column, over bodies)
    pub max_rel: f64,
    pub worst_column: String,
    pub pos_max_abs: f64,
}

#[derive(Clone, Debug, serde::Serialize)]
pub struct MesoReport {
    pub bodies: usize,
    pub steps: u64,
    pub first_diff_step: Option<u64>,
    pub identical_steps: u64,
    pub at: Vec<StepDiff>,
}

pub fn diff_meso(dir: &Path) -> Result<MesoReport> {
    let sp = dir.join("settle.scene.json");
    let sf = scene_json::load(&sp)?;
    let digests = read_digests(&dir.join("settle.digest.csv"))?;
    let rows = golden::read_bodies(&dir.join("settle.bodies.csv.gz"))?;
    let mut full: BTreeMap<u64, Vec<[f64; 19]>> = BTreeMap::new();
    for r in rows {
        full.entry(r.step).or_default().push(r.v);
    }
    let steps = *digests
        .keys()
        .max()
        .ok_or_else(|| anyhow!("empty digest file"))?;
    let mut scene = sf.scene;
    let nb = scene.bodies.len();
    let mut rep = MesoReport {
        bodies: nb,
        steps,
        first_diff_step: None,
        identical_steps: 0,
        at: Vec::new(),
    };
    for step in 0..=steps {
        if step > 0 {
            scene.step().map_err(|e| anyhow!("ryade stopped: {}", e))?;
        }
        if let Some(d) = digests.get(&step) {
            if *d == state_digest(&scene) {
                if rep.first_diff_step.is_none() {
                    rep.identical_steps += 1;
                }
            } else if rep.first_diff_step.is_none() {
                rep.first_diff_step = Some(step);
            }
        }
        if let Some(g) = full.get(&step) {
            if g.len() != nb {
                bail!("golden step {} has {} bodies, ryade {}", step, g.len(), nb);
            }
            let mut worst = (0.0, 0usize);
            let mut pos_abs: f64 = 0.0;
            for col in 0..19 {
                let mut dmax: f64 = 0.0;
                let mut vmax: f64 = 0.0;
                for (id, gv) in g.iter().enumerate() {
                    let ours = golden::body_values(&scene, id)[col];
                    dmax = dmax.max((ours - gv[col]).abs());
                    vmax = vmax.max(gv[col].abs());
                    if col < 3 {
                        pos_abs = pos_abs.max((ours - gv[col]).abs());
                    }
                }
                let rel = if vmax > 0.0 { dmax / vmax } else { dmax };
                if rel > worst.0 {
                    worst = (rel, col);
                }
            }
            rep.at.push(StepDiff {
                step,
                max_rel: worst.0,
                worst_column: BODY_COLS[worst.1].into(),
                pos_max_abs: pos_abs,
            });
        }
    }
    Ok(rep)
}

fn read_digests(p: &Path) -> Result<BTreeMap<u64, String>> {
    let text = std::fs::read_to_string(p).with_context(|| format!("reading {}", p.display()))?;
    let mut out = BTreeMap::new();
    for (i, line) in text.lines().enumerate() {
        if i == 0 {
            if line.trim() != "step,sha256" {
                bail!("{}: expected header 'step,sha256'", p.display());
            }
            continue;
        }
        let (s, d) = line
            .split_once(',')
            .ok_or_else(|| anyhow!("{}: malformed line {}", p.display(), i + 1))?;
        out.insert(
            s.trim()
                .parse()
                .with_context(|| format!("{}: bad step on line {}", p.display(), i + 1))?,
            d.trim().to_string(),
        );
    }
    Ok(out)
}

pub fn format_report(r: &MesoReport) -> String {
    let mut s = format!(
        "meso: {} bodies, {} steps; first step with any differing value: {}\n",
        r.bodies,
        r.steps,
        r.first_diff_step
            .map_or("none (identical at every step)".to_string(), |x| x
                .to_string())
    );
    for d in &r.at {
        s.push_str(&format!(
            "  step {:>5}: max relative difference {:.3e} (column {}), max |Δpos| {:.3e} m\n",
            d.step, d.max_rel, d.worst_column, d.pos_max_abs
        ));
    }
    s
}
