//! `compat gap` orchestration: the candidate effects, the library sweep and the blind datasets, all
//! as yade-batch tables run through `compat batch` (ryade) or `compat batch --command 'yade -n -x'`
//! (Debian YADE), so the same sweep can go to a cluster (`--emit-slurm`).

use crate::gap::{self, Effect, Library, Series};
use anyhow::{bail, Context, Result};
use serde::{Deserialize, Serialize};
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
            &[0.05, 0.2, 0.5],
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
            &[-10.0, 10.0],
        ),
        e("damping", "local damping change (from 0.2)", &[-0.15, 0.3]),
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
            other => bail!(
                "unknown effect '{}' (known: rolling, grading, subgrade, grid_soft, friction, damping)",
                other
            ),
        });
    }
    Ok(out.join(","))
}

/// Does the effect change generation (needs a new specimen)?
fn generates(k: &str) -> bool {
    k == "grading"
}

/// The study case every run of a library or dataset shares.
#[derive(Clone, Debug)]
pub struct Scenario {
    pub ratio: u8,
    pub case: char,
    pub size: String,
    pub cycles: u32,
}

/// One table line.
#[derive(Clone, Debug)]
struct Line {
    description: String,
    seed: u32,
    specimen: String,
    effects: String,
    out: PathBuf,
}

/// Run, as one yade-batch table `path`, the lines whose run has no history.csv yet (a sweep resumes
/// where it stopped): with `compat batch` (ryade), or with Debian YADE as the command (`yade`).
fn run_missing(
    root: &Path,
    path: &Path,
    sc: &Scenario,
    lines: &[Line],
    jobs: usize,
    yade: bool,
) -> Result<()> {
    let todo: Vec<&Line> = lines
        .iter()
        .filter(|l| !l.out.join("history.csv").is_file())
        .collect();
    if todo.is_empty() {
        return Ok(());
    }
    let mut f =
        std::fs::File::create(path).with_context(|| format!("writing {}", path.display()))?;
    writeln!(
        f,
        "description ratio case size seed cycles specimen effects out"
    )?;
    for l in &todo {
        writeln!(
            f,
            "{} {} '{}' '{}' {} {} '{}' '{}' '{}'",
            l.description,
            sc.ratio as f64 / 10.0,
            sc.case,
            sc.size,
            l.seed,
            sc.cycles,
            l.specimen,
            l.effects,
            l.out.display()
        )?;
    }
    drop(f);
    eprintln!(
        "[gap] {} runs to do in {} ({})",
        todo.len(),
        if yade { "Debian YADE" } else { "ryade" },
        path.display()
    );
    let mut c = Command::new(crate::harness::env::python());
    c.args(["-m", "yade.batch"])
        .arg(path)
        .arg(root.join("yade_ref/gap/run_case.py"))
        .args(["-j", &jobs.to_string()]);
    if yade {
        c.args(["--command", "yade -n -x"]);
    }
    let st = c.status().context("starting python3 -m yade.batch")?;
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
}

/// Build (or complete) a library: baseline seeds + each effect at its strengths for `effect_seeds`.
/// Specimens: `golden/study/<scenario>_<case>_<size>_s<seed>/specimen.json` when committed, else
/// generated.
pub fn make_library(
    root: &Path,
    dir: &Path,
    sc: &Scenario,
    baseline_seeds: &[u32],
    effect_seeds: &[u32],
    jobs: usize,
) -> Result<()> {
    std::fs::create_dir_all(dir)?;
    let dir = dir.canonicalize()?;
    let spec = |s: u32| {
        let p = root.join(format!(
            "golden/study/r{:02}_{}_{}_s{}/specimen.json",
            sc.ratio, sc.case, sc.size, s
        ));
        if p.is_file() {
            p.display().to_string()
        } else {
            String::new()
        }
    };
    let mut lines = Vec::new();
    for &s in baseline_seeds {
        lines.push(Line {
            description: format!("base_s{}", s),
            seed: s,
            specimen: spec(s),
            effects: String::new(),
            out: dir.join(format!("base_s{}", s)),
        });
    }
    let effects = catalogue();
    for e in &effects {
        for (k, st) in e.strengths.iter().enumerate() {
            for &s in effect_seeds {
                lines.push(Line {
                    description: format!("{}_{}_s{}", e.knob, k, s),
                    seed: s,
                    specimen: if generates(&e.knob) {
                        String::new()
                    } else {
                        spec(s)
                    },
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
    };
    std::fs::write(
        dir.join("library.json"),
        serde_json::to_string_pretty(&idx)?,
    )?;
    run_missing(root, &dir.join("library.table"), sc, &lines, jobs, false)
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
        ..Default::default()
    };
    for s in &idx.baseline_seeds {
        let p = dir.join(format!("base_s{}", s)).join("history.csv");
        match gap::series_of_history(&p) {
            Ok(x) => lib.baseline.push(x),
            Err(e) => eprintln!("warning: library run missing: {:#}", e),
        }
    }
    for e in &idx.effects {
        for k in 0..e.strengths.len() {
            let mut v: Vec<Series> = Vec::new();
            for s in &idx.effect_seeds {
                let p = dir
                    .join(format!("{}_{}_s{}", e.knob, k, s))
                    .join("history.csv");
                match gap::series_of_history(&p) {
                    Ok(x) => v.push(x),
                    Err(err) => eprintln!("warning: library run missing: {:#}", err),
                }
            }
            if !v.is_empty() {
                lib.runs.insert((e.knob.clone(), k), v);
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
    pub effects: Vec<(String, f64)>,
}

/// Blind datasets made by Debian YADE: `n` cases, each with one or two hidden effects at random
/// strengths (MT19937 seeded), on specimens of seeds the library does not use. Writes
/// `DIR/cases/<name>/observed.csv` and, apart, `DIR/truth/<name>.json`.
pub fn make_observed(
    root: &Path,
    dir: &Path,
    sc: &Scenario,
    n: usize,
    seed: u32,
    jobs: usize,
) -> Result<()> {
    use rand_mt::Mt19937GenRand32 as Mt;
    std::fs::create_dir_all(dir.join("runs"))?;
    std::fs::create_dir_all(dir.join("truth"))?;
    std::fs::create_dir_all(dir.join("cases"))?;
    let dir = dir.canonicalize()?;
    let mut rng = Mt::new(seed);
    let mut u = move || rng.next_u32() as f64 / 4294967296.0;
    let cat = catalogue();
    let mut lines = Vec::new();
    for i in 0..n {
        let name = format!("case{:02}", i + 1);
        let n_eff = if u() < 0.7 { 1 } else { 2 };
        let mut chosen: Vec<(String, f64)> = Vec::new();
        while chosen.len() < n_eff {
            let e = &cat[(u() * cat.len() as f64) as usize % cat.len()];
            if chosen.iter().any(|c| c.0 == e.knob) {
                continue;
            }
            // a strength between 40 % and 100 % of the library's extreme on a random side
            let hi = e.strengths.iter().cloned().fold(0.0, f64::max);
            let lo = e.strengths.iter().cloned().fold(0.0, f64::min);
            let side = if lo < 0.0 && (hi <= 0.0 || u() < 0.5) {
                lo
            } else {
                hi
            };
            let s = side * (0.4 + 0.6 * u());
            chosen.push((e.knob.clone(), (s * 1e4).round() / 1e4));
        }
        let spec_seed = 1000 + i as u32;
        std::fs::write(
            dir.join("truth").join(format!("{}.json", name)),
            serde_json::to_string_pretty(&Truth {
                seed: spec_seed,
                effects: chosen.clone(),
            })?,
        )?;
        lines.push(Line {
            description: name.clone(),
            seed: spec_seed,
            specimen: String::new(),
            effects: knobs(&chosen)?,
            out: dir.join("runs").join(&name),
        });
    }
    run_missing(root, &dir.join("observed.table"), sc, &lines, jobs, true)?;
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
        writeln!(f, "cycle,rut_mm,porosity,rebound_mm")?;
        for c in 0..s.cycles() {
            writeln!(
                f,
                "{},{:.17e},{:.17e},{:.17e}",
                c,
                s.rut_mm[c],
                s.porosity.as_ref().unwrap()[c],
                s.rebound_mm.as_ref().unwrap()[c]
            )?;
        }
    }
    Ok(())
}

/// The hidden effect that moves the final rut most by itself (its surrogate prediction at the true
/// strength against today's model), with that shift in mm; ("none", 0) without a known effect.
fn dominant_shift(lib: &Library, t: &Truth) -> (String, f64) {
    let last = lib.baseline.iter().map(|s| s.cycles()).min().unwrap_or(1) - 1;
    let base = lib.baseline_mean("rut_mm", last).unwrap_or(0.0);
    t.effects
        .iter()
        .filter_map(|(k, s)| {
            let e = lib.effects.iter().find(|e| &e.knob == k)?;
            Some((
                k.clone(),
                (lib.predict(e, *s, "rut_mm", last)? - base).abs(),
            ))
        })
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or_else(|| ("none".into(), 0.0))
}

/// Dominant hidden effect: the one whose surrogate prediction alone moves the final rut most.
pub fn dominant_truth(lib: &Library, t: &Truth) -> String {
    dominant_shift(lib, t).0
}

/// Signal-to-noise of the dominant hidden effect: its surrogate shift of the final rut over the noise
/// of one realisation there. Below 2 the effect is not detectable from one run, whatever the method.
pub fn detectability(lib: &Library, t: &Truth) -> f64 {
    let last = lib.baseline.iter().map(|s| s.cycles()).min().unwrap_or(1) - 1;
    dominant_shift(lib, t).1 / lib.noise("rut_mm", last)
}

#[derive(Serialize)]
pub struct CaseScore {
    pub case: String,
    pub truth: Vec<(String, f64)>,
    pub dominant_truth: String,
    /// Surrogate shift of the final rut by the dominant effect / noise of one run.
    pub detectability: f64,
    pub named: String,
    pub confidence: f64,
    pub correct: bool,
    pub fitted_strength: Option<f64>,
    pub strength_error: Option<f64>,
    pub gap_reduction: f64,
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
    // 1. blind: every diagnosis is made and written before any truth file is opened
    let mut diags = Vec::new();
    for n in &names {
        let obs = gap::read_observed(&dir.join("cases").join(n).join("observed.csv"))?;
        let d = gap::diagnose(lib, &obs, fit_cycles)?;
        std::fs::write(
            dir.join("cases").join(n).join("diagnosis.md"),
            gap::report_markdown(n, &d, lib),
        )?;
        std::fs::write(
            dir.join("cases").join(n).join("diagnosis.json"),
            serde_json::to_string_pretty(&d)?,
        )?;
        diags.push(d);
    }
    // 2. scoring
    let mut out = Vec::new();
    for (n, d) in names.iter().zip(diags) {
        let t: Truth = serde_json::from_str(&std::fs::read_to_string(
            dir.join("truth").join(format!("{}.json", n)),
        )?)?;
        let dom = dominant_truth(lib, &t);
        let fitted = d
            .candidates
            .iter()
            .find(|c| c.knob == dom)
            .map(|c| c.strength);
        let true_s = t.effects.iter().find(|e| e.0 == dom).map(|e| e.1);
        out.push(CaseScore {
            case: n.clone(),
            truth: t.effects.clone(),
            dominant_truth: dom.clone(),
            detectability: detectability(lib, &t),
            named: d.winner.clone(),
            confidence: d.confidence,
            correct: d.winner == dom,
            fitted_strength: if d.winner == dom { fitted } else { None },
            strength_error: match (fitted, true_s) {
                (Some(f), Some(t)) if d.winner == dom && t != 0.0 => Some((f - t).abs() / t.abs()),
                _ => None,
            },
            gap_reduction: d.gap_reduction,
        });
    }
    Ok(out)
}

pub fn format_scores(s: &[CaseScore]) -> String {
    let mut t = String::from("| case | hidden effects (strength) | dominant | detectability (shift / noise) | named (confidence) | fitted strength (rel. error) | held-out gap reduction |\n|---|---|---|---|---|---|---|\n");
    for c in s {
        t += &format!(
            "| {} | {} | {} | {:.1} | {} {} ({:.2}) | {} | {:.0} % |\n",
            c.case,
            c.truth
                .iter()
                .map(|(k, v)| format!("{} {}", k, v))
                .collect::<Vec<_>>()
                .join(", "),
            c.dominant_truth,
            c.detectability,
            if c.correct { "yes:" } else { "NO:" },
            c.named,
            c.confidence,
            match (c.fitted_strength, c.strength_error) {
                (Some(f), Some(e)) => format!("{:.3} ({:.0} %)", f, 100.0 * e),
                _ => "-".into(),
            },
            100.0 * c.gap_reduction
        );
    }
    let n = s.len().max(1) as f64;
    let correct = s.iter().filter(|c| c.correct).count() as f64;
    let mut red: Vec<f64> = s.iter().map(|c| c.gap_reduction).collect();
    red.sort_by(|a, b| a.total_cmp(b));
    let med = if red.is_empty() {
        f64::NAN
    } else if red.len() % 2 == 1 {
        red[red.len() / 2]
    } else {
        0.5 * (red[red.len() / 2 - 1] + red[red.len() / 2])
    };
    let mut errs: Vec<f64> = s.iter().filter_map(|c| c.strength_error).collect();
    errs.sort_by(|a, b| a.total_cmp(b));
    let det: Vec<&CaseScore> = s.iter().filter(|c| c.detectability >= 2.0).collect();
    let mut det_red: Vec<f64> = det.iter().map(|c| c.gap_reduction).collect();
    det_red.sort_by(|a, b| a.total_cmp(b));
    t += &format!(
        "\nDetectable cases (dominant effect shifts the final rut by >= 2 noise sd): {}; named correctly: {}; median held-out gap reduction: {}\n",
        det.len(),
        det.iter().filter(|c| c.correct).count(),
        if det_red.is_empty() { "-".to_string() } else { format!("{:.0} %", 100.0 * det_red[det_red.len() / 2]) }
    );
    t += &format!(
        "\nDominant effect named correctly: {}/{} ({:.0} %); median held-out gap reduction: {:.0} %; median relative strength error (correct cases): {}\n",
        correct as usize,
        s.len(),
        100.0 * correct / n,
        100.0 * med,
        if errs.is_empty() { "-".into() } else { format!("{:.0} %", 100.0 * errs[errs.len() / 2]) }
    );
    t
}

/// Per-cycle data for the report figure: observed, today's model (mean and noise), the winner's fit.
pub fn write_plot_data(out: &Path, lib: &Library, obs: &Series, d: &gap::Diagnosis) -> Result<()> {
    let mut f = std::fs::File::create(out.join("plot.csv"))?;
    writeln!(
        f,
        "observable,cycle,observed,model_mean,model_sd,winner,fit_cycles"
    )?;
    let win = lib.effects.iter().find(|e| e.knob == d.winner);
    let s = d
        .candidates
        .iter()
        .find(|c| c.knob == d.winner)
        .map(|c| c.strength);
    for o in gap::OBSERVABLES {
        let Some(ov) = obs.get(o) else { continue };
        for (c, v) in ov.iter().enumerate().take(d.split.last_cycle + 1) {
            let m = lib.baseline_mean(o, c).unwrap_or(f64::NAN);
            let w = match (win, s) {
                (Some(e), Some(s)) => lib.predict(e, s, o, c).unwrap_or(f64::NAN),
                _ => f64::NAN,
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
