//! `compat calibrate --triaxial`: the element test of the aggregate model. Runs the periodic drained
//! triaxial test `yade_ref/calibration/triaxial.py` (YADE's PeriTriaxController; the script defines the
//! test and the per-variant results: peak and critical-state friction angles, maximum dilatancy angle,
//! initial porosity) for each variant on ryade (`compat run`) or YADE (`yade -n -x`), then writes the
//! merged curves (`triaxial.csv`), the per-variant table (`triaxial_summary.csv`, `triaxial.md`, also
//! printed) with the classical bearing-capacity estimate for the study's footing, and a plot of q/p and
//! volumetric strain against axial strain (`triaxial.png`).
//!
//! Bearing capacity (here only): a drained surface footing of width B on the layer,
//! q_ult = 0.5 γ B N_γ (strip), N_γ = 2 (N_q + 1) tan φ (Vesic 1973), N_q = e^(π tan φ) tan²(45° + φ/2),
//! with γ = 15.6 kN/m³ and B = 0.09 / 0.15 / 0.30 m (the study's piston diameters), against the study's
//! 275.8 kPa peak pressure. The circular form 0.3 γ B N_γ (shape factor 0.6, study.md) is given as the
//! required φ only.

use super::{read_json, run_plot, scripts_dir, Engine, Runner};
use anyhow::{anyhow, bail, Context, Result};
use serde_json::Value;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The plotting script (matplotlib), run with the output folder as argument.
const PLOT_PY: &str = include_str!("../../calibration/plot_triaxial.py");

/// Unit weight of the study's layer [N/m³] (study.md).
pub const GAMMA: f64 = 15.6e3;
/// The study's footing widths (piston diameters) [m]: tiny, medium, full.
pub const WIDTHS: [f64; 3] = [0.09, 0.15, 0.30];
/// The study's peak pressure [Pa].
pub const Q_PEAK: f64 = 275.8e3;

/// Options of `compat calibrate --triaxial`.
#[derive(Clone, Debug)]
pub struct Options {
    pub engine: Engine,
    pub out: PathBuf,
    pub quick: bool,
    /// Comma-separated variants (default: the script's DEFAULT_VARIANTS).
    pub variants: Option<String>,
    /// Variants run at the same time.
    pub jobs: usize,
    /// Folder with triaxial.py (default: yade_ref/calibration).
    pub scripts: Option<PathBuf>,
    /// Further arguments for the script (e.g. `--n=2000`).
    pub args: Vec<String>,
    pub plot: bool,
}

/// Vesic's bearing capacity factors (N_q, N_γ) of a friction angle in degrees.
pub fn vesic_factors(phi_deg: f64) -> (f64, f64) {
    let t = phi_deg.to_radians().tan();
    let nq = (std::f64::consts::PI * t).exp() * (45f64 + 0.5 * phi_deg).to_radians().tan().powi(2);
    (nq, 2.0 * (nq + 1.0) * t)
}

/// q_ult = shape · γ · B · N_γ(φ) [Pa] (shape 0.5: strip, 0.3: circular).
pub fn q_ult(phi_deg: f64, width: f64, shape: f64) -> f64 {
    shape * GAMMA * width * vesic_factors(phi_deg).1
}

/// The friction angle [deg] at which q_ult(φ, B, shape) equals `q` (bisection on 1..60 deg).
pub fn phi_required(q: f64, width: f64, shape: f64) -> f64 {
    let (mut lo, mut hi) = (1.0f64, 60.0f64);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if q_ult(mid, width, shape) < q {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The variants the script runs by default (its `DEFAULT_VARIANTS = '...'` line).
fn default_variants(script: &Path) -> Result<String> {
    let text =
        std::fs::read_to_string(script).with_context(|| format!("reading {}", script.display()))?;
    text.lines()
        .find_map(|l| l.strip_prefix("DEFAULT_VARIANTS = '"))
        .and_then(|l| l.strip_suffix('\''))
        .map(str::to_string)
        .ok_or_else(|| anyhow!("{} has no DEFAULT_VARIANTS line", script.display()))
}

/// One finished variant: the script's summary and the wall time of its run.
struct Done {
    variant: String,
    summary: Value,
    wall_s: f64,
}

fn num(s: &Value, k: &str) -> Result<f64> {
    s[k].as_f64()
        .ok_or_else(|| anyhow!("summary of {} has no number '{}'", s["variant"], k))
}

/// Runs the variants and writes the report. Returns Ok(true) when every variant finished.
pub fn run(opts: &Options) -> Result<bool> {
    let scripts = scripts_dir(&opts.scripts, "triaxial.py")?;
    let script = scripts.join("triaxial.py");
    let variants: Vec<String> = match &opts.variants {
        Some(v) => v.clone(),
        None => default_variants(&script)?,
    }
    .split(',')
    .map(|s| s.trim().to_string())
    .filter(|s| !s.is_empty())
    .collect();
    if variants.is_empty() {
        bail!("no variant to run (--variants)");
    }
    let jobs = opts.jobs.max(1);
    std::fs::create_dir_all(&opts.out)
        .with_context(|| format!("creating {}", opts.out.display()))?;
    let out = opts.out.canonicalize()?;
    let runs = out.join("runs");
    let cache = out.join("cache");
    std::fs::create_dir_all(&runs)?;
    println!(
        "calibrate --triaxial: {} variant(s) [{}] on {}{}, {} at a time; output {}",
        variants.len(),
        variants.join(", "),
        opts.engine,
        if opts.quick { " (--quick)" } else { "" },
        jobs,
        out.display()
    );
    let t0 = Instant::now();
    let queue = std::sync::Mutex::new(
        variants
            .iter()
            .cloned()
            .collect::<std::collections::VecDeque<_>>(),
    );
    let results = std::sync::Mutex::new(Vec::<(String, Result<f64>)>::new());
    std::thread::scope(|s| {
        for _ in 0..jobs.min(variants.len()) {
            s.spawn(|| loop {
                let Some(v) = queue.lock().unwrap().pop_front() else {
                    break;
                };
                let r = (|| -> Result<f64> {
                    let log = std::fs::File::create(runs.join(format!("{}.log", v)))?;
                    let mut runner = Runner {
                        engine: opts.engine,
                        scripts: scripts.clone(),
                        log,
                    };
                    let mut args: Vec<String> = vec![
                        "--".into(),
                        "--variant".into(),
                        v.clone(),
                        "--out".into(),
                        runs.to_string_lossy().into(),
                        "--cache".into(),
                        cache.to_string_lossy().into(),
                    ];
                    if opts.quick {
                        args.push("--quick".into());
                    }
                    args.extend(opts.args.iter().cloned());
                    let t = Instant::now();
                    runner.run("triaxial.py", &args)?;
                    Ok(t.elapsed().as_secs_f64())
                })();
                if let Err(e) = &r {
                    eprintln!("calibrate --triaxial: variant {} failed: {:#}", v, e);
                }
                results.lock().unwrap().push((v, r));
            });
        }
    });
    let wall_total = t0.elapsed().as_secs_f64();
    let results = results.into_inner().unwrap();
    let mut done = Vec::new();
    let mut failed = Vec::new();
    for v in &variants {
        match results.iter().find(|(n, _)| n == v) {
            Some((_, Ok(w))) => done.push(Done {
                variant: v.clone(),
                summary: read_json(&runs.join(format!("{}.summary.json", v)))?,
                wall_s: *w,
            }),
            _ => failed.push(v.clone()),
        }
    }
    if done.is_empty() {
        bail!(
            "no variant finished ({}); see the logs in {}",
            failed.join(", "),
            runs.display()
        );
    }
    write_curves(&runs, &out, &done)?;
    let md = report(opts, &done, &failed, wall_total)?;
    std::fs::write(out.join("triaxial.md"), &md)?;
    write_summary_csv(&out, &done)?;
    println!("\n{}", md);
    if opts.plot {
        match run_plot(PLOT_PY, &out) {
            Ok(files) => println!("  plots: {}", files.join(", ")),
            Err(e) => eprintln!(
                "warning: plot not made ({:#}); the curves are in triaxial.csv",
                e
            ),
        }
    }
    println!("  report: {}", out.join("triaxial.md").display());
    Ok(failed.is_empty())
}

/// `triaxial.csv`: every variant's curve rows, with the variant name as first column.
fn write_curves(runs: &Path, out: &Path, done: &[Done]) -> Result<()> {
    let mut text = String::new();
    for (k, d) in done.iter().enumerate() {
        let p = runs.join(format!("{}.curve.csv", d.variant));
        let c = std::fs::read_to_string(&p).with_context(|| format!("reading {}", p.display()))?;
        for (i, l) in c.lines().enumerate() {
            if i == 0 {
                if k == 0 {
                    writeln!(text, "variant,{}", l)?;
                }
            } else {
                writeln!(text, "{},{}", d.variant, l)?;
            }
        }
    }
    std::fs::write(out.join("triaxial.csv"), text)?;
    Ok(())
}

/// `triaxial_summary.csv`: one row per variant.
fn write_summary_csv(out: &Path, done: &[Done]) -> Result<()> {
    const KEYS: [&str; 12] = [
        "n_particles",
        "porosity_0",
        "phi_peak_deg",
        "eps_a_peak",
        "q_over_p_peak",
        "phi_cv_deg",
        "q_over_p_cv",
        "psi_max_deg",
        "eps_a_psi_max",
        "eps_v_end",
        "inertial_number",
        "steps_shear",
    ];
    let mut t = format!("variant,{},wall_s", KEYS.join(","));
    for b in WIDTHS {
        write!(t, ",q_ult_peak_B{}_kPa,q_ult_cv_B{}_kPa", b, b)?;
    }
    t.push('\n');
    for d in done {
        write!(t, "{}", d.variant)?;
        for k in KEYS {
            write!(t, ",{}", num(&d.summary, k)?)?;
        }
        write!(t, ",{:.1}", d.wall_s)?;
        let (pk, cv) = (
            num(&d.summary, "phi_peak_deg")?,
            num(&d.summary, "phi_cv_deg")?,
        );
        for b in WIDTHS {
            write!(
                t,
                ",{:.1},{:.1}",
                q_ult(pk, b, 0.5) / 1e3,
                q_ult(cv, b, 0.5) / 1e3
            )?;
        }
        t.push('\n');
    }
    std::fs::write(out.join("triaxial_summary.csv"), t)?;
    Ok(())
}

/// The markdown report: results per variant, bearing capacity, required friction angles.
fn report(opts: &Options, done: &[Done], failed: &[String], wall_total: f64) -> Result<String> {
    let s0 = &done[0].summary;
    let mut m = String::new();
    writeln!(
        m,
        "# Periodic drained triaxial test of the aggregate model\n"
    )?;
    writeln!(
        m,
        "{} on {}: d = {} m, E = {:e} Pa, ks/kn = {}, friction {} deg, density {} kg/m3, local damping {}; \
         isotropic p0 = {} kPa, then lateral stress p0 and axial log strain to {} at {:.3} 1/s (inertial number {:.1e}). \
         Results per variant as defined in yade_ref/calibration/triaxial.py (phi_peak: max of sin(phi_mob) \
         smoothed over 0.5 % strain; phi_cv: mean over the last 0.05 of strain; psi_max: triaxial dilatancy angle \
         from d(eps_v)/d(eps_a) over 0.02 windows; n0: porosity at the start of shear).\n",
        if opts.quick { "Quick run" } else { "Full run" },
        opts.engine,
        num(s0, "d")?,
        num(s0, "young")?,
        num(s0, "poisson")?,
        num(s0, "friction_deg")?,
        num(s0, "density")?,
        num(s0, "damping")?,
        num(s0, "p0")? / 1e3,
        num(s0, "eps_max")?,
        num(s0, "rate")?,
        num(s0, "inertial_number")?,
    )?;
    writeln!(
        m,
        "| variant | particles | n0 | phi_peak [deg] | eps_a at peak | q/p peak | phi_cv [deg] | q/p cv | psi_max [deg] | eps_v end | wall [s] |"
    )?;
    writeln!(m, "|---|---|---|---|---|---|---|---|---|---|---|")?;
    for d in done {
        let s = &d.summary;
        writeln!(
            m,
            "| {} | {} | {:.4} | {:.2} | {:.3} | {:.3} | {:.2} | {:.3} | {:.2} | {:+.4} | {:.1} |",
            d.variant,
            num(s, "n_particles")?,
            num(s, "porosity_0")?,
            num(s, "phi_peak_deg")?,
            num(s, "eps_a_peak")?,
            num(s, "q_over_p_peak")?,
            num(s, "phi_cv_deg")?,
            num(s, "q_over_p_cv")?,
            num(s, "psi_max_deg")?,
            num(s, "eps_v_end")?,
            d.wall_s
        )?;
    }
    if !failed.is_empty() {
        writeln!(
            m,
            "\nFailed (see runs/<variant>.log): {}",
            failed.join(", ")
        )?;
    }
    writeln!(m, "\nWall time in all: {:.0} s.\n", wall_total)?;
    writeln!(
        m,
        "## Bearing capacity of the study's footing\n\nDrained surface footing of width B on the layer, \
         q_ult = 0.5 gamma B N_gamma, N_gamma = 2 (N_q + 1) tan phi (Vesic), gamma = {} kN/m3; in kPa, with the ratio \
         to the study's {} kPa peak pressure (< 1: the footing punches through).\n",
        GAMMA / 1e3,
        Q_PEAK / 1e3
    )?;
    write!(m, "| variant | phi [deg] | N_gamma |")?;
    for b in WIDTHS {
        write!(m, " B = {} m |", b)?;
    }
    writeln!(m)?;
    writeln!(m, "|---|---|---|---|---|---|")?;
    for d in done {
        for (label, key) in [("peak", "phi_peak_deg"), ("cv", "phi_cv_deg")] {
            let phi = num(&d.summary, key)?;
            write!(
                m,
                "| {} ({}) | {:.2} | {:.1} |",
                d.variant,
                label,
                phi,
                vesic_factors(phi).1
            )?;
            for b in WIDTHS {
                let q = q_ult(phi, b, 0.5);
                write!(m, " {:.1} ({:.2}) |", q / 1e3, q / Q_PEAK)?;
            }
            writeln!(m)?;
        }
    }
    write!(m, "\nFriction angle needed to carry {} kPa:", Q_PEAK / 1e3)?;
    for b in WIDTHS {
        write!(
            m,
            " B = {} m: {:.1} deg (strip, 0.5 gamma B N_gamma), {:.1} deg (circular, 0.3 gamma B N_gamma);",
            b,
            phi_required(Q_PEAK, b, 0.5),
            phi_required(Q_PEAK, b, 0.3)
        )?;
    }
    m.pop();
    writeln!(m, ".")?;
    Ok(m)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vesic_factors_match_the_tables() {
        // Vesic (1973) as tabulated (e.g. Das, Principles of Foundation Engineering): phi 30 deg:
        // Nq 18.40, N_gamma 22.40; phi 40 deg: Nq 64.20, N_gamma 109.41
        let (nq, ng) = vesic_factors(30.0);
        assert!(
            (nq - 18.40).abs() < 0.01 && (ng - 22.40).abs() < 0.01,
            "{} {}",
            nq,
            ng
        );
        let (nq, ng) = vesic_factors(40.0);
        assert!(
            (nq - 64.20).abs() < 0.01 && (ng - 109.41).abs() < 0.02,
            "{} {}",
            nq,
            ng
        );
    }

    #[test]
    fn required_phi_inverts_q_ult() {
        for b in WIDTHS {
            let phi = phi_required(Q_PEAK, b, 0.5);
            assert!((q_ult(phi, b, 0.5) / Q_PEAK - 1.0).abs() < 1e-9);
        }
        // study.md: 0.3 gamma B N_gamma needs N_gamma ~ 200 at B = 0.30 m (phi ~ 43 deg)
        let ng = Q_PEAK / (0.3 * GAMMA * 0.30);
        assert!((ng - 196.4).abs() < 0.1, "{}", ng);
        assert!((phi_required(Q_PEAK, 0.30, 0.3) - 43.3).abs() < 0.3);
    }
}
