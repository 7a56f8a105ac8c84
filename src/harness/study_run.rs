//! Running the study in YADE and in ryade: `compat diff rXX` and `compat study`.
//!
//! Both engines run the same script, `yade_ref/study/study.py` (YADE as `yade -n -x`, always one
//! thread; ryade as `compat run`). Runs go in parallel (`-j`), each with a progress bar fed by the
//! script's `[study]` lines; every run writes its own directory and log, so an interrupted or failed
//! sweep keeps every finished run.

use super::study::{self, CaseSpec, CycleBand, HistoryRow, Horizon};
use anyhow::{anyhow, bail, Context, Result};
use indicatif::{MultiProgress, ProgressBar, ProgressStyle};
use serde::Serialize;
use std::collections::VecDeque;
use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::Mutex;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Engine {
    Yade,
    Ryade,
}

impl Engine {
    pub fn name(self) -> &'static str {
        match self {
            Engine::Yade => "yade",
            Engine::Ryade => "ryade",
        }
    }
}

/// One study.py run.
#[derive(Clone, Debug)]
pub struct Run {
    pub spec: CaseSpec,
    pub engine: Engine,
    pub out: PathBuf,
    /// Load this specimen instead of generating one.
    pub import: Option<PathBuf>,
    /// Write the generated specimen to `out/specimen.json`.
    pub export: bool,
    pub cycles: Option<u32>,
    /// Extra study.py arguments (e.g. `--controller servopid`).
    pub extra: Vec<String>,
    /// ryade only: every `O.run` the fast path can take runs there (`compat run --fast`; the
    /// others, e.g. the generation's PyRunner phases, stay on the YADE-order path).
    pub fast: bool,
}

pub use super::env::repo_root;

fn study_script(root: &Path) -> Result<PathBuf> {
    let p = root.join("yade_ref/study/study.py");
    if !p.is_file() {
        bail!(
            "{} not found (RYADE_ROOT names a folder without the ryade scripts; unset it to use the built-in ones)",
            p.display()
        );
    }
    Ok(p)
}

/// study.py's named presets (`PRESETS` there) and the cycles each runs by default. study.py holds
/// their values; this list lets `compat study|diff --preset` refuse an unknown name before any run.
pub const PRESETS: &[(&str, u32)] = &[("paper200", 200)];

/// The study.py arguments `compat study|diff` add in front of the user's: `--preset=NAME` and, unless
/// the user chose a controller, `--controller=native` (ryade's engine for the study's PI law, byte-identical
/// to the PyRunner; YADE runs the PyRunner for it). Returns them with the preset's default cycles.
pub fn preset_args(preset: Option<&str>, user: &[String]) -> Result<(Vec<String>, Option<u32>)> {
    let mut v = Vec::new();
    let mut cycles = None;
    if let Some(p) = preset {
        let Some((_, c)) = PRESETS.iter().find(|(n, _)| *n == p) else {
            let names: Vec<&str> = PRESETS.iter().map(|(n, _)| *n).collect();
            bail!(
                "unknown preset '{}' (study.py has: {})",
                p,
                names.join(", ")
            );
        };
        v.push(format!("--preset={}", p));
        cycles = Some(*c);
    }
    if !user.iter().any(|a| a.starts_with("--controller")) {
        v.push("--controller=native".to_string());
    }
    v.extend(user.iter().cloned());
    Ok((v, cycles))
}

/// Cycles a size runs by default (study.py SIZES).
pub fn default_cycles(size: &str) -> u32 {
    if size == "tiny" {
        5
    } else {
        10
    }
}

/// Run study.py once; the progress bar follows the script's phases and cycles. The full output goes
/// to `out/<engine>.log`.
pub fn run_one(root: &Path, run: &Run, bar: &ProgressBar) -> Result<()> {
    let script = study_script(root)?;
    std::fs::create_dir_all(&run.out).with_context(|| format!("creating {}", run.out.display()))?;
    let mut args: Vec<String> = vec!["--".into()];
    match &run.import {
        Some(sp) => {
            args.push("--import-specimen".into());
            args.push(sp.display().to_string());
        }
        None => args.extend(run.spec.study_args()),
    }
    if let Some(c) = run.cycles {
        args.push("--cycles".into());
        args.push(c.to_string());
    }
    args.push("--out".into());
    args.push(run.out.display().to_string());
    if run.export {
        args.push("--export-specimen".into());
        args.push(run.out.join("specimen.json").display().to_string());
    }
    args.extend(run.extra.iter().cloned());
    let mut cmd = match run.engine {
        Engine::Yade => {
            let mut c = Command::new("yade");
            c.env("OMP_NUM_THREADS", "1")
                .args(["-n", "-x"])
                .arg(&script);
            c
        }
        Engine::Ryade => {
            let mut c = Command::new(super::env::compat_exe()?);
            c.arg("run").arg(&script);
            if run.fast {
                c.env("RYADE_FAST", "on");
            }
            c
        }
    };
    cmd.args(&args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    // a finished run with the same arguments is reused (an interrupted sweep resumes where it stopped)
    let marker = run.out.join(format!(".{}_run.json", run.engine.name()));
    let key = if run.fast {
        serde_json::json!({"engine": run.engine.name(), "args": &args, "fast": true})
    } else {
        serde_json::json!({"engine": run.engine.name(), "args": &args})
    }
    .to_string();
    if run.out.join("history.csv").is_file()
        && std::fs::read_to_string(&marker).ok().as_deref() == Some(key.as_str())
    {
        bar.set_message("reused (finished earlier with the same arguments)");
        return Ok(());
    }
    std::fs::remove_file(&marker).ok();
    let log_path = run.out.join(format!("{}.log", run.engine.name()));
    let mut log = std::fs::File::create(&log_path)
        .with_context(|| format!("creating {}", log_path.display()))?;
    let mut tracked = super::proc::spawn(&mut cmd).with_context(|| match run.engine {
        Engine::Yade => {
            "starting yade (install it: apt-get install -y --no-install-recommends yade)"
                .to_string()
        }
        Engine::Ryade => "starting `compat run`".to_string(),
    })?;
    let stderr = tracked.child.stderr.take().unwrap();
    let err_thread = std::thread::spawn(move || {
        let mut s = String::new();
        for l in BufReader::new(stderr).lines().map_while(Result::ok) {
            s.push_str(&l);
            s.push('\n');
        }
        s
    });
    let stdout = tracked.child.stdout.take().unwrap();
    for line in BufReader::new(stdout).lines() {
        let line = line.unwrap_or_default();
        writeln!(log, "{}", line).ok();
        if let Some(rest) = line.strip_prefix("[study] ") {
            if let Some(c) = rest.strip_prefix("cycle ") {
                if let Some(k) = c
                    .split_whitespace()
                    .next()
                    .and_then(|t| t.parse::<u64>().ok())
                {
                    bar.set_position(k);
                    bar.set_message(format!(
                        "cycle {}: {}",
                        k,
                        c.split_once(' ').map(|x| x.1).unwrap_or("").trim()
                    ));
                }
            } else if let Some(ph) = rest.split_whitespace().next() {
                bar.set_message(ph.to_string());
            }
        }
    }
    let status = tracked.wait()?;
    let err = err_thread.join().unwrap_or_default();
    log.write_all(err.as_bytes()).ok();
    if !status.success() {
        let tail: Vec<&str> = err.lines().rev().take(6).collect();
        let tail: Vec<&str> = tail.into_iter().rev().collect();
        bail!(
            "{} {} failed ({}); log: {}\n{}",
            run.engine.name(),
            run.spec.name(),
            status,
            log_path.display(),
            tail.join("\n")
        );
    }
    if run.out.join("history.csv").is_file() {
        std::fs::write(&marker, &key).ok();
    } else {
        bail!(
            "{} {} wrote no history.csv (log: {})",
            run.engine.name(),
            run.spec.name(),
            log_path.display()
        );
    }
    Ok(())
}

/// What a stopped `compat study` / `diff rXX` keeps in `out`: its finished runs (each marked by its
/// `.<engine>_run.json`), which the same command reuses.
pub fn kept_summary(out: &Path) -> String {
    let mut done = 0;
    for case in std::fs::read_dir(out).into_iter().flatten().flatten() {
        for e in ["ryade", "yade"] {
            let d = case.path().join(e);
            if d.join(format!(".{}_run.json", e)).is_file() && d.join("history.csv").is_file() {
                done += 1;
            }
        }
    }
    format!(
        "kept {} finished run(s) in {}; the same command again reuses them and runs the rest",
        done,
        out.display()
    )
}

/// (chain index, index in the chain, run, outcome)
type Finished = (usize, usize, Run, Result<()>);

/// A chain of runs executed in order by one worker (e.g. YADE generates, then ryade imports).
pub type Chain = Vec<Run>;

/// Run chains on `jobs` workers with one progress bar per run. Returns one result per run, in order.
pub fn run_chains(
    root: &Path,
    chains: Vec<Chain>,
    jobs: usize,
    quiet: bool,
) -> Vec<(Run, Result<()>)> {
    let mp = if quiet {
        MultiProgress::with_draw_target(indicatif::ProgressDrawTarget::hidden())
    } else {
        MultiProgress::new()
    };
    let style = ProgressStyle::with_template(
        "{prefix:>22} {bar:20} {pos:>2}/{len} cycles {elapsed:>4} {wide_msg}",
    )
    .unwrap();
    let queue: Mutex<VecDeque<(usize, Chain)>> =
        Mutex::new(chains.into_iter().enumerate().collect());
    let results: Mutex<Vec<Finished>> = Mutex::new(Vec::new());
    std::thread::scope(|s| {
        for _ in 0..jobs.max(1) {
            s.spawn(|| loop {
                let Some((ci, chain)) = queue.lock().unwrap().pop_front() else {
                    break;
                };
                let mut failed = false;
                for (ri, run) in chain.into_iter().enumerate() {
                    let r = if failed {
                        Err(anyhow!("skipped: an earlier run of its chain failed"))
                    } else {
                        let cycles = run.cycles.unwrap_or_else(|| default_cycles(&run.spec.size));
                        let bar = mp.add(ProgressBar::new(cycles as u64));
                        bar.set_style(style.clone());
                        bar.set_prefix(format!("{} {}", run.engine.name(), run.spec.name()));
                        let r = run_one(root, &run, &bar);
                        match &r {
                            Ok(()) => bar.finish_with_message("done"),
                            Err(_) => bar.abandon_with_message("FAILED"),
                        }
                        r
                    };
                    failed |= r.is_err();
                    results.lock().unwrap().push((ci, ri, run, r));
                }
            });
        }
    });
    let mut v = results.into_inner().unwrap();
    v.sort_by_key(|(c, r, _, _)| (*c, *r));
    v.into_iter().map(|(_, _, run, r)| (run, r)).collect()
}

// ------------------------------------------------------------------------------------------------
// compat diff rXX

pub struct DiffOptions {
    pub ratio: u8,
    pub cases: Vec<char>,
    pub size: String,
    pub seeds: u32,
    pub first_seed: u32,
    pub cycles: Option<u32>,
    pub jobs: usize,
    pub out: PathBuf,
    /// Take YADE's runs from `<dir>/<case name>/` instead of running YADE.
    pub yade_from: Option<PathBuf>,
    pub band_k: f64,
    /// Which verdict decides PASS: the band rule, or the paired mean test (`study::MeanTest`).
    pub rule: DiffRule,
    /// Family-wise level of the paired mean test.
    pub alpha: f64,
    /// Extra study.py arguments for both engines' runs (e.g. `--preset=paper200`).
    pub extra: Vec<String>,
    /// Extra study.py arguments for the ryade runs only (e.g. a deliberate perturbation).
    pub ryade_extra: Vec<String>,
    pub quiet: bool,
    /// ryade on the fast path where the scene allows (`Run::fast`).
    pub fast: bool,
}

/// The verdict of `compat diff rXX`: every ryade run inside YADE's mean +- k sd on every cycle (the
/// rule for the YADE-order path, whose runs are YADE's), or the paired mean test (for the fast engine,
/// whose runs are other realisations of YADE's chaos: its false-alarm rate is the chosen alpha, where
/// the band rule's grows with the cycles compared and shrinks with the seeds).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum DiffRule {
    Band,
    Mean,
}

#[derive(Serialize)]
pub struct CaseDiff {
    pub case: char,
    pub seeds: Vec<u32>,
    pub bands: Vec<CycleBand>,
    pub horizons: Vec<(u32, Horizon)>,
    /// Every ryade run inside the band on every cycle.
    pub pass_band: bool,
    pub mean_test: Option<study::MeanTest>,
    /// The verdict of the report's rule.
    pub pass: bool,
}

#[derive(Serialize)]
pub struct DiffReport {
    pub scenario: String,
    pub size: String,
    pub band_k: f64,
    pub rule: DiffRule,
    pub cases: Vec<CaseDiff>,
    pub errors: Vec<String>,
    pub pass: bool,
}

fn history_of(dir: &Path) -> Result<Vec<HistoryRow>> {
    study::read_history(&dir.join("history.csv"))
}

pub fn diff(root: &Path, o: &DiffOptions) -> Result<DiffReport> {
    study::check_size(&o.size)?;
    if o.seeds < 2 {
        bail!("--seeds must be at least 2: the band is YADE's seed-to-seed spread");
    }
    std::fs::create_dir_all(&o.out).with_context(|| format!("creating {}", o.out.display()))?;
    let specs: Vec<CaseSpec> = o
        .cases
        .iter()
        .flat_map(|&c| (o.first_seed..o.first_seed + o.seeds).map(move |s| (c, s)))
        .map(|(case, seed)| CaseSpec {
            ratio: o.ratio,
            case,
            size: o.size.clone(),
            seed,
        })
        .collect();
    let yade_dir = |s: &CaseSpec| match &o.yade_from {
        Some(d) => d.join(s.name()),
        None => o.out.join(s.name()).join("yade"),
    };
    let chains: Vec<Chain> = specs
        .iter()
        .map(|s| {
            let mut chain = Vec::new();
            if o.yade_from.is_none() {
                chain.push(Run {
                    spec: s.clone(),
                    engine: Engine::Yade,
                    out: yade_dir(s),
                    import: None,
                    export: true,
                    cycles: o.cycles,
                    extra: o.extra.clone(),
                    fast: false,
                });
            }
            chain.push(Run {
                spec: s.clone(),
                engine: Engine::Ryade,
                out: o.out.join(s.name()).join("ryade"),
                import: Some(yade_dir(s).join("specimen.json")),
                export: false,
                cycles: o.cycles,
                extra: o.extra.iter().chain(&o.ryade_extra).cloned().collect(),
                fast: o.fast,
            });
            chain
        })
        .collect();
    if let Some(d) = &o.yade_from {
        if !d.is_dir() {
            bail!(
                "--yade-from {}: no such folder ({})",
                d.display(),
                super::env::GOLDEN_HINT.replace("--golden DIR", "--yade-from DIR")
            );
        }
        for s in &specs {
            let sp = d.join(s.name()).join("specimen.json");
            if !sp.is_file() {
                bail!(
                    "{} not found: --yade-from needs YADE's run directories (yade_ref/study/golden.sh {} writes them)",
                    sp.display(),
                    s.name()
                );
            }
        }
    }
    let results = run_chains(root, chains, o.jobs, o.quiet);
    let mut errors: Vec<String> = results
        .iter()
        .filter_map(|(_, r)| r.as_ref().err().map(|e| format!("{:#}", e)))
        .collect();
    let mut cases = Vec::new();
    for &c in &o.cases {
        let mine: Vec<&CaseSpec> = specs.iter().filter(|s| s.case == c).collect();
        let mut yh = Vec::new();
        let mut rh = Vec::new();
        let mut horizons = Vec::new();
        let mut seeds = Vec::new();
        for s in &mine {
            let rd = o.out.join(s.name()).join("ryade");
            match (history_of(&yade_dir(s)), history_of(&rd)) {
                (Ok(y), Ok(r)) => {
                    let y = match o.cycles {
                        Some(k) => y.into_iter().take(k as usize + 1).collect(),
                        None => y,
                    };
                    yh.push(y);
                    rh.push(r);
                    seeds.push(s.seed);
                    match study::exact_match_horizon(
                        &yade_dir(s).join("steps.csv"),
                        &rd.join("steps.csv"),
                    ) {
                        Ok(mut h) => {
                            let read = |d: &Path| std::fs::read(d.join("history.csv")).ok();
                            let (a, b) = (read(&yade_dir(s)), read(&rd));
                            h.history_identical = a.is_some() && a == b;
                            horizons.push((s.seed, h))
                        }
                        Err(e) => errors.push(format!("{:#}", e)),
                    }
                }
                (y, r) => {
                    for e in [y.err(), r.err()].into_iter().flatten() {
                        errors.push(format!("{}: {:#}", s.name(), e));
                    }
                }
            }
        }
        let bands = if yh.len() >= 2 && !rh.is_empty() {
            study::compare_case(&yh, &rh, o.band_k)?
        } else {
            errors.push(format!(
                "case {}: only {} complete seed(s), the band needs 2",
                c,
                yh.len()
            ));
            vec![]
        };
        let complete = !bands.is_empty() && seeds.len() == mine.len();
        let pass_band = complete && bands.iter().all(|b| b.inside);
        let mean_test = study::mean_test(&bands, o.alpha);
        let pass = match o.rule {
            DiffRule::Band => pass_band,
            DiffRule::Mean => complete && mean_test.as_ref().is_some_and(|t| t.pass),
        };
        cases.push(CaseDiff {
            case: c,
            seeds,
            bands,
            horizons,
            pass_band,
            mean_test,
            pass,
        });
    }
    errors.dedup();
    let pass = errors.is_empty() && cases.iter().all(|c| c.pass);
    let rep = DiffReport {
        scenario: format!("r{:02}", o.ratio),
        size: o.size.clone(),
        band_k: o.band_k,
        rule: o.rule,
        cases,
        errors,
        pass,
    };
    write_diff_outputs(&rep, &o.out)?;
    Ok(rep)
}

/// Table for stdout.
pub fn format_diff(rep: &DiffReport) -> String {
    let mut s = String::new();
    for c in &rep.cases {
        s += &format!(
            "\n{} case {} ({} seeds {:?}): band = YADE mean +- {} sd per cycle\n",
            rep.scenario,
            c.case,
            c.seeds.len(),
            c.seeds,
            rep.band_k
        );
        s += &format!(
            "{:>5} {:>12} {:>12} {:>10} {:>12} {:>8} {:>8}  {}\n",
            "cycle", "metric", "YADE mean", "YADE sd", "ryade mean", "z(mean)", "max|z|", "verdict"
        );
        for b in &c.bands {
            s += &format!(
                "{:>5} {:>12} {:>12.6} {:>10.3e} {:>12.6} {:>8.2} {:>8.2}  {}\n",
                b.cycle,
                b.metric,
                b.yade_mean,
                b.yade_sd,
                b.ryade_mean,
                b.z_mean,
                b.z_max_run,
                if b.inside { "inside" } else { "OUTSIDE" }
            );
        }
        for (seed, h) in &c.horizons {
            s += &match h.first_diff_iter {
                None if h.history_identical => format!(
                    "  seed {}: exact-match horizon: none; identical at all {} sampled steps (through iteration {}) and history.csv byte-identical (17 digits)\n",
                    seed, h.rows_compared, h.last_iter
                ),
                None => format!(
                    "  seed {}: exact-match horizon: none, identical at all {} sampled steps (through iteration {})\n",
                    seed, h.rows_compared, h.last_iter
                ),
                Some(_) if h.one_ran_longer => format!(
                    "  seed {}: exact-match horizon: none; identical at all {} sampled steps of the shorter run (through iteration {}), the other ran on\n",
                    seed, h.rows_compared, h.last_iter
                ),
                Some(it) => format!(
                    "  seed {}: exact-match horizon: first difference at iteration {} ({}), after {} identical samples\n",
                    seed,
                    it,
                    h.first_diff_phase.as_deref().unwrap_or("?"),
                    h.rows_compared.saturating_sub(1)
                ),
            };
        }
        s += &format!(
            "  band rule: {}\n",
            if c.pass_band {
                "every run inside on every cycle"
            } else {
                "a run OUTSIDE"
            }
        );
        s += &match &c.mean_test {
            Some(t) => format!(
                "  paired mean test ({} seeds, {} comparisons, family alpha {}): max |t| {:.2} (cycle {} {}) against {:.2}: {}; it detects a mean difference above {:.2} YADE sd there\n",
                t.n,
                t.m,
                t.alpha,
                t.t_max,
                t.cycle,
                t.metric,
                t.t_crit,
                if t.pass { "no bias found" } else { "BIASED" },
                t.detectable_sd
            ),
            None => "  paired mean test: not available (YADE and ryade have different seeds)\n".into(),
        };
        s += &format!(
            "  case {}: {} ({})\n",
            c.case,
            if c.pass { "PASS" } else { "FAIL" },
            match rep.rule {
                DiffRule::Band => "band rule",
                DiffRule::Mean => "paired mean test",
            }
        );
    }
    for e in &rep.errors {
        s += &format!("error: {}\n", e);
    }
    s += &format!(
        "\n{} {}: {}\n",
        rep.scenario,
        rep.size,
        match (rep.pass, rep.rule) {
            (true, DiffRule::Band) => "PASS (every cycle inside YADE's band)",
            (true, DiffRule::Mean) => "PASS (no mean difference from YADE the seeds can resolve)",
            (false, _) => "FAIL",
        }
    );
    s
}

fn write_diff_outputs(rep: &DiffReport, out: &Path) -> Result<()> {
    let name = format!("diff_{}_{}", rep.scenario, rep.size);
    let csv_path = out.join(format!("{}.csv", name));
    let mut w = csv::Writer::from_path(&csv_path)
        .with_context(|| format!("writing {}", csv_path.display()))?;
    w.write_record([
        "case",
        "cycle",
        "metric",
        "yade_mean",
        "yade_sd",
        "band_lo",
        "band_hi",
        "ryade_mean",
        "z_mean",
        "z_max_run",
        "inside",
        "yade_values",
        "ryade_values",
    ])?;
    let join = |v: &[f64]| {
        v.iter()
            .map(|x| format!("{:.17e}", x))
            .collect::<Vec<_>>()
            .join(" ")
    };
    for c in &rep.cases {
        for b in &c.bands {
            w.write_record([
                c.case.to_string(),
                b.cycle.to_string(),
                b.metric.to_string(),
                format!("{:.17e}", b.yade_mean),
                format!("{:.17e}", b.yade_sd),
                format!("{:.17e}", b.lo),
                format!("{:.17e}", b.hi),
                format!("{:.17e}", b.ryade_mean),
                format!("{}", b.z_mean),
                format!("{}", b.z_max_run),
                (b.inside as u8).to_string(),
                join(&b.yade),
                join(&b.ryade),
            ])?;
        }
    }
    w.flush()?;
    let json_path = out.join(format!("{}.json", name));
    std::fs::write(&json_path, serde_json::to_string_pretty(rep)?)?;
    figures(&[
        "diff",
        &csv_path.display().to_string(),
        &out.join(format!("{}.png", name)).display().to_string(),
    ]);
    Ok(())
}

/// Draw figures with the compat package's matplotlib helper (`python3 -m yade._ryade_figures`).
/// Figures are a convenience: a missing matplotlib is reported, never fatal.
pub fn figures(args: &[&str]) -> bool {
    let py = super::env::python();
    match super::proc::status(
        Command::new(&py)
            .arg("-m")
            .arg("yade._ryade_figures")
            .args(args),
    ) {
        Ok(s) if s.success() => true,
        Ok(s) => {
            eprintln!(
                "warning: figure '{}' not drawn (python exited with {})",
                args[0], s
            );
            false
        }
        Err(e) => {
            eprintln!(
                "warning: figure '{}' not drawn ({}: {})",
                args[0],
                py.to_string_lossy(),
                e
            );
            false
        }
    }
}

// ------------------------------------------------------------------------------------------------
// compat study

pub struct StudyOptions {
    pub size: String,
    pub ratios: Vec<u8>,
    pub cases: Vec<char>,
    pub seeds: u32,
    pub first_seed: u32,
    pub cycles: Option<u32>,
    pub jobs: usize,
    pub out: PathBuf,
    pub with_yade: bool,
    pub extra: Vec<String>,
    pub quiet: bool,
    /// ryade on the fast path where the scene allows (`Run::fast`).
    pub fast: bool,
}

#[derive(Serialize, Clone)]
pub struct SdrPoint {
    pub ratio: u8,
    pub engine: &'static str,
    pub cycle: u32,
    pub seeds: Vec<u32>,
    pub values: Vec<f64>,
    pub mean: f64,
    pub sd: f64,
    /// Eq 1 on the seed-mean ruts of N, G and F.
    pub of_means: f64,
}

pub struct StudyResult {
    pub runs: Vec<(Run, Result<()>)>,
    pub sdr: Vec<SdrPoint>,
    pub summary_path: PathBuf,
}

pub fn study_sweep(root: &Path, o: &StudyOptions) -> Result<StudyResult> {
    study::check_size(&o.size)?;
    std::fs::create_dir_all(&o.out).with_context(|| format!("creating {}", o.out.display()))?;
    let mut chains = Vec::new();
    // the expensive ratio (0.3: most spheres) first, so that parallel workers finish together
    let mut ratios = o.ratios.clone();
    ratios.sort();
    for &r in &ratios {
        for s in o.first_seed..o.first_seed + o.seeds {
            for &c in &o.cases {
                let spec = CaseSpec {
                    ratio: r,
                    case: c,
                    size: o.size.clone(),
                    seed: s,
                };
                let mut engines = vec![Engine::Ryade];
                if o.with_yade {
                    engines.push(Engine::Yade);
                }
                for e in engines {
                    chains.push(vec![Run {
                        out: o.out.join(spec.name()).join(e.name()),
                        spec: spec.clone(),
                        engine: e,
                        import: None,
                        export: true,
                        cycles: o.cycles,
                        extra: o.extra.clone(),
                        fast: o.fast && e == Engine::Ryade,
                    }]);
                }
            }
        }
    }
    let runs = run_chains(root, chains, o.jobs, o.quiet);
    // combined histories
    let mut profiles = vec!["ratio,case,seed,cycle,file".to_string()];
    let hist_path = o.out.join("histories.csv");
    let mut w = csv::Writer::from_path(&hist_path)?;
    w.write_record([
        "engine",
        "ratio",
        "case",
        "seed",
        "cycle",
        "complete",
        "rut_mm",
        "rut_max_mm",
        "peak_kPa",
        "tracking_rms_kPa",
        "porosity_box",
        "piston_z_m",
        "grid_z_m",
    ])?;
    let mut hist: std::collections::BTreeMap<(&'static str, u8, char, u32), Vec<HistoryRow>> =
        Default::default();
    for (run, r) in &runs {
        if r.is_err() {
            continue;
        }
        let h = history_of(&run.out)?;
        for row in &h {
            w.write_record([
                run.engine.name().to_string(),
                format!("{}", run.spec.ratio_value()),
                run.spec.case.to_string(),
                run.spec.seed.to_string(),
                row.cycle.to_string(),
                row.complete.to_string(),
                format!("{:.17e}", row.rut_mm),
                format!("{:.17e}", row.rut_max_mm),
                format!("{:.17e}", row.peak_kpa),
                format!("{:.17e}", row.tracking_rms_kpa),
                format!("{:.17e}", row.porosity_box),
                format!("{:.17e}", row.piston_z_m),
                row.grid_z_m
                    .map(|g| format!("{:.17e}", g))
                    .unwrap_or_default(),
            ])?;
        }
        hist.insert(
            (
                run.engine.name(),
                run.spec.ratio,
                run.spec.case,
                run.spec.seed,
            ),
            h,
        );
        // paper Fig 7 of the whole study: the profile at --profile-cycle K where the run wrote one
        let at = std::fs::read_dir(&run.out).ok().and_then(|d| {
            d.filter_map(|e| e.ok()?.file_name().into_string().ok())
                .filter_map(|n| {
                    let k = n.strip_prefix("profile_c")?.strip_suffix(".csv")?;
                    Some((k.parse::<u32>().ok()?, n))
                })
                .min()
        });
        let final_prof = run.out.join("profile.csv");
        let (pc, pf) = match at {
            Some((k, n)) => (k.to_string(), run.out.join(n)),
            None => ("last".to_string(), final_prof.clone()),
        };
        if pf.is_file() && run.engine == Engine::Ryade {
            profiles.push(format!(
                "{:.1},{},{},{},{}",
                run.spec.ratio_value(),
                run.spec.case,
                run.spec.seed,
                pc,
                pf.display()
            ));
        }
        let prof = final_prof;
        if prof.is_file() {
            figures(&[
                "profile",
                &prof.display().to_string(),
                &run.out.join("profile.png").display().to_string(),
                &run.spec.name(),
            ]);
        }
    }
    w.flush()?;
    if profiles.len() > 1 {
        let idx = o.out.join("profiles.csv");
        std::fs::write(&idx, profiles.join("\n") + "\n")
            .with_context(|| format!("writing {}", idx.display()))?;
        figures(&[
            "profiles",
            &idx.display().to_string(),
            &o.out.join("fig_profiles.png").display().to_string(),
        ]);
    }
    // surface displacement ratio per ratio, engine and cycle, over seeds
    let mut sdr = Vec::new();
    for eng in ["ryade", "yade"] {
        for &r in &ratios {
            let mut per_cycle: std::collections::BTreeMap<u32, Vec<(u32, f64)>> =
                Default::default();
            for s in o.first_seed..o.first_seed + o.seeds {
                let g = |c: char| hist.get(&(eng, r, c, s));
                if let (Some(n), Some(gg), Some(f)) = (g('N'), g('G'), g('F')) {
                    for (cyc, v) in study::sdr(n, gg, f) {
                        per_cycle.entry(cyc).or_default().push((s, v));
                    }
                }
            }
            // Eq 1 applied to the seed-mean ruts (more stable than the mean of per-seed ratios, whose
            // denominators F - N can be near zero for single seeds)
            let mean_rut = |c: char, cyc: usize| {
                let v: Vec<f64> = (o.first_seed..o.first_seed + o.seeds)
                    .filter_map(|s| {
                        hist.get(&(eng, r, c, s))
                            .and_then(|h| h.get(cyc))
                            .map(|x| x.rut_mm)
                    })
                    .collect();
                (v.len() == o.seeds as usize).then(|| study::mean_sd(&v).0)
            };
            for (cycle, v) in per_cycle {
                let vals: Vec<f64> = v.iter().map(|x| x.1).collect();
                let (mean, sd) = study::mean_sd(&vals);
                let c = cycle as usize;
                let of_means = match (mean_rut('N', c), mean_rut('G', c), mean_rut('F', c)) {
                    (Some(n), Some(g), Some(f)) => (g - n) / (f - n),
                    _ => f64::NAN,
                };
                sdr.push(SdrPoint {
                    ratio: r,
                    engine: eng,
                    cycle,
                    seeds: v.iter().map(|x| x.0).collect(),
                    values: vals,
                    mean,
                    sd,
                    of_means,
                });
            }
        }
    }
    let sdr_path = o.out.join("sdr.csv");
    let mut w = csv::Writer::from_path(&sdr_path)?;
    w.write_record([
        "engine",
        "ratio",
        "cycle",
        "n_seeds",
        "sdr_mean",
        "sdr_sd",
        "sdr_of_mean_ruts",
        "values",
    ])?;
    for p in &sdr {
        w.write_record([
            p.engine.to_string(),
            format!("{}", p.ratio as f64 / 10.0),
            p.cycle.to_string(),
            p.values.len().to_string(),
            format!("{:.17e}", p.mean),
            format!("{:.17e}", p.sd),
            format!("{:.17e}", p.of_means),
            p.values
                .iter()
                .map(|x| format!("{:.17e}", x))
                .collect::<Vec<_>>()
                .join(" "),
        ])?;
    }
    w.flush()?;
    let h = hist_path.display().to_string();
    let s = sdr_path.display().to_string();
    let od = o.out.display().to_string();
    figures(&["study", &h, &s, &od]);
    let summary_path = o.out.join("summary.md");
    std::fs::write(&summary_path, summary_markdown(o, &runs, &hist, &sdr))?;
    Ok(StudyResult {
        runs,
        sdr,
        summary_path,
    })
}

type Histories = std::collections::BTreeMap<(&'static str, u8, char, u32), Vec<HistoryRow>>;

fn summary_markdown(
    o: &StudyOptions,
    runs: &[(Run, Result<()>)],
    hist: &Histories,
    sdr: &[SdrPoint],
) -> String {
    let mut s = String::new();
    s += &format!(
        "# Study summary: size {}, ratios {:?}, cases {:?}, seeds {}..{}\n\n",
        o.size,
        o.ratios
            .iter()
            .map(|r| *r as f64 / 10.0)
            .collect::<Vec<_>>(),
        o.cases,
        o.first_seed,
        o.first_seed + o.seeds - 1
    );
    s += "Generated by `compat study` (yade_ref/study/study.py under ryade's `compat run`";
    s += if o.with_yade {
        ", and in Debian YADE"
    } else {
        ""
    };
    s += if o.fast {
        "; ryade's engine: fast, every O.run the fast path takes, results in YADE's seed band, not its bits"
    } else {
        "; ryade's engine: yade-order, YADE's bits"
    };
    s += "). Histories: `histories.csv`; surface displacement ratio (seed-paper.txt Eq 1): `sdr.csv`; figures: `fig_rutting.png`, `fig_porosity.png` (seed mean and range), `fig_sdr.png`, `fig_profiles.png` (every run's profile at `--profile-cycle`, or its last, in one figure) and `profile.png` per run (paper Fig 7).\n\n";
    s += "## Rutting and porosity under the piston (last cycle run)\n\n";
    s += "| engine | ratio | case | seed | cycles | rut [mm] | porosity (cycle 0 -> last) | status |\n|---|---|---|---|---|---|---|---|\n";
    for (run, r) in runs {
        let key = (
            run.engine.name(),
            run.spec.ratio,
            run.spec.case,
            run.spec.seed,
        );
        match (r, hist.get(&key)) {
            (Ok(()), Some(h)) => {
                let last = h.last().unwrap();
                s += &format!(
                    "| {} | {} | {} | {} | {} | {:.2} | {:.4} -> {:.4} | {} |\n",
                    run.engine.name(),
                    run.spec.ratio_value(),
                    run.spec.case,
                    run.spec.seed,
                    last.cycle,
                    last.rut_mm,
                    h[0].porosity_box,
                    last.porosity_box,
                    if last.complete == 0 {
                        "stopped: rut limit"
                    } else {
                        "ok"
                    }
                );
            }
            (Err(e), _) => {
                s += &format!(
                    "| {} | {} | {} | {} | - | - | - | FAILED: {} |\n",
                    run.engine.name(),
                    run.spec.ratio_value(),
                    run.spec.case,
                    run.spec.seed,
                    format!("{:#}", e).lines().next().unwrap_or("")
                )
            }
            _ => {}
        }
    }
    s += &findings_markdown(o, hist, sdr);
    s += "\n## Surface displacement ratio (G - N) / (F - N) per cycle\n\nWith several seeds: Eq 1 on the seed-mean ruts, then in brackets the mean +- sd of the per-seed ratios. Past cycle 20, every 10th cycle (all of them in `sdr.csv`).\n\n";
    if sdr.is_empty() {
        s += "Not available: it needs the N, G and F runs of one ratio and seed.\n";
    }
    for eng in ["ryade", "yade"] {
        let pts: Vec<&SdrPoint> = sdr.iter().filter(|p| p.engine == eng).collect();
        if pts.is_empty() {
            continue;
        }
        s += &format!("\n{}:\n\n| cycle |", eng);
        let mut ratios: Vec<u8> = pts.iter().map(|p| p.ratio).collect();
        ratios.dedup();
        for r in &ratios {
            s += &format!(" d/a = {} |", *r as f64 / 10.0);
        }
        s += "\n|---|";
        s += &"---|".repeat(ratios.len());
        s += "\n";
        let maxc = pts.iter().map(|p| p.cycle).max().unwrap_or(0);
        for c in (1..=maxc).filter(|c| *c <= 20 || c % 10 == 0 || *c == maxc) {
            s += &format!("| {} |", c);
            for r in &ratios {
                match pts.iter().find(|p| p.ratio == *r && p.cycle == c) {
                    Some(p) if p.values.len() > 1 => {
                        s += &format!(" {:.2} ({:.2} +- {:.2}) |", p.of_means, p.mean, p.sd)
                    }
                    Some(p) => s += &format!(" {:.2} |", p.mean),
                    None => s += " - |",
                }
            }
            s += "\n";
        }
    }
    s += "\nThe ratio is undefined (large or of either sign) where F and N rut alike: study.md warns that single seeds at small sizes scatter by 18-30 %, so read trends over seeds.\n";
    s
}

/// Least-squares slope of y over x.
fn slope(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = x.iter().map(|a| (a - mx) * (a - mx)).sum();
    sxy / sxx
}

/// The paper's findings (seed-paper.txt section 3) checked on ryade's runs, per ratio: the N > G > F order of
/// the seed-mean ruts at the last cycle every run reached, the ratio of Eq 1 on those means early
/// (cycles 1-20) and late (cycles 100-200, or the second half of a shorter study) with its trend, and the
/// paper's trend for that ratio: 0.7 near 1 early then degrading, 0.5 steady, 0.3 rising late.
fn findings_markdown(o: &StudyOptions, hist: &Histories, sdr: &[SdrPoint]) -> String {
    let mut s = String::from("\n## The paper's findings, checked (ryade runs, seed means)\n\n");
    s += "| d/a | last common cycle | rut N / G / F [mm] (mean +- sd) | N > G > F | SDR cycles 1-20 | SDR late window: mean, first -> last (trend /100 cycles) | inside [0, 1] +- 1 sd | paper's trend | reproduced |\n|---|---|---|---|---|---|---|---|---|\n";
    let mut any = false;
    for &r in &o.ratios {
        let seeds: Vec<u32> = (o.first_seed..o.first_seed + o.seeds).collect();
        let runs: Vec<&Vec<HistoryRow>> = ['N', 'G', 'F']
            .iter()
            .flat_map(|&c| seeds.iter().map(move |&sd| (c, sd)))
            .filter_map(|(c, sd)| hist.get(&("ryade", r, c, sd)))
            .collect();
        if runs.len() != 3 * seeds.len() {
            continue;
        }
        any = true;
        let last = runs.iter().map(|h| h.len() - 1).min().unwrap_or(0);
        let stat = |c: char| {
            let v: Vec<f64> = seeds
                .iter()
                .map(|&sd| hist[&("ryade", r, c, sd)][last].rut_mm)
                .collect();
            study::mean_sd(&v)
        };
        let (n, g, f) = (stat('N'), stat('G'), stat('F'));
        let order = n.0 > g.0 && g.0 > f.0;
        let pts: Vec<&SdrPoint> = sdr
            .iter()
            .filter(|p| p.engine == "ryade" && p.ratio == r && (p.cycle as usize) <= last)
            .collect();
        let val = |p: &SdrPoint| if seeds.len() > 1 { p.of_means } else { p.mean };
        let early: Vec<f64> = pts
            .iter()
            .filter(|p| p.cycle <= 20)
            .map(|p| val(p))
            .collect();
        let lo = if last >= 200 {
            100
        } else {
            (last as u32).div_ceil(2)
        };
        let late: Vec<&&SdrPoint> = pts.iter().filter(|p| p.cycle >= lo).collect();
        let ly: Vec<f64> = late.iter().map(|p| val(p)).collect();
        let lx: Vec<f64> = late.iter().map(|p| p.cycle as f64).collect();
        let (em, lm) = (study::mean_sd(&early).0, study::mean_sd(&ly).0);
        let tr = if ly.len() > 2 {
            100.0 * slope(&lx, &ly)
        } else {
            f64::NAN
        };
        let inside = late
            .iter()
            .filter(|p| {
                let sd = if p.values.len() > 1 { p.sd } else { 0.0 };
                val(p) >= -sd && val(p) <= 1.0 + sd
            })
            .count();
        let (paper, ok) = match r {
            7 => ("near 1 early, then degrading", em > 0.7 && tr < 0.0),
            5 => (
                "steady improvement",
                lm > 0.0 && lm <= 1.0 && tr.abs() < 0.2,
            ),
            _ => ("rising late", tr > 0.0 && lm > 0.0),
        };
        s += &format!(
            "| {} | {} | {:.2} +- {:.2} / {:.2} +- {:.2} / {:.2} +- {:.2} | {} | {:.2} | {:.2}, {:.2} -> {:.2} ({:+.2}), cycles {}-{} | {} of {} | {} | {} |\n",
            r as f64 / 10.0,
            last,
            n.0,
            n.1,
            g.0,
            g.1,
            f.0,
            f.1,
            if order { "yes" } else { "no" },
            em,
            lm,
            ly.first().copied().unwrap_or(f64::NAN),
            ly.last().copied().unwrap_or(f64::NAN),
            tr,
            lo,
            last,
            inside,
            ly.len(),
            paper,
            if ok && order { "yes" } else { "no" }
        );
    }
    if !any {
        return String::new();
    }
    s += "\n'reproduced' asks for the order N > G > F at the last cycle and the trend: 0.7 early mean > 0.7 with a falling late ratio; 0.5 a late mean in (0, 1] that moves less than 0.2 per 100 cycles; 0.3 a rising, positive late ratio.\n";
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn preset_args_put_the_preset_and_native_controller_first() {
        let (v, c) = preset_args(Some("paper200"), &["--damping=0.3".into()]).unwrap();
        assert_eq!(
            v,
            ["--preset=paper200", "--controller=native", "--damping=0.3"]
        );
        assert_eq!(c, Some(200));
        // a controller the user chose is kept, and no preset means no cycles
        let (v, c) = preset_args(None, &["--controller=servopid".into()]).unwrap();
        assert_eq!(v, ["--controller=servopid"]);
        assert_eq!(c, None);
        let e = preset_args(Some("paper300"), &[]).unwrap_err().to_string();
        assert!(
            e.contains("unknown preset 'paper300'") && e.contains("paper200"),
            "{e}"
        );
    }

    #[test]
    fn presets_listed_here_exist_in_study_py() {
        let py =
            std::fs::read_to_string(repo_root().unwrap().join("yade_ref/study/study.py")).unwrap();
        for (name, cycles) in PRESETS {
            let at = py
                .find(&format!("'{}': {{", name))
                .expect("preset missing in study.py");
            assert!(
                py[at..].contains(&format!("'cycles': {}", cycles)),
                "{name}: cycles differ"
            );
        }
    }

    /// Synthetic seed histories with ruts a*k: N > G > F with a ratio of Eq 1 that is constant (0.5,
    /// 'steady') must read 'yes' for d/a 0.5 and 'no' for 0.7 (no early ratio above 0.7, no fall).
    #[test]
    fn findings_read_the_order_and_the_trend() {
        let row = HistoryRow::with_rut;
        let mut hist = Histories::new();
        let mut sdr = Vec::new();
        for r in [5u8, 7] {
            for seed in 1..=2u32 {
                let jitter = 1.0 + 0.01 * seed as f64;
                for (c, a) in [('N', 0.3), ('G', 0.2), ('F', 0.1)] {
                    hist.insert(
                        ("ryade", r, c, seed),
                        (0..=200).map(|k| row(k, a * jitter * k as f64)).collect(),
                    );
                }
            }
            for cycle in 1..=200 {
                sdr.push(SdrPoint {
                    ratio: r,
                    engine: "ryade",
                    cycle,
                    seeds: vec![1, 2],
                    values: vec![0.5, 0.5],
                    mean: 0.5,
                    sd: 0.0,
                    of_means: 0.5,
                });
            }
        }
        let o = StudyOptions {
            size: "full".into(),
            ratios: vec![5, 7],
            cases: vec!['N', 'G', 'F'],
            seeds: 2,
            first_seed: 1,
            cycles: Some(200),
            jobs: 1,
            out: PathBuf::from("unused"),
            with_yade: false,
            extra: vec![],
            quiet: true,
            fast: false,
        };
        let md = findings_markdown(&o, &hist, &sdr);
        let line = |d: &str| {
            md.lines()
                .find(|l| l.starts_with(&format!("| {} |", d)))
                .unwrap()
                .to_string()
        };
        assert!(line("0.5").ends_with("| yes | 0.50 | 0.50, 0.50 -> 0.50 (+0.00), cycles 100-200 | 101 of 101 | steady improvement | yes |"), "{}", line("0.5"));
        assert!(
            line("0.7").ends_with("| near 1 early, then degrading | no |"),
            "{}",
            line("0.7")
        );
        assert!((slope(&[0.0, 1.0, 2.0], &[1.0, 3.0, 5.0]) - 2.0).abs() < 1e-15);
    }
}
