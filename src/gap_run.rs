//! `compat gap` orchestration: the candidate effects, the library sweep and the blind datasets, all
//! as yade-batch tables run through `compat batch` (ryade) or `compat batch --command 'yade -n -x'`
//! (Debian YADE), so the same sweep can go to a cluster (`--emit-slurm`).

use crate::gap::{self, Effect, Library, Series};
pub use crate::gap::{detectable_ranges, DetectableRange, DETECTABILITY_FLOOR};
use anyhow::{bail, Context, Result};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The candidate effects (study.py knobs, yade_ref/study/README.md "Unmodelled effects"). Strength 0 is
/// today's model; `knobs(s)` are the study.py options of strength s.
pub fn catalogue() -> Vec<Effect> {
    let e = |k: &str, m: &str, st: &[f64]| Effect {
        knob: k.into(),
        meaning: m.into(),
        zero: 0.0,
        strengths: st.to_vec(),
    };
    vec![
        e(
            "rolling",
            "rolling resistance on sphere contacts (etaRoll; angularity proxy)",
            &[0.02, 0.05, 0.2, 0.5],
        ),
        e(
            "grading",
            "particle size dispersion (makeCloud rRelFuzz)",
            &[0.15, 0.3],
        ),
        e(
            "subgrade",
            "compliant subgrade (compliance 1e7/K, K in N/m^3)",
            &[0.1, 0.3, 1.0],
        ),
        e(
            "grid_soft",
            "softer geogrid (log10 of 1/stiffness scale of kn, kr)",
            &[0.5, 1.0],
        ),
        e(
            "friction",
            "interparticle friction change [deg from 30]",
            &[-10.0, -5.0, 5.0, 10.0],
        ),
        e(
            "damping",
            "local damping change (from 0.2)",
            &[-0.15, -0.075, 0.15, 0.3],
        ),
    ]
}

/// study.py knob pairs (`name=value`, comma-separated) for effect strengths.
pub fn knobs(effects: &[(String, f64)]) -> Result<String> {
    let mut out = Vec::new();
    for (k, s) in effects {
        if *s == 0.0 {
            continue;
        }
        out.push(match k.as_str() {
            "rolling" => format!("eta_roll={}", s),
            "grading" => format!("psd_fuzz={}", s),
            "subgrade" => format!("subgrade_k={:e}", 1e7 / s),
            "grid_soft" => {
                let sc = 10f64.powf(-s);
                format!("grid_kn_scale={},grid_kr_scale={}", sc, sc)
            }
            "friction" => format!("load_friction={}", 30.0 + s),
            "damping" => format!("damping={}", 0.2 + s),
            // outside the catalogue (issue 20's blind cases): clumps of K spheres
            "clump" => format!("clump_size={}", s.round() as i64),
            other => bail!(
                "unknown effect '{}' (known: rolling, grading, subgrade, grid_soft, friction, damping; clump outside the catalogue)",
                other
            ),
        });
    }
    Ok(out.join(","))
}

/// Does the effect change generation (needs a new specimen)?
fn generates(k: &str) -> bool {
    k == "grading" || k == "clump"
}

/// How a blind dataset draws its hidden effects.
#[derive(Clone, Copy, Debug)]
pub struct Design {
    /// Strengths drawn over each effect's whole library range (every effect, detectable or not;
    /// the second effect of a two-effect case too), not only where the signal reaches the floor.
    pub unfiltered: bool,
    /// Cases of an effect outside the catalogue: clumps of 2-4 spheres (`--clump-size`).
    pub n_clump: usize,
}

/// A strength drawn uniformly over the library range of effect `i` (both signs where it has them).
fn draw_over_range(sur: &gap::Surrogate, i: usize, u: &mut dyn FnMut() -> f64) -> f64 {
    let (lo, hi) = sur.range(i);
    let (lo, hi) = (lo.min(0.0), hi.max(0.0));
    let x = lo + u() * (hi - lo);
    let x = if x == 0.0 { hi.max(lo.abs()) * 1e-3 } else { x };
    (x * 1e4).round() / 1e4
}

/// study.py's cell for `size`: (width, the SIZES nx times the 0.06 m rib length; default piston
/// diameter, SIZES' D) [m].
fn study_cell(size: &str) -> Option<(f64, f64)> {
    let (nx, d) = match size {
        "tiny" => (3.0, 0.09),
        "small" => (4.0, 0.10),
        "medium" => (5.0, 0.15),
        "full" => (10.0, 0.30),
        _ => return None,
    };
    Some((nx * 0.06, d))
}

/// study.py's default seating and peak pressures (`--seat-kpa`, `--peak-kpa`) [kPa], layer
/// (`--layer`) [m] and frequency (`--freq`) [Hz].
const STUDY_SEAT_KPA: f64 = 27.6;
const STUDY_PEAK_KPA: f64 = 275.8;
const STUDY_LAYER: f64 = 0.25;
const STUDY_FREQ: f64 = 50.0;

/// The study case every run of a library or dataset shares.
#[derive(Clone, Debug)]
pub struct Scenario {
    pub ratio: u8,
    pub case: char,
    pub size: String,
    pub cycles: u32,
    /// The user's test conditions where they are not the study's.
    pub test: TestConditions,
}

/// A plate test's own conditions where they differ from the study's (issue 20: a user names the
/// plate, the load and the layer of their test): study.py's `--piston-d`, `--seat-kpa`, `--peak-kpa`,
/// `--layer`, `--freq`; None keeps the study's value (yade_ref/study/README.md).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TestConditions {
    /// Plate (piston) diameter [m].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub piston_d: Option<f64>,
    /// Seating pressure [kPa].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seat_kpa: Option<f64>,
    /// Peak pressure [kPa].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub peak_kpa: Option<f64>,
    /// Base layer thickness [m].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub layer: Option<f64>,
    /// Load frequency [Hz].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub freq: Option<f64>,
}

impl TestConditions {
    fn pairs(&self) -> Vec<(&'static str, f64)> {
        [
            ("piston_d", self.piston_d),
            ("seat_kpa", self.seat_kpa),
            ("peak_kpa", self.peak_kpa),
            ("layer", self.layer),
            ("freq", self.freq),
        ]
        .into_iter()
        .filter_map(|(k, v)| Some((k, v?)))
        .collect()
    }

    /// The `compat gap` option of knob `k` (the plate diameter is study.py's piston diameter).
    fn flag(k: &str) -> String {
        match k {
            "piston_d" => "--plate-d".into(),
            _ => format!("--{}", k.replace('_', "-")),
        }
    }

    /// The conditions as `compat gap` options (`--plate-d 0.2`, ...).
    fn flags(&self) -> Vec<String> {
        self.pairs()
            .iter()
            .map(|(k, v)| format!("{} {}", Self::flag(k), v))
            .collect()
    }

    /// The study.py knob pairs (`piston_d=0.2,peak_kpa=550`; '' for the study's conditions).
    pub fn knobs(&self) -> String {
        self.pairs()
            .iter()
            .map(|(k, v)| format!("{}={}", k, v))
            .collect::<Vec<_>>()
            .join(",")
    }

    /// Whether they change the specimen itself (the layer and the frequency are specimen
    /// parameters: study.py's SPECIMEN_PARAMS), so the study's committed specimens do not serve.
    pub fn change_generation(&self) -> bool {
        self.layer.is_some() || self.freq.is_some()
    }

    /// Folder-name suffix ('' for the study's conditions), e.g. `_piston_d0.2_peak_kpa550`.
    pub fn tag(&self) -> String {
        self.pairs()
            .iter()
            .map(|(k, v)| format!("_{}{}", k, v))
            .collect()
    }

    /// The study's own values (the STUDY_ constants, the piston of SIZES for `size`) written as
    /// None, so that a library built with them given explicitly is the study's.
    pub fn normalised(&self, size: &str) -> TestConditions {
        let d = study_cell(size).map(|c| c.1);
        let off = |v: Option<f64>, default: Option<f64>| v.filter(|x| Some(*x) != default);
        TestConditions {
            piston_d: off(self.piston_d, d),
            seat_kpa: off(self.seat_kpa, Some(STUDY_SEAT_KPA)),
            peak_kpa: off(self.peak_kpa, Some(STUDY_PEAK_KPA)),
            layer: off(self.layer, Some(STUDY_LAYER)),
            freq: off(self.freq, Some(STUDY_FREQ)),
        }
    }

    /// Refuse values study.py cannot load, or a plate the periodic cell of `size` cannot hold
    /// (before any run starts).
    pub fn check(&self, size: &str) -> Result<()> {
        // study.py: the cell is nx rib lengths wide (rib 0.06 m; SIZES' nx), its default plate half
        // of that (D/Lx = 0.5): a wider plate meets its own periodic image's influence zone
        if let (Some(d), Some((lx, _))) = (self.piston_d, study_cell(size)) {
            if d > 0.5 * lx {
                let fits: Vec<&str> = crate::harness::study::SIZES
                    .into_iter()
                    .filter(|s| study_cell(s).is_some_and(|(w, _)| d <= 0.5 * w))
                    .collect();
                bail!(
                    "--plate-d {} needs a cell at least {} m wide (2 plate diameters); --size {}'s cell is {} m{}",
                    d,
                    2.0 * d,
                    size,
                    lx,
                    if fits.is_empty() {
                        ": no study size holds it".to_string()
                    } else {
                        format!(": use --size {}", fits.join(" or "))
                    }
                );
            }
        }
        for (k, v) in self.pairs() {
            if !(v.is_finite() && v > 0.0) {
                bail!("{} {}: must be a positive number", Self::flag(k), v);
            }
        }
        let (seat, peak) = (
            self.seat_kpa.unwrap_or(STUDY_SEAT_KPA),
            self.peak_kpa.unwrap_or(STUDY_PEAK_KPA),
        );
        if peak <= seat {
            bail!(
                "the peak pressure ({} kPa) must exceed the seating pressure ({} kPa)",
                peak,
                seat
            );
        }
        Ok(())
    }
}

/// One table line.
#[derive(Clone, Debug)]
struct Line {
    description: String,
    seed: u32,
    specimen: String,
    /// Where a generating run also writes its specimen ('' = nowhere).
    export: String,
    /// Stop after generation (and the export).
    generate_only: bool,
    effects: String,
    out: PathBuf,
}

/// What runs a table: Debian YADE, or ryade on its YADE-order or fast path.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum RunEngine {
    Yade,
    Ryade,
    RyadeFast,
}

/// Run, as one yade-batch table `path`, the lines whose run has no history.csv yet (a sweep resumes
/// where it stopped): with `compat batch` (ryade), or with Debian YADE as the command (`yade`).
fn run_missing(
    root: &Path,
    path: &Path,
    sc: &Scenario,
    lines: &[Line],
    jobs: usize,
    engine: RunEngine,
) -> Result<()> {
    let todo: Vec<&Line> = lines
        .iter()
        .filter(|l| {
            if l.generate_only {
                !Path::new(&l.export).is_file()
            } else {
                !l.out.join("history.csv").is_file()
            }
        })
        .collect();
    if todo.is_empty() {
        return Ok(());
    }
    let mut f =
        std::fs::File::create(path).with_context(|| format!("writing {}", path.display()))?;
    writeln!(
        f,
        "description ratio case size seed cycles specimen export generate_only effects controller out"
    )?;
    // the fast path takes the cycles only with the piston law in Rust (byte-identical to the
    // PyRunner's, which YADE runs)
    let controller = if engine == RunEngine::RyadeFast {
        "native"
    } else {
        ""
    };
    // the test's conditions go to study.py with the effects, as its options
    let test = sc.test.knobs();
    for l in &todo {
        let knobs = [test.as_str(), l.effects.as_str()]
            .iter()
            .filter(|k| !k.is_empty())
            .copied()
            .collect::<Vec<_>>()
            .join(",");
        writeln!(
            f,
            "{} {} '{}' '{}' {} {} '{}' '{}' {} '{}' '{}' '{}'",
            l.description,
            sc.ratio as f64 / 10.0,
            sc.case,
            sc.size,
            l.seed,
            sc.cycles,
            l.specimen,
            l.export,
            l.generate_only as u8,
            knobs,
            controller,
            l.out.display()
        )?;
    }
    drop(f);
    eprintln!(
        "[gap] {} runs to do in {} ({})",
        todo.len(),
        match engine {
            RunEngine::Yade => "Debian YADE",
            RunEngine::Ryade => "ryade (YADE-order path)",
            RunEngine::RyadeFast => "ryade (fast path)",
        },
        path.display()
    );
    let mut c = Command::new(crate::harness::env::python());
    c.args(["-m", "yade.batch"])
        .arg(path)
        .arg(root.join("yade_ref/gap/run_case.py"))
        .args(["-j", &jobs.to_string()]);
    match engine {
        RunEngine::Yade => {
            c.args(["--command", "yade -n -x"]);
        }
        RunEngine::RyadeFast => {
            c.env("RYADE_FAST", "on");
        }
        RunEngine::Ryade => {
            c.env_remove("RYADE_FAST");
        }
    }
    let st = crate::harness::proc::status(&mut c).context("starting python3 -m yade.batch")?;
    if crate::harness::proc::stopping() {
        bail!("stopped: the finished runs of {} are kept", path.display());
    }
    if !st.success() {
        eprintln!(
            "warning: some jobs of {} failed (see its .logs/summary.csv); finished runs are kept",
            path.display()
        );
    }
    Ok(())
}

#[derive(Serialize, Deserialize)]
pub struct LibraryIndex {
    pub scenario: String,
    pub case: char,
    pub size: String,
    pub cycles: u32,
    pub baseline_seeds: Vec<u32>,
    pub effect_seeds: Vec<u32>,
    pub effects: Vec<Effect>,
    /// ryade's engine of the runs: "fast" or "yade-order" (a library from before the choice:
    /// yade-order).
    #[serde(default = "yade_order")]
    pub engine: String,
    /// The seed counts chosen from the measured noise (absent when the counts were given).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed_choice: Option<gap::SeedChoice>,
    /// The test's conditions where they are not the study's (absent: the study's).
    #[serde(default)]
    pub test: TestConditions,
}

impl LibraryIndex {
    /// A diagnosis given test conditions: they must be the library's.
    pub fn check_test(&self, t: &TestConditions) -> Result<()> {
        if *t != self.test {
            let show = |t: &TestConditions| {
                let v = t.flags();
                if v.is_empty() {
                    "the study's".to_string()
                } else {
                    v.join(" ")
                }
            };
            bail!(
                "the library was built for the test conditions `{}`, not `{}`: diagnose with a library of your test's conditions (build it with --make-library and them)",
                show(&self.test),
                show(t)
            );
        }
        Ok(())
    }

    /// The library's runs are of scenario `sc` (its study case, cycles and test conditions), or
    /// which of them differs and what to give instead.
    pub fn check_scenario(&self, sc: &Scenario) -> Result<()> {
        let here = |ratio: &str, case: char, size: &str, cycles: u32, t: &TestConditions| {
            let mut v = vec![
                format!("--scenario {}", ratio),
                format!("--case {}", case),
                format!("--size {}", size),
                format!("--cycles {}", cycles),
            ];
            v.extend(t.flags());
            v
        };
        let lib = here(
            &self.scenario,
            self.case,
            &self.size,
            self.cycles,
            &self.test,
        );
        let asked = here(
            &format!("r{:02}", sc.ratio),
            sc.case,
            &sc.size,
            sc.cycles,
            &sc.test,
        );
        if lib != asked {
            bail!(
                "the library was built for `{}`, not `{}`: give its options (or use another --library folder)",
                lib.join(" "),
                asked.join(" ")
            );
        }
        Ok(())
    }
}

fn yade_order() -> String {
    "yade-order".into()
}

/// Seed counts of a library build: given, or (None) chosen from the measured noise.
#[derive(Clone, Copy, Debug, Default)]
pub struct SeedCounts {
    pub baseline: Option<u32>,
    pub effect: Option<u32>,
}

/// Effect seeds of the pilot from which the noise is measured (2 degrees of freedom per paired
/// group: 30+ over the catalogue's paired groups).
pub const PILOT_EFFECT_SEEDS: u32 = 3;
/// Most effect seeds the noise may ask for (a scenario whose runs decorrelate completely asks
/// for 2 / `gap::SHIFT_VAR` = 20; beyond this cap the surrogate carries the larger shift variance).
pub const MAX_AUTO_SEEDS: u32 = 40;

/// Build (or complete) a library (`run_library`). Seed counts not given are chosen from the
/// measured noise (issue 20): a pilot runs the baseline (at least 1 / `gap::SHIFT_VAR` seeds) and
/// every effect at `PILOT_EFFECT_SEEDS` seeds (or the seeds an existing library already has);
/// `gap::seeds_needed` reads the scatter of the paired differences on the fitted cycles and the
/// library is completed to the counts it asks for (at most `MAX_AUTO_SEEDS`).
#[allow(clippy::too_many_arguments)]
pub fn make_library(
    root: &Path,
    dir: &Path,
    sc: &Scenario,
    seeds: SeedCounts,
    fit_cycles: usize,
    fast: bool,
    jobs: usize,
) -> Result<()> {
    let old: Option<LibraryIndex> = std::fs::read_to_string(dir.join("library.json"))
        .ok()
        .and_then(|t| serde_json::from_str(&t).ok());
    let had = |f: fn(&LibraryIndex) -> usize| old.as_ref().map_or(0, f) as u32;
    let min_base = (1.0 / gap::SHIFT_VAR).round() as u32;
    let range = |n: u32| (1..=n).collect::<Vec<u32>>();
    let e0 = seeds
        .effect
        .unwrap_or_else(|| PILOT_EFFECT_SEEDS.max(had(|i| i.effect_seeds.len())));
    let b0 = seeds
        .baseline
        .unwrap_or_else(|| min_base.max(had(|i| i.baseline_seeds.len())).max(e0));
    // a library is completed, never cut: explicit counts under its own would drop runs
    for (given, have, what) in [
        (seeds.baseline, had(|i| i.baseline_seeds.len()), "baseline"),
        (seeds.effect, had(|i| i.effect_seeds.len()), "effect"),
    ] {
        if let Some(g) = given.filter(|g| *g < have) {
            bail!(
                "the library in {} has {} {} seeds: give --{}-seeds {} or more, or leave it out (--{}-seeds {} would leave runs out of it)",
                dir.display(),
                have,
                what,
                what,
                have,
                what,
                g
            );
        }
    }
    if seeds.effect.is_some() {
        // counts given: no choice from the noise to record
        return run_library(root, dir, sc, &range(b0), &range(e0), None, fast, jobs);
    }
    eprintln!(
        "[gap] pilot: {} baseline seeds, {} effect seeds (the noise they measure sets the counts)",
        b0, e0
    );
    run_library(root, dir, sc, &range(b0), &range(e0), None, fast, jobs)?;
    let (_, lib) = load_library(dir)?;
    let Some(choice) = gap::seeds_needed(&lib, fit_cycles) else {
        bail!(
            "{}: the pilot left no paired effect runs of 2+ seeds to measure the noise from (see the runs' logs)",
            dir.display()
        );
    };
    let e1 = (choice.effect as u32).clamp(e0, MAX_AUTO_SEEDS.max(e0));
    let b1 = match seeds.baseline {
        Some(b) => b.max(e1),
        None => b0.max(choice.baseline as u32).max(e1),
    };
    eprintln!("[gap] {}", format_seed_choice(&choice, fit_cycles));
    if (choice.effect as u32) > MAX_AUTO_SEEDS {
        eprintln!(
            "[gap] warning: capped at {} effect seeds: the fits carry the larger variance of the library's shifts",
            MAX_AUTO_SEEDS
        );
    }
    if seeds.baseline.is_some_and(|b| b < e1) {
        eprintln!(
            "[gap] {} baseline seeds: every effect seed needs its baseline run",
            b1
        );
    }
    run_library(
        root,
        dir,
        sc,
        &range(b1),
        &range(e1),
        Some(choice),
        fast,
        jobs,
    )
}

/// One line on the seed counts a library's noise asks for.
pub fn format_seed_choice(c: &gap::SeedChoice, fit_cycles: usize) -> String {
    format!(
        "the paired differences (effect run - baseline run of the same specimen) scatter {:.2} times one run's noise \
         (RMS over the observables and cycles 1-{}; largest {:.2}, {} at cycle {}; {:.0}+ degrees of freedom): \
         {} effect seeds keep the variance of the library's shifts under {:.0} % of the noise's, {} baseline seeds that of its mean",
        c.mean_ratio2.sqrt(),
        fit_cycles,
        c.worst.2,
        c.worst.0,
        c.worst.1,
        c.dof,
        c.effect,
        100.0 * gap::SHIFT_VAR,
        c.baseline
    )
}

/// Build (or complete) a library: baseline seeds + each effect at its strengths for `effect_seeds`
/// (a subset of the baseline seeds). Phase 1 runs the baseline: a committed
/// `golden/study/<scenario>_<case>_<size>_s<seed>/specimen.json` is imported, else the run generates
/// its specimen and exports it to `base_s<seed>/specimen.json`. Phase 2 runs every loading effect on
/// the baseline specimen of the same seed (common random numbers: the effect's run differs from its
/// baseline run by the effect alone, which the paired surrogate of `gap::Library` uses); an effect
/// that changes the generation (grading) generates its own specimen.
#[allow(clippy::too_many_arguments)]
fn run_library(
    root: &Path,
    dir: &Path,
    sc: &Scenario,
    baseline_seeds: &[u32],
    effect_seeds: &[u32],
    seed_choice: Option<gap::SeedChoice>,
    fast: bool,
    jobs: usize,
) -> Result<()> {
    std::fs::create_dir_all(dir)?;
    let dir = dir.canonicalize()?;
    let engine = if fast { "fast" } else { "yade-order" };
    // a library is completed on the engine it was started with
    if let Ok(old) = std::fs::read_to_string(dir.join("library.json")) {
        let old: LibraryIndex = serde_json::from_str(&old)
            .with_context(|| format!("reading {}", dir.join("library.json").display()))?;
        if old.engine != engine {
            bail!(
                "the library in {} was built on ryade's {} engine: complete it with --engine {} (or build a new one in another --library folder)",
                dir.display(),
                old.engine,
                old.engine
            );
        }
        old.check_scenario(sc)
            .with_context(|| format!("completing the library in {}", dir.display()))?;
    }
    if let Some(s) = effect_seeds.iter().find(|s| !baseline_seeds.contains(s)) {
        bail!(
            "effect seed {} is not a baseline seed (effect runs reuse the baseline specimens): give --baseline-seeds {} or more",
            s,
            effect_seeds.iter().max().copied().unwrap_or(0)
        );
    }
    // a checkout's committed YADE specimen saves the generation (without a checkout it is made)
    let checkout = crate::harness::env::checkout_root();
    let golden = |s: u32| {
        if sc.test.change_generation() {
            return None;
        }
        let p = checkout.as_ref()?.join(format!(
            "golden/study/r{:02}_{}_{}_s{}/specimen.json",
            sc.ratio, sc.case, sc.size, s
        ));
        p.is_file().then(|| p.display().to_string())
    };
    let base_spec = |s: u32| {
        golden(s).unwrap_or_else(|| {
            dir.join(format!("base_s{}", s))
                .join("specimen.json")
                .display()
                .to_string()
        })
    };
    let mut base_lines = Vec::new();
    for &s in baseline_seeds {
        let g = golden(s);
        base_lines.push(Line {
            description: format!("base_s{}", s),
            seed: s,
            specimen: g.clone().unwrap_or_default(),
            export: if g.is_some() {
                String::new()
            } else {
                base_spec(s)
            },
            generate_only: false,
            effects: String::new(),
            out: dir.join(format!("base_s{}", s)),
        });
    }
    let effects = catalogue();
    let mut lines = Vec::new();
    for e in &effects {
        for (k, st) in e.strengths.iter().enumerate() {
            for &s in effect_seeds {
                lines.push(Line {
                    description: format!("{}_{}_s{}", e.knob, k, s),
                    seed: s,
                    specimen: if generates(&e.knob) {
                        String::new()
                    } else {
                        base_spec(s)
                    },
                    export: String::new(),
                    generate_only: false,
                    effects: knobs(&[(e.knob.clone(), *st)])?,
                    out: dir.join(format!("{}_{}_s{}", e.knob, k, s)),
                });
            }
        }
    }
    let idx = LibraryIndex {
        scenario: format!("r{:02}", sc.ratio),
        case: sc.case,
        size: sc.size.clone(),
        cycles: sc.cycles,
        baseline_seeds: baseline_seeds.to_vec(),
        effect_seeds: effect_seeds.to_vec(),
        effects,
        engine: engine.into(),
        seed_choice,
        test: sc.test.clone(),
    };
    let run_engine = if fast {
        RunEngine::RyadeFast
    } else {
        RunEngine::Ryade
    };
    std::fs::write(
        dir.join("library.json"),
        serde_json::to_string_pretty(&idx)?,
    )?;
    run_missing(
        root,
        &dir.join("library_base.table"),
        sc,
        &base_lines,
        jobs,
        run_engine,
    )?;
    run_missing(
        root,
        &dir.join("library.table"),
        sc,
        &lines,
        jobs,
        run_engine,
    )
}

/// Load a library directory (library.json + run directories with history.csv).
pub fn load_library(dir: &Path) -> Result<(LibraryIndex, Library)> {
    let idx: LibraryIndex = serde_json::from_str(
        &std::fs::read_to_string(dir.join("library.json")).with_context(|| {
            format!(
                "{}: no library.json (build it with compat gap --make-library)",
                dir.display()
            )
        })?,
    )?;
    let mut lib = Library {
        effects: idx.effects.clone(),
        unpaired: idx
            .effects
            .iter()
            .filter(|e| generates(&e.knob))
            .map(|e| e.knob.clone())
            .collect(),
        ..Default::default()
    };
    for s in &idx.baseline_seeds {
        let p = dir.join(format!("base_s{}", s)).join("history.csv");
        match gap::series_of_history(&p) {
            Ok(x) => {
                lib.baseline.push(x);
                lib.baseline_seeds.push(*s);
            }
            Err(e) => eprintln!("warning: library run missing: {:#}", e),
        }
    }
    for e in &idx.effects {
        for k in 0..e.strengths.len() {
            let mut v: Vec<Series> = Vec::new();
            let mut seeds = Vec::new();
            for s in &idx.effect_seeds {
                let p = dir
                    .join(format!("{}_{}_s{}", e.knob, k, s))
                    .join("history.csv");
                match gap::series_of_history(&p) {
                    Ok(x) => {
                        v.push(x);
                        seeds.push(*s);
                    }
                    Err(err) => eprintln!("warning: library run missing: {:#}", err),
                }
            }
            if !v.is_empty() {
                lib.runs.insert((e.knob.clone(), k), v);
                lib.run_seeds.insert((e.knob.clone(), k), seeds);
            }
        }
    }
    if lib.baseline.len() < 2 {
        bail!("{}: fewer than 2 baseline runs finished", dir.display());
    }
    Ok((idx, lib))
}

#[derive(Serialize, Deserialize, Clone)]
pub struct Truth {
    pub seed: u32,
    /// Hidden effects and strengths (empty: today's model itself, the answer must be "none").
    pub effects: Vec<(String, f64)>,
}

/// Signal of effects (knob, strength) on cycles `cycles` for an observation with the observables of
/// `like`, in noise units after the noise inflation of `fit_cycles`.
pub fn signal(
    lib: &Library,
    effects: &[(String, f64)],
    like: &Series,
    cycles: std::ops::RangeInclusive<usize>,
    fit_cycles: usize,
) -> f64 {
    let sur = gap::Surrogate::new(lib);
    let eff: Vec<(usize, f64)> = effects
        .iter()
        .filter_map(|(k, s)| Some((lib.effects.iter().position(|e| &e.knob == k)?, *s)))
        .collect();
    sur.signal(&eff, like, cycles) / gap::noise_inflation(lib, fit_cycles).sqrt()
}

/// Blind datasets made by Debian YADE on specimens of seeds the library does not use (set seed x 100
/// + case number), with the truth written apart. Design (fixed from the library alone, before any dataset is made):
/// * `n_null` cases (positions drawn at random) are today's model itself: the answer must be "none";
/// * every other case has a first hidden effect drawn uniformly among the effects that can reach
///   the detectability floor in this scenario, at a strength drawn uniformly from the strengths
///   where the library predicts a signal >= the floor ("a gap diagnosis presumes there is a gap");
/// * with probability 0.3 a second effect, any other candidate, at 40-100 % of its library extreme
///   on a random side (it may be undetectable, and it may even dominate).
///
/// Each case's specimen is generated first (`generate.table`: generation effects only, i.e. grading,
/// `--generate-only --export-specimen`), then imported and loaded with the loading effects
/// (`observed.table`), as in the library: `--damping` acts in every phase of study.py, and a
/// generation at low damping is a different specimen population (one at 0.06 never finished).
/// All draws come from MT19937(`seed`). `DIR/design.json` records the floor and the ranges.
#[allow(clippy::too_many_arguments)]
pub fn make_observed(
    root: &Path,
    dir: &Path,
    sc: &Scenario,
    n: usize,
    n_null: usize,
    seed: u32,
    jobs: usize,
    lib: &Library,
    fit_cycles: usize,
    design: Design,
) -> Result<()> {
    use rand_mt::Mt19937GenRand32 as Mt;
    if n_null + design.n_clump > n {
        bail!(
            "--n-null {} plus --n-clump {} is more than --n {}",
            n_null,
            design.n_clump,
            n
        );
    }
    std::fs::create_dir_all(dir.join("runs"))?;
    std::fs::create_dir_all(dir.join("truth"))?;
    std::fs::create_dir_all(dir.join("cases"))?;
    let dir = dir.canonicalize()?;
    let ranges = detectable_ranges(lib, fit_cycles, DETECTABILITY_FLOOR);
    let drawable: Vec<&DetectableRange> =
        ranges.iter().filter(|r| !r.intervals.is_empty()).collect();
    if drawable.is_empty() && !design.unfiltered {
        bail!(
            "no candidate effect reaches the detectability floor {} in this scenario (largest signals: {})",
            DETECTABILITY_FLOOR,
            ranges
                .iter()
                .map(|r| format!("{} {:.1}", r.knob, r.max_signal))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    std::fs::write(
        dir.join("design.json"),
        serde_json::to_string_pretty(&serde_json::json!({
            "seed": seed,
            "n": n,
            "n_null": n_null,
            "fit_cycles": fit_cycles,
            "detectability_floor": DETECTABILITY_FLOOR,
            "ranges": ranges,
            "unfiltered": design.unfiltered,
            "n_clump": design.n_clump,
        }))?,
    )?;
    let sur = gap::Surrogate::new(lib);
    let mut rng = Mt::new(seed);
    let mut u = move || rng.next_u32() as f64 / 4294967296.0;
    // null positions: a partial Fisher-Yates shuffle
    let mut pos: Vec<usize> = (0..n).collect();
    for i in 0..n_null {
        let j = i + ((u() * (n - i) as f64) as usize).min(n - i - 1);
        pos.swap(i, j);
    }
    let nulls: Vec<usize> = pos[..n_null].to_vec();
    let clumps: Vec<usize> = pos[n_null..n_null + design.n_clump].to_vec();
    let cat = &lib.effects;
    let mut gen_lines = Vec::new();
    let mut lines = Vec::new();
    for i in 0..n {
        let name = format!("case{:02}", i + 1);
        let mut chosen: Vec<(String, f64)> = Vec::new();
        if clumps.contains(&i) {
            chosen.push(("clump".into(), (2 + ((u() * 3.0) as u32).min(2)) as f64));
        } else if design.unfiltered && !nulls.contains(&i) {
            // any effect, any strength of its library range; a second one three times in ten
            let first = ((u() * cat.len() as f64) as usize).min(cat.len() - 1);
            chosen.push((
                cat[first].knob.clone(),
                draw_over_range(&sur, first, &mut u),
            ));
            if u() < 0.3 {
                let mut second = ((u() * (cat.len() - 1) as f64) as usize).min(cat.len() - 2);
                if second >= first {
                    second += 1;
                }
                chosen.push((
                    cat[second].knob.clone(),
                    draw_over_range(&sur, second, &mut u),
                ));
            }
        } else if !nulls.contains(&i) {
            let r = drawable[((u() * drawable.len() as f64) as usize).min(drawable.len() - 1)];
            let total: f64 = r.intervals.iter().map(|(a, b)| (b - a).abs()).sum();
            let mut x = u() * total;
            let mut s = r.intervals[0].0;
            for (a, b) in &r.intervals {
                let w = (b - a).abs();
                if x <= w {
                    s = a + (b - a).signum() * x;
                    break;
                }
                x -= w;
            }
            chosen.push((r.knob.clone(), (s * 1e4).round() / 1e4));
            if u() < 0.3 {
                loop {
                    let e = &cat[((u() * cat.len() as f64) as usize).min(cat.len() - 1)];
                    if e.knob == r.knob {
                        continue;
                    }
                    let hi = e.strengths.iter().cloned().fold(0.0, f64::max);
                    let lo = e.strengths.iter().cloned().fold(0.0, f64::min);
                    let side = if lo < 0.0 && (hi <= 0.0 || u() < 0.5) {
                        lo
                    } else {
                        hi
                    };
                    let s = side * (0.4 + 0.6 * u());
                    chosen.push((e.knob.clone(), (s * 1e4).round() / 1e4));
                    break;
                }
            }
        }
        // a fresh specimen per case and per set (set seed x 100 + case): no two blind sets share
        // a specimen, and none is a library seed
        let spec_seed = seed
            .checked_mul(100)
            .and_then(|x| x.checked_add(i as u32 + 1))
            .filter(|_| n < 100)
            .with_context(|| format!("--seed {} with --n {}: specimen seeds overflow", seed, n))?;
        std::fs::write(
            dir.join("truth").join(format!("{}.json", name)),
            serde_json::to_string_pretty(&Truth {
                seed: spec_seed,
                effects: chosen.clone(),
            })?,
        )?;
        // as in the library: the specimen is generated with the generation effects only (grading),
        // then loaded with the loading effects (damping, for one, acts in every phase of study.py)
        let spec = dir
            .join("runs")
            .join(format!("{}_gen", name))
            .join("specimen.json");
        let gen: Vec<(String, f64)> = chosen
            .iter()
            .filter(|(k, _)| generates(k))
            .cloned()
            .collect();
        let load: Vec<(String, f64)> = chosen
            .iter()
            .filter(|(k, _)| !generates(k))
            .cloned()
            .collect();
        gen_lines.push(Line {
            description: format!("{}_gen", name),
            seed: spec_seed,
            specimen: String::new(),
            export: spec.display().to_string(),
            generate_only: true,
            effects: knobs(&gen)?,
            out: dir.join("runs").join(format!("{}_gen", name)),
        });
        lines.push(Line {
            description: name.clone(),
            seed: spec_seed,
            specimen: spec.display().to_string(),
            export: String::new(),
            generate_only: false,
            effects: knobs(&load)?,
            out: dir.join("runs").join(&name),
        });
    }
    run_missing(
        root,
        &dir.join("generate.table"),
        sc,
        &gen_lines,
        jobs,
        RunEngine::Yade,
    )?;
    run_missing(
        root,
        &dir.join("observed.table"),
        sc,
        &lines,
        jobs,
        RunEngine::Yade,
    )?;
    for l in &lines {
        let h = l.out.join("history.csv");
        let Ok(s) = gap::series_of_history(&h) else {
            eprintln!(
                "warning: {} has no YADE history (see its log)",
                l.description
            );
            continue;
        };
        let cdir = dir.join("cases").join(&l.description);
        std::fs::create_dir_all(&cdir)?;
        let mut f = std::fs::File::create(cdir.join("observed.csv"))?;
        let grid = s.grid_settlement_mm.clone();
        let track = s.tracking_kpa.clone().unwrap_or_default();
        writeln!(
            f,
            "cycle,rut_mm,porosity,rebound_mm{},tracking_kPa",
            if grid.is_some() {
                ",grid_settlement_mm"
            } else {
                ""
            }
        )?;
        for c in 0..s.cycles() {
            write!(
                f,
                "{},{:.17e},{:.17e},{:.17e}",
                c,
                s.rut_mm[c],
                s.porosity.as_ref().unwrap()[c],
                s.rebound_mm.as_ref().unwrap()[c]
            )?;
            if let Some(g) = &grid {
                write!(f, ",{:.17e}", g[c])?;
            }
            // cycle 0 (end of seating) has no load cycle: nan
            match track.get(c) {
                Some(t) if t.is_finite() => writeln!(f, ",{:.17e}", t)?,
                _ => writeln!(f, ",nan")?,
            }
        }
    }
    Ok(())
}

/// The hidden effect with the largest noiseless signal by itself over every cycle (its surrogate
/// at the true strength against today's model, for an observation with the observables of `like`),
/// and its signal on the fitted cycles (noise units, after the inflation); ("none", 0) without one.
fn dominant_signal(lib: &Library, t: &Truth, like: &Series, fit_cycles: usize) -> (String, f64) {
    let last = lib.last_cycle().min(like.cycles().saturating_sub(1));
    t.effects
        .iter()
        .filter(|(k, _)| lib.effects.iter().any(|e| &e.knob == k))
        .map(|(k, s)| {
            let one = [(k.clone(), *s)];
            (
                k.clone(),
                signal(lib, &one, like, 1..=last, fit_cycles),
                signal(lib, &one, like, 1..=fit_cycles, fit_cycles),
            )
        })
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(k, _, f)| (k, f))
        .unwrap_or_else(|| ("none".into(), 0.0))
}

/// What a library can detect: its noise inflation and, per effect, the largest signal over its
/// strengths and the strengths whose signal on the fitted cycles reaches `DETECTABILITY_FLOOR`
/// (a markdown section; printed before any diagnosis and by `compat gap --detectability`).
pub fn format_detectability(lib: &Library, fit_cycles: usize) -> String {
    // the library's seeds against those its noise asks for
    let have = lib.runs.values().map(|v| v.len()).max().unwrap_or(0);
    let seeds = gap::seeds_needed(lib, fit_cycles).map_or(String::new(), |c| {
        format!(
            "Seeds: {} baseline, {} per effect strength; {}{}\n\n",
            lib.baseline.len(),
            have,
            format_seed_choice(&c, fit_cycles),
            // (--make-library chooses on every observable: the hint only for the whole library)
            if (have < c.effect || lib.baseline.len() < c.baseline)
                && observables_of(lib).len() == gap::OBSERVABLES.len()
            {
                " (complete the library with --make-library to reach them)"
            } else {
                ""
            }
        )
    });
    let mut s = format!(
        "## What this library can detect\n\n{}noise inflation {:.2}; detectability floor {} (signal over one run's noise on cycles 1-{}); an effect weaker than its range below is answered \"none\"\n\n| effect | largest signal (at strength) | strengths reaching the floor |\n|---|---|---|\n",
        seeds,
        gap::noise_inflation(lib, fit_cycles),
        DETECTABILITY_FLOOR,
        fit_cycles
    );
    for r in detectable_ranges(lib, fit_cycles, DETECTABILITY_FLOOR) {
        s += &format!(
            "| {} | {:.1} ({}) | {} |\n",
            r.knob,
            r.max_signal,
            r.strength_at_max,
            if r.intervals.is_empty() {
                "none: invisible in this scenario".to_string()
            } else {
                r.intervals
                    .iter()
                    .map(|(a, b)| format!("{:.4} .. {:.4}", a, b))
                    .collect::<Vec<_>>()
                    .join(", ")
            }
        );
    }
    s
}

#[derive(Serialize)]
pub struct CaseScore {
    pub case: String,
    pub truth: Vec<(String, f64)>,
    pub dominant_truth: String,
    /// Signal of the dominant effect on the fitted cycles (noise units).
    pub detectability: f64,
    pub named: String,
    /// The chosen model's effects and strengths.
    pub model: Vec<(String, f64)>,
    pub confidence: f64,
    pub correct: bool,
    pub fitted_strength: Option<f64>,
    pub strength_error: Option<f64>,
    /// Held-out rut RMS reduction.
    pub gap_reduction: f64,
    /// Held-out normalised RMS reduction over every observed observable.
    pub norm_gap_reduction: f64,
    /// The diagnosis warns that the chosen model predicts the held-out rut worse.
    pub rut_warned: bool,
    /// The dominant effect's signal reaches `DETECTABILITY_FLOOR` (false for today's model).
    pub detectable: bool,
    /// A hidden effect outside the library's catalogue (e.g. clumps): scored apart.
    pub outside: Option<String>,
    /// The held-out gap of each observed observable (empty when the answer is "none").
    pub heldout_by_observable: Vec<gap::HeldOut>,
    /// The diagnosis' evidence for its best model (`gap::Diagnosis::evidence`).
    pub evidence: f64,
    /// The held-out gap of each observable with the true effects at their true strengths, as the
    /// library predicts them (`gap::heldout_of`; empty for today's model or an effect outside the
    /// catalogue): what the true model itself gains, the reference for a right identification.
    #[serde(skip)]
    pub oracle: Vec<gap::HeldOut>,
}

impl CaseScore {
    /// The hidden effects as the tables print them ("none (today's model)" for none).
    fn truth_label(&self) -> String {
        if self.truth.is_empty() {
            "none (today's model)".to_string()
        } else {
            gap::format_effects(&self.truth, ", ", None)
        }
    }
}

/// Issue 20's counts of a scored set when an effect is named only from evidence `floor` (the
/// method's own answers at `DETECTABILITY_FLOOR`; catalogue effects only, outside ones apart).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RuleCounts {
    /// Detectable dominant effects named, of `detectable`.
    pub named: usize,
    pub detectable: usize,
    /// Cases named an effect other than their dominant one, of `catalogue`.
    pub wrong: usize,
    pub catalogue: usize,
    /// Cases of today's model named an effect.
    pub false_pos: usize,
}

pub fn rule_counts(s: &[CaseScore], floor: f64) -> RuleCounts {
    let named = |c: &CaseScore| c.named != "none" && c.evidence >= floor;
    let cat: Vec<&CaseScore> = s
        .iter()
        .filter(|c| !c.truth.is_empty() && c.outside.is_none())
        .collect();
    RuleCounts {
        named: cat
            .iter()
            .filter(|c| c.detectable && named(c) && c.named == c.dominant_truth)
            .count(),
        detectable: cat.iter().filter(|c| c.detectable).count(),
        wrong: cat
            .iter()
            .filter(|c| named(c) && c.named != c.dominant_truth)
            .count(),
        catalogue: cat.len(),
        false_pos: s.iter().filter(|c| c.truth.is_empty() && named(c)).count(),
    }
}

/// Issue 20's scoring of one answer: the dominant hidden effect named is right; "none" is right
/// for today's model (`dominant` "none") and for an effect whose signal is under the floor; any
/// other effect is wrong. A case of an effect outside the catalogue is scored apart (never right).
pub fn answer_is_right(named: &str, dominant: &str, detectable: bool, outside: bool) -> bool {
    !outside && (named == dominant || (named == "none" && !detectable))
}

/// Score one diagnosis `d` of observation `obs` against its truth `t` (issue 20's rule, see
/// `answer_is_right`), with the library `lib` the diagnosis used.
fn score_case(
    name: &str,
    lib: &Library,
    obs: &Series,
    d: &gap::Diagnosis,
    t: &Truth,
    fit_cycles: usize,
) -> CaseScore {
    let outside = t
        .effects
        .iter()
        .find(|(k, _)| !lib.effects.iter().any(|e| &e.knob == k))
        .map(|(k, s)| format!("{} {}", k, s));
    let (dom, det) = dominant_signal(lib, t, obs, fit_cycles);
    let detectable = !t.effects.is_empty() && outside.is_none() && det >= DETECTABILITY_FLOOR;
    let correct = answer_is_right(&d.winner, &dom, detectable, outside.is_some());
    let fitted = d.model.iter().find(|c| c.0 == dom).map(|c| c.1);
    let true_s = t.effects.iter().find(|e| e.0 == dom).map(|e| e.1);
    let oracle = if t.effects.is_empty() || outside.is_some() {
        vec![]
    } else {
        gap::heldout_of(lib, obs, fit_cycles, &t.effects)
    };
    CaseScore {
        case: name.to_string(),
        truth: t.effects.clone(),
        dominant_truth: outside.clone().unwrap_or_else(|| dom.clone()),
        detectability: det,
        named: d.winner.clone(),
        model: d.model.clone(),
        confidence: d.confidence,
        correct,
        fitted_strength: if correct { fitted } else { None },
        strength_error: match (fitted, true_s) {
            (Some(f), Some(t)) if correct && t != 0.0 => Some((f - t).abs() / t.abs()),
            _ => None,
        },
        gap_reduction: d.gap_reduction,
        norm_gap_reduction: d.norm_gap_reduction,
        rut_warned: d.warnings.iter().any(|w| w.contains("held-out rut")),
        detectable,
        outside,
        heldout_by_observable: d.heldout_by_observable.clone(),
        evidence: d.evidence,
        oracle,
    }
}

/// Diagnose every case blind, then score against the truth files.
pub fn validate(dir: &Path, lib: &Library, fit_cycles: usize) -> Result<Vec<CaseScore>> {
    let mut names: Vec<String> = std::fs::read_dir(dir.join("cases"))
        .with_context(|| {
            format!(
                "{}/cases: no blind cases (make them with --make-observed)",
                dir.display()
            )
        })?
        .filter_map(|e| e.ok().map(|e| e.file_name().to_string_lossy().to_string()))
        .collect();
    names.sort();
    if names.is_empty() {
        bail!(
            "{}/cases is empty: no blind case to validate (did --make-observed finish?)",
            dir.display()
        );
    }
    // 1. blind: every diagnosis is made and written before any truth file is opened; the library
    // as each observation sees it (its observables), penalties calibrated once per set of them
    let mut pens: Vec<(Vec<bool>, gap::Penalties)> = Vec::new();
    let mut diags = Vec::new();
    for n in &names {
        let obs = gap::read_observed(&dir.join("cases").join(n).join("observed.csv"))?;
        let lib_o = lib.restricted_to(&obs);
        let lib = &lib_o;
        let has: Vec<bool> = gap::OBSERVABLES
            .iter()
            .map(|o| obs.get(o).is_some())
            .collect();
        let pen = match pens.iter().find(|(h, _)| *h == has) {
            Some((_, p)) => p.clone(),
            None => {
                let p = gap::calibrated_penalties(lib, fit_cycles);
                pens.push((has, p.clone()));
                p
            }
        };
        let d = gap::diagnose_with(lib, &obs, fit_cycles, &pen)?;
        std::fs::write(
            dir.join("cases").join(n).join("diagnosis.md"),
            gap::report_markdown(n, &d, lib),
        )?;
        std::fs::write(
            dir.join("cases").join(n).join("diagnosis.json"),
            serde_json::to_string_pretty(&d)?,
        )?;
        diags.push((obs, d, lib_o));
    }
    // 2. scoring
    let mut out = Vec::new();
    for (n, (obs, d, lib_o)) in names.iter().zip(diags) {
        let t: Truth = serde_json::from_str(&std::fs::read_to_string(
            dir.join("truth").join(format!("{}.json", n)),
        )?)?;
        out.push(score_case(n, &lib_o, &obs, &d, &t, fit_cycles));
    }
    Ok(out)
}

/// The library without every run of specimen `seed` (its baseline run and its run of each effect
/// strength), and those runs as cases with their truth: (name, run, truth).
fn leave_seed_out(lib: &Library, seed: u32) -> (Library, Vec<(String, Series, Truth)>) {
    let mut rest = lib.clone();
    let mut cases = Vec::new();
    if let Some(i) = lib.baseline_seeds.iter().position(|s| *s == seed) {
        rest.baseline.remove(i);
        rest.baseline_seeds.remove(i);
        cases.push((
            format!("base_s{}", seed),
            lib.baseline[i].clone(),
            Truth {
                seed,
                effects: vec![],
            },
        ));
    }
    for ((knob, k), seeds) in &lib.run_seeds {
        let Some(i) = seeds.iter().position(|s| *s == seed) else {
            continue;
        };
        let key = (knob.clone(), *k);
        let strength = lib
            .effects
            .iter()
            .find(|e| &e.knob == knob)
            .map_or(f64::NAN, |e| e.strengths[*k]);
        cases.push((
            format!("{}_{}_s{}", knob, k, seed),
            lib.runs[&key][i].clone(),
            Truth {
                seed,
                effects: vec![(knob.clone(), strength)],
            },
        ));
        if let (Some(r), Some(rs)) = (rest.runs.get_mut(&key), rest.run_seeds.get_mut(&key)) {
            r.remove(i);
            rs.remove(i);
        }
    }
    rest.runs.retain(|_, v| !v.is_empty());
    rest.run_seeds.retain(|_, v| !v.is_empty());
    (rest, cases)
}

/// Leave-one-specimen-out self-test of a library (issue 20, "how far, honestly", on hundreds of
/// cases where a blind set has 14): for each seed, the library without every run of that specimen
/// diagnoses each of them (today's model and each effect strength), scored by the blind sets' rule.
/// The cases share the library's engine and specimen generator, so this bounds from above what a
/// blind set of Debian YADE runs can show; it costs no simulation.
pub fn self_test(lib: &Library, fit_cycles: usize, jobs: usize) -> Result<Vec<CaseScore>> {
    if lib.baseline_seeds.len() != lib.baseline.len() || lib.baseline.len() < 4 {
        bail!("the self-test needs a library with 4 or more baseline seeds of known number");
    }
    // every effect run must be known by its seed, and its specimen be a baseline one (so that
    // leaving a seed out leaves every run of that specimen out)
    for (key, runs) in &lib.runs {
        let ok = lib.run_seeds.get(key).is_some_and(|s| {
            s.len() == runs.len() && s.iter().all(|x| lib.baseline_seeds.contains(x))
        }) && lib
            .effects
            .iter()
            .any(|e| e.knob == key.0 && key.1 < e.strengths.len());
        if !ok {
            bail!(
                "the self-test needs every library run paired with a baseline seed: {} strength {} is not",
                key.0,
                key.1
            );
        }
    }
    let seeds = lib.baseline_seeds.clone();
    let next = std::sync::atomic::AtomicUsize::new(0);
    let per_seed = |seed: u32| -> Result<Vec<CaseScore>> {
        let (rest, cases) = leave_seed_out(lib, seed);
        let pen = gap::calibrated_penalties(&rest, fit_cycles);
        cases
            .iter()
            .map(|(name, obs, t)| {
                let d = gap::diagnose_with(&rest, obs, fit_cycles, &pen)?;
                Ok(score_case(name, &rest, obs, &d, t, fit_cycles))
            })
            .collect()
    };
    let results: Vec<Result<Vec<CaseScore>>> = std::thread::scope(|sc| {
        let workers: Vec<_> = (0..jobs.clamp(1, seeds.len()))
            .map(|_| {
                sc.spawn(|| {
                    let mut mine = Vec::new();
                    loop {
                        let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                        let Some(&s) = seeds.get(i) else { break };
                        eprintln!("[gap self-test] specimen {} ({}/{})", s, i + 1, seeds.len());
                        mine.push((i, per_seed(s)));
                    }
                    mine
                })
            })
            .collect();
        let mut all: Vec<(usize, Result<Vec<CaseScore>>)> = workers
            .into_iter()
            .flat_map(|w| w.join().expect("a self-test worker panicked"))
            .collect();
        all.sort_by_key(|(i, _)| *i);
        all.into_iter().map(|(_, r)| r).collect()
    });
    let mut out = Vec::new();
    for r in results {
        out.extend(r?);
    }
    Ok(out)
}

/// One answer of a library's self-test, as a library keeps it: the run's group ("none" for today's
/// model, else "knob strength"), its dominant effect, whether that reaches the floor, and the answer.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct SelfTestAnswer {
    pub group: String,
    pub dominant: String,
    pub detectable: bool,
    pub named: String,
    /// The held-out gap reduction per observable with the diagnosed model (empty for "none").
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub heldout: Vec<(String, f64)>,
    /// The same with the true effect at its true strength (`CaseScore::oracle`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub oracle: Vec<(String, f64)>,
}

/// The self-test a library keeps next to its library.json (`compat gap --self-test` writes it), so
/// that every later diagnosis can say how often its answer was right on the library's own runs.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct StoredSelfTest {
    /// Library runs when it was made (a library completed since then needs a new one).
    pub runs: usize,
    pub fit_cycles: usize,
    /// The observables it was made with.
    pub observables: Vec<String>,
    pub answers: Vec<SelfTestAnswer>,
}

pub const SELF_TEST_FILE: &str = "self_test.json";

/// The self-tests kept with the library in `dir` (one per observables and fit cycles; none when the
/// file is missing).
pub fn read_self_tests(dir: &Path) -> Result<Vec<StoredSelfTest>> {
    let p = dir.join(SELF_TEST_FILE);
    match std::fs::read_to_string(&p) {
        Ok(t) => serde_json::from_str(&t).with_context(|| format!("{} is unreadable", p.display())),
        Err(_) => Ok(Vec::new()),
    }
}

/// Keep `st` with the library in `dir`, replacing a kept one of the same observables and fit cycles.
pub fn keep_self_test(dir: &Path, st: StoredSelfTest) -> Result<()> {
    let mut v = read_self_tests(dir).unwrap_or_default();
    v.retain(|t| !(t.observables == st.observables && t.fit_cycles == st.fit_cycles));
    v.push(st);
    std::fs::write(dir.join(SELF_TEST_FILE), serde_json::to_string(&v)?)
        .with_context(|| format!("writing {}", dir.join(SELF_TEST_FILE).display()))
}

fn library_runs(lib: &Library) -> usize {
    lib.baseline.len() + lib.runs.values().map(|v| v.len()).sum::<usize>()
}

fn observables_of(lib: &Library) -> Vec<String> {
    gap::OBSERVABLES
        .iter()
        .filter(|o| lib.baseline.iter().all(|s| s.get(o).is_some()))
        .map(|o| o.to_string())
        .collect()
}

impl StoredSelfTest {
    pub fn new(lib: &Library, fit_cycles: usize, scores: &[CaseScore]) -> StoredSelfTest {
        StoredSelfTest {
            runs: library_runs(lib),
            fit_cycles,
            observables: observables_of(lib),
            answers: scores
                .iter()
                .map(|c| SelfTestAnswer {
                    group: if c.truth.is_empty() {
                        "none".into()
                    } else {
                        gap::format_effects(&c.truth, ", ", None)
                    },
                    dominant: c.dominant_truth.clone(),
                    detectable: c.detectable,
                    named: c.named.clone(),
                    heldout: c
                        .heldout_by_observable
                        .iter()
                        .map(|h| (h.observable.clone(), h.reduction))
                        .collect(),
                    oracle: c
                        .oracle
                        .iter()
                        .map(|h| (h.observable.clone(), h.reduction))
                        .collect(),
                })
                .collect(),
        }
    }
}

/// How often the answer `winner` was right in the library's own self-test (the library folder's
/// `SELF_TEST_FILE`), for a diagnosis made with `lib` (restricted to the observation's observables)
/// on `fit_cycles`: a markdown section for the report.
pub fn format_reliability(dir: &Path, lib: &Library, fit_cycles: usize, winner: &str) -> String {
    let mut s = String::from("## How often this answer is right (the library's self-test)\n\n");
    let how = format!(
        "`compat gap --self-test --library {}` (every library run diagnosed by the library without its specimen; seconds)",
        dir.display()
    );
    let kept = match read_self_tests(dir) {
        Ok(v) if v.is_empty() => {
            return s + &format!("No self-test kept with this library: {} adds it.\n", how)
        }
        Ok(v) => v,
        Err(e) => return s + &format!("{:#}: {} remakes it.\n", e, how),
    };
    let obs = observables_of(lib);
    let Some(st) = kept.iter().find(|t| {
        t.runs == library_runs(lib) && t.fit_cycles == fit_cycles && t.observables == obs
    }) else {
        return s + &format!(
            "No kept self-test matches this diagnosis ({} runs, fit cycles 1-{}, observables {}): {}, given your observed file with `--observed` (for its observables), makes one.\n",
            library_runs(lib),
            fit_cycles,
            obs.join(", "),
            how
        );
    };
    let count = |v: Vec<&SelfTestAnswer>| -> String {
        let mut m: BTreeMap<&str, usize> = BTreeMap::new();
        for a in v {
            *m.entry(a.group.as_str()).or_default() += 1;
        }
        let mut l: Vec<(&str, usize)> = m.into_iter().collect();
        l.sort_by_key(|x| std::cmp::Reverse(x.1));
        l.iter()
            .map(|(g, n)| format!("{} ({})", g, n))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let same: Vec<&SelfTestAnswer> = st.answers.iter().filter(|a| a.named == winner).collect();
    let nulls = st.answers.iter().filter(|a| a.dominant == "none").count();
    if winner == "none" {
        let missed: Vec<&SelfTestAnswer> = same.iter().copied().filter(|a| a.detectable).collect();
        s += &format!(
            "The self-test answered \"none\" for {} of the library's {} runs: {} of today's model (of {}), {} of effects under the detectability floor, and {} of effects above it (missed{}).\n",
            same.len(),
            st.answers.len(),
            same.iter().filter(|a| a.dominant == "none").count(),
            nulls,
            same.iter().filter(|a| a.dominant != "none" && !a.detectable).count(),
            missed.len(),
            if missed.is_empty() {
                String::new()
            } else {
                format!(": {}", count(missed.clone()))
            }
        );
    } else {
        let right = same.iter().filter(|a| a.dominant == winner).count();
        let other: Vec<&SelfTestAnswer> = same
            .iter()
            .copied()
            .filter(|a| a.dominant != winner)
            .collect();
        s += &format!(
            "The self-test named **{}** for {} of the library's {} runs; {} of them had it as their dominant effect ({}){}.\n",
            winner,
            same.len(),
            st.answers.len(),
            right,
            if same.is_empty() {
                "-".to_string()
            } else {
                format!("{:.0} %", 100.0 * right as f64 / same.len() as f64)
            },
            if other.is_empty() {
                String::new()
            } else {
                format!(
                    "; the others were runs of {}, read as {}",
                    count(other.clone()),
                    winner
                )
            }
        );
        s += &format_expected_heldout(st, winner);
    }
    s
}

/// What a right answer `winner` closes of the held-out gap on the self-test's runs (its runs named
/// right: the diagnosed model, and the oracle, the true effects at their true strengths), median per
/// observable: the yardstick
/// for the report's own held-out reductions, most of whose shortfall on some observables is one
/// run's noise.
fn format_expected_heldout(st: &StoredSelfTest, winner: &str) -> String {
    let right: Vec<&SelfTestAnswer> = st
        .answers
        .iter()
        .filter(|a| a.named == winner && a.dominant == winner)
        .collect();
    let med = |o: &str, oracle: bool| -> Option<f64> {
        median(
            right
                .iter()
                .filter_map(|a| {
                    let v = if oracle { &a.oracle } else { &a.heldout };
                    v.iter().find(|(k, _)| k == o).map(|(_, r)| *r)
                })
                .collect(),
        )
    };
    let line = |oracle: bool| -> Option<String> {
        let parts: Vec<String> = st
            .observables
            .iter()
            .filter_map(|o| med(o, oracle).map(|r| format!("{} {:.0} %", o, 100.0 * r)))
            .collect();
        (!parts.is_empty()).then(|| parts.join(", "))
    };
    match (line(false), line(true)) {
        (Some(m), Some(o)) => format!(
            "\nWhere the self-test named {} right ({} runs), the held-out gap reduction per observable was, median: {}; with the true effects at their true strengths instead of the fitted model: {}. A reduction in this report well under these is a reason to doubt the answer; one near them is what a right answer gives (the rest is one run's noise, which no model removes).\n",
            winner,
            right.len(),
            m,
            o
        ),
        _ => String::new(),
    }
}

/// The self-test by library group (today's model, each effect strength): its signal (median over
/// the specimens) and what was named, then the blind sets' summary.
pub fn format_self_test(s: &[CaseScore]) -> String {
    let mut groups: Vec<(String, Vec<&CaseScore>)> = Vec::new();
    for c in s {
        let g = c.truth_label();
        match groups.iter_mut().find(|(k, _)| *k == g) {
            Some((_, v)) => v.push(c),
            None => groups.push((g, vec![c])),
        }
    }
    let mut t = String::from(
        "| library group | specimens | signal (median) | named right | none | named another (which) |\n|---|---|---|---|---|---|\n",
    );
    for (g, v) in &groups {
        let mut others: BTreeMap<&str, usize> = BTreeMap::new();
        for c in v
            .iter()
            .filter(|c| c.named != "none" && c.named != c.dominant_truth)
        {
            *others.entry(c.named.as_str()).or_default() += 1;
        }
        t += &format!(
            "| {} | {} | {:.1} | {} | {} | {} |\n",
            g,
            v.len(),
            median(v.iter().map(|c| c.detectability).collect()).unwrap_or(0.0),
            v.iter()
                .filter(|c| !c.truth.is_empty() && c.named == c.dominant_truth)
                .count(),
            v.iter().filter(|c| c.named == "none").count(),
            others
                .iter()
                .map(|(k, n)| format!("{} {}", k, n))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    t + &format_floor_sweep(s) + &format_score_summary(s) + &format_oracle(s)
}

/// The held-out gap reductions of observable `o` over `cases`: the diagnosed model's, or the
/// oracle's; `gap_only`: only where today's model misses by more than one run's noise.
pub fn heldout_reductions(cases: &[&CaseScore], o: &str, oracle: bool, gap_only: bool) -> Vec<f64> {
    cases
        .iter()
        .filter_map(|c| {
            let v = if oracle {
                &c.oracle
            } else {
                &c.heldout_by_observable
            };
            v.iter().find(|h| h.observable == o)
        })
        .filter(|h| !gap_only || h.before > 1.0)
        .map(|h| h.reduction)
        .collect()
}

/// The held-out gap reductions of the method's named cases next to those of the oracle (the true
/// effects at their true strengths) on the same cases, and the oracle's on every detectable case:
/// how much of the shortfall from a target is identification and how much is one run's noise,
/// which no model removes.
pub fn format_oracle(s: &[CaseScore]) -> String {
    let pct = |x: Option<f64>| x.map_or("-".to_string(), |v| format!("{:.0} %", 100.0 * v));
    let det: Vec<&CaseScore> = s.iter().filter(|c| c.detectable).collect();
    let named: Vec<&CaseScore> = det.iter().filter(|c| c.correct).copied().collect();
    let med = |cs: &[&CaseScore], o: &str, oracle: bool, gap_only: bool| -> String {
        let r = heldout_reductions(cs, o, oracle, gap_only);
        if gap_only {
            format!("{} ({})", pct(median(r.clone())), r.len())
        } else {
            pct(median(r))
        }
    };
    let mut t = String::from(
        "\nMedian held-out gap reduction per observable: the method against the oracle (the true effects at their true strengths, as the library predicts them: the true model's own reduction, a reference, not a bound: a fitted strength can do a little better by absorbing part of the specimen's own departure)\n\n\
         | cases | rut | porosity | rebound | grid settlement | tracking error |\n|---|---|---|---|---|---|\n"
    );
    let obs = gap::OBSERVABLES;
    let mut row = |label: String, cs: &[&CaseScore], oracle: bool, gap_only: bool| {
        t += &format!(
            "| {} | {} |\n",
            label,
            obs.map(|o| med(cs, o, oracle, gap_only)).join(" | ")
        );
    };
    row(
        format!("method, detectable effects named right ({})", named.len()),
        &named,
        false,
        false,
    );
    row(
        format!("oracle, the same cases ({})", named.len()),
        &named,
        true,
        false,
    );
    row(
        format!("oracle, every detectable case ({})", det.len()),
        &det,
        true,
        false,
    );
    row(
        "oracle, the detectable cases where today's model misses the observable by more than one run's noise (held-out normalised RMS > 1; cases)".to_string(),
        &det,
        true,
        true,
    );
    t
}

/// What the same diagnoses would answer if an effect were named only from a higher evidence
/// (`gap::Diagnosis::evidence`; the method names from `DETECTABILITY_FLOOR`), still scored by issue
/// 20's rule at the floor: the trade between detectable effects named and wrong effects named.
pub fn format_floor_sweep(s: &[CaseScore]) -> String {
    let mut t = String::from(
        "\n| naming from evidence | detectable dominant effects named | wrong effect named | effect named for today's model |\n|---|---|---|---|\n",
    );
    for f in [DETECTABILITY_FLOOR, 5.5, 6.0, 7.0, 8.0] {
        let k = rule_counts(s, f);
        t += &format!(
            "| {:.1}{} | {}/{} ({:.0} %) | {} of {} ({:.1} %) | {} |\n",
            f,
            if f == DETECTABILITY_FLOOR {
                " (the method)"
            } else {
                ""
            },
            k.named,
            k.detectable,
            100.0 * k.named as f64 / k.detectable.max(1) as f64,
            k.wrong,
            k.catalogue,
            100.0 * k.wrong as f64 / k.catalogue.max(1) as f64,
            k.false_pos
        );
    }
    t
}

/// The median (the mean of the two middle values of an even count; None when empty).
pub fn median(mut v: Vec<f64>) -> Option<f64> {
    v.sort_by(|a, b| a.total_cmp(b));
    if v.is_empty() {
        None
    } else if v.len() % 2 == 1 {
        Some(v[v.len() / 2])
    } else {
        Some(0.5 * (v[v.len() / 2 - 1] + v[v.len() / 2]))
    }
}

pub fn format_scores(s: &[CaseScore]) -> String {
    let mut t = String::from("| case | hidden effects (strength) | dominant | detectability (signal / noise, fitted cycles) | named (confidence) | model | fitted strength (rel. error) | held-out rut gap reduction | held-out normalised gap reduction |\n|---|---|---|---|---|---|---|---|---|\n");
    for c in s {
        t += &format!(
            "| {} | {} | {} | {:.1} | {} {} ({:.2}) | {} | {} | {:.0} % | {:.0} % |\n",
            c.case,
            c.truth_label(),
            c.dominant_truth,
            c.detectability,
            if c.correct { "yes:" } else { "NO:" },
            c.named,
            c.confidence,
            if c.model.is_empty() {
                "-".to_string()
            } else {
                gap::format_effects(&c.model, " + ", Some(3))
            },
            match (c.fitted_strength, c.strength_error) {
                (Some(f), Some(e)) => format!("{:.3} ({:.0} %)", f, 100.0 * e),
                _ => "-".into(),
            },
            100.0 * c.gap_reduction,
            100.0 * c.norm_gap_reduction
        );
    }
    t + &format_score_summary(s)
}

/// The summary lines of a scored set (counts, issue 20's rule, held-out reductions).
pub fn format_score_summary(s: &[CaseScore]) -> String {
    let mut t = String::new();
    let pct = |x: Option<f64>| x.map_or("-".to_string(), |v| format!("{:.0} %", 100.0 * v));
    let correct = s.iter().filter(|c| c.correct).count();
    let eff: Vec<&CaseScore> = s.iter().filter(|c| !c.truth.is_empty()).collect();
    let nulls: Vec<&CaseScore> = s.iter().filter(|c| c.truth.is_empty()).collect();
    let none_answers = s.iter().filter(|c| c.named == "none").count();
    let false_pos = nulls.iter().filter(|c| c.named != "none").count();
    let missed = eff.iter().filter(|c| c.named == "none").count();
    let wrong = eff
        .iter()
        .filter(|c| c.named != "none" && !c.correct)
        .count();
    let worse: Vec<&CaseScore> = s
        .iter()
        .filter(|c| c.named != "none" && c.gap_reduction < 0.0)
        .collect();
    // issue 20's scoring: catalogue effects only (outside ones apart)
    let cat: Vec<&CaseScore> = eff
        .iter()
        .filter(|c| c.outside.is_none())
        .copied()
        .collect();
    let undet: Vec<&CaseScore> = cat.iter().filter(|c| !c.detectable).copied().collect();
    let rule = rule_counts(s, DETECTABILITY_FLOOR);
    let per_obs = |o: &str| -> String {
        pct(median(
            cat.iter()
                .filter(|c| c.named != "none")
                .filter_map(|c| {
                    c.heldout_by_observable
                        .iter()
                        .find(|h| h.observable == o)
                        .map(|h| h.reduction)
                })
                .collect(),
        ))
    };
    // the same where there is a gap to close: today's model misses the held-out observable by
    // more than one run's noise (a gap inside the noise cannot be reduced by a right model either)
    let per_obs_gap = |o: &str| -> String {
        let r: Vec<f64> = cat
            .iter()
            .filter(|c| c.named != "none")
            .filter_map(|c| c.heldout_by_observable.iter().find(|h| h.observable == o))
            .filter(|h| h.before > 1.0)
            .map(|h| h.reduction)
            .collect();
        format!("{} ({})", pct(median(r.clone())), r.len())
    };
    t += &format!(
        "\nDominant effect named correctly (\"none\" for today's model): {}/{} ({:.0} %)\n\
         Cases with hidden effects: {}; named correctly: {}; answered none: {}; named a wrong effect: {}\n\
         Cases of today's model: {}; false positives (an effect named): {}\n\
         \"none\" answers in all: {}\n\
         Median relative strength error (correct cases): {}\n\
         Median held-out gap reduction, cases with hidden effects: rut RMS {}, normalised over every observable {}\n\
         (all cases: rut {}, normalised {})\n\
         Named cases whose held-out rut gets worse: {}, of which the report warns: {}\n",
        correct,
        s.len(),
        100.0 * correct as f64 / s.len().max(1) as f64,
        eff.len(),
        eff.iter().filter(|c| c.correct).count(),
        missed,
        wrong,
        nulls.len(),
        false_pos,
        none_answers,
        pct(median(s.iter().filter_map(|c| c.strength_error).collect())),
        pct(median(eff.iter().map(|c| c.gap_reduction).collect())),
        pct(median(eff.iter().map(|c| c.norm_gap_reduction).collect())),
        pct(median(s.iter().map(|c| c.gap_reduction).collect())),
        pct(median(s.iter().map(|c| c.norm_gap_reduction).collect())),
        worse.len(),
        worse.iter().filter(|c| c.rut_warned).count(),
    );
    t += &format!(
        "\nBy issue 20's rule (catalogue effects; \"none\" right only under the floor {}):\n\
         Detectable dominant effects named: {}/{} ({})\n\
         Dominant effects under the floor: {} (answered none {}, named it {}, named another {})\n\
         Wrong effect named: {} of {} cases with catalogue effects\n\
         Median held-out gap reduction per observable, named cases: rut {}, porosity {}, rebound {}, grid settlement {}, tracking error {}\n\
         The same where today's model misses the observable by more than one run's noise (held-out normalised RMS > 1; cases): rut {}, porosity {}, rebound {}, grid settlement {}, tracking error {}\n",
        DETECTABILITY_FLOOR,
        rule.named,
        rule.detectable,
        pct(if rule.detectable == 0 {
            None
        } else {
            Some(rule.named as f64 / rule.detectable as f64)
        }),
        undet.len(),
        undet.iter().filter(|c| c.named == "none").count(),
        undet.iter().filter(|c| c.named == c.dominant_truth).count(),
        undet
            .iter()
            .filter(|c| c.named != "none" && c.named != c.dominant_truth)
            .count(),
        rule.wrong,
        rule.catalogue,
        per_obs("rut_mm"),
        per_obs("porosity"),
        per_obs("rebound_mm"),
        per_obs("grid_settlement_mm"),
        per_obs("tracking_kpa"),
        per_obs_gap("rut_mm"),
        per_obs_gap("porosity"),
        per_obs_gap("rebound_mm"),
        per_obs_gap("grid_settlement_mm"),
        per_obs_gap("tracking_kpa"),
    );
    for c in s.iter().filter(|c| c.outside.is_some()) {
        t += &format!(
            "Outside the catalogue: {} ({}): named {} (confidence {:.2})\n",
            c.case,
            c.outside.as_deref().unwrap_or(""),
            c.named,
            c.confidence
        );
    }
    t
}

/// Per-cycle data for the report figure: observed, today's model (mean and noise), the winner's fit.
pub fn write_plot_data(out: &Path, lib: &Library, obs: &Series, d: &gap::Diagnosis) -> Result<()> {
    let mut f = std::fs::File::create(out.join("plot.csv"))?;
    writeln!(
        f,
        "observable,cycle,observed,model_mean,model_sd,winner,fit_cycles"
    )?;
    let sur = gap::Surrogate::new(lib);
    let model: Vec<(usize, f64)> = d
        .model
        .iter()
        .filter_map(|(k, s)| Some((lib.effects.iter().position(|e| &e.knob == k)?, *s)))
        .collect();
    for (oi, o) in gap::OBSERVABLES.iter().enumerate() {
        let Some(ov) = obs.get(o) else { continue };
        for (c, v) in ov.iter().enumerate().take(d.split.last_cycle + 1) {
            let m = lib.baseline_mean(o, c).unwrap_or(f64::NAN);
            let w = if model.is_empty() {
                f64::NAN
            } else {
                sur.predict(&model, oi, c).unwrap_or(f64::NAN)
            };
            writeln!(
                f,
                "{},{},{},{},{},{},{}",
                o,
                c,
                v,
                m,
                lib.noise(o, c),
                w,
                d.split.fit_cycles
            )?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The report's reliability section reads the kept self-test: for a named effect, how many of
    /// the runs it was named for had it as their dominant effect and what the others were; for
    /// "none", which runs got it; and a self-test of another library (other run count) is not used.
    #[test]
    fn reliability_comes_from_the_kept_self_test() {
        let dir = std::env::temp_dir().join(format!("ryade_gap_rel_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let lib = Library {
            baseline: vec![
                Series {
                    rut_mm: vec![0.0, 1.0, 2.0],
                    ..Default::default()
                };
                19
            ],
            ..Default::default()
        };
        let a = |group: &str, dominant: &str, detectable: bool, named: &str| SelfTestAnswer {
            group: group.into(),
            dominant: dominant.into(),
            detectable,
            named: named.into(),
            heldout: vec![],
            oracle: vec![],
        };
        // the runs named right: held-out rut reductions 0.1 .. 0.7 (median 0.4), the oracle 0.5;
        // the runs of another effect read as rolling do not count (0.99)
        let mut answers: Vec<SelfTestAnswer> = (1..=7)
            .map(|k| SelfTestAnswer {
                heldout: vec![("rut_mm".into(), 0.1 * k as f64)],
                oracle: vec![("rut_mm".into(), 0.5)],
                ..a("rolling 0.2", "rolling", true, "rolling")
            })
            .collect();
        answers.extend(vec![
            SelfTestAnswer {
                heldout: vec![("rut_mm".into(), 0.99)],
                ..a("friction 10", "friction", false, "rolling")
            };
            2
        ]);
        answers.push(a("grading 0.3", "grading", false, "rolling"));
        answers.extend(vec![a("none", "none", false, "none"); 3]);
        answers.extend(vec![a("friction -5", "friction", false, "none"); 4]);
        answers.push(a("damping -0.15", "damping", true, "none"));
        answers.push(a("none", "none", false, "damping"));
        let st = StoredSelfTest {
            runs: 19,
            fit_cycles: 4,
            observables: vec!["rut_mm".into()],
            answers,
        };
        keep_self_test(&dir, st).unwrap();
        let r = format_reliability(&dir, &lib, 4, "rolling");
        assert!(
            r.contains("named **rolling** for 10 of the library's 19 runs; 7 of them had it as their dominant effect (70 %); the others were runs of friction 10 (2), grading 0.3 (1), read as rolling"),
            "{r}"
        );
        assert!(
            r.contains("named rolling right (7 runs), the held-out gap reduction per observable was, median: rut_mm 40 %; with the true effects at their true strengths instead of the fitted model: rut_mm 50 %"),
            "{r}"
        );
        let n = format_reliability(&dir, &lib, 4, "none");
        assert!(!n.contains("held-out gap reduction"), "{n}");
        assert!(
            n.contains("\"none\" for 8 of the library's 19 runs: 3 of today's model (of 4), 4 of effects under the detectability floor, and 1 of effects above it (missed: damping -0.15 (1))"),
            "{n}"
        );
        let other = format_reliability(&dir, &lib, 3, "rolling");
        assert!(
            other.contains("No kept self-test matches this diagnosis (19 runs, fit cycles 1-3"),
            "{other}"
        );
        let _ = std::fs::remove_dir_all(&dir);
        let none = format_reliability(&dir, &lib, 4, "rolling");
        assert!(
            none.contains("No self-test kept with this library"),
            "{none}"
        );
    }

    /// The self-test's case of specimen s is diagnosed by a library with no run of s: neither its
    /// baseline run nor its run of any effect strength (the pairing would otherwise see it), and its
    /// truth is the run's group.
    #[test]
    fn leaving_a_seed_out_removes_every_run_of_that_specimen() {
        let ser = |x: f64| Series {
            rut_mm: vec![0.0, x, 2.0 * x],
            ..Default::default()
        };
        let effect = Effect {
            knob: "rolling".into(),
            meaning: String::new(),
            zero: 0.0,
            strengths: vec![0.1, 0.5],
        };
        let mut lib = Library {
            effects: vec![effect],
            baseline: vec![ser(1.0), ser(2.0), ser(3.0)],
            baseline_seeds: vec![1, 2, 3],
            ..Default::default()
        };
        for k in 0..2 {
            let key = ("rolling".to_string(), k);
            lib.runs.insert(
                key.clone(),
                vec![ser(10.0 + k as f64), ser(20.0 + k as f64)],
            );
            lib.run_seeds.insert(key, vec![2, 3]);
        }
        let (rest, cases) = leave_seed_out(&lib, 2);
        assert_eq!(rest.baseline_seeds, vec![1, 3]);
        assert_eq!(
            rest.baseline
                .iter()
                .map(|s| s.rut_mm[1])
                .collect::<Vec<_>>(),
            vec![1.0, 3.0]
        );
        for k in 0..2 {
            let key = ("rolling".to_string(), k);
            assert_eq!(rest.run_seeds[&key], vec![3]);
            assert_eq!(rest.runs[&key][0].rut_mm[1], 20.0 + k as f64);
        }
        type Case = (String, f64, Vec<(String, f64)>);
        let got: Vec<Case> = cases
            .iter()
            .map(|(n, s, t)| (n.clone(), s.rut_mm[1], t.effects.clone()))
            .collect();
        assert_eq!(
            got,
            vec![
                ("base_s2".to_string(), 2.0, vec![]),
                (
                    "rolling_0_s2".to_string(),
                    10.0,
                    vec![("rolling".to_string(), 0.1)]
                ),
                (
                    "rolling_1_s2".to_string(),
                    11.0,
                    vec![("rolling".to_string(), 0.5)]
                ),
            ]
        );
        // a seed with no effect runs leaves the groups whole
        let (rest1, cases1) = leave_seed_out(&lib, 1);
        assert_eq!(cases1.len(), 1);
        assert_eq!(rest1.run_seeds, lib.run_seeds);
    }

    /// A library is completed on the engine it was started with: a library.json from before the
    /// engine choice (no `engine`: the YADE-order path) refuses `--engine fast` and says which
    /// engine completes it, before any run starts.
    #[test]
    fn a_library_keeps_its_engine() {
        let dir = std::env::temp_dir().join(format!("ryade_gap_engine_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let old = r#"{"scenario":"r07","case":"G","size":"tiny","cycles":1,"baseline_seeds":[1],"effect_seeds":[1],"effects":[]}"#;
        std::fs::write(dir.join("library.json"), old).unwrap();
        let idx: LibraryIndex = serde_json::from_str(old).unwrap();
        assert_eq!(idx.engine, "yade-order");
        let sc = Scenario {
            ratio: 7,
            case: 'G',
            size: "tiny".into(),
            cycles: 1,
            test: TestConditions::default(),
        };
        let counts = SeedCounts {
            baseline: Some(1),
            effect: Some(1),
        };
        let e = make_library(Path::new("."), &dir, &sc, counts, 4, true, 1).unwrap_err();
        let msg = e.to_string();
        assert!(
            msg.contains("yade-order engine") && msg.contains("--engine yade-order"),
            "{msg}"
        );
        assert!(
            !dir.join("library_base.table").exists(),
            "no run was started"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
    /// A library is completed, never cut: explicit counts under its own are refused before any
    /// run, with the count that completes it; so is a completion for other test conditions.
    #[test]
    fn a_library_is_never_cut_and_keeps_its_conditions() {
        let dir = std::env::temp_dir().join(format!("ryade_gap_cut_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let old = r#"{"scenario":"r07","case":"G","size":"tiny","cycles":1,"baseline_seeds":[1,2,3],"effect_seeds":[1,2,3],"effects":[],"engine":"fast","test":{"peak_kpa":400.0}}"#;
        std::fs::write(dir.join("library.json"), old).unwrap();
        let mut sc = Scenario {
            ratio: 7,
            case: 'G',
            size: "tiny".into(),
            cycles: 1,
            test: TestConditions {
                peak_kpa: Some(400.0),
                ..Default::default()
            },
        };
        let counts = SeedCounts {
            baseline: Some(3),
            effect: Some(2),
        };
        let e = make_library(Path::new("."), &dir, &sc, counts, 1, true, 1).unwrap_err();
        assert!(e.to_string().contains("--effect-seeds 3 or more"), "{e}");
        sc.test.peak_kpa = Some(300.0);
        let counts = SeedCounts {
            baseline: Some(3),
            effect: Some(3),
        };
        let e = make_library(Path::new("."), &dir, &sc, counts, 1, true, 1).unwrap_err();
        assert!(format!("{e:#}").contains("--peak-kpa 400"), "{e:#}");
        assert!(
            !dir.join("library_base.table").exists(),
            "no run was started"
        );
        // the study's own values are the study's conditions; a plate the cell cannot hold is refused
        let t = TestConditions {
            peak_kpa: Some(275.8),
            piston_d: Some(0.15),
            ..Default::default()
        };
        assert_eq!(t.normalised("medium"), TestConditions::default());
        let wide = TestConditions {
            piston_d: Some(0.2),
            ..Default::default()
        };
        let e = wide.check("medium").unwrap_err().to_string();
        assert!(e.contains("use --size full"), "{e}");
        assert!(wide.check("full").is_ok());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
