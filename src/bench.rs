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
    /// ryade's YADE-order (bit-exact) path with this many threads (same bits for any count).
    YadeOrder(usize),
    /// ryade's fast path with this many threads.
    Fast(usize),
}

impl Variant {
    pub fn name(&self) -> String {
        match self {
            Variant::Yade => "YADE".into(),
            Variant::YadeOrder(1) => "ryade yade-order".into(),
            Variant::YadeOrder(t) => format!("ryade yade-order {}t", t),
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
    /// Where the fast path's time went over the timed steps (None for the other variants).
    pub phases: Option<Phases>,
    /// A script scene's history.csv (compared between the engines, not logged).
    #[serde(skip)]
    pub history: Option<String>,
}

/// The fast path's time per step by phase (ms, wall clock) and its Verlet list builds.
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct Phases {
    pub contacts_ms: f64,
    pub integration_ms: f64,
    pub rebuild_ms: f64,
    pub rebuilds: u64,
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
    let mut phases = None;
    let (dt, nc, mem) = match v {
        Variant::Yade => bail!("run_ryade cannot run YADE"),
        Variant::YadeOrder(threads) => {
            let mut s = s;
            s.threads = threads;
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
            let (tm0, nb0) = (f.timing, f.rebuilds);
            let t0 = Instant::now();
            f.run(steps);
            let dt = t0.elapsed().as_secs_f64();
            let ms = 1e3 / steps.max(1) as f64;
            phases = Some(Phases {
                contacts_ms: (f.timing.contacts - tm0.contacts) * ms,
                integration_ms: (f.timing.newton - tm0.newton) * ms,
                rebuild_ms: (f.timing.rebuild - tm0.rebuild) * ms,
                rebuilds: f.rebuilds - nb0,
            });
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
            phases,
            history: None,
        },
        mem,
    ))
}

/// Time the scene in Debian YADE (one thread) through `yade_ref/bench/run_scene.py`.
pub fn run_yade(root: &Path, scene: &Path, steps: u64, warmup: u64) -> Result<Sample> {
    let script = root.join("yade_ref/bench/run_scene.py");
    let out = crate::harness::proc::output(
        Command::new("yade")
            .env("OMP_NUM_THREADS", "1")
            .args(["-n", "-x"])
            .arg(&script)
            .arg(scene)
            .arg(steps.to_string())
            .arg(warmup.to_string()),
    )
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
        phases: None,
        history: None,
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

/// A bench scene that is a YADE script run unchanged by both engines (`*.study.json`): `yade -n -x
/// SCRIPT ARGS --out DIR` against `compat run SCRIPT ARGS --out DIR` (the YADE-order path; the fast
/// path models spheres only). The script writes `DIR/summary.json` with `timings` (phase, steps,
/// cpu_s, wall_s) and `derived.nSpheres`; the CPU seconds of `phase` are timed (wall seconds for
/// a threaded variant), so start-up, the specimen import and the other phases are not.
#[derive(Clone, Debug, serde::Deserialize)]
pub struct ScriptScene {
    pub label: String,
    /// The script, relative to the repository.
    pub script: String,
    /// Its arguments (paths relative to the repository; `--out` is added).
    pub args: Vec<String>,
    /// The timed phase in summary.json's `timings`.
    pub phase: String,
    /// Arguments for ryade's runs only, after `args` (the study's `--controller native`: ryade runs the
    /// script's PI law in its Rust engine while YADE runs the script's PyRunner; same bytes)
    #[serde(default)]
    pub ryade_args: Vec<String>,
}

/// Is this a script scene (`*.study.json`) rather than a scene file?
pub fn is_script_scene(p: &Path) -> bool {
    p.to_string_lossy().ends_with(".study.json")
}

pub fn load_script_scene(p: &Path) -> Result<ScriptScene> {
    let text = std::fs::read_to_string(p).with_context(|| format!("reading {}", p.display()))?;
    serde_json::from_str(&text).with_context(|| {
        format!(
            "{}: expected {{\"label\", \"script\", \"args\": [..], \"phase\"}}",
            p.display()
        )
    })
}

/// Run a script scene once in YADE or in ryade's YADE-order path and time its phase.
pub fn run_script(root: &Path, sc: &ScriptScene, v: Variant) -> Result<Sample> {
    with_temp_dir(|dir| run_script_in(root, sc, v, dir, None))
}

fn with_temp_dir<T>(f: impl FnOnce(&Path) -> Result<T>) -> Result<T> {
    static RUN: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let k = RUN.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("ryade_bench_{}_{}", std::process::id(), k));
    std::fs::create_dir_all(&dir)?;
    let res = f(&dir);
    let _ = std::fs::remove_dir_all(&dir);
    res
}

/// The wrapper that runs a script with `O.timingEnabled` and writes the engines' timings.
pub const TIMED_RUN: &str = "yade_ref/bench/timed_run.py";

/// One engine's timing in a profiled script run (`yade_ref/bench/timed_run.py`): YADE's
/// `Engine.execTime` (ns) and `execCount`, summed over every step of the final engine list.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct EngineProfile {
    pub engine: String,
    pub count: u64,
    pub ns: u64,
}

/// A profiled script run of one engine.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Profile {
    pub variant: String,
    /// Steps the engines ran (the most runs of any engine).
    pub steps: u64,
    pub engines: Vec<EngineProfile>,
    #[serde(skip)]
    pub history: Option<String>,
}

/// Run a script scene once more in `v` with `O.timingEnabled = True` (through `TIMED_RUN`) and read
/// the per-engine timings.
pub fn profile_script(root: &Path, sc: &ScriptScene, v: Variant) -> Result<Profile> {
    with_temp_dir(|dir| {
        let json = dir.join("timings.json");
        let s = run_script_in(root, sc, v, dir, Some(&json))?;
        #[derive(serde::Deserialize)]
        struct Timings {
            engines: Vec<EngineProfile>,
        }
        let t: Timings = serde_json::from_str(
            &std::fs::read_to_string(&json)
                .with_context(|| format!("{} wrote no {}", TIMED_RUN, json.display()))?,
        )
        .with_context(|| format!("reading {}", json.display()))?;
        Ok(Profile {
            variant: v.name(),
            steps: t.engines.iter().map(|e| e.count).max().unwrap_or(0),
            engines: t.engines,
            history: s.history,
        })
    })
}

/// `timings`: run the script through `TIMED_RUN`, which writes the engines' timings there.
fn run_script_in(
    root: &Path,
    sc: &ScriptScene,
    v: Variant,
    dir: &Path,
    timings: Option<&Path>,
) -> Result<Sample> {
    let mut cmd = match v {
        Variant::Yade => {
            let mut c = Command::new("yade");
            c.env("OMP_NUM_THREADS", "1").args(["-n", "-x"]);
            c
        }
        Variant::YadeOrder(t) => {
            let mut c = Command::new(crate::harness::env::compat_exe()?);
            c.args(["run", "-j", &t.to_string()]);
            c
        }
        // `compat run --fast`: every O.run the fast path can take (the study's cycles with the
        // native piston: spheres, boxes, facets, rolling resistance; not the grid case)
        Variant::Fast(t) => {
            let mut c = Command::new(crate::harness::env::compat_exe()?);
            c.env("RYADE_FAST", "on")
                .args(["run", "-j", &t.to_string()]);
            c
        }
    };
    if let Some(t) = timings {
        cmd.arg(root.join(TIMED_RUN)).arg(t);
    }
    cmd.current_dir(root)
        .arg(root.join(&sc.script))
        .args(&sc.args)
        .args(if matches!(v, Variant::Yade) {
            &[][..]
        } else {
            &sc.ryade_args[..]
        })
        .arg("--out")
        .arg(dir);
    let out = crate::harness::proc::output(&mut cmd)
        .with_context(|| format!("starting {} for {}", v.name(), sc.label))?;
    if !out.status.success() {
        bail!(
            "{} failed on {} ({}):\n{}",
            v.name(),
            sc.label,
            out.status,
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let sum: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.join("summary.json"))
            .context("the script wrote no summary.json")?,
    )?;
    let ph = sum["timings"]
        .as_array()
        .and_then(|t| t.iter().find(|p| p["phase"] == sc.phase.as_str()))
        .ok_or_else(|| anyhow!("summary.json has no timing for phase '{}'", sc.phase))?;
    let steps = ph["steps"].as_f64().unwrap_or(0.0);
    // one thread: CPU seconds (robust on a shared machine); more: wall seconds (the CPU of all
    // threads adds up)
    let threaded = matches!(v, Variant::YadeOrder(t) | Variant::Fast(t) if t > 1);
    let cpu = ph[if threaded { "wall_s" } else { "cpu_s" }]
        .as_f64()
        .unwrap_or(0.0);
    let n = sum["derived"]["nSpheres"].as_f64().unwrap_or(0.0);
    if steps <= 0.0 || cpu <= 0.0 || n <= 0.0 {
        bail!(
            "summary.json: phase '{}' has steps {} cpu {} spheres {}",
            sc.phase,
            steps,
            cpu,
            n
        );
    }
    Ok(Sample {
        engine: v.name(),
        seconds: cpu,
        particle_steps_per_s: steps * n / cpu,
        contact_updates_per_s: 0.0,
        bodies: n as usize,
        contacts: 0,
        phases: None,
        history: std::fs::read_to_string(dir.join("history.csv")).ok(),
    })
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
    /// The label of a script scene (None for a scene file).
    pub script: Option<String>,
    /// Script scenes: every run of every engine wrote the same history.csv.
    pub histories_identical: Option<bool>,
    pub steps: u64,
    pub reps: usize,
    pub samples: Vec<Sample>,
    pub variants: Vec<VariantReport>,
    /// Named ratios between ryade variants over the repetitions (e.g. fast 2t / fast 1t).
    pub ratios: Vec<(String, Stats)>,
    /// Script scenes: one more run of YADE and of the one-thread YADE-order path with
    /// `O.timingEnabled` (per-engine breakdown; not part of the timed repetitions).
    pub profiles: Vec<Profile>,
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
    let script = if is_script_scene(scene) {
        Some(load_script_scene(scene)?)
    } else {
        None
    };
    if variants.is_empty() {
        bail!(
            "{}: nothing to time (a script scene runs in YADE and the YADE-order path only)",
            scene.display()
        );
    }
    let load_before = loadavg();
    let mut samples = Vec::new();
    let mut per: Vec<Vec<Sample>> = vec![Vec::new(); variants.len()];
    let mut mem: Vec<Option<Memory>> = vec![None; variants.len()];
    for _ in 0..reps {
        for (k, v) in variants.iter().enumerate() {
            let s = match (v, &script) {
                (_, Some(sc)) => run_script(root, sc, *v)?,
                (Variant::Yade, None) => run_yade(root, scene, steps, warmup)?,
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
    let mut profiles = Vec::new();
    if let Some(sc) = &script {
        for v in [Variant::Yade, Variant::YadeOrder(1)] {
            if variants.contains(&v) {
                profiles.push(profile_script(root, sc, v)?);
            }
        }
    }
    let mut ratios = Vec::new();
    let find = |v: Variant| variants.iter().position(|x| *x == v);
    if let (Some(a), Some(b)) = (find(Variant::Fast(2)), find(Variant::Fast(1))) {
        ratios.push(("fast 2t / fast 1t".to_string(), ratio_of(a, b)));
    }
    if let (Some(a), Some(b)) = (find(Variant::Fast(1)), find(Variant::YadeOrder(1))) {
        ratios.push(("fast 1t / yade-order".to_string(), ratio_of(a, b)));
    }
    if let (Some(a), Some(b)) = (find(Variant::YadeOrder(2)), find(Variant::YadeOrder(1))) {
        ratios.push(("yade-order 2t / 1t".to_string(), ratio_of(a, b)));
    }
    Ok(BenchReport {
        scene: scene.display().to_string(),
        histories_identical: script.as_ref().map(|_| {
            // the fast path's runs agree with YADE in its band, not in its bits: not compared here
            let h: Vec<&Option<String>> = samples
                .iter()
                .filter(|s| !s.engine.starts_with("ryade fast"))
                .map(|s: &Sample| &s.history)
                .chain(profiles.iter().map(|p| &p.history))
                .collect();
            h.iter().all(|x| x.is_some() && *x == h[0])
        }),
        script: script.map(|s| format!("{}, timed phase '{}'", s.label, s.phase)),
        steps,
        reps,
        samples,
        variants: reports,
        ratios,
        profiles,
        load_before,
        load_after: loadavg(),
    })
}

/// The per-engine table of a script scene's profiled runs: µs per step in each engine, and the
/// first profile (YADE) over the others.
fn format_profiles(ps: &[Profile]) -> String {
    let Some(first) = ps.first() else {
        return String::new();
    };
    let per_step = |p: &Profile, ns: u64| ns as f64 / 1e3 / p.steps.max(1) as f64;
    let mut out = format!(
        "  per engine, µs per step (one more run each with O.timingEnabled, all steps of the final engine list;\n  ratio = first column / second):\n  {:28}",
        "engine"
    );
    for p in ps {
        out += &format!(" {:>18}", p.variant);
    }
    if ps.len() > 1 {
        out += &format!(" {:>14}", "ratio");
    }
    out += "\n";
    let total = |p: &Profile| p.engines.iter().map(|e| e.ns).sum::<u64>();
    let rows = first.engines.len();
    for k in 0..=rows {
        let name = if k < rows {
            first.engines[k].engine.clone()
        } else {
            "TOTAL".to_string()
        };
        let vals: Vec<Option<f64>> = ps
            .iter()
            .map(|p| {
                if k < rows {
                    p.engines.get(k).map(|e| per_step(p, e.ns))
                } else {
                    Some(per_step(p, total(p)))
                }
            })
            .collect();
        out += &format!("  {:28}", name);
        for v in &vals {
            out += &match v {
                Some(x) => format!(" {:>18.1}", x),
                None => format!(" {:>18}", "-"),
            };
        }
        if let (Some(Some(a)), Some(Some(b))) = (vals.first(), vals.get(1)) {
            if *b > 0.0 {
                out += &format!(" {:>14.2}", a / b);
            }
        }
        out += "\n";
    }
    out
}

/// The report as text lines.
/// Fewest bodies of a scene file whose timing says something about the physics.
pub const MIN_TIMED_BODIES: usize = 1000;
/// Shortest timed run (s) whose rate is not dominated by the timer and start-up.
pub const MIN_TIMED_SECONDS: f64 = 0.2;

/// Why the ratios of a report say little (a scene too small or too short to time), if they do.
pub fn too_small_warning(r: &BenchReport) -> Option<String> {
    let bodies = r.samples.iter().map(|s| s.bodies).max().unwrap_or(0);
    let shortest = r
        .samples
        .iter()
        .map(|s| s.seconds)
        .fold(f64::INFINITY, f64::min);
    if r.script.is_none() && bodies < MIN_TIMED_BODIES {
        Some(format!(
            "{} bodies: too small to time; the ratios measure per-step overhead (YADE's engine dispatch and \
             Python), not the contact physics. Time a scene of {}+ bodies (e.g. bench/scenes/dense8000.scene.json)",
            bodies, MIN_TIMED_BODIES
        ))
    } else if shortest < MIN_TIMED_SECONDS {
        Some(format!(
            "the shortest timed run took {:.3} s (< {} s): too short to time reliably; give more --steps",
            shortest, MIN_TIMED_SECONDS
        ))
    } else {
        None
    }
}

pub fn format_report(r: &BenchReport) -> String {
    let mut out = String::new();
    let (b, c) = r
        .samples
        .last()
        .map(|s| (s.bodies, s.contacts))
        .unwrap_or((0, 0));
    out += &match &r.script {
        Some(label) => format!(
            "{}: {}; {} spheres, {} reps (alternating)\n",
            r.scene, label, b, r.reps
        ),
        None => format!(
            "{}: {} bodies, ~{} contacts, {} steps x {} reps (alternating)\n",
            r.scene, b, c, r.steps, r.reps
        ),
    };
    if let Some(w) = too_small_warning(r) {
        out += &format!("  WARNING: {}\n", w);
    }
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
        if v.contact_updates.max > 0.0 {
            out += &format!("  {:18} contact updates/s: {}\n", "", p(&v.contact_updates));
        }
        if let Some(x) = &v.ratio_to_yade {
            out += &format!("  {:18} ratio to YADE:     {}\n", "", q(x));
        }
        let ph: Vec<Phases> = r
            .samples
            .iter()
            .filter(|s| s.engine == v.name)
            .filter_map(|s| s.phases)
            .collect();
        if !ph.is_empty() {
            let med =
                |f: &dyn Fn(&Phases) -> f64| stats(&ph.iter().map(f).collect::<Vec<_>>()).median;
            out += &format!(
                "  {:18} per step (median): contacts {:.3} ms, integration {:.3} ms, list builds {:.3} ms ({:.0} builds)\n",
                "",
                med(&|p| p.contacts_ms),
                med(&|p| p.integration_ms),
                med(&|p| p.rebuild_ms),
                med(&|p| p.rebuilds as f64)
            );
        }
        if let Some(m) = &v.memory {
            out += &format!(
                "  {:18} memory: {:.0} B/particle, {:.0} B/contact\n",
                "", m.per_particle, m.per_contact
            );
        }
    }
    if r.script.is_some() {
        out += "  (script scene: CPU seconds of the timed phase, wall seconds for 2+ threads, particles = spheres; contacts not counted; `ryade fast` is `compat run --fast`: its runs agree with YADE in the seed band, `compat diff rXX --engine fast`, not in its bits)\n";
        out += &format!(
            "  history.csv of every YADE and YADE-order run: {}\n",
            if r.histories_identical == Some(true) {
                "byte-identical"
            } else {
                "DIFFERENT (the engines did not compute the same run)"
            }
        );
    }
    out += &format_profiles(&r.profiles);
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

#[cfg(test)]
mod tests {
    use super::*;

    fn report(bodies: usize, seconds: f64) -> BenchReport {
        BenchReport {
            scene: "s".into(),
            script: None,
            histories_identical: None,
            steps: 100,
            reps: 1,
            samples: vec![Sample {
                engine: "yade".into(),
                seconds,
                particle_steps_per_s: 1.0,
                contact_updates_per_s: 0.0,
                bodies,
                contacts: 0,
                phases: None,
                history: None,
            }],
            variants: vec![],
            ratios: vec![],
            profiles: vec![],
            load_before: String::new(),
            load_after: String::new(),
        }
    }

    /// Issue 18: a 2-body scene gave a 342x ratio without a word; now the report warns.
    #[test]
    fn small_or_short_scenes_are_flagged() {
        let f = format_report(&report(2, 1.0));
        assert!(f.contains("WARNING: 2 bodies: too small to time"), "{}", f);
        let f = format_report(&report(8000, 0.05));
        assert!(
            f.contains("WARNING: the shortest timed run took 0.050 s"),
            "{}",
            f
        );
        assert!(!format_report(&report(8000, 3.0)).contains("WARNING"));
    }

    /// The committed script scenes parse, and every file they name exists in the repository.
    #[test]
    fn committed_script_scenes_name_existing_files() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let mut n = 0;
        for e in std::fs::read_dir(root.join("bench/scenes")).unwrap() {
            let p = e.unwrap().path();
            if !is_script_scene(&p) {
                continue;
            }
            let sc = load_script_scene(&p).unwrap();
            assert!(root.join(&sc.script).is_file(), "{}", sc.script);
            for a in sc.args.iter().filter(|a| a.ends_with(".json")) {
                assert!(root.join(a).is_file(), "{}: {} missing", p.display(), a);
            }
            assert_eq!(sc.phase, "cycles");
            n += 1;
        }
        assert_eq!(n, 4, "scenes (b), (c), (d) and (e)");
    }

    /// The per-engine table divides each engine's ns by the steps of its run, adds a TOTAL row, and
    /// gives the first run over the second; an engine missing from the second run shows as "-".
    #[test]
    fn profile_table_is_per_step_with_total_and_ratio() {
        let e = |n: &str, count, ns| EngineProfile {
            engine: n.into(),
            count,
            ns,
        };
        let yade = Profile {
            variant: "YADE".into(),
            steps: 10,
            engines: vec![e("InteractionLoop", 10, 30_000), e("ctl", 9, 10_000)],
            history: None,
        };
        let ryade = Profile {
            variant: "ryade".into(),
            steps: 20,
            engines: vec![e("InteractionLoop", 20, 20_000)],
            history: None,
        };
        let t = format_profiles(&[yade, ryade]);
        let rows: Vec<Vec<&str>> = t
            .lines()
            .skip(3)
            .map(|l| l.split_whitespace().collect())
            .collect();
        assert_eq!(rows[0], ["InteractionLoop", "3.0", "1.0", "3.00"], "{}", t);
        assert_eq!(rows[1], ["ctl", "1.0", "-"], "{}", t);
        assert_eq!(rows[2], ["TOTAL", "4.0", "1.0", "4.00"], "{}", t);
        assert!(Path::new(env!("CARGO_MANIFEST_DIR"))
            .join(TIMED_RUN)
            .is_file());
    }

    #[test]
    fn a_malformed_script_scene_says_what_is_expected() {
        let d = std::env::temp_dir().join(format!("ryade_bench_test_{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        let p = d.join("bad.study.json");
        std::fs::write(&p, "{\"label\": \"x\"}").unwrap();
        let e = format!("{:#}", load_script_scene(&p).unwrap_err());
        assert!(e.contains("expected") && e.contains("script"), "{}", e);
        std::fs::remove_dir_all(&d).unwrap();
    }
}
