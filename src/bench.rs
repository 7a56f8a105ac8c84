//! `compat bench`: the same scene timed in YADE and in ryade in one invocation, repetitions
//! alternating between the engines so that both see the same machine load.
//!
//! YADE loads the scene file with `yade_ref/bench/run_scene.py` (17-digit state, same engines) and
//! times `O.run(steps, True)`; ryade loads it with `io::scene_json` and times `Scene::step`. Both
//! report particle-steps/s (bodies × steps / s) and contact updates/s (real contacts × steps / s).

use crate::io::scene_json;
use anyhow::{anyhow, bail, Context, Result};
use std::path::Path;
use std::process::Command;
use std::time::Instant;

#[derive(Clone, Debug, serde::Serialize)]
pub struct Sample {
    pub engine: String,
    pub seconds: f64,
    pub particle_steps_per_s: f64,
    pub contact_updates_per_s: f64,
    pub bodies: usize,
    pub contacts: usize,
}

/// Time `steps` steps of the scene in ryade (after `warmup` untimed steps).
pub fn run_ryade(scene: &Path, steps: u64, warmup: u64) -> Result<Sample> {
    let mut s = scene_json::load(scene)?.scene;
    for _ in 0..warmup {
        s.step().map_err(|e| anyhow!("{}", e))?;
    }
    let t0 = Instant::now();
    for _ in 0..steps {
        s.step().map_err(|e| anyhow!("{}", e))?;
    }
    let dt = t0.elapsed().as_secs_f64();
    let nc = s.interactions.count_real();
    Ok(Sample {
        engine: "ryade".into(),
        seconds: dt,
        particle_steps_per_s: steps as f64 * s.bodies.len() as f64 / dt,
        contact_updates_per_s: steps as f64 * nc as f64 / dt,
        bodies: s.bodies.len(),
        contacts: nc,
    })
}

/// Time the scene in Debian YADE (one thread) through `yade_ref/bench/run_scene.py`.
pub fn run_yade(root: &Path, scene: &Path, steps: u64, warmup: u64) -> Result<Sample> {
    let script = root.join("yade_ref/bench/run_scene.py");
    let out = Command::new("yade")
        .env("OMP_NUM_THREADS", "1")
        .args(["-n", "-x"])
        .arg(&script)
        .arg(scene)
        .arg(steps.to_string())
        .arg(warmup.to_string())
        .output()
        .context("starting yade (apt-get install -y --no-install-recommends yade)")?;
    let text = String::from_utf8_lossy(&out.stdout);
    let line = text
        .lines()
        .find(|l| l.starts_with("BENCH "))
        .ok_or_else(|| {
            anyhow!(
                "yade printed no BENCH line:\n{}{}",
                text,
                String::from_utf8_lossy(&out.stderr)
            )
        })?;
    let field = |k: &str| -> Result<f64> {
        line.split_whitespace()
            .find_map(|t| t.strip_prefix(&format!("{}=", k)))
            .ok_or_else(|| anyhow!("no {} in '{}'", k, line))?
            .parse::<f64>()
            .map_err(|e| anyhow!("bad {} in '{}': {}", k, line, e))
    };
    Ok(Sample {
        engine: "yade".into(),
        seconds: field("seconds")?,
        particle_steps_per_s: field("particle_steps_per_s")?,
        contact_updates_per_s: field("contact_updates_per_s")?,
        bodies: field("bodies")? as usize,
        contacts: field("contacts")? as usize,
    })
}

#[derive(Clone, Debug, serde::Serialize)]
pub struct Stats {
    pub min: f64,
    pub median: f64,
    pub max: f64,
}

pub fn stats(v: &[f64]) -> Stats {
    let mut s = v.to_vec();
    s.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let n = s.len();
    let median = if n % 2 == 1 {
        s[n / 2]
    } else {
        0.5 * (s[n / 2 - 1] + s[n / 2])
    };
    Stats {
        min: s[0],
        median,
        max: s[n - 1],
    }
}

#[derive(Clone, Debug, serde::Serialize)]
pub struct BenchReport {
    pub scene: String,
    pub steps: u64,
    pub samples: Vec<Sample>,
    pub ryade_particle_steps: Stats,
    pub yade_particle_steps: Option<Stats>,
    /// ryade / YADE particle-steps/s, over the pairs of alternating repetitions.
    pub ratio: Option<Stats>,
}

/// Alternate `reps` YADE and ryade runs of the same scene.
pub fn bench(
    root: &Path,
    scene: &Path,
    steps: u64,
    warmup: u64,
    reps: usize,
    with_yade: bool,
) -> Result<BenchReport> {
    if reps == 0 {
        bail!("--reps must be at least 1");
    }
    let mut samples = Vec::new();
    let mut ratios = Vec::new();
    for _ in 0..reps {
        let y = if with_yade {
            Some(run_yade(root, scene, steps, warmup)?)
        } else {
            None
        };
        let r = run_ryade(scene, steps, warmup)?;
        if let Some(y) = &y {
            ratios.push(r.particle_steps_per_s / y.particle_steps_per_s);
            samples.push(y.clone());
        }
        samples.push(r);
    }
    let of = |e: &str| -> Vec<f64> {
        samples
            .iter()
            .filter(|s| s.engine == e)
            .map(|s| s.particle_steps_per_s)
            .collect()
    };
    Ok(BenchReport {
        scene: scene.display().to_string(),
        steps,
        ryade_particle_steps: stats(&of("ryade")),
        yade_particle_steps: with_yade.then(|| stats(&of("yade"))),
        ratio: with_yade.then(|| stats(&ratios)),
        samples,
    })
}
