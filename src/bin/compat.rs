//! `compat`: the ryade command line (YADE comparison harness and scene runner).

use anyhow::{bail, Context, Result};
use clap::{Parser, Subcommand};
use ryade::harness::micro;
use ryade::io::{golden::Recorder, scene_json};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "compat",
    version,
    about = "ryade: YADE's DEM core in Rust, and the tools to prove it matches YADE"
)]
struct Cli {
    #[command(subcommand)]
    cmd: Cmd,
}

#[derive(Subcommand)]
enum Cmd {
    /// Compare ryade with YADE. Targets: `micro` and `micro_grid` (golden records, bit for bit, every
    /// step), `meso`, and the study scenarios `r03`, `r05`, `r07` (both engines run the case from the
    /// same specimens; rutting and porosity must stay inside YADE's seed-to-seed band every cycle).
    Diff {
        /// What to compare: micro | micro_grid | meso | r03 | r05 | r07
        target: String,
        /// Golden directory (default: golden/<target>)
        #[arg(long)]
        golden: Option<PathBuf>,
        /// Only scenes whose name contains this text
        #[arg(long)]
        only: Option<String>,
        /// Also write the report as JSON here
        #[arg(long)]
        json: Option<PathBuf>,
        /// rXX: case N, G, F, a list (N,G) or all
        #[arg(long, default_value = "all")]
        case: String,
        /// rXX: specimen size (tiny | small | medium | full)
        #[arg(long, default_value = "tiny")]
        size: String,
        /// rXX: number of seeds (YADE's band needs >= 2)
        #[arg(long, default_value_t = 3)]
        seeds: u32,
        /// rXX: first seed (seeds FIRST..FIRST+SEEDS-1)
        #[arg(long, default_value_t = 1)]
        first_seed: u32,
        /// rXX: load cycles (default: the size's, 5 for tiny)
        #[arg(long)]
        cycles: Option<u32>,
        /// rXX: parallel runs (default: number of cores)
        #[arg(short = 'j', long)]
        jobs: Option<usize>,
        /// rXX: output directory (default: diff_out/<target>_<size>)
        #[arg(long)]
        out: Option<PathBuf>,
        /// rXX: take YADE's runs from DIR/<case>/ (e.g. golden/study) instead of running YADE
        #[arg(long)]
        yade_from: Option<PathBuf>,
        /// rXX: band half-width in YADE standard deviations
        #[arg(long, default_value_t = 3.0)]
        band_k: f64,
        /// rXX: the verdict: band (every run inside YADE's band on every cycle; the YADE-order path's
        /// rule) or mean (the paired t test of ryade - YADE over the seeds at each cycle, Bonferroni
        /// over the cycles: for the fast engine, whose runs are other realisations of YADE's chaos;
        /// its false-alarm rate is --alpha). Both are printed.
        #[arg(long, default_value = "band", value_parser = ["band", "mean"])]
        rule: String,
        /// rXX: family-wise level of the paired mean test
        #[arg(long, default_value_t = 0.01)]
        alpha: f64,
        /// rXX: extra study.py argument for the ryade runs only (repeatable; e.g.
        /// --ryade-arg=--load-friction=10 to see the diff fail)
        #[arg(long, allow_hyphen_values = true)]
        ryade_arg: Vec<String>,
        /// rXX: a study.py preset for both engines (e.g. paper200: 200 cycles, rolling resistance;
        /// yade_ref/study/README.md); YADE's runs of it at medium size are in golden/study_paper200
        #[arg(long)]
        preset: Option<String>,
        /// rXX: ryade's engine: yade-order (YADE's bits) or fast (every O.run the fast path can take,
        /// as `compat run --fast`; results in YADE's band, not its bits)
        #[arg(long, default_value = "yade-order", value_parser = ["yade-order", "fast"])]
        engine: String,
    },
    /// The study: every ratio x case (x seed) in ryade, histories, the paper's figures and a summary.
    Study {
        /// Specimen size: tiny | small | medium | full
        #[arg(long, default_value = "small")]
        size: String,
        /// Scenarios (r03,r05,r07 or all)
        #[arg(long, default_value = "all")]
        ratios: String,
        /// Cases (N,G,F or all)
        #[arg(long, default_value = "all")]
        cases: String,
        /// Seeds per ratio and case (specimens; each seed rebuilds the same specimen in both engines)
        #[arg(long, default_value_t = 1)]
        seeds: u32,
        /// First seed (the runs use seeds FIRST..FIRST+SEEDS-1)
        #[arg(long, default_value_t = 1)]
        first_seed: u32,
        /// Load cycles (default: the size's)
        #[arg(long)]
        cycles: Option<u32>,
        /// Parallel runs (default: number of cores)
        #[arg(short = 'j', long)]
        jobs: Option<usize>,
        /// Output directory (default: study_out/<size>)
        #[arg(long)]
        out: Option<PathBuf>,
        /// Also run every case in Debian YADE (one thread per run)
        #[arg(long)]
        with_yade: bool,
        /// Extra study.py argument for every run (repeatable; e.g. --arg=--controller=servopid)
        #[arg(long, allow_hyphen_values = true)]
        arg: Vec<String>,
        /// A study.py preset (paper200: 200 cycles, rolling resistance, the paper's specimen;
        /// yade_ref/study/README.md "Preset paper200")
        #[arg(long)]
        preset: Option<String>,
        /// ryade's engine: fast (the default: every O.run the fast path can take, as
        /// `compat run --fast`, the three cases' loading included; results in YADE's seed band, not
        /// its bits; one that it cannot take says why and runs on the YADE-order path) or yade-order
        /// (YADE's bits, run for run)
        #[arg(long, default_value = "fast", value_parser = ["yade-order", "fast"])]
        engine: String,
    },
    /// Run an unmodified YADE script (as `yade -n -x script.py args`) on ryade.
    ///
    /// The script gets YADE's startup namespace (O, every YADE class, utils, pack, geom, math...) and
    /// its arguments in sys.argv. Before its first line runs, it is checked for YADE names ryade does
    /// not provide (classes, functions, O's methods, refused keywords, also inside PyRunner command
    /// strings): if it uses any, each is listed with its line and the run is refused (exit code 1), so
    /// a long run cannot die at its last line. Code inside try/except, or an `if` marked with a
    /// `# YADE only` comment, is not refused. What depends on run-time values is still found when
    /// reached (exit code 1, naming it and the line).
    #[command(trailing_var_arg = true)]
    Run {
        /// Threads of the YADE-order path (like `yade -jN`; the results have the same bits for any
        /// count)
        #[arg(short = 'j', long = "threads", default_value_t = 1)]
        threads: usize,
        /// Only check: list every unsupported name the script can reach, run nothing (exit 0 when
        /// none refuses the run, 1 otherwise)
        #[arg(long)]
        check: bool,
        /// Run without the check (the run stops at the first unsupported name it reaches)
        #[arg(long, conflicts_with = "check")]
        no_check: bool,
        /// Run every `O.run` the fast path can take on it (spheres, FrictMat, Cundall-Strack; results
        /// agree with YADE statistically, not bit for bit); any other run says why in one line and takes
        /// the YADE-order path. `--fast=strict` makes that an error. Also: env RYADE_FAST=on|strict
        #[arg(long, num_args = 0..=1, default_missing_value = "on", require_equals = true,
              value_parser = ["on", "strict"])]
        fast: Option<String>,
        /// The YADE script
        script: PathBuf,
        /// Arguments passed to the script in sys.argv
        #[arg(allow_hyphen_values = true)]
        args: Vec<String>,
    },
    /// Run a yade-batch parameter table: one job per line, in parallel (see `compat batch -- --help`).
    #[command(trailing_var_arg = true)]
    Batch {
        /// TABLE script.py [-j N] [--log DIR] [--lines ...] [--dry-run] [--emit-slurm FILE] ...
        #[arg(allow_hyphen_values = true)]
        args: Vec<String>,
    },
    /// Time the same scene in YADE and ryade, alternating repetitions; ratio with min/median/max.
    Bench {
        /// Scene files (*.scene.json; e.g. bench/scenes/dense8000.scene.json)
        scenes: Vec<PathBuf>,
        #[arg(long, default_value_t = 2000)]
        steps: u64,
        #[arg(long, default_value_t = 50)]
        warmup: u64,
        #[arg(long, default_value_t = 3)]
        reps: usize,
        /// ryade paths to time: yade (the YADE-order path), fast, or all
        #[arg(long, default_value = "all")]
        path: String,
        /// Thread counts for both ryade paths, comma-separated (e.g. 1,2; the YADE-order path has
        /// the same bits at any count)
        #[arg(long, default_value = "1,2")]
        threads: String,
        /// Time ryade only
        #[arg(long)]
        no_yade: bool,
        /// Append the report (JSON lines) to this log file
        #[arg(long)]
        log: Option<PathBuf>,
    },
    /// Fit the geogrid rib stiffness multipliers (kn_scale; kr_scale = ktw_scale) to datasheet targets
    /// with the ASTM D6637 tensile and D7748 cantilever model tests (calibration/README.md).
    Calibrate {
        /// Targets file (e.g. calibration/tx190l.toml; empty strings are missing values); not with --triaxial
        targets: Option<PathBuf>,
        /// The aggregate's element test instead: periodic drained triaxial runs of
        /// yade_ref/calibration/triaxial.py (friction and dilatancy angles, bearing capacity; default out
        /// out/calibrate/triaxial)
        #[arg(long)]
        triaxial: bool,
        /// With --triaxial: comma-separated variants (plain, roll0.25, roll0.5, roll1, clump2, clump3, clump4)
        #[arg(long)]
        variants: Option<String>,
        /// With --triaxial: variants run at the same time
        #[arg(short = 'j', long, default_value_t = 1)]
        jobs: usize,
        /// With --triaxial: a further argument for triaxial.py (repeatable, e.g. --arg=--n=2000)
        #[arg(long = "arg", allow_hyphen_values = true)]
        script_args: Vec<String>,
        /// Engine that runs the model tests: ryade (`compat run`) or yade (`yade -n -x`)
        #[arg(long, default_value = "ryade", value_parser = ["ryade", "yade"])]
        engine: String,
        /// Output folder (calibration.json, model outputs, plots; default out/calibrate/<targets name>)
        #[arg(long)]
        out: Option<PathBuf>,
        /// Step 2 stops after one cantilever evaluation (smoke test); --triaxial: the small fast version
        #[arg(long)]
        quick: bool,
        /// Starting k of step 2 (default: beam scaling from the 817.6 mm overhang at k = 1)
        #[arg(long)]
        k0: Option<f64>,
        /// Most cantilever evaluations in step 2
        #[arg(long, default_value_t = 10)]
        max_evals: usize,
        /// Overhang tolerance [mm] of step 2 (default: [fit] overhang_tolerance_mm of the targets file)
        #[arg(long)]
        tolerance_mm: Option<f64>,
        /// Folder with tensile.py and cantilever.py (default: yade_ref/calibration)
        #[arg(long)]
        scripts: Option<PathBuf>,
        /// Do not make the PNG plots
        #[arg(long)]
        no_plot: bool,
    },
    /// Sim-to-real gap diagnosis: where a model departs from an observed history, which unmodelled
    /// effect explains it, how far adding it closes the gap on held-out cycles (yade_ref/gap/README.md).
    Gap {
        /// Observed history CSV (cycle, rut_mm|rut_m [, porosity, rebound_mm|rebound_m,
        /// grid_settlement_mm|grid_settlement_m, tracking_kPa])
        #[arg(long)]
        observed: Option<PathBuf>,
        /// Diagnose every case of a blind dataset DIR (cases/ and, read only after diagnosing, truth/)
        #[arg(long)]
        validate: Option<PathBuf>,
        /// Build (or complete) the library of simulated runs in --library (baseline seeds + each
        /// effect at its strengths); without it a missing library is an error
        #[arg(long)]
        make_library: bool,
        /// Make blind datasets with Debian YADE in DIR (hidden effects, truth stored apart)
        #[arg(long)]
        make_observed: Option<PathBuf>,
        /// Print, from the library alone, each effect's signal and the strengths that reach the
        /// detectability floor of the blind-dataset design
        #[arg(long)]
        detectability: bool,
        /// Diagnose each library run with the library left without its specimen (every seed in
        /// turn) and score the answers as a blind set is scored: the method's error rates on
        /// hundreds of cases, from the library alone (written to --out/self_test.{md,json}, and kept
        /// with the library so that each diagnosis says how often its answer was right; with
        /// --observed FILE, on the observables that file has)
        #[arg(long, conflicts_with_all = ["validate", "make_observed", "make_library"])]
        self_test: bool,
        /// The study scenario of the library runs (r03 | r05 | r07)
        #[arg(long, default_value = "r07")]
        scenario: String,
        /// The study case of the library runs (N | G | F)
        #[arg(long, default_value = "G")]
        case: String,
        /// Specimen size of the library runs (tiny | small | medium | full)
        #[arg(long, default_value = "medium")]
        size: String,
        /// Load cycles of every library / dataset run
        #[arg(long, default_value_t = 6)]
        cycles: u32,
        /// The test's plate diameter [m] (default: the study's piston for --size)
        #[arg(long)]
        plate_d: Option<f64>,
        /// The test's seating pressure [kPa] (default: the study's, 27.6)
        #[arg(long)]
        seat_kpa: Option<f64>,
        /// The test's peak plate pressure [kPa] (default: the study's, 275.8)
        #[arg(long)]
        peak_kpa: Option<f64>,
        /// The test's base layer thickness [m] (default: the study's, 0.25)
        #[arg(long)]
        layer: Option<f64>,
        /// The test's load frequency [Hz] (default: the study's, 50)
        #[arg(long)]
        freq: Option<f64>,
        /// Cycles 1..K are fitted, the later ones held out
        #[arg(long, default_value_t = 4)]
        fit_cycles: usize,
        /// Library directory (default gap_lib/<scenario>_<case>_<size>_c<cycles>); it must hold a
        /// library (library.json) unless --make-library builds it there
        #[arg(long)]
        library: Option<PathBuf>,
        /// Library building: baseline runs (seeds 1..N) of today's model (default: chosen from the
        /// measured noise, at least 10)
        #[arg(long)]
        baseline_seeds: Option<u32>,
        /// Library building: runs (seeds 1..N) of each effect at each strength (default: chosen
        /// from the noise a pilot of 3 seeds measures, so that the library's shifts add under 10 %
        /// to the variance of a fit)
        #[arg(long)]
        effect_seeds: Option<u32>,
        /// Library building: ryade's engine, fast (every O.run the fast path can take, with the
        /// study's native piston engine: YADE's statistics, not its bits) or yade-order (YADE's bits).
        /// A library keeps the engine it was started with
        #[arg(long, default_value = "fast", value_parser = ["yade-order", "fast"])]
        engine: String,
        /// Blind datasets to make
        #[arg(long, default_value_t = 14)]
        n: usize,
        /// Of which cases of today's model (no hidden effect)
        #[arg(long, default_value_t = 2)]
        n_null: usize,
        /// Seed of the hidden-effect draw
        #[arg(long, default_value_t = 2026)]
        seed: u32,
        /// Blind datasets: draw every effect over its whole library range (detectable or not, the
        /// second effect of a two-effect case too) instead of where its signal reaches the floor;
        /// validation then counts "none" right only for an effect under the floor
        #[arg(long)]
        unfiltered: bool,
        /// Blind datasets: of --n, cases of an effect outside the catalogue (clumps of 2-4 spheres)
        #[arg(long, default_value_t = 0)]
        n_clump: usize,
        /// Report directory for --observed
        #[arg(long, default_value = "gap_out")]
        out: PathBuf,
        /// Simulation runs at the same time while building a library or blind datasets (default:
        /// number of cores)
        #[arg(short = 'j', long)]
        jobs: Option<usize>,
    },
    /// Run a scene file (*.scene.json) and record every step in the golden format.
    Scene {
        file: PathBuf,
        /// Number of steps (default: the scene file's recorded count)
        #[arg(long)]
        steps: Option<u64>,
        /// Output directory for <name>.bodies.csv and <name>.intrs.csv
        #[arg(long, default_value = "out")]
        out: PathBuf,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    // SIGINT/SIGTERM/SIGHUP stop every process this command starts (`compat run` and `compat batch`
    // become Python, which handles them itself)
    ryade::harness::proc::install();
    let r = run(cli);
    // stopped by a signal: the watcher thread reports what was kept and exits
    ryade::harness::proc::wait_if_stopping();
    match r {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {:#}", e);
            ExitCode::from(2)
        }
    }
}

/// Replace this process with `python -m module args` (the Python that has the `yade` compat package:
/// `RYADE_PYTHON`, default `python3`): the script's exit code and the signals sent to `compat run` /
/// `compat batch` (SIGINT, SIGTERM) are Python's own, and no process is left behind.
fn python(module: &str, args: &[std::ffi::OsString], threads: usize) -> Result<ExitCode> {
    use std::os::unix::process::CommandExt;
    let py = ryade::harness::env::python();
    let mut cmd = std::process::Command::new(&py);
    // read by the yade package when it makes the scene (O.numThreads)
    cmd.env("RYADE_THREADS", threads.to_string());
    // numpy (in YADE's script namespace) would start OpenBLAS threads that spin after any numpy
    // call and burn the other cores; the simulation itself runs on one
    if std::env::var_os("OPENBLAS_NUM_THREADS").is_none() {
        cmd.env("OPENBLAS_NUM_THREADS", "1");
    }
    let e = cmd.arg("-m").arg(module).args(args).exec();
    Err(anyhow::Error::new(e).context(format!(
        "starting {:?} (set RYADE_PYTHON to the Python that has the yade package)",
        py
    )))
}

/// `--cycles 0` would run no load cycle and write empty histories and figures.
fn check_cycles(cycles: Option<u32>) -> Result<()> {
    if cycles == Some(0) {
        bail!("--cycles must be at least 1 (0 load cycles give empty histories and figures)");
    }
    Ok(())
}

/// A bench scene: the path if it exists, else a scene of bench/scenes (the checkout's or the built-in
/// copy) named by its file name or stem (`dense8000`, `r05_G_medium.study.json`,
/// `bench/scenes/dense8000.scene.json`).
fn bench_scene(root: &std::path::Path, p: &std::path::Path) -> Result<PathBuf> {
    if p.is_file() {
        return Ok(p.to_path_buf());
    }
    let name = p
        .file_name()
        .map(|n| n.to_string_lossy().to_string())
        .unwrap_or_default();
    let dir = root.join("bench/scenes");
    for cand in [
        name.clone(),
        format!("{}.scene.json", name),
        format!("{}.study.json", name),
    ] {
        if dir.join(&cand).is_file() {
            return Ok(dir.join(cand));
        }
    }
    let known: Vec<String> = std::fs::read_dir(&dir)
        .map(|d| {
            d.filter_map(|e| e.ok()?.file_name().into_string().ok())
                .filter(|n| n.ends_with(".scene.json") || n.ends_with(".study.json"))
                .collect()
        })
        .unwrap_or_default();
    bail!(
        "{}: no such scene file, nor a built-in scene of that name (built in: {})",
        p.display(),
        known.join(", ")
    )
}

/// `--golden DIR`, else golden/<target> of the working directory, else of the checkout
/// (`checkout_root`); an error that says how to point the command at one otherwise.
fn golden_dir(given: Option<PathBuf>, target: &str) -> Result<PathBuf> {
    if let Some(d) = given {
        if !d.is_dir() {
            bail!("--golden {}: no such folder", d.display());
        }
        return Ok(d);
    }
    let here = PathBuf::from("golden").join(target);
    if here.is_dir() {
        return Ok(here);
    }
    match ryade::harness::env::checkout_root() {
        Some(r) if r.join("golden").join(target).is_dir() => Ok(r.join("golden").join(target)),
        _ => bail!(
            "golden/{} not found here ({}): {}",
            target,
            std::env::current_dir()
                .map(|d| d.display().to_string())
                .unwrap_or_default(),
            ryade::harness::env::GOLDEN_HINT
        ),
    }
}

fn cores() -> usize {
    std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1)
}

fn run(cli: Cli) -> Result<ExitCode> {
    match cli.cmd {
        Cmd::Run {
            threads,
            check,
            no_check,
            fast,
            script,
            args,
        } => {
            if threads == 0 {
                bail!("-j/--threads: counts start at 1");
            }
            if let Some(mode) = fast {
                // read by the yade package (O's fast-path mode); a child process inherits it
                std::env::set_var("RYADE_FAST", mode);
            }
            let mut a: Vec<std::ffi::OsString> = Vec::new();
            if check {
                a.push("--check".into());
            } else if no_check {
                a.push("--no-check".into());
            }
            a.push(script.into_os_string());
            a.extend(args.into_iter().map(Into::into));
            python("yade.runner", &a, threads)
        }
        Cmd::Calibrate {
            targets,
            triaxial,
            variants,
            jobs,
            script_args,
            engine,
            out,
            quick,
            k0,
            max_evals,
            tolerance_mm,
            scripts,
            no_plot,
        } => {
            if triaxial {
                let ok = ryade::calibrate::triaxial::run(&ryade::calibrate::triaxial::Options {
                    engine: engine.parse()?,
                    out: out.unwrap_or_else(|| PathBuf::from("out/calibrate/triaxial")),
                    quick,
                    variants,
                    jobs,
                    scripts,
                    args: script_args,
                    plot: !no_plot,
                })?;
                return Ok(if ok {
                    ExitCode::SUCCESS
                } else {
                    ExitCode::from(1)
                });
            }
            let targets = targets.ok_or_else(|| {
                anyhow::anyhow!("compat calibrate needs a TARGETS file (or --triaxial)")
            })?;
            let out = out.unwrap_or_else(|| {
                let stem = targets
                    .file_stem()
                    .map(|s| s.to_string_lossy().to_string())
                    .unwrap_or_else(|| "targets".into());
                PathBuf::from("out").join("calibrate").join(stem)
            });
            let ok = ryade::calibrate::calibrate(&ryade::calibrate::Options {
                targets,
                engine: engine.parse()?,
                out,
                quick,
                k0,
                max_evals,
                tol_mm: tolerance_mm,
                scripts,
                plot: !no_plot,
            })?;
            Ok(if ok {
                ExitCode::SUCCESS
            } else {
                ExitCode::from(1)
            })
        }
        Cmd::Batch { args } => {
            let a: Vec<std::ffi::OsString> = args.into_iter().map(Into::into).collect();
            python("yade.batch", &a, 1)
        }
        Cmd::Diff {
            target,
            golden,
            only,
            json,
            case,
            size,
            seeds,
            first_seed,
            cycles,
            jobs,
            out,
            yade_from,
            band_k,
            rule,
            alpha,
            ryade_arg,
            preset,
            engine,
        } => {
            if target.starts_with('r') && target.len() == 3 {
                check_cycles(cycles)?;
                if !(alpha > 0.0 && alpha < 1.0) {
                    bail!(
                        "--alpha {}: the family-wise level of the paired mean test must lie between 0 and 1 (e.g. 0.01)",
                        alpha
                    );
                }
                use ryade::harness::{study, study_run};
                let (extra, preset_cycles) = study_run::preset_args(preset.as_deref(), &[])?;
                let o = study_run::DiffOptions {
                    ratio: study::parse_scenario(&target)?,
                    cases: study::parse_cases(&case)?,
                    out: out.unwrap_or_else(|| {
                        PathBuf::from("diff_out").join(format!("{}_{}", target, size))
                    }),
                    size,
                    seeds,
                    first_seed,
                    cycles: cycles.or(preset_cycles),
                    jobs: jobs.unwrap_or_else(cores),
                    yade_from,
                    band_k,
                    rule: if rule == "mean" {
                        study_run::DiffRule::Mean
                    } else {
                        study_run::DiffRule::Band
                    },
                    alpha,
                    extra,
                    ryade_extra: ryade_arg,
                    quiet: false,
                    fast: engine == "fast",
                };
                let out = o.out.clone();
                ryade::harness::proc::set_kept(move || study_run::kept_summary(&out));
                let rep = study_run::diff(&study_run::repo_root()?, &o)?;
                print!("{}", study_run::format_diff(&rep));
                println!(
                    "outputs: {}/diff_{}_{}.{{csv,json,png}}",
                    o.out.display(),
                    target,
                    o.size
                );
                return Ok(if rep.pass {
                    ExitCode::SUCCESS
                } else {
                    ExitCode::from(1)
                });
            }
            if !matches!(target.as_str(), "micro" | "micro_grid" | "meso") {
                bail!(
                    "unknown diff target '{}': available targets are: micro, micro_grid, meso, r03, r05, r07",
                    target
                );
            }
            let dir = golden_dir(golden, &target)?;
            if target == "meso" {
                let rep = ryade::harness::meso::diff_meso(&dir)?;
                print!("{}", ryade::harness::meso::format_report(&rep));
                if let Some(j) = json {
                    std::fs::write(&j, serde_json::to_string_pretty(&rep)?)
                        .with_context(|| format!("writing {}", j.display()))?;
                }
                return Ok(if rep.first_diff_step.is_none() {
                    ExitCode::SUCCESS
                } else {
                    ExitCode::from(1)
                });
            }
            let mut reps = Vec::new();
            for p in micro::scene_files(&dir)? {
                let name = p.file_name().unwrap().to_string_lossy().to_string();
                if let Some(o) = &only {
                    if !name.contains(o.as_str()) {
                        continue;
                    }
                }
                let sf = scene_json::load(&p)?;
                reps.push(micro::diff_scene(sf, &p)?);
            }
            if reps.is_empty() {
                bail!(
                    "no *.scene.json found in {} (run yade_ref/regen.sh to create goldens)",
                    dir.display()
                );
            }
            print!("{}", micro::format_table(&reps));
            let total: u64 = reps.iter().map(|r| r.mismatches).sum();
            let values: u64 = reps.iter().map(|r| r.values).sum();
            println!(
                "{} scenes, {} values compared, {} mismatches",
                reps.len(),
                values,
                total
            );
            if let Some(j) = json {
                std::fs::write(&j, serde_json::to_string_pretty(&reps)?)
                    .with_context(|| format!("writing {}", j.display()))?;
            }
            Ok(if total == 0 {
                ExitCode::SUCCESS
            } else {
                ExitCode::from(1)
            })
        }
        Cmd::Bench {
            scenes,
            steps,
            warmup,
            reps,
            path,
            threads,
            no_yade,
            log,
        } => {
            use ryade::bench::Variant;
            if scenes.is_empty() {
                bail!("give at least one scene file (e.g. bench/scenes/dense8000.scene.json)");
            }
            let mut variants = Vec::new();
            if !no_yade {
                variants.push(Variant::Yade);
            }
            let mut counts = Vec::new();
            for t in threads.split(',') {
                let t: usize = t
                    .trim()
                    .parse()
                    .map_err(|_| anyhow::anyhow!("--threads: '{}' is not a count", t))?;
                if t == 0 {
                    bail!("--threads: counts start at 1");
                }
                counts.push(t);
            }
            if path == "yade" || path == "all" {
                variants.extend(counts.iter().map(|&t| Variant::YadeOrder(t)));
            }
            if path == "fast" || path == "all" {
                variants.extend(counts.iter().map(|&t| Variant::Fast(t)));
            }
            if !matches!(path.as_str(), "yade" | "fast" | "all") {
                bail!("--path: yade, fast or all, not '{}'", path);
            }
            let root = ryade::harness::env::repo_root()?;
            for sc in &scenes {
                let sc = &bench_scene(&root, sc)?;
                let r = ryade::bench::bench(&root, sc, steps, warmup, reps, &variants)?;
                print!("{}", ryade::bench::format_report(&r));
                if let Some(l) = &log {
                    use std::io::Write;
                    let mut f = std::fs::OpenOptions::new()
                        .create(true)
                        .append(true)
                        .open(l)?;
                    writeln!(f, "{}", serde_json::to_string(&r)?)?;
                }
            }
            Ok(ExitCode::SUCCESS)
        }
        Cmd::Study {
            size,
            ratios,
            cases,
            seeds,
            first_seed,
            cycles,
            jobs,
            out,
            with_yade,
            arg,
            preset,
            engine,
        } => {
            use ryade::harness::{study, study_run};
            let (extra, preset_cycles) = study_run::preset_args(preset.as_deref(), &arg)?;
            let ratios: Vec<u8> = if ratios.eq_ignore_ascii_case("all") {
                study::RATIOS.to_vec()
            } else {
                ratios
                    .split(',')
                    .map(|r| study::parse_scenario(r.trim()))
                    .collect::<Result<_>>()?
            };
            if seeds == 0 {
                bail!("--seeds must be at least 1");
            }
            check_cycles(cycles)?;
            let o = study_run::StudyOptions {
                out: out.unwrap_or_else(|| PathBuf::from("study_out").join(&size)),
                size,
                ratios,
                cases: study::parse_cases(&cases)?,
                seeds,
                first_seed,
                cycles: cycles.or(preset_cycles),
                jobs: jobs.unwrap_or_else(cores),
                with_yade,
                extra,
                quiet: false,
                fast: engine == "fast",
            };
            let out = o.out.clone();
            ryade::harness::proc::set_kept(move || study_run::kept_summary(&out));
            let r = study_run::study_sweep(&study_run::repo_root()?, &o)?;
            let failed: Vec<String> = r
                .runs
                .iter()
                .filter_map(|(run, res)| {
                    res.as_ref()
                        .err()
                        .map(|e| format!("{} {}: {:#}", run.engine.name(), run.spec.name(), e))
                })
                .collect();
            print!("{}", std::fs::read_to_string(&r.summary_path)?);
            println!("outputs in {}", o.out.display());
            for f in &failed {
                eprintln!("error: {}", f);
            }
            Ok(if failed.is_empty() {
                ExitCode::SUCCESS
            } else {
                ExitCode::from(1)
            })
        }
        Cmd::Gap {
            observed,
            validate,
            make_library,
            make_observed,
            detectability,
            self_test,
            scenario,
            case,
            size,
            cycles,
            plate_d,
            seat_kpa,
            peak_kpa,
            layer,
            freq,
            fit_cycles,
            library,
            baseline_seeds,
            effect_seeds,
            engine,
            n,
            n_null,
            unfiltered,
            n_clump,
            seed,
            out,
            jobs,
        } => {
            use ryade::harness::{study, study_run};
            use ryade::{gap, gap_run};
            let ratio = study::parse_scenario(&scenario)?;
            let cases = study::parse_cases(&case)?;
            if cases.len() != 1 {
                bail!("--case takes one case (N, G or F)");
            }
            study::check_size(&size)?;
            check_cycles(Some(cycles))?;
            let root = study_run::repo_root()?;
            let jobs = jobs.unwrap_or_else(cores);
            let test = gap_run::TestConditions {
                piston_d: plate_d,
                seat_kpa,
                peak_kpa,
                layer,
                freq,
            };
            test.check(&size)?;
            let test = test.normalised(&size);
            let sc = gap_run::Scenario {
                ratio,
                case: cases[0],
                size: size.clone(),
                cycles,
                test: test.clone(),
            };
            let lib_dir = library.unwrap_or_else(|| {
                PathBuf::from("gap_lib").join(format!(
                    "{}_{}_{}_c{}{}",
                    scenario,
                    cases[0],
                    size,
                    cycles,
                    test.tag()
                ))
            });
            if make_library {
                if baseline_seeds.is_some_and(|b| b < 2) {
                    bail!("--baseline-seeds must be at least 2 (the noise is their scatter)");
                }
                if effect_seeds == Some(0) {
                    bail!("--effect-seeds must be at least 1");
                }
                let counts = gap_run::SeedCounts {
                    baseline: baseline_seeds,
                    effect: effect_seeds,
                };
                let (dir, cmd) = (
                    lib_dir.clone(),
                    std::env::args().collect::<Vec<_>>().join(" "),
                );
                ryade::harness::proc::set_kept(move || {
                    format!(
                        "the library runs finished so far are kept in {}; `{}` completes it",
                        dir.display(),
                        cmd
                    )
                });
                gap_run::make_library(
                    &root,
                    &lib_dir,
                    &sc,
                    counts,
                    fit_cycles,
                    engine == "fast",
                    jobs,
                )?;
            } else if !lib_dir.join("library.json").is_file() {
                bail!(
                    "no gap library at {} ({} missing): give --library with the folder of an existing one \
                     (a checkout has results/gap/library_r07_G_medium_c6), or build it there with --make-library \
                     (r07 G medium, 6 cycles: about 11 min on 2 cores)",
                    lib_dir.display(),
                    lib_dir.join("library.json").display()
                );
            }
            let (idx, lib) = gap_run::load_library(&lib_dir)?;
            // a diagnosis with test conditions given: they must be the library's
            if test != gap_run::TestConditions::default() {
                idx.check_test(&test)?;
            }
            if detectability {
                print!("{}", gap_run::format_detectability(&lib, fit_cycles));
                return Ok(ExitCode::SUCCESS);
            }
            if self_test {
                // with --observed: the library as that observation sees it (its observables)
                let lib = match &observed {
                    Some(f) => lib.restricted_to(&gap::read_observed(f)?),
                    None => lib,
                };
                let scores = gap_run::self_test(&lib, fit_cycles, jobs)?;
                let md = format!(
                    "# Self-test of the library {}\n\nEach run diagnosed by the library without its specimen; scored as a blind set (\"none\" right only under the floor).\n\n{}",
                    lib_dir.display(),
                    gap_run::format_self_test(&scores)
                );
                print!("{}", md);
                // kept with the library: every later diagnosis says how often its answer was right
                gap_run::keep_self_test(
                    &lib_dir,
                    gap_run::StoredSelfTest::new(&lib, fit_cycles, &scores),
                )?;
                std::fs::create_dir_all(&out)?;
                std::fs::write(out.join("self_test.md"), &md)?;
                std::fs::write(
                    out.join("self_test.json"),
                    serde_json::to_string_pretty(&scores)?,
                )?;
                println!(
                    "self-test: {}/self_test.{{md,json}}; kept with the library as {} (every diagnosis with it says how often its answer was right)",
                    out.display(),
                    lib_dir.join(gap_run::SELF_TEST_FILE).display()
                );
                return Ok(ExitCode::SUCCESS);
            }
            if let Some(d) = make_observed {
                // the blind runs are of the library's scenario
                idx.check_scenario(&sc)?;
                let design = gap_run::Design {
                    unfiltered,
                    n_clump,
                };
                gap_run::make_observed(
                    &root, &d, &sc, n, n_null, seed, jobs, &lib, fit_cycles, design,
                )?;
                println!(
                    "blind datasets in {}/cases (truth apart in {}/truth)",
                    d.display(),
                    d.display()
                );
                return Ok(ExitCode::SUCCESS);
            }
            if let Some(d) = validate {
                let scores = gap_run::validate(&d, &lib, fit_cycles)?;
                let table = gap_run::format_scores(&scores);
                print!("{}", table);
                std::fs::write(d.join("validation.md"), &table)?;
                std::fs::write(
                    d.join("validation.json"),
                    serde_json::to_string_pretty(&scores)?,
                )?;
                return Ok(ExitCode::SUCCESS);
            }
            if let Some(f) = observed {
                let obs = gap::read_observed(&f)?;
                // the library as the observation sees it (its observables)
                let lib = lib.restricted_to(&obs);
                let d = gap::diagnose(&lib, &obs, fit_cycles)?;
                std::fs::create_dir_all(&out)?;
                let name = f.display().to_string();
                // what this library can see comes before the diagnosis (issue 20)
                let report = format!(
                    "{}\n{}",
                    gap::report_markdown(&name, &d, &lib),
                    gap_run::format_reliability(&lib_dir, &lib, fit_cycles, &d.winner)
                );
                let detect = gap_run::format_detectability(&lib, fit_cycles);
                let md = format!("{}\n{}", report, detect);
                println!("{}", detect);
                std::fs::write(out.join("report.md"), &md)?;
                std::fs::write(out.join("report.json"), serde_json::to_string_pretty(&d)?)?;
                gap_run::write_plot_data(&out, &lib, &obs, &d)?;
                let (plot, png) = (out.join("plot.csv"), out.join("report.png"));
                ryade::harness::study_run::figures(&[
                    "gap",
                    &plot.to_string_lossy(),
                    &png.to_string_lossy(),
                ]);
                print!("{}", report);
                println!("report: {}/report.{{md,json,png}}", out.display());
                return Ok(ExitCode::SUCCESS);
            }
            if !make_library {
                bail!(
                    "give --observed FILE, --validate DIR, --self-test, --make-library or --make-observed DIR"
                );
            }
            print!("{}", gap_run::format_detectability(&lib, fit_cycles));
            println!("library in {}", lib_dir.display());
            Ok(ExitCode::SUCCESS)
        }
        Cmd::Scene { file, steps, out } => {
            let sf = scene_json::load(&file)?;
            let steps = steps.unwrap_or(sf.steps);
            let name = sf.name.clone();
            let mut scene = sf.scene;
            ryade::utils::check_time_step(&scene).map_err(anyhow::Error::msg)?;
            let grid = scene_json::to_value(&scene, 0)["format"] == scene_json::GRID_FORMAT_ID;
            let mut rec = Recorder::create_with(&out, &name, grid)?;
            rec.record(&scene)?;
            let bar = indicatif::ProgressBar::new(steps);
            bar.set_style(
                indicatif::ProgressStyle::with_template(
                    "{bar:40} {pos}/{len} steps {elapsed}<{eta}",
                )
                .unwrap(),
            );
            for _ in 0..steps {
                if let Err(e) = scene.step() {
                    bar.abandon();
                    eprintln!("stopped: {}", e);
                    eprintln!(
                        "records up to step {} are kept in {}",
                        scene.iter,
                        out.display()
                    );
                    return Ok(ExitCode::from(1));
                }
                rec.record(&scene)?;
                bar.inc(1);
            }
            bar.finish();
            println!("{} steps of {} recorded in {}", steps, name, out.display());
            Ok(ExitCode::SUCCESS)
        }
    }
}
