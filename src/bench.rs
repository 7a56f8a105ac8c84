//! `compat bench`: the same scene timed in YADE and in ryade in one invocation, repetitions
//! alternating between the engines so that all see the same machine load.
//!
//! YADE loads the scene file with `yade_ref/bench/run_scene.py` (17-digit state, same engines) and
//! times `O.run(steps, True)`; ryade loads it with `io::scene_json` and times either the YADE-order
//! path (`Scene::step`) or the fast path (`fast::FastSim`, with 1 or more threads). All report
//! particle-steps/s (bodies × steps / s) and contact updates/s (real contacts × steps / s).

use crate::fast::{FastOptions, FastSim};
use crate::io::scene_json;
use crate::scene::Scene;
use anyhow::{anyhow, bail, Context, Result};
use std::path::Path;
use std::process::Command;
use std::time::Instant;

/// What is timed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum Variant {
    /// Debian YADE, one thread.
    Yade,
    /// ryade's YADE-order (bit-exact) path.
    YadeOrder,
    /// ryade's fast path with this many threads.
    Fast(usize),
}

impl Variant {
    pub fn name(&self) -> String {
        match self {
            Variant::Yade => "YADE".into(),
            Variant::YadeOrder => "ryade yade-order".into(),
            Variant::Fast(t) => format!("ryade fast {}t", t),
        }
    }
}

#[derive(Clone, Debug, serde::Serialize)]
pub struct Sample {
    pub engine: String,
    pub seconds: f64,
    pub particle_steps_per_s: f64,
    pub contact_updates_per_s: f64,
    pub bodies: usize,
    pub contacts: usize,
}

/// Memory held per particle and per real contact (bytes, from container sizes and capacities).
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct Memory {
    pub per_particle: f64,
    pub per_contact: f64,
}

/// Bytes held by the YADE-order path: per body (body arrays, forces, bounds, collider lists) and
/// per real contact (the whole interaction container, potential pairs included, over real contacts).
pub fn scene_memory(s: &Scene) -> Memory {
    use crate::math::{Quat, Vec3};
    use std::mem::size_of;
    let b = &s.bodies;
    let per_body = size_of::<crate::shape::Shape>()
        + size_of::<usize>()
        + size_of::<i32>()
        + 2 * size_of::<bool>()
        + 4 * size_of::<Vec3>()
        + size_of::<Quat>()
        + size_of::<f64>()
        + size_of::<u8>()
        + size_of::<Option<crate::body::Bound>>()
        + 4 * size_of::<Vec3>();
    let collider: usize = s
        .engines
        .iter()
        .map(|e| match e {
            crate::scene::Engine::Collider(c) => c.memory_bytes(),
            _ => 0,
        })
        .sum();
    let n = b.len().max(1) as f64;
    let i = &s.interactions;
    // the hash index: key, value and one control byte per bucket, buckets ~ 8/7 of the entries
    let index = i.list.capacity() * (size_of::<u64>() + size_of::<u32>() + 1) * 8 / 7;
    let container = i.list.capacity() * size_of::<crate::interaction::Interaction>()
        + i.scan.capacity() * size_of::<crate::interaction::ScanEntry>()
        + index;
    Memory {
        per_particle: (per_body * b.len() + collider) as f64 / n,
        per_contact: container as f64 / i.count_real().max(1) as f64,
    }
}

/// Time `steps` steps of the scene in ryade (after `warmup` untimed steps).
pub fn run_ryade(scene: &Path, v: Variant, steps: u64, warmup: u64) -> Result<(Sample, Memory)> {
    let s = scene_json::load(scene)?.scene;
    let n = s.bodies.len();
    let (dt, nc, mem) = match v {
        Variant::Yade => bail!("run_ryade cannot run YADE"),
        Variant::YadeOrder => {
            let mut s = s;
            for _ in 0..warmup {
                s.step().map_err(|e| anyhow!("{}", e))?;
            }
            let t0 = Instant::now();
            for _ in 0..steps {
                s.step().map_err(|e| anyhow!("{}", e))?;
            }
            let dt = t0.elapsed().as_secs_f64();
            (dt, s.interactions.count_real(), scene_memory(&s))
        }
        Variant::Fast(threads) => {
            let opt = FastOptions {
                threads,
                ..FastOptions::default()
            };
            let mut f = FastSim::from_scene(&s, opt).map_err(|e| anyhow!("{}", e))?;
            f.run(warmup);
            let t0 = Instant::now();
            f.run(steps);
            let dt = t0.elapsed().as_secs_f64();
            let m = f.memory();
            (
                dt,
                f.active_contacts(),
                Memory {
                    per_particle: m.per_particle,
                    per_contact: m.per_contact,
                },
            )
        }
    };
    Ok((
        Sample {
            engine: v.name(),
            seconds: dt,
            particle_steps_per_s: steps as f64 * n as f64 / dt,
            contact_updates_per_s: steps as f64 * nc as f64 / dt,
            bodies: n,
            contacts: nc,
        },
        mem,
    ))
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
        engine: Variant::Yade.name(),
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

/// The results of one variant over the repetitions.
#[derive(Clone, Debug, serde::Serialize)]
pub struct VariantReport {
    pub variant: Variant,
    pub name: String,
    pub particle_steps: Stats,
    pub contact_updates: Stats,
    /// This variant / YADE particle-steps/s, over the repetitions (each against the YADE run of the
    /// same repetition).
    pub ratio_to_yade: Option<Stats>,
    pub memory: Option<Memory>,
}

#[derive(Clone, Debug, serde::Serialize)]
pub struct BenchReport {
    pub scene: String,
    pub steps: u64,
    pub reps: usize,
    pub samples: Vec<Sample>,
    pub variants: Vec<VariantReport>,
    /// Named ratios between ryade variants over the repetitions (e.g. fast 2t / fast 1t).
    pub ratios: Vec<(String, Stats)>,
    /// `/proc/loadavg` before and after (the machine may be shared).
    pub load_before: String,
    pub load_after: String,
}

fn loadavg() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_default()
}

/// Alternate `reps` runs of every variant of the same scene (YADE first in each repetition).
pub fn bench(
    root: &Path,
    scene: &Path,
    steps: u64,
    warmup: u64,
    reps: usize,
    variants: &[Variant],
) -> Result<BenchReport> {
    if reps == 0 {
        bail!("--reps must be at least 1");
    }
    if variants.is_empty() {
        bail!("nothing to time");
    }
    let load_before = loadavg();
    let mut samples = Vec::new();
    let mut per: Vec<Vec<Sample>> = vec![Vec::new(); variants.len()];
    let mut mem: Vec<Option<Memory>> = vec![None; variants.len()];
    for _ in 0..reps {
        for (k, v) in variants.iter().enumerate() {
            let s = match v {
                Variant::Yade => run_yade(root, scene, steps, warmup)?,
                _ => {
                    let (s, m) = run_ryade(scene, *v, steps, warmup)?;
                    mem[k] = Some(m);
                    s
                }
            };
            per[k].push(s.clone());
            samples.push(s);
        }
    }
    let yade = variants.iter().position(|v| *v == Variant::Yade);
    let ratio_of = |a: usize, b: usize| -> Stats {
        let r: Vec<f64> = per[a]
            .iter()
            .zip(&per[b])
            .map(|(x, y)| x.particle_steps_per_s / y.particle_steps_per_s)
            .collect();
        stats(&r)
    };
    let reports = variants
        .iter()
        .enumerate()
        .map(|(k, v)| VariantReport {
            variant: *v,
            name: v.name(),
            particle_steps: stats(
                &per[k]
                    .iter()
                    .map(|s| s.particle_steps_per_s)
                    .collect::<Vec<_>>(),
            ),
            contact_updates: stats(
                &per[k]
                    .iter()
                    .map(|s| s.contact_updates_per_s)
                    .collect::<Vec<_>>(),
            ),
            ratio_to_yade: match yade {
                Some(y) if y != k => Some(ratio_of(k, y)),
                _ => None,
            },
            memory: mem[k],
        })
        .collect();
    let mut ratios = Vec::new();
    let find = |v: Variant| variants.iter().position(|x| *x == v);
    if let (Some(a), Some(b)) = (find(Variant::Fast(2)), find(Variant::Fast(1))) {
        ratios.push(("fast 2t / fast 1t".to_string(), ratio_of(a, b)));
    }
    if let (Some(a), Some(b)) = (find(Variant::Fast(1)), find(Variant::YadeOrder)) {
        ratios.push(("fast 1t / yade-order".to_string(), ratio_of(a, b)));
    }
    Ok(BenchReport {
        scene: scene.display().to_string(),
        steps,
        reps,
        samples,
        variants: reports,
        ratios,
        load_before,
        load_after: loadavg(),
    })
}

/// The report as text lines.
pub fn format_report(r: &BenchReport) -> String {
    let mut out = String::new();
    let (b, c) = r
        .samples
        .last()
        .map(|s| (s.bodies, s.contacts))
        .unwrap_or((0, 0));
    out += &format!(
        "{}: {} bodies, ~{} contacts, {} steps x {} reps (alternating)\n",
        r.scene, b, c, r.steps, r.reps
    );
    let p = |s: &Stats| {
        format!(
            "min {:.3e} median {:.3e} max {:.3e}",
            s.min, s.median, s.max
        )
    };
    let q = |s: &Stats| format!("min {:.2} median {:.2} max {:.2}", s.min, s.median, s.max);
    for v in &r.variants {
        out += &format!(
            "  {:18} particle-steps/s: {}\n",
            v.name,
            p(&v.particle_steps)
        );
        out += &format!("  {:18} contact updates/s: {}\n", "", p(&v.contact_updates));
        if let Some(x) = &v.ratio_to_yade {
            out += &format!("  {:18} ratio to YADE:     {}\n", "", q(x));
        }
        if let Some(m) = &v.memory {
            out += &format!(
                "  {:18} memory: {:.0} B/particle, {:.0} B/contact\n",
                "", m.per_particle, m.per_contact
            );
        }
    }
    for (name, s) in &r.ratios {
        out += &format!("  {:30} {}\n", name, q(s));
    }
    out += &format!(
        "  load average before {} / after {} on {} cores\n",
        r.load_before,
        r.load_after,
        std::thread::available_parallelism().map_or(0, |n| n.get())
    );
    out
}
