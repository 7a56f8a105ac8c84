//! `compat calibrate`: fits the geogrid rib model's stiffness multipliers to datasheet targets.
//!
//! Procedure (designed in calibration/README.md): step 1 runs the single-rib tensile test
//! (`yade_ref/calibration/tensile.py`, ASTM D6637) at `kn_scale = 1`, takes the closed-form relative
//! least-squares `kn_scale` (the bond is linear) and re-runs at it to report the residual per strain;
//! step 2 bisects `k = kr_scale = ktw_scale / ratio` in log k on the 45-degree overhang of the
//! cantilever test (`cantilever.py`, ASTM D7748), starting from the beam scaling Lo45 ~ k^(1/3).
//! The model tests are the unmodified YADE scripts, run either on ryade (`compat run`) or on YADE
//! (`yade -n -x`). Targets come from a TOML file (calibration/tx190l.toml); empty strings are missing
//! values and stop the fit before anything runs. Results are written to `calibration.json` after every
//! model run (a crash loses nothing already computed), plots by a small matplotlib script.

pub mod triaxial;

use anyhow::{anyhow, bail, Context, Result};
use serde_json::{json, Value};
use std::fmt;
use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Instant;

/// Overhang at 45 deg of the study's rib with every scale factor 1 (golden/calibration/cantilever.json,
/// YADE 2023.02a, quadratic interpolation). Used only for the starting guess of step 2.
pub const LO45_REF_MM: f64 = 817.6004951404133;
/// The study's rib radius and density, at which [`LO45_REF_MM`] was obtained (yade_ref/calibration).
pub const R_REF: f64 = 0.002;
pub const RHO_REF: f64 = 950.0;

/// The plotting script (matplotlib), run with the result file as argument.
const PLOT_PY: &str = include_str!("../calibration/plot_fit.py");

/// Which DEM code runs the model tests.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Engine {
    /// ryade: the current executable's `run` subcommand (`compat run script.py args`).
    Ryade,
    /// YADE: `yade -n -x script.py args` (the `YADE` environment variable overrides the command).
    Yade,
}

impl std::str::FromStr for Engine {
    type Err = anyhow::Error;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "ryade" => Ok(Engine::Ryade),
            "yade" => Ok(Engine::Yade),
            _ => bail!("unknown engine '{}': ryade | yade", s),
        }
    }
}

impl fmt::Display for Engine {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Engine::Ryade => "ryade",
            Engine::Yade => "yade",
        })
    }
}

/// Options of `compat calibrate`.
#[derive(Clone, Debug)]
pub struct Options {
    pub targets: PathBuf,
    pub engine: Engine,
    pub out: PathBuf,
    /// Step 2 stops after one cantilever evaluation (a smoke test of the whole chain).
    pub quick: bool,
    /// Starting k of step 2 (default: the beam scaling from [`LO45_REF_MM`]).
    pub k0: Option<f64>,
    /// Most cantilever evaluations (Lo45 runs) in step 2.
    pub max_evals: usize,
    /// Overrides [fit] overhang_tolerance_mm.
    pub tol_mm: Option<f64>,
    /// Folder with tensile.py and cantilever.py (default: yade_ref/calibration of this checkout).
    pub scripts: Option<PathBuf>,
    pub plot: bool,
}

/// The datasheet targets and fit settings read from the TOML file.
#[derive(Clone, Debug)]
pub struct Targets {
    pub path: PathBuf,
    pub product: String,
    /// Strains of the secant targets ([tensile] strains) and the targets in kN per unit strain, per rib.
    pub strains: Vec<f64>,
    pub secant_keys: Vec<String>,
    pub secant_kn: Vec<f64>,
    /// [flexural] overhang_45deg_mm.
    pub overhang_mm: f64,
    pub target_angle_deg: f64,
    /// Rib pitch a [m] ([geometry] rib_pitch_mm).
    pub a: f64,
    /// Step 0: rib radius from [rib] area_mm2 and density from [mass] mass_per_area_g_m2 (None: the
    /// scripts' defaults r = 2 mm, rho = 950 kg/m^3).
    pub r: Option<f64>,
    pub rho: Option<f64>,
    pub ks_scale: f64,
    pub ktw_over_kr: f64,
    pub tol_mm: f64,
    /// Remarks printed before the fit (step 0 skipped, ...).
    pub notes: Vec<String>,
}

/// Required targets that are empty or absent in the TOML file: the fit cannot run.
#[derive(Debug)]
pub struct MissingTargets {
    pub path: PathBuf,
    /// (TOML key as `[section] key`, what it is and where to get it)
    pub missing: Vec<(String, String)>,
    pub optional_empty: Vec<String>,
}

impl fmt::Display for MissingTargets {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "{}: {} required target(s) missing (an empty string means no value):",
            self.path.display(),
            self.missing.len()
        )?;
        for (k, hint) in &self.missing {
            writeln!(f, "  {:<30} {}", k, hint)?;
        }
        writeln!(
            f,
            "Fill them in as plain TOML numbers in the units of the key name, and cite the source next to \
             each (document, revision date, page/table): Tensar's product specification for TX190L, or your \
             own ASTM D6637 (single rib) / D7748 (cantilever) tests. The comments in the file say more; \
             calibration/README.md describes the fit. Do not copy numbers without a source."
        )?;
        if !self.optional_empty.is_empty() {
            writeln!(
                f,
                "Optional (step 0), also empty: {} (without them the fit uses the study's r = 2 mm and \
                 rho = 950 kg/m^3).",
                self.optional_empty.join(", ")
            )?;
        }
        write!(f, "Nothing was run.")
    }
}

impl std::error::Error for MissingTargets {}

/// TOML key of the secant target at strain `e` (0.02 -> `secant_2pct_kN`, 0.005 -> `secant_0p5pct_kN`).
pub fn secant_key(e: f64) -> String {
    let pct = e * 100.0;
    let s = if (pct - pct.round()).abs() < 1e-9 {
        format!("{}", pct.round() as i64)
    } else {
        format!("{}", (pct * 1e9).round() / 1e9).replace('.', "p")
    };
    format!("secant_{}pct_kN", s)
}

/// A number, or None for an empty string / absent key; any other value is an error.
fn num(doc: &toml::Table, sect: &str, key: &str) -> Result<Option<f64>> {
    let v = match doc
        .get(sect)
        .and_then(|s| s.as_table())
        .and_then(|t| t.get(key))
    {
        None => return Ok(None),
        Some(v) => v,
    };
    match v {
        toml::Value::Float(x) => Ok(Some(*x)),
        toml::Value::Integer(i) => Ok(Some(*i as f64)),
        toml::Value::String(s) if s.trim().is_empty() => Ok(None),
        other => bail!(
            "[{}] {} = {} is not a number: write a plain TOML number (no quotes, no unit) or leave it \"\" \
             when no source is available",
            sect,
            key,
            other
        ),
    }
}

fn positive(v: Option<f64>, what: &str) -> Result<Option<f64>> {
    match v {
        Some(x) if !(x.is_finite() && x > 0.0) => {
            bail!("{} must be a positive number, got {}", what, x)
        }
        _ => Ok(v),
    }
}

impl Targets {
    /// Reads and checks a targets file. Missing required values give a [`MissingTargets`] error.
    pub fn load(path: &Path) -> Result<Targets> {
        let text =
            std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
        let doc: toml::Table = toml::from_str(&text)
            .with_context(|| format!("{} is not valid TOML", path.display()))?;
        let product = doc
            .get("product")
            .and_then(|p| p.get("name"))
            .and_then(|n| n.as_str())
            .unwrap_or("(unnamed product)")
            .to_string();
        let strains: Vec<f64> = match doc.get("tensile").and_then(|t| t.get("strains")) {
            None => vec![0.02, 0.05],
            Some(v) => v
                .as_array()
                .and_then(|a| {
                    a.iter()
                        .map(|x| x.as_float().or_else(|| x.as_integer().map(|i| i as f64)))
                        .collect::<Option<Vec<f64>>>()
                })
                .ok_or_else(|| anyhow!("[tensile] strains must be a list of numbers"))?,
        };
        if strains.is_empty() || strains.iter().any(|e| !(*e > 0.0 && *e < 0.1)) {
            bail!(
                "[tensile] strains = {:?}: give one or more strains in (0, 0.1) (tensile.py strains the rib \
                 to 10 %)",
                strains
            );
        }
        let mut missing = Vec::new();
        let mut secant_keys = Vec::new();
        let mut secant_kn = Vec::new();
        for &e in &strains {
            let key = secant_key(e);
            match positive(num(&doc, "tensile", &key)?, &format!("[tensile] {}", key))? {
                Some(x) => secant_kn.push(x),
                None => missing.push((
                    format!("[tensile] {}", key),
                    format!(
                        "single-rib secant stiffness at {} % strain, kN per unit strain per rib (ASTM D6637 \
                         single-rib method; per-width kN/m values must be divided by the ribs per metre)",
                        (e * 1e11).round() / 1e9
                    ),
                )),
            }
            secant_keys.push(key);
        }
        let overhang = positive(
            num(&doc, "flexural", "overhang_45deg_mm")?,
            "[flexural] overhang_45deg_mm",
        )?;
        if overhang.is_none() {
            let mut hint =
                "overhang [mm] at which the tip of a strip two apertures wide makes the target \
                            angle with the horizontal (ASTM D7748 cantilever test of the product)"
                    .to_string();
            if num(&doc, "flexural", "flexural_rigidity_mg_cm")?.is_some() {
                hint.push_str(
                    "; [flexural] flexural_rigidity_mg_cm is filled in, but converting it needs D7748's \
                     formula and the specimen's mass per area: convert it yourself and cite both",
                );
            }
            missing.push(("[flexural] overhang_45deg_mm".into(), hint));
        }
        let area = positive(num(&doc, "rib", "area_mm2")?, "[rib] area_mm2")?;
        let mass = positive(
            num(&doc, "mass", "mass_per_area_g_m2")?,
            "[mass] mass_per_area_g_m2",
        )?;
        let mut optional_empty = Vec::new();
        if area.is_none() {
            optional_empty.push("[rib] area_mm2".to_string());
        }
        if mass.is_none() {
            optional_empty.push("[mass] mass_per_area_g_m2".to_string());
        }
        if !missing.is_empty() {
            return Err(MissingTargets {
                path: path.to_path_buf(),
                missing,
                optional_empty,
            }
            .into());
        }
        let a = positive(
            num(&doc, "geometry", "rib_pitch_mm")?,
            "[geometry] rib_pitch_mm",
        )?
        .unwrap_or(60.0)
            * 1e-3;
        let mut notes = Vec::new();
        let r = area.map(|am| (am * 1e-6 / std::f64::consts::PI).sqrt());
        let r_used = r.unwrap_or(R_REF);
        // model mass per plan area = 6 pi r^2 rho / (a sqrt 3)  (calibration/README.md, step 0)
        let rho = mass
            .map(|m| m * 1e-3 * a * 3f64.sqrt() / (6.0 * std::f64::consts::PI * r_used * r_used));
        match r {
            Some(r) => notes.push(format!(
                "step 0: r = sqrt(area / pi) = {:.6} mm from [rib] area_mm2",
                r * 1e3
            )),
            None => notes.push(
                "step 0 skipped for r: [rib] area_mm2 is empty, the study's r = 2 mm is used"
                    .into(),
            ),
        }
        match rho {
            Some(x) => notes.push(format!(
                "step 0: rho = {:.3} kg/m^3 reproduces [mass] mass_per_area_g_m2",
                x
            )),
            None => notes.push(
                "step 0 skipped for rho: [mass] mass_per_area_g_m2 is empty, the study's rho = 950 kg/m^3 \
                 is used (the fitted bending stiffness then absorbs any weight difference)"
                    .into(),
            ),
        }
        let fit = |k: &str, d: f64| -> Result<f64> {
            Ok(positive(num(&doc, "fit", k)?, &format!("[fit] {}", k))?.unwrap_or(d))
        };
        let target_angle_deg = positive(
            num(&doc, "flexural", "target_angle_deg")?,
            "[flexural] target_angle_deg",
        )?
        .unwrap_or(45.0);
        if target_angle_deg >= 90.0 {
            bail!("[flexural] target_angle_deg must be below 90");
        }
        Ok(Targets {
            path: path.to_path_buf(),
            product,
            strains,
            secant_keys,
            secant_kn,
            overhang_mm: overhang.unwrap(),
            target_angle_deg,
            a,
            r,
            rho,
            ks_scale: fit("ks_scale", 1.0)?,
            ktw_over_kr: fit("ktw_over_kr_scale", 1.0)?,
            tol_mm: fit("overhang_tolerance_mm", 1.0)?,
            notes,
        })
    }
}

/// Closed-form minimiser of sum_i ((s S_i - T_i) / T_i)^2: s = sum(S/T) / sum((S/T)^2).
pub fn kn_scale_lsq(model: &[f64], targets: &[f64]) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for (s, t) in model.iter().zip(targets) {
        let q = s / t;
        num += q;
        den += q * q;
    }
    num / den
}

/// C-style `%+.3e` (exponent with sign and two digits), for the residual table.
fn e3(x: f64) -> String {
    let s = format!("{:+.3e}", x);
    match s.split_once('e') {
        Some((m, e)) => {
            let (sign, digits) = match e.strip_prefix('-') {
                Some(d) => ('-', d),
                None => ('+', e),
            };
            format!("{}e{}{:0>2}", m, sign, digits)
        }
        None => s,
    }
}

/// A number as a `key=value` argument of the YADE scripts (JSON, shortest round-trip form).
fn jnum(x: f64) -> String {
    serde_json::to_string(&x).expect("finite number")
}

fn jstr(p: &Path) -> String {
    serde_json::to_string(&p.to_string_lossy()).unwrap()
}

/// The folder of the calibration scripts: `given`, else yade_ref/calibration of the working directory or
/// of this checkout (the first that holds `probe`), canonicalized.
fn scripts_dir(given: &Option<PathBuf>, probe: &str) -> Result<PathBuf> {
    let dir = match given {
        Some(s) => s.clone(),
        None => {
            let mut c = vec![PathBuf::from("yade_ref/calibration")];
            c.push(crate::harness::env::repo_root()?.join("yade_ref/calibration"));
            c.into_iter()
                .find(|c| c.join(probe).is_file())
                .ok_or_else(|| {
                    anyhow!(
                        "yade_ref/calibration/{} not found: pass --scripts DIR (or set RYADE_ROOT to a ryade checkout)",
                        probe
                    )
                })?
        }
    };
    dir.canonicalize()
        .with_context(|| format!("scripts folder {}", dir.display()))
}

/// Runs the model scripts on the chosen engine, echoing their output (progress) and logging it.
struct Runner {
    engine: Engine,
    scripts: PathBuf,
    log: std::fs::File,
}

fn is_banner(l: &str) -> bool {
    [
        "Welcome to Yade",
        "Using python version",
        "TCP python prompt",
        "XMLRPC info provider",
        "Running script",
    ]
    .iter()
    .any(|b| l.starts_with(b))
}

impl Runner {
    fn run(&mut self, script: &str, args: &[String]) -> Result<()> {
        let path = self.scripts.join(script);
        let mut cmd = match self.engine {
            Engine::Ryade => {
                let mut c = Command::new(crate::harness::env::compat_exe()?);
                c.arg("run");
                c
            }
            Engine::Yade => {
                let y = std::env::var("YADE").unwrap_or_else(|_| "yade".into());
                let mut c = Command::new(y);
                c.args(["-n", "-x"]);
                c.env("OMP_NUM_THREADS", "1");
                c
            }
        };
        cmd.arg(&path).args(args).env("PYTHONUNBUFFERED", "1");
        let shown = format!(
            "{} {} {}",
            match self.engine {
                Engine::Ryade => "compat run",
                Engine::Yade => "yade -n -x",
            },
            path.display(),
            args.join(" ")
        );
        writeln!(self.log, "$ {}", shown)?;
        cmd.stdout(Stdio::piped()).stderr(Stdio::piped());
        let mut tracked =
            crate::harness::proc::spawn(&mut cmd).with_context(|| match self.engine {
                Engine::Yade => format!(
                    "starting YADE for `{}` (is `yade` installed? set YADE to its command)",
                    shown
                ),
                Engine::Ryade => format!("starting `{}`", shown),
            })?;
        let stderr = tracked.child.stderr.take().unwrap();
        let err_thread = std::thread::spawn(move || {
            BufReader::new(stderr)
                .lines()
                .map_while(|l| l.ok())
                .collect::<Vec<String>>()
        });
        let mut tail: Vec<String> = Vec::new();
        for line in BufReader::new(tracked.child.stdout.take().unwrap()).lines() {
            let line = line?;
            writeln!(self.log, "{}", line)?;
            if !is_banner(&line) {
                println!("    | {}", line);
                std::io::stdout().flush().ok();
            }
            tail.push(line);
            if tail.len() > 20 {
                tail.remove(0);
            }
        }
        let status = tracked.wait()?;
        let err = err_thread.join().unwrap_or_default();
        for l in &err {
            writeln!(self.log, "{}", l)?;
        }
        if !status.success() {
            let e: Vec<&String> = err.iter().rev().take(20).collect::<Vec<_>>();
            let e: Vec<&str> = e.into_iter().rev().map(|s| s.as_str()).collect();
            bail!(
                "model run failed ({}): {}\n--- stdout (end) ---\n{}\n--- stderr (end) ---\n{}",
                status,
                shown,
                tail.join("\n"),
                e.join("\n")
            );
        }
        Ok(())
    }
}

fn read_json(p: &Path) -> Result<Value> {
    let t = std::fs::read_to_string(p).with_context(|| format!("reading {}", p.display()))?;
    serde_json::from_str(&t).with_context(|| format!("parsing {}", p.display()))
}

fn write_json(p: &Path, v: &Value) -> Result<()> {
    let tmp = p.with_extension("json.tmp");
    std::fs::write(&tmp, serde_json::to_string_pretty(v)? + "\n")
        .with_context(|| format!("writing {}", tmp.display()))?;
    std::fs::rename(&tmp, p).with_context(|| format!("writing {}", p.display()))
}

/// Secants [kN] at `strains` from a tensile.py summary (its keys are the strains printed with %g).
fn secants_from_summary(s: &Value, strains: &[f64]) -> Result<Vec<f64>> {
    let m = s["secant_stiffness_kN"]
        .as_object()
        .ok_or_else(|| anyhow!("tensile summary has no secant_stiffness_kN"))?;
    strains
        .iter()
        .map(|&e| {
            m.iter()
                .find(|(k, _)| k.parse::<f64>().is_ok_and(|x| (x - e).abs() <= 1e-12 * e))
                .and_then(|(_, v)| v.as_f64())
                .ok_or_else(|| anyhow!("tensile summary has no secant at strain {}", e))
        })
        .collect()
}

/// One Lo45 evaluation of step 2.
#[derive(Clone, Debug)]
pub struct CantEval {
    pub k: f64,
    pub lo45_mm: f64,
    pub file: String,
}

/// The whole fit. Returns Ok(true) when every target is reproduced within its tolerance
/// (quick mode: when the one evaluation done is), Ok(false) otherwise.
pub fn calibrate(opts: &Options) -> Result<bool> {
    let mut t = Targets::load(&opts.targets)?;
    if let Some(tol) = opts.tol_mm {
        if !(tol.is_finite() && tol > 0.0) {
            bail!("--tolerance-mm must be positive");
        }
        t.tol_mm = tol;
        t.notes
            .push(format!("overhang tolerance {} mm (--tolerance-mm)", tol));
    }
    let scripts = scripts_dir(&opts.scripts, "tensile.py")?;
    for s in ["tensile.py", "cantilever.py"] {
        if !scripts.join(s).is_file() {
            bail!("{} not found in {}", s, scripts.display());
        }
    }
    std::fs::create_dir_all(&opts.out)
        .with_context(|| format!("creating {}", opts.out.display()))?;
    let out = opts.out.canonicalize()?;
    let result_path = out.join("calibration.json");
    let mut runner = Runner {
        engine: opts.engine,
        scripts: scripts.clone(),
        log: std::fs::File::create(out.join("calibrate.log"))?,
    };

    println!(
        "compat calibrate: {} ({}), engine {}, output {}",
        t.path.display(),
        t.product,
        opts.engine,
        out.display()
    );
    for n in &t.notes {
        println!("  {}", n);
    }
    let mut common = vec![format!("a={}", jnum(t.a))];
    if let Some(r) = t.r {
        common.push(format!("r={}", jnum(r)));
    }
    if let Some(rho) = t.rho {
        common.push(format!("rho={}", jnum(rho)));
    }
    let mut res = json!({
        "tool": "compat calibrate (ryade), procedure: calibration/README.md",
        "targets_file": t.path.to_string_lossy(),
        "product": t.product,
        "engine": opts.engine.to_string(),
        "quick": opts.quick,
        "model_args": common,
        "notes": t.notes,
        "targets": {
            "strains": t.strains,
            "secant_kN": t.secant_kn,
            "secant_keys": t.secant_keys,
            "overhang_45deg_mm": t.overhang_mm,
            "target_angle_deg": t.target_angle_deg,
        },
        "fit_settings": {"ks_scale": t.ks_scale, "ktw_over_kr_scale": t.ktw_over_kr,
                         "overhang_tolerance_mm": t.tol_mm, "max_evals": opts.max_evals},
        "status": "running step 1",
    });
    write_json(&result_path, &res)?;

    // ---- step 1: kn_scale from the tensile secants
    println!(
        "== step 1: rib axial stiffness (kn_scale) from the single-rib tensile test (ASTM D6637)"
    );
    let tensile = |runner: &mut Runner, s: f64, tag: &str| -> Result<Vec<f64>> {
        let csv = out.join(format!("tensile_{}.csv", tag));
        let sum = out.join(format!("tensile_{}.summary.json", tag));
        let mut a = common.clone();
        a.push(format!("kn_scale={}", jnum(s)));
        a.push(format!(
            "secant_strains={}",
            serde_json::to_string(&t.strains).unwrap()
        ));
        a.push(format!("out={}", jstr(&csv)));
        a.push(format!("summary={}", jstr(&sum)));
        runner.run("tensile.py", &a)?;
        secants_from_summary(&read_json(&sum)?, &t.strains)
    };
    let base = tensile(&mut runner, 1.0, "scale1")?;
    let s_star = kn_scale_lsq(&base, &t.secant_kn);
    println!(
        "  model secants at kn_scale = 1: {:?} kN -> relative least squares kn_scale = {}",
        base, s_star
    );
    res["step1"] = json!({"baseline_kn_scale": 1.0, "baseline_secant_kN": base,
                          "baseline_files": ["tensile_scale1.csv", "tensile_scale1.summary.json"],
                          "kn_scale": s_star});
    write_json(&result_path, &res)?;
    let fitted = tensile(&mut runner, s_star, "fit")?;
    let resid: Vec<f64> = fitted
        .iter()
        .zip(&t.secant_kn)
        .map(|(s, t)| (s - t) / t)
        .collect();
    let rms = (resid.iter().map(|r| r * r).sum::<f64>() / resid.len() as f64).sqrt();
    let linear_dev = fitted
        .iter()
        .zip(&base)
        .map(|(f, b)| (f / b / s_star - 1.0).abs())
        .fold(0.0, f64::max);
    res["step1"]["fitted_secant_kN"] = json!(fitted);
    res["step1"]["fitted_files"] = json!(["tensile_fit.csv", "tensile_fit.summary.json"]);
    res["step1"]["residuals_rel"] = json!(resid);
    res["step1"]["residual_rms"] = json!(rms);
    res["step1"]["linearity_max_rel_dev"] = json!(linear_dev);
    res["status"] = json!("running step 2");
    write_json(&result_path, &res)?;

    // ---- step 2: k = kr_scale (ktw_scale = ratio * k) from the 45-deg overhang
    println!(
        "== step 2: bending and torsion (kr_scale = k, ktw_scale = {} k) from the cantilever test (ASTM D7748)",
        t.ktw_over_kr
    );
    let target = t.overhang_mm;
    let r_used = t.r.unwrap_or(R_REF);
    let rho_used = t.rho.unwrap_or(RHO_REF);
    let lo_ref = LO45_REF_MM * ((r_used / R_REF).powi(2) * RHO_REF / rho_used).cbrt();
    let k0 = opts.k0.unwrap_or((target / lo_ref).powi(3));
    if !(k0.is_finite() && k0 > 0.0) {
        bail!("--k0 must be positive");
    }
    println!(
        "  target overhang {} mm (tolerance {} mm); start k0 = {:.6} ({}; Lo45 ~ k^(1/3), {:.1} mm at k = 1)",
        target,
        t.tol_mm,
        k0,
        if opts.k0.is_some() {
            "given by --k0"
        } else {
            "beam scaling"
        },
        lo_ref
    );
    res["step2"] = json!({"k0": k0, "lo45_ref_mm_at_k1": lo_ref, "evaluations": []});
    write_json(&result_path, &res)?;
    let a_mm = t.a * 1e3;
    let max_evals = if opts.quick { 1 } else { opts.max_evals.max(1) };
    let mut evals: Vec<CantEval> = Vec::new();
    let (mut k_lo, mut k_hi): (Option<f64>, Option<f64>) = (None, None);
    let mut k = k0;
    let mut converged = false;
    let mut stop_reason = String::from("evaluation limit reached");
    let mut last_sides: Vec<bool> = Vec::new();
    for n in 1..=max_evals {
        // expected Lo45 at k, from the nearest evaluated point (or the reference) with Lo ~ k^(1/3)
        let expect = evals
            .iter()
            .min_by(|x, y| {
                (x.k / k)
                    .ln()
                    .abs()
                    .partial_cmp(&(y.k / k).ln().abs())
                    .unwrap()
            })
            .map(|e| e.lo45_mm * (k / e.k).cbrt())
            .unwrap_or(lo_ref * k.cbrt());
        let half = (0.1 * expect).max(a_mm);
        let lo_min = ((expect - half) / 1e3).max(t.a);
        let lo_max = ((expect + half) / 1e3).max(lo_min + t.a);
        let file = format!("cantilever_{:02}.json", n);
        let mut args = common.clone();
        args.extend([
            format!("kn_scale={}", jnum(s_star)),
            format!("ks_scale={}", jnum(t.ks_scale)),
            format!("kr_scale={}", jnum(k)),
            format!("ktw_scale={}", jnum(k * t.ktw_over_kr)),
            format!("target_deg={}", jnum(t.target_angle_deg)),
            format!("lo_min={}", jnum(lo_min)),
            format!("lo_max={}", jnum(lo_max)),
            format!("out={}", jstr(&out.join(&file))),
        ]);
        println!(
            "  evaluation {}: k = {:.6} (kr_scale {}, ktw_scale {}), overhang window {:.0}-{:.0} mm",
            n,
            k,
            jnum(k),
            jnum(k * t.ktw_over_kr),
            lo_min * 1e3,
            lo_max * 1e3
        );
        let t0 = Instant::now();
        runner.run("cantilever.py", &args)?;
        let wall = t0.elapsed().as_secs_f64();
        let cj = read_json(&out.join(&file))?;
        let r = &cj["result"];
        let lo45 = r["overhang_m"].as_f64().ok_or_else(|| {
            anyhow!(
                "cantilever run {} gave no 45-deg overhang: {}",
                file,
                r["error"].as_str().unwrap_or("(no error text)")
            )
        })? * 1e3;
        let spread = ["overhang_loglog_m", "overhang_linear_m"]
            .iter()
            .filter_map(|kk| r[*kk].as_f64())
            .map(|x| (x * 1e3 - lo45).abs())
            .fold(0.0, f64::max);
        let npts = cj["points"].as_array().map(|p| p.len()).unwrap_or(0);
        let all_conv = r["all_converged"].as_bool().unwrap_or(false);
        let d = lo45 - target;
        println!(
            "  evaluation {}: k = {:.6} -> Lo45 = {:.4} mm (target {:.4}, diff {:+.4} mm = {}) [{} overhangs, \
             settled: {}, interpolation spread {:.2} mm, {:.1} s]",
            n,
            k,
            lo45,
            target,
            d,
            e3(d / target),
            npts,
            all_conv,
            spread,
            wall
        );
        res["step2"]["evaluations"]
            .as_array_mut()
            .unwrap()
            .push(json!({
                "n": n, "k": k, "kr_scale": k, "ktw_scale": k * t.ktw_over_kr,
                "lo_window_m": [lo_min, lo_max], "lo45_mm": lo45, "diff_mm": d,
                "interp_spread_mm": spread, "overhangs_evaluated": npts,
                "all_converged": all_conv, "file": file, "wall_s": wall,
            }));
        write_json(&result_path, &res)?;
        evals.push(CantEval {
            k,
            lo45_mm: lo45,
            file,
        });
        if !all_conv {
            eprintln!(
                "  warning: not every overhang of this run settled (see {})",
                out.join(&evals.last().unwrap().file).display()
            );
        }
        if d.abs() <= t.tol_mm {
            converged = true;
            stop_reason = format!("|Lo45 - target| <= {} mm", t.tol_mm);
            break;
        }
        let below = d < 0.0; // Lo45 grows with k: too short -> k larger
        if below {
            k_lo = Some(k_lo.map_or(k, |x: f64| x.max(k)));
        } else {
            k_hi = Some(k_hi.map_or(k, |x: f64| x.min(k)));
        }
        last_sides.push(below);
        if let (Some(l), Some(h)) = (k_lo, k_hi) {
            if h / l < 1.002 {
                stop_reason = "k bracket narrower than 0.2 %".into();
                break;
            }
        }
        // next k: root of the log-log secant through the two evaluations nearest the target
        // (one evaluation: slope 1/3 of the beam scaling)
        let mut by_dist = evals.clone();
        by_dist.sort_by(|x, y| {
            (x.lo45_mm - target)
                .abs()
                .partial_cmp(&(y.lo45_mm - target).abs())
                .unwrap()
        });
        let e1 = &by_dist[0];
        let mut slope = 1.0 / 3.0;
        if by_dist.len() > 1 {
            let e2 = &by_dist[1];
            let sl = (e2.lo45_mm / e1.lo45_mm).ln() / (e2.k / e1.k).ln();
            if sl.is_finite() && sl > 0.05 && sl < 3.0 {
                slope = sl;
            }
        }
        let mut next = e1.k * ((target / e1.lo45_mm).ln() / slope).exp();
        match (k_lo, k_hi) {
            (Some(l), Some(h)) => {
                let g = (l * h).sqrt();
                // stay strictly inside the bracket; after two updates of the same side in a row
                // take the geometric midpoint (keeps the bracket shrinking)
                let n = last_sides.len();
                let same_side = n >= 2 && last_sides[n - 1] == last_sides[n - 2];
                if !(next > l * 1.0005 && next < h / 1.0005) || same_side {
                    next = g;
                }
            }
            (Some(l), None) => next = next.clamp(l * 1.0005, l * 10.0),
            (None, Some(h)) => next = next.clamp(h / 10.0, h / 1.0005),
            (None, None) => unreachable!(),
        }
        k = next;
    }
    if opts.quick && !converged {
        stop_reason = "quick mode: one evaluation only".into();
    }
    let best = evals
        .iter()
        .min_by(|x, y| {
            (x.lo45_mm - target)
                .abs()
                .partial_cmp(&(y.lo45_mm - target).abs())
                .unwrap()
        })
        .unwrap()
        .clone();
    let d_best = best.lo45_mm - target;
    res["step2"]["k"] = json!(best.k);
    res["step2"]["kr_scale"] = json!(best.k);
    res["step2"]["ktw_scale"] = json!(best.k * t.ktw_over_kr);
    res["step2"]["lo45_mm"] = json!(best.lo45_mm);
    res["step2"]["residual_mm"] = json!(d_best);
    res["step2"]["residual_rel"] = json!(d_best / target);
    res["step2"]["converged"] = json!(converged);
    res["step2"]["stop_reason"] = json!(stop_reason);
    res["step2"]["file"] = json!(best.file);
    let max_rel = resid
        .iter()
        .map(|r| r.abs())
        .fold((d_best / target).abs(), f64::max);
    res["max_abs_residual_rel"] = json!(max_rel);
    res["within_1_percent"] = json!(max_rel <= 0.01);
    res["status"] = json!(if converged {
        "done"
    } else {
        "done (step 2 not within tolerance)"
    });
    write_json(&result_path, &res)?;

    // ---- report
    let mut rep = String::new();
    use std::fmt::Write as _;
    let ea = fitted.first().copied().unwrap_or(f64::NAN);
    writeln!(
        rep,
        "== fitted values ({}; engine {})",
        t.path.display(),
        opts.engine
    )?;
    writeln!(
        rep,
        "  kn_scale  = {}   (secant {:.6} kN per unit strain per rib at the first strain)",
        jnum(s_star),
        ea
    )?;
    writeln!(
        rep,
        "  kr_scale  = {}   ktw_scale = {}   (ktw/kr scale ratio {} from [fit])",
        jnum(best.k),
        jnum(best.k * t.ktw_over_kr),
        t.ktw_over_kr
    )?;
    writeln!(rep, "  ks_scale  = {}   (fixed, [fit])", jnum(t.ks_scale))?;
    writeln!(
        rep,
        "  step 2: {} evaluation(s), {} ({})",
        evals.len(),
        if converged {
            "converged"
        } else {
            "NOT within tolerance"
        },
        stop_reason
    )?;
    writeln!(rep, "== residuals (model - target) / target")?;
    writeln!(
        rep,
        "  {:<32} {:>16} {:>16} {:>12}",
        "target", "datasheet", "model", "residual"
    )?;
    for (i, e) in t.strains.iter().enumerate() {
        writeln!(
            rep,
            "  {:<32} {:>16.6} {:>16.6} {:>12}",
            format!("secant at {} % strain [kN]", (e * 1e11).round() / 1e9),
            t.secant_kn[i],
            fitted[i],
            e3(resid[i])
        )?;
    }
    writeln!(
        rep,
        "  {:<32} {:>16.4} {:>16.4} {:>12}   ({:+.4} mm; tolerance {} mm)",
        format!("overhang at {} deg [mm]", t.target_angle_deg),
        target,
        best.lo45_mm,
        e3(d_best / target),
        d_best,
        t.tol_mm
    )?;
    writeln!(
        rep,
        "  tensile residual rms {}",
        e3(rms).trim_start_matches('+')
    )?;
    writeln!(
        rep,
        "  every target within 1 %: {} (largest |residual| {})",
        if max_rel <= 0.01 { "yes" } else { "NO" },
        e3(max_rel).trim_start_matches('+')
    )?;
    print!("{}", rep);
    std::fs::write(out.join("summary.txt"), &rep)?;
    writeln!(runner.log, "== result written to {}", result_path.display())?;

    if opts.plot {
        match plot(&result_path) {
            Ok(files) => {
                for f in &files {
                    println!("  plot: {}", out.join(f).display());
                }
                res["plots"] = json!(files);
                write_json(&result_path, &res)?;
            }
            Err(e) => eprintln!(
                "warning: plots not made ({:#}); the results are in {}",
                e,
                result_path.display()
            ),
        }
    }
    println!("  result: {}", result_path.display());
    Ok(converged || opts.quick)
}

/// Runs the plotting script on the result file; returns the PNG names written next to it.
pub fn plot(result: &Path) -> Result<Vec<String>> {
    run_plot(PLOT_PY, result)
}

/// Runs a plotting script (Python source) with `arg`; returns the names it reports ("wrote NAME").
fn run_plot(script: &str, arg: &Path) -> Result<Vec<String>> {
    let py = crate::harness::env::python();
    let o = crate::harness::proc::output(Command::new(&py).arg("-c").arg(script).arg(arg))
        .with_context(|| format!("starting {:?}", py))?;
    if !o.status.success() {
        bail!(
            "plot script failed: {}",
            String::from_utf8_lossy(&o.stderr).trim()
        );
    }
    Ok(String::from_utf8_lossy(&o.stdout)
        .lines()
        .filter_map(|l| l.strip_prefix("wrote ").map(|s| s.trim().to_string()))
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_and_lsq() {
        assert_eq!(secant_key(0.02), "secant_2pct_kN");
        assert_eq!(secant_key(0.05), "secant_5pct_kN");
        assert_eq!(secant_key(0.005), "secant_0p5pct_kN");
        assert_eq!(e3(0.0), "+0.000e+00");
        assert_eq!(e3(-1.5e-7), "-1.500e-07");
    }

    #[test]
    fn step0_values_from_area_and_mass() {
        let d = std::env::temp_dir().join(format!("ryade-calib-step0-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        let f = d.join("t.toml");
        // area 4 pi mm^2 -> r = 2 mm; the model's own 689.24 g/m^2 -> rho = 950 kg/m^3
        std::fs::write(
            &f,
            "[rib]\narea_mm2 = 12.566370614359172\n[mass]\nmass_per_area_g_m2 = 689.2437584090029\n\
             [tensile]\nsecant_2pct_kN = 1\nsecant_5pct_kN = 1\n[flexural]\noverhang_45deg_mm = 800\n",
        )
        .unwrap();
        let t = Targets::load(&f).unwrap();
        assert!((t.r.unwrap() - 0.002).abs() < 1e-15);
        assert!((t.rho.unwrap() - 950.0).abs() < 1e-9);
        assert_eq!(t.a, 0.06);
        assert_eq!(t.tol_mm, 1.0);
        let _ = std::fs::remove_dir_all(&d);
        // a linear model with exact targets: s recovered exactly up to rounding
        let s = kn_scale_lsq(&[2.0, 2.0], &[3.4, 3.4]);
        assert!((s - 1.7).abs() < 1e-15);
        // inconsistent targets: the relative least squares lies between the two ratios
        let s = kn_scale_lsq(&[1.0, 1.0], &[1.0, 2.0]);
        assert!((s - 1.5 / 1.25).abs() < 1e-15);
    }
}
