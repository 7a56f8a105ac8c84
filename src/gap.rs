//! Sim-to-real gap diagnosis (`compat gap`): where a model departs from observed histories, which
//! unmodelled effect explains it, and how far adding it closes the gap on held-out data.
//!
//! Inputs: an observed history (per cycle: rut, optionally porosity under the piston and resilient
//! rebound) and a *library* of simulated runs of the same scenario: a baseline ensemble (today's model,
//! several seeds) and, per candidate effect, runs at a few strengths (study.py knobs, see
//! yade_ref/gap/README.md). The library is the screening surrogate: a run's prediction at any strength
//! is the seed-mean interpolated linearly between library strengths, so one diagnosis costs no new
//! simulation once the library exists, and one library serves every observation of that scenario.
//!
//! Statistics: the noise of one realisation is the seed-to-seed sd per cycle and observable, pooled
//! over every library group (baseline and each effect strength; floored); the rut enters as its
//! increment per cycle (the cumulative rut is strongly correlated from cycle to cycle); each effect's strength is fitted by least squares on the first cycles
//! (`fit_cycles`), its evidence is BIC = chi2 + ln(n) against the baseline's chi2 (no parameter), the
//! confidence is the BIC weight, and the gap before/after is measured on the later (held-out) cycles.

use anyhow::{bail, Context, Result};
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::Path;

/// Observables compared, in the observed file's units after conversion to mm / -.
pub const OBSERVABLES: [&str; 3] = ["rut_mm", "porosity", "rebound_mm"];

/// Per-cycle observed (or simulated) series; index = cycle (0 = end of seating).
#[derive(Clone, Debug, Default, Serialize)]
pub struct Series {
    pub rut_mm: Vec<f64>,
    pub porosity: Option<Vec<f64>>,
    pub rebound_mm: Option<Vec<f64>>,
}

impl Series {
    pub fn get(&self, obs: &str) -> Option<&Vec<f64>> {
        match obs {
            "rut_mm" => Some(&self.rut_mm),
            "porosity" => self.porosity.as_ref(),
            "rebound_mm" => self.rebound_mm.as_ref(),
            _ => None,
        }
    }
    pub fn cycles(&self) -> usize {
        self.rut_mm.len()
    }
}

/// Read an observed history CSV. Columns: `cycle` (0, 1, 2, ... with 0 = end of seating), a rut column
/// `rut_mm` or `rut_m`, optional `porosity` (-) and `rebound_mm`/`rebound_m` (rut_max - rut within the
/// cycle: the resilient part). Units are taken from the column names.
pub fn read_observed(path: &Path) -> Result<Series> {
    let mut rd = csv::Reader::from_path(path)
        .with_context(|| format!("reading the observed history {}", path.display()))?;
    let head: Vec<String> = rd.headers()?.iter().map(|h| h.trim().to_string()).collect();
    let col = |names: &[&str]| names.iter().find_map(|n| head.iter().position(|h| h == n));
    let c_cycle = col(&["cycle"]).with_context(|| {
        format!(
            "{}: no 'cycle' column (header: {})",
            path.display(),
            head.join(",")
        )
    })?;
    let (c_rut, rut_scale) = match (col(&["rut_mm"]), col(&["rut_m"])) {
        (Some(c), _) => (c, 1.0),
        (None, Some(c)) => (c, 1e3),
        _ => bail!(
            "{}: no rut column: name it rut_mm or rut_m (units are read from the name); header: {}",
            path.display(),
            head.join(",")
        ),
    };
    let c_por = col(&["porosity", "porosity_box"]);
    let (c_reb, reb_scale) = match (col(&["rebound_mm"]), col(&["rebound_m"])) {
        (Some(c), _) => (Some(c), 1.0),
        (None, Some(c)) => (Some(c), 1e3),
        _ => (None, 1.0),
    };
    for h in &head {
        let known = [
            "cycle",
            "rut_mm",
            "rut_m",
            "porosity",
            "porosity_box",
            "rebound_mm",
            "rebound_m",
        ];
        if !known.contains(&h.as_str()) {
            bail!(
                "{}: column '{}' is not understood (known: {}); settlement at depths is not supported yet",
                path.display(),
                h,
                known.join(", ")
            );
        }
    }
    let mut s = Series::default();
    let mut por = Vec::new();
    let mut reb = Vec::new();
    for (i, r) in rd.records().enumerate() {
        let r = r.with_context(|| format!("{}: record {} is malformed", path.display(), i + 1))?;
        let num = |c: usize, what: &str| -> Result<f64> {
            let t = r.get(c).unwrap_or("").trim();
            let v: f64 = t.parse().with_context(|| {
                format!(
                    "{}: record {}: {} '{}' is not a number",
                    path.display(),
                    i + 1,
                    what,
                    t
                )
            })?;
            if !v.is_finite() {
                bail!(
                    "{}: record {}: {} is not finite",
                    path.display(),
                    i + 1,
                    what
                );
            }
            Ok(v)
        };
        let cyc = num(c_cycle, "cycle")?;
        if cyc != i as f64 {
            bail!(
                "{}: record {} has cycle {} (cycles must be 0, 1, 2, ... in order; 0 = end of seating)",
                path.display(),
                i + 1,
                cyc
            );
        }
        s.rut_mm.push(num(c_rut, "rut")? * rut_scale);
        if let Some(c) = c_por {
            por.push(num(c, "porosity")?);
        }
        if let Some(c) = c_reb {
            reb.push(num(c, "rebound")? * reb_scale);
        }
    }
    if s.rut_mm.len() < 3 {
        bail!("{}: at least cycles 0-2 are needed", path.display());
    }
    s.porosity = c_por.map(|_| por);
    s.rebound_mm = c_reb.map(|_| reb);
    Ok(s)
}

/// A study run's history.csv as a Series (rebound = rut_max - rut; NaN at cycle 0).
pub fn series_of_history(path: &Path) -> Result<Series> {
    let h = crate::harness::study::read_history(path)?;
    Ok(Series {
        rut_mm: h.iter().map(|r| r.rut_mm).collect(),
        porosity: Some(h.iter().map(|r| r.porosity_box).collect()),
        rebound_mm: Some(
            h.iter()
                .map(|r| {
                    if r.cycle == 0 {
                        0.0
                    } else {
                        r.rut_max_mm - r.rut_mm
                    }
                })
                .collect(),
        ),
    })
}

/// One candidate effect with its library strengths (0 = today's model = the baseline).
#[derive(Clone, Debug, Serialize, serde::Deserialize)]
pub struct Effect {
    /// study.py knob (`--eta-roll` is `eta_roll`).
    pub knob: String,
    /// What the knob means physically.
    pub meaning: String,
    /// Knob value at strength 0 (today's model).
    pub zero: f64,
    /// Library strengths (knob value = zero + strength).
    pub strengths: Vec<f64>,
}

/// The simulated runs: baseline seeds and per effect per strength per seed.
#[derive(Clone, Debug, Default)]
pub struct Library {
    pub effects: Vec<Effect>,
    pub baseline: Vec<Series>,
    /// (knob, strength index) -> seeds' series
    pub runs: BTreeMap<(String, usize), Vec<Series>>,
}

fn mean_at(v: &[Series], obs: &str, c: usize) -> Option<f64> {
    let xs: Vec<f64> = v
        .iter()
        .filter_map(|s| s.get(obs).and_then(|x| x.get(c)).copied())
        .collect();
    (!xs.is_empty()).then(|| crate::harness::study::mean_sd(&xs).0)
}

impl Library {
    /// Every group of runs that differ only by seed (baseline, each effect at each strength).
    fn groups(&self) -> impl Iterator<Item = &Vec<Series>> {
        std::iter::once(&self.baseline).chain(self.runs.values())
    }

    /// Seed-to-seed sd of one realisation of `x(series)`, pooled over every library group with at
    /// least 2 seeds (the scatter of one run is not only today's model's), floored.
    fn pooled_sd<F: Fn(&Series) -> Option<f64>>(&self, x: F) -> f64 {
        let (mut ss, mut dof) = (0.0, 0.0);
        for g in self.groups() {
            let v: Vec<f64> = g.iter().filter_map(&x).collect();
            if v.len() >= 2 {
                let (_, sd) = crate::harness::study::mean_sd(&v);
                ss += sd * sd * (v.len() - 1) as f64;
                dof += (v.len() - 1) as f64;
            }
        }
        if dof > 0.0 {
            (ss / dof).sqrt()
        } else {
            0.0
        }
    }

    /// Noise of one realisation of observable `obs` at cycle c: the pooled seed-to-seed sd, floored
    /// at 2 % of the baseline mean and an absolute floor (0.2 mm, 0.001 porosity).
    pub fn noise(&self, obs: &str, c: usize) -> f64 {
        let sd = self.pooled_sd(|s| s.get(obs).and_then(|x| x.get(c)).copied());
        let m = self.baseline_mean(obs, c).unwrap_or(0.0);
        let abs_floor = if obs == "porosity" { 1e-3 } else { 0.2 };
        sd.max(0.02 * m.abs()).max(abs_floor)
    }

    /// The same for the rut increment of cycle c (floored at 5 % of the mean increment and 0.2 mm).
    pub fn increment_noise(&self, c: usize) -> f64 {
        let inc = |s: &Series| Some(s.rut_mm.get(c)? - s.rut_mm.get(c.checked_sub(1)?)?);
        let sd = self.pooled_sd(inc);
        let xs: Vec<f64> = self.baseline.iter().filter_map(inc).collect();
        let (m, _) = crate::harness::study::mean_sd(&xs);
        sd.max(0.05 * m.abs()).max(0.2)
    }

    /// Prediction of effect `e` at strength `s` (linear between library strengths; 0 = baseline).
    pub fn predict(&self, e: &Effect, s: f64, obs: &str, c: usize) -> Option<f64> {
        let mut pts: Vec<(f64, f64)> = vec![(0.0, mean_at(&self.baseline, obs, c)?)];
        for (k, st) in e.strengths.iter().enumerate() {
            if let Some(v) = self.runs.get(&(e.knob.clone(), k)) {
                if let Some(m) = mean_at(v, obs, c) {
                    pts.push((*st, m));
                }
            }
        }
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        let (lo, hi) = (pts[0], pts[pts.len() - 1]);
        if s <= lo.0 {
            return Some(lo.1);
        }
        if s >= hi.0 {
            return Some(hi.1);
        }
        for w in pts.windows(2) {
            if s >= w[0].0 && s <= w[1].0 {
                let t = (s - w[0].0) / (w[1].0 - w[0].0);
                return Some(w[0].1 + t * (w[1].1 - w[0].1));
            }
        }
        None
    }

    pub fn baseline_mean(&self, obs: &str, c: usize) -> Option<f64> {
        mean_at(&self.baseline, obs, c)
    }
}

/// Cycles used to fit (1..=fit_cycles), held out (fit_cycles+1..).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Split {
    pub fit_cycles: usize,
    pub last_cycle: usize,
}

fn chi2<F: Fn(&str, usize) -> Option<f64> + ?Sized>(
    lib: &Library,
    obs: &Series,
    pred: &F,
    cycles: std::ops::RangeInclusive<usize>,
) -> (f64, usize) {
    let mut x2 = 0.0;
    let mut n = 0;
    for o in OBSERVABLES {
        let Some(ov) = obs.get(o) else { continue };
        for c in cycles.clone() {
            if c >= ov.len() || c == 0 {
                continue;
            }
            // the rut is cumulative, so successive cycles are strongly correlated: compare its
            // increment per cycle (nearly independent), with the ensemble's sd of increments
            let r = if o == "rut_mm" {
                match (pred(o, c), pred(o, c - 1)) {
                    (Some(p1), Some(p0)) => {
                        ((ov[c] - ov[c - 1]) - (p1 - p0)) / lib.increment_noise(c)
                    }
                    _ => continue,
                }
            } else {
                match pred(o, c) {
                    Some(p) => (ov[c] - p) / lib.noise(o, c),
                    None => continue,
                }
            };
            x2 += r * r;
            n += 1;
        }
    }
    (x2, n)
}

/// RMS rut error [mm] over cycles.
fn rut_rms<F: Fn(usize) -> Option<f64>>(
    obs: &Series,
    pred: F,
    cycles: std::ops::RangeInclusive<usize>,
) -> f64 {
    let mut s = 0.0;
    let mut n = 0;
    for c in cycles {
        if let (Some(o), Some(p)) = (obs.rut_mm.get(c), pred(c)) {
            s += (o - p) * (o - p);
            n += 1;
        }
    }
    if n == 0 {
        f64::NAN
    } else {
        (s / n as f64).sqrt()
    }
}

/// "Where": the baseline's discrepancy split by observable and phase.
#[derive(Clone, Debug, Serialize)]
pub struct WherePart {
    pub observable: String,
    pub phase: String,
    pub cycles: String,
    /// Mean of (observed - baseline mean) in the observable's units.
    pub mean_diff: f64,
    /// Sum of squared normalised residuals.
    pub chi2: f64,
    pub share: f64,
}

pub fn where_analysis(lib: &Library, obs: &Series, last: usize) -> Vec<WherePart> {
    let mut parts = Vec::new();
    let early_end = 2.min(last);
    let mut push = |observable: &str,
                    phase: &str,
                    cyc: Vec<usize>,
                    val: &dyn Fn(&Series, usize) -> Option<f64>,
                    base: &dyn Fn(usize) -> Option<f64>,
                    noise: &dyn Fn(usize) -> f64| {
        let mut x2 = 0.0;
        let mut d = 0.0;
        let mut n = 0;
        for &c in &cyc {
            if let (Some(o), Some(b)) = (val(obs, c), base(c)) {
                let r = (o - b) / noise(c);
                x2 += r * r;
                d += o - b;
                n += 1;
            }
        }
        if n > 0 {
            parts.push(WherePart {
                observable: observable.into(),
                phase: phase.into(),
                cycles: format!("{}-{}", cyc[0], cyc[cyc.len() - 1]),
                mean_diff: d / n as f64,
                chi2: x2,
                share: 0.0,
            });
        }
    };
    // early densification: rut level after the first cycles
    push(
        "rut_mm",
        "early densification (rut after cycles 1-2)",
        (1..=early_end).collect(),
        &|s, c| s.rut_mm.get(c).copied(),
        &|c| lib.baseline_mean("rut_mm", c),
        &|c| lib.noise("rut_mm", c),
    );
    // steady accumulation: rut increment per cycle after the early phase
    if last > early_end {
        let inc = |s: &Series, c: usize| Some(s.rut_mm.get(c)? - s.rut_mm.get(c - 1)?);
        let base_inc =
            |c: usize| Some(lib.baseline_mean("rut_mm", c)? - lib.baseline_mean("rut_mm", c - 1)?);
        push(
            "rut_mm",
            "steady accumulation (rut increment per cycle)",
            (early_end + 1..=last).collect(),
            &inc,
            &base_inc,
            &|c| lib.increment_noise(c),
        );
    }
    if obs.rebound_mm.is_some() {
        push(
            "rebound_mm",
            "resilient rebound within each cycle",
            (1..=last).collect(),
            &|s, c| s.rebound_mm.as_ref()?.get(c).copied(),
            &|c| lib.baseline_mean("rebound_mm", c),
            &|c| lib.noise("rebound_mm", c),
        );
    }
    if obs.porosity.is_some() {
        push(
            "porosity",
            "porosity under the piston",
            (0..=last).collect(),
            &|s, c| s.porosity.as_ref()?.get(c).copied(),
            &|c| lib.baseline_mean("porosity", c),
            &|c| lib.noise("porosity", c),
        );
    }
    let tot: f64 = parts.iter().map(|p| p.chi2).sum();
    for p in parts.iter_mut() {
        p.share = if tot > 0.0 { p.chi2 / tot } else { 0.0 };
    }
    parts
}

/// "Which": one candidate's fit and evidence.
#[derive(Clone, Debug, Serialize)]
pub struct Candidate {
    pub knob: String,
    pub meaning: String,
    /// Fitted strength (knob value = zero + strength).
    pub strength: f64,
    pub knob_value: f64,
    pub chi2_fit: f64,
    pub n_fit: usize,
    pub bic: f64,
    /// BIC weight among the candidates and "none".
    pub weight: f64,
    /// Held-out rut RMS [mm] with this effect at the fitted strength.
    pub heldout_rut_rms_mm: f64,
}

#[derive(Clone, Debug, Serialize)]
pub struct Diagnosis {
    pub split: Split,
    /// Leave-one-out calibration of the noise model on today's model (every chi2 is divided by it).
    pub noise_inflation: f64,
    pub where_parts: Vec<WherePart>,
    pub dominant_part: String,
    pub candidates: Vec<Candidate>,
    pub none_bic: f64,
    pub none_weight: f64,
    /// Winning knob, or "none" when no candidate beats today's model by the evidence margin.
    pub winner: String,
    pub confidence: f64,
    pub heldout_rut_rms_before_mm: f64,
    pub heldout_rut_rms_after_mm: f64,
    /// 1 - after / before (held-out cycles; 0 when the winner is none).
    pub gap_reduction: f64,
}

/// BIC margin an effect must win by (about "positive evidence" on Kass & Raftery's scale).
pub const EVIDENCE_MARGIN: f64 = 2.0;

pub fn diagnose(lib: &Library, obs: &Series, fit_cycles: usize) -> Result<Diagnosis> {
    let last = obs
        .cycles()
        .min(lib.baseline.iter().map(|s| s.cycles()).min().unwrap_or(0))
        - 1;
    if lib.baseline.len() < 2 {
        bail!("the library needs at least 2 baseline seeds to estimate the seed-to-seed noise");
    }
    if fit_cycles < 1 || fit_cycles >= last {
        bail!(
            "fit cycles {} leave nothing to fit or nothing held out (observed and simulated cycles: {})",
            fit_cycles,
            last
        );
    }
    let split = Split {
        fit_cycles,
        last_cycle: last,
    };
    let fit = 0..=fit_cycles;
    let held = fit_cycles + 1..=last;
    // Calibrate the noise model on today's model itself: leave each baseline seed out, compare it
    // with the mean of the others; the mean chi2 per observation (>= 1) inflates every chi2 below.
    let mut ratios = Vec::new();
    for i in 0..lib.baseline.len() {
        let others: Vec<Series> = lib
            .baseline
            .iter()
            .enumerate()
            .filter(|(j, _)| *j != i)
            .map(|(_, s)| s.clone())
            .collect();
        let (x2, n) = chi2(
            lib,
            &lib.baseline[i],
            &|o, c| mean_at(&others, o, c),
            fit.clone(),
        );
        if n > 0 {
            // the left-out seed is compared with a mean of K-1 seeds: its expected chi2 is
            // n (1 + 1/(K-1)) for a right noise model
            ratios.push(x2 / (n as f64 * (1.0 + 1.0 / others.len() as f64)));
        }
    }
    let inflation = crate::harness::study::mean_sd(&ratios).0.max(1.0);
    let chi2 =
        |o: &Series, p: &dyn Fn(&str, usize) -> Option<f64>, r: std::ops::RangeInclusive<usize>| {
            let (x2, n) = chi2(lib, o, p, r);
            (x2 / inflation, n)
        };
    let (none_chi2, n_fit) = chi2(obs, &|o, c| lib.baseline_mean(o, c), fit.clone());
    let none_bic = none_chi2;
    let before = rut_rms(obs, |c| lib.baseline_mean("rut_mm", c), held.clone());
    let mut cands = Vec::new();
    for e in &lib.effects {
        let lo = e.strengths.iter().cloned().fold(0.0, f64::min);
        let hi = e.strengths.iter().cloned().fold(0.0, f64::max);
        let mut best = (f64::INFINITY, 0.0, 0);
        for k in 0..=400 {
            let s = lo + (hi - lo) * k as f64 / 400.0;
            let (x2, n) = chi2(obs, &|o, c| lib.predict(e, s, o, c), fit.clone());
            if x2 < best.0 {
                best = (x2, s, n);
            }
        }
        let s = best.1;
        cands.push(Candidate {
            knob: e.knob.clone(),
            meaning: e.meaning.clone(),
            strength: s,
            knob_value: e.zero + s,
            chi2_fit: best.0,
            n_fit: best.2,
            bic: best.0 + (best.2.max(1) as f64).ln(),
            weight: 0.0,
            heldout_rut_rms_mm: rut_rms(obs, |c| lib.predict(e, s, "rut_mm", c), held.clone()),
        });
    }
    let bmin = cands.iter().map(|c| c.bic).fold(none_bic, f64::min);
    let mut z = (-(none_bic - bmin) / 2.0).exp();
    for c in &cands {
        z += (-(c.bic - bmin) / 2.0).exp();
    }
    for c in cands.iter_mut() {
        c.weight = (-(c.bic - bmin) / 2.0).exp() / z;
    }
    let none_weight = (-(none_bic - bmin) / 2.0).exp() / z;
    cands.sort_by(|a, b| a.bic.total_cmp(&b.bic));
    let (winner, confidence, after) = match cands.first() {
        Some(c) if c.bic + EVIDENCE_MARGIN < none_bic => {
            (c.knob.clone(), c.weight, c.heldout_rut_rms_mm)
        }
        _ => ("none".to_string(), none_weight, before),
    };
    let wp = where_analysis(lib, obs, last);
    let dominant_part = wp
        .iter()
        .max_by(|a, b| a.chi2.total_cmp(&b.chi2))
        .map(|p| format!("{}: {}", p.observable, p.phase))
        .unwrap_or_default();
    let _ = n_fit;
    Ok(Diagnosis {
        split,
        noise_inflation: inflation,
        where_parts: wp,
        dominant_part,
        candidates: cands,
        none_bic,
        none_weight,
        winner,
        confidence,
        heldout_rut_rms_before_mm: before,
        heldout_rut_rms_after_mm: after,
        gap_reduction: if before > 0.0 {
            1.0 - after / before
        } else {
            0.0
        },
    })
}

/// Markdown report of one diagnosis.
pub fn report_markdown(name: &str, d: &Diagnosis, lib: &Library) -> String {
    let mut s = format!("# Gap diagnosis: {}\n\n", name);
    s += &format!(
        "Fit on cycles 1-{}, held out: cycles {}-{}. Noise of one realisation: the seed-to-seed sd pooled over the library's groups ({} baseline seeds), inflated by {:.2} (leave-one-out calibration on today's model).\n\n",
        d.split.fit_cycles,
        d.split.fit_cycles + 1,
        d.split.last_cycle,
        lib.baseline.len(),
        d.noise_inflation
    );
    s += "## Where the model departs (today's model vs observed)\n\n| observable | phase | cycles | mean (obs - model) | chi2 | share |\n|---|---|---|---|---|---|\n";
    for p in &d.where_parts {
        s += &format!(
            "| {} | {} | {} | {:+.4} | {:.1} | {:.0} % |\n",
            p.observable,
            p.phase,
            p.cycles,
            p.mean_diff,
            p.chi2,
            100.0 * p.share
        );
    }
    s += &format!("\nDominant part: **{}**.\n\n", d.dominant_part);
    s += "## Which unmodelled effect explains it\n\n| rank | effect | meaning | fitted knob value | chi2 (fit) | BIC | weight | held-out rut RMS [mm] |\n|---|---|---|---|---|---|---|---|\n";
    for (i, c) in d.candidates.iter().enumerate() {
        s += &format!(
            "| {} | {} | {} | {:.4} | {:.1} | {:.1} | {:.2} | {:.2} |\n",
            i + 1,
            c.knob,
            c.meaning,
            c.knob_value,
            c.chi2_fit,
            c.bic,
            c.weight,
            c.heldout_rut_rms_mm
        );
    }
    s += &format!(
        "| - | none | today's model | - | {:.1} | {:.1} | {:.2} | {:.2} |\n\n",
        d.none_bic, d.none_bic, d.none_weight, d.heldout_rut_rms_before_mm
    );
    s += &format!(
        "Verdict: **{}** (confidence {:.2}; an effect must beat today's model by {} in BIC).\n\n",
        if d.winner == "none" {
            "none of the candidates explains the gap".to_string()
        } else {
            d.winner.clone()
        },
        d.confidence,
        EVIDENCE_MARGIN
    );
    s += &format!(
        "## How far it closes\n\nHeld-out rut RMS: {:.2} mm with today's model, {:.2} mm with the winning effect: gap reduced by {:.0} %.\n",
        d.heldout_rut_rms_before_mm,
        d.heldout_rut_rms_after_mm,
        100.0 * d.gap_reduction
    );
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ser(rut: &[f64]) -> Series {
        Series {
            rut_mm: rut.to_vec(),
            porosity: None,
            rebound_mm: None,
        }
    }

    /// A synthetic library where the effect scales the rut linearly: the fit recovers the strength,
    /// the held-out gap closes, and an observation equal to the baseline gives "none".
    #[test]
    fn recovers_a_linear_effect_and_says_none_for_the_baseline() {
        let base = |k: f64| -> Vec<f64> { (0..8).map(|c| c as f64 * 5.0 * k).collect() };
        let mut lib = Library {
            effects: vec![
                Effect {
                    knob: "soft".into(),
                    meaning: "more rut".into(),
                    zero: 0.0,
                    strengths: vec![0.5, 1.0],
                },
                Effect {
                    knob: "flat".into(),
                    meaning: "no effect".into(),
                    zero: 0.0,
                    strengths: vec![1.0],
                },
            ],
            ..Default::default()
        };
        lib.baseline = vec![ser(&base(0.95)), ser(&base(1.0)), ser(&base(1.05))];
        lib.runs
            .insert(("soft".into(), 0), vec![ser(&base(1.45)), ser(&base(1.55))]);
        lib.runs
            .insert(("soft".into(), 1), vec![ser(&base(1.95)), ser(&base(2.05))]);
        lib.runs
            .insert(("flat".into(), 0), vec![ser(&base(0.98)), ser(&base(1.02))]);
        let obs = ser(&base(1.7)); // strength 0.7
        let d = diagnose(&lib, &obs, 4).unwrap();
        assert_eq!(d.winner, "soft");
        assert!(
            (d.candidates[0].strength - 0.7).abs() < 0.01,
            "{}",
            d.candidates[0].strength
        );
        assert!(d.gap_reduction > 0.95);
        let d = diagnose(&lib, &ser(&base(1.0)), 4).unwrap();
        assert_eq!(d.winner, "none");
    }

    #[test]
    fn observed_file_errors_are_clear() {
        let dir = std::env::temp_dir().join(format!("ryade_gap_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("obs.csv");
        std::fs::write(&p, "cycle,rut_in\n0,0\n1,1\n2,2\n").unwrap();
        let e = format!("{:#}", read_observed(&p).unwrap_err());
        assert!(e.contains("name it rut_mm or rut_m"), "{}", e);
        std::fs::write(
            &p,
            "cycle,rut_m,porosity\n0,0,0.4\n1,0.001,0.41\n2,0.003,0.42\n",
        )
        .unwrap();
        let s = read_observed(&p).unwrap();
        assert_eq!(s.rut_mm[2], 3.0);
        std::fs::write(&p, "cycle,rut_mm\n0,0\n2,1\n").unwrap();
        assert!(format!("{:#}", read_observed(&p).unwrap_err()).contains("in order"));
        std::fs::remove_dir_all(&dir).ok();
    }
}
