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
    /// Compare ryade with YADE's golden records. Targets: `micro` and `micro_grid` (bit for bit,
    /// every step), `meso`.
    Diff {
        /// What to compare: micro | micro_grid | meso
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
    },
    /// Run an unmodified YADE script (as `yade -n -x script.py args`) on ryade.
    #[command(trailing_var_arg = true)]
    Run {
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
        /// Thread counts for the fast path, comma-separated (e.g. 1,2)
        #[arg(long, default_value = "1,2")]
        threads: String,
        /// Time ryade only
        #[arg(long)]
        no_yade: bool,
        /// Append the report (JSON lines) to this log file
        #[arg(long)]
        log: Option<PathBuf>,
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
    match run(cli) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {:#}", e);
            ExitCode::from(2)
        }
    }
}

/// The Python that has the `yade` compat package installed (`RYADE_PYTHON`, default `python3`).
fn python(module: &str, args: &[std::ffi::OsString]) -> Result<ExitCode> {
    let py = std::env::var_os("RYADE_PYTHON").unwrap_or_else(|| "python3".into());
    let status = std::process::Command::new(&py)
        .arg("-m")
        .arg(module)
        .args(args)
        .status()
        .with_context(|| {
            format!(
                "starting {:?} (set RYADE_PYTHON to the Python that has the yade package)",
                py
            )
        })?;
    Ok(match status.code() {
        Some(0) => ExitCode::SUCCESS,
        Some(c) => ExitCode::from(c.clamp(1, 255) as u8),
        None => ExitCode::from(1),
    })
}

fn run(cli: Cli) -> Result<ExitCode> {
    match cli.cmd {
        Cmd::Run { script, args } => {
            let mut a: Vec<std::ffi::OsString> = vec![script.into_os_string()];
            a.extend(args.into_iter().map(Into::into));
            python("yade.runner", &a)
        }
        Cmd::Batch { args } => {
            let a: Vec<std::ffi::OsString> = args.into_iter().map(Into::into).collect();
            python("yade.batch", &a)
        }
        Cmd::Diff {
            target,
            golden,
            only,
            json,
        } => {
            let dir = golden.unwrap_or_else(|| PathBuf::from("golden").join(&target));
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
            if target != "micro" && target != "micro_grid" {
                bail!(
                    "unknown diff target '{}': available targets are: micro, micro_grid, meso",
                    target
                );
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
            if path == "yade" || path == "all" {
                variants.push(Variant::YadeOrder);
            }
            if path == "fast" || path == "all" {
                for t in threads.split(',') {
                    let t: usize = t
                        .trim()
                        .parse()
                        .map_err(|_| anyhow::anyhow!("--threads: '{}' is not a count", t))?;
                    if t == 0 {
                        bail!("--threads: counts start at 1");
                    }
                    variants.push(Variant::Fast(t));
                }
            }
            if !matches!(path.as_str(), "yade" | "fast" | "all") {
                bail!("--path: yade, fast or all, not '{}'", path);
            }
            let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
            for sc in &scenes {
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
