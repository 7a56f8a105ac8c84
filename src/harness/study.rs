//! The study (seed-paper.txt, /work/shared/study.md) as cases, histories and the statistical diff.
//!
//! A case is `r<RR>_<C>_<size>_s<seed>` (ratio d/a = RR/10, stabilization N, G or F). Its histories
//! (`history.csv`, one row per load cycle; `steps.csv`, the piston every 10 steps) are written by
//! `yade_ref/study/study.py`, which runs unchanged in Debian YADE and in ryade (`compat run`). This
//! module reads them and compares engines: granular flow is chaotic, so the verdict uses YADE's own
//! seed-to-seed spread (the band rule), and the exact-match horizon says how long the two engines
//! stayed bit-identical on the same specimen.

use anyhow::{anyhow, bail, Context, Result};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The three stabilization cases of the paper.
pub const CASES: [char; 3] = ['N', 'G', 'F'];
/// The three diameter-to-rib-length ratios (tags: 0.3, 0.5, 0.7).
pub const RATIOS: [u8; 3] = [3, 5, 7];
pub const SIZES: [&str; 4] = ["tiny", "small", "medium", "full"];

/// One run of the study: ratio, case, size, seed.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct CaseSpec {
    /// d/a in tenths (3, 5 or 7).
    pub ratio: u8,
    pub case: char,
    pub size: String,
    pub seed: u32,
}

impl CaseSpec {
    pub fn name(&self) -> String {
        format!(
            "r{:02}_{}_{}_s{}",
            self.ratio, self.case, self.size, self.seed
        )
    }

    pub fn ratio_value(&self) -> f64 {
        self.ratio as f64 / 10.0
    }

    /// study.py arguments that build this case.
    pub fn study_args(&self) -> Vec<String> {
        vec![
            "--ratio".into(),
            format!("{}", self.ratio_value()),
            "--case".into(),
            self.case.to_string(),
            "--size".into(),
            self.size.clone(),
            "--seed".into(),
            self.seed.to_string(),
        ]
    }
}

/// `r05` -> 5. Unknown names get an error listing the scenarios.
pub fn parse_scenario(s: &str) -> Result<u8> {
    let r = s
        .strip_prefix('r')
        .and_then(|t| t.parse::<u8>().ok())
        .filter(|r| RATIOS.contains(r) && s.len() == 3);
    r.ok_or_else(|| {
        anyhow!(
            "unknown scenario '{}': the study's scenarios are r03, r05 and r07 (d/a = 0.3, 0.5, 0.7)",
            s
        )
    })
}

/// `N`, `all`, `N,G` -> the cases.
pub fn parse_cases(s: &str) -> Result<Vec<char>> {
    if s.eq_ignore_ascii_case("all") {
        return Ok(CASES.to_vec());
    }
    let mut out = Vec::new();
    for t in s.split(',') {
        let t = t.trim();
        match t {
            "N" | "G" | "F" => out.push(t.chars().next().unwrap()),
            _ => bail!(
                "unknown case '{}': use N (non-stabilized), G (geogrid), F (full lateral confinement) or all",
                t
            ),
        }
    }
    Ok(out)
}

pub fn check_size(s: &str) -> Result<()> {
    if SIZES.contains(&s) {
        Ok(())
    } else {
        bail!("unknown size '{}': use one of {}", s, SIZES.join(", "))
    }
}

/// One row of `history.csv` (columns: yade_ref/study/README.md).
#[derive(Clone, Debug, Deserialize, Serialize)]
pub struct HistoryRow {
    pub cycle: u32,
    pub complete: u8,
    pub steps: u64,
    pub time_s: f64,
    pub rut_mm: f64,
    pub rut_max_mm: f64,
    #[serde(rename = "peak_kPa")]
    pub peak_kpa: f64,
    #[serde(rename = "peak_raw_kPa")]
    pub peak_raw_kpa: f64,
    #[serde(rename = "tracking_rms_kPa")]
    pub tracking_rms_kpa: f64,
    #[serde(rename = "tracking_rms_raw_kPa")]
    pub tracking_rms_raw_kpa: f64,
    pub porosity_box: f64,
    pub piston_z_m: f64,
    #[serde(default)]
    pub grid_z_m: Option<f64>,
}

impl HistoryRow {
    /// A row with only the cycle and the rut set (porosity 0.4, piston at 0.2 m): for tests of what reads ruts.
    #[cfg(test)]
    pub(crate) fn with_rut(cycle: u32, rut_mm: f64) -> Self {
        HistoryRow {
            cycle,
            complete: 1,
            steps: 0,
            time_s: 0.0,
            rut_mm,
            rut_max_mm: rut_mm,
            peak_kpa: 0.0,
            peak_raw_kpa: 0.0,
            tracking_rms_kpa: 0.0,
            tracking_rms_raw_kpa: 0.0,
            porosity_box: 0.4,
            piston_z_m: 0.2,
            grid_z_m: None,
        }
    }
}

/// Read a `history.csv`; a malformed file gets an error naming the file and the record.
pub fn read_history(path: &Path) -> Result<Vec<HistoryRow>> {
    let mut rd = csv::Reader::from_path(path)
        .with_context(|| format!("reading {} (a study history.csv)", path.display()))?;
    let mut rows = Vec::new();
    for (i, r) in rd.deserialize().enumerate() {
        let row: HistoryRow = r.with_context(|| {
            format!(
                "{}: record {} is malformed (expected the columns of yade_ref/study/README.md 'Outputs')",
                path.display(),
                i + 1
            )
        })?;
        rows.push(row);
    }
    if rows.is_empty() {
        bail!(
            "{}: no rows (the run did not reach the end of seating)",
            path.display()
        );
    }
    for (i, r) in rows.iter().enumerate() {
        if r.cycle as usize != i {
            bail!(
                "{}: row {} has cycle {} (rows must be cycles 0, 1, 2, ... in order)",
                path.display(),
                i + 1,
                r.cycle
            );
        }
        if !r.rut_mm.is_finite() || !r.porosity_box.is_finite() {
            bail!(
                "{}: cycle {} has a non-finite rut or porosity",
                path.display(),
                r.cycle
            );
        }
    }
    Ok(rows)
}

/// First difference between two `steps.csv` files of the same specimen (the exact-match horizon).
#[derive(Clone, Debug, Serialize)]
pub struct Horizon {
    /// Rows compared (each is one sampled step).
    pub rows_compared: usize,
    /// Iteration of the first sampled step where any value differs; None if all compared rows agree.
    pub first_diff_iter: Option<i64>,
    /// Phase (approach/seat/cycle) at that step.
    pub first_diff_phase: Option<String>,
    /// Last iteration compared.
    pub last_iter: i64,
    /// Whether the two history.csv files (17 significant digits) are byte-identical (set by the caller).
    pub history_identical: bool,
    /// Every compared row agreed and one run simply has more rows (a rut stop, or `--cycles` shorter
    /// than the other run's); `first_diff_iter` is then the longer run's next sample.
    pub one_ran_longer: bool,
}

pub fn exact_match_horizon(a: &Path, b: &Path) -> Result<Horizon> {
    let read = |p: &Path| -> Result<Vec<Vec<String>>> {
        let mut rd = csv::Reader::from_path(p)
            .with_context(|| format!("reading {} (a study steps.csv)", p.display()))?;
        let mut v = Vec::new();
        for r in rd.records() {
            let r = r.with_context(|| format!("{}: malformed record", p.display()))?;
            v.push(r.iter().map(str::to_string).collect());
        }
        Ok(v)
    };
    let (ra, rb) = (read(a)?, read(b)?);
    let n = ra.len().min(rb.len());
    let iter_of = |r: &Vec<String>| r.first().and_then(|s| s.parse::<i64>().ok()).unwrap_or(-1);
    for i in 0..n {
        if ra[i] != rb[i] {
            return Ok(Horizon {
                rows_compared: i + 1,
                first_diff_iter: Some(iter_of(&ra[i]).min(iter_of(&rb[i]))),
                first_diff_phase: ra[i].get(1).cloned(),
                last_iter: iter_of(&ra[i]),
                history_identical: false,
                one_ran_longer: false,
            });
        }
    }
    if ra.len() != rb.len() {
        // one run stopped earlier (rut limit) than the other: they differ right after
        let longer = if ra.len() > rb.len() { &ra } else { &rb };
        return Ok(Horizon {
            rows_compared: n,
            first_diff_iter: Some(iter_of(&longer[n])),
            first_diff_phase: longer[n].get(1).cloned(),
            last_iter: n.checked_sub(1).map(|k| iter_of(&ra[k])).unwrap_or(-1),
            history_identical: false,
            one_ran_longer: true,
        });
    }
    Ok(Horizon {
        rows_compared: n,
        first_diff_iter: None,
        first_diff_phase: None,
        last_iter: n.checked_sub(1).map(|k| iter_of(&ra[k])).unwrap_or(-1),
        history_identical: false,
        one_ran_longer: false,
    })
}

/// Sample mean and standard deviation (n - 1).
pub fn mean_sd(v: &[f64]) -> (f64, f64) {
    let n = v.len() as f64;
    if v.is_empty() {
        return (f64::NAN, f64::NAN);
    }
    let m = v.iter().sum::<f64>() / n;
    if v.len() < 2 {
        return (m, 0.0);
    }
    let s2 = v.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (n - 1.0);
    (m, s2.sqrt())
}

/// The band rule for one observable at one cycle.
#[derive(Clone, Debug, Serialize)]
pub struct CycleBand {
    pub cycle: u32,
    pub metric: &'static str,
    pub yade: Vec<f64>,
    pub yade_mean: f64,
    pub yade_sd: f64,
    pub lo: f64,
    pub hi: f64,
    pub ryade: Vec<f64>,
    pub ryade_mean: f64,
    /// (ryade_mean - yade_mean) / (yade_sd * sqrt(1/K_yade + 1/K_ryade)); 0 when both agree exactly.
    pub z_mean: f64,
    /// Largest |x - yade_mean| / yade_sd over the ryade runs (0 when they agree exactly).
    pub z_max_run: f64,
    pub inside: bool,
}

/// Band half-width: k standard deviations of YADE's runs, plus a floor of 1e-9 relative (so that
/// exactly equal values, e.g. a zero rut at cycle 0 in every run, are inside).
pub fn band(cycle: u32, metric: &'static str, yade: &[f64], ryade: &[f64], k: f64) -> CycleBand {
    let (m, sd) = mean_sd(yade);
    let (mr, _) = mean_sd(ryade);
    let floor = 1e-9 * m.abs().max(1e-12);
    let half = k * sd + floor;
    let z = |d: f64, s: f64| {
        if d.abs() <= floor {
            0.0
        } else if s > 0.0 {
            d / s
        } else {
            f64::INFINITY.copysign(d)
        }
    };
    let se = sd * (1.0 / yade.len() as f64 + 1.0 / ryade.len().max(1) as f64).sqrt();
    CycleBand {
        cycle,
        metric,
        yade: yade.to_vec(),
        yade_mean: m,
        yade_sd: sd,
        lo: m - half,
        hi: m + half,
        ryade: ryade.to_vec(),
        ryade_mean: mr,
        z_mean: z(mr - m, se),
        z_max_run: ryade.iter().map(|x| z(x - m, sd).abs()).fold(0.0, f64::max),
        inside: !ryade.is_empty() && ryade.iter().all(|x| *x >= m - half && *x <= m + half),
    }
}

/// The paired mean test of a chaotic engine against YADE on the same specimens: per cycle and metric,
/// Student's t of the differences ryade - YADE over the seeds (paired: seed s of both engines starts
/// from the same specimen), against the two-sided critical value at family-wise level `alpha` with
/// Bonferroni's correction over the `m` comparisons of the case. It asks whether the engine is biased
/// beyond what the seeds can resolve; its false-alarm rate is `alpha` by construction (a run of the same
/// distribution as YADE's gives t ~ Student(n - 1)), where the band rule's depends on the seeds and cycles.
#[derive(Clone, Debug, Serialize)]
pub struct MeanTest {
    /// Seeds (pairs).
    pub n: usize,
    /// Comparisons (cycles x metrics where the two engines differ).
    pub m: usize,
    pub alpha: f64,
    pub t_crit: f64,
    /// Largest |t| and where.
    pub t_max: f64,
    pub cycle: u32,
    pub metric: &'static str,
    /// The smallest mean difference the test detects at that cycle, in YADE's seed sd (t_crit sd(d) /
    /// sqrt(n) / sd(YADE)): how coarse the verdict is with these seeds.
    pub detectable_sd: f64,
    pub pass: bool,
}

/// Student's t of the paired differences b - a (0 when all are equal; infinite when they are all
/// equal to a non-zero value).
pub fn paired_t(a: &[f64], b: &[f64]) -> f64 {
    let d = differences(a, b);
    let (m, sd) = mean_sd(&d);
    t_of(m, sd, d.len())
}

fn differences(a: &[f64], b: &[f64]) -> Vec<f64> {
    a.iter().zip(b).map(|(x, y)| y - x).collect()
}

/// Student's t of `n` differences of mean `m` and sd `sd` (see [`paired_t`]).
fn t_of(m: f64, sd: f64, n: usize) -> f64 {
    if sd > 0.0 {
        m / (sd / (n as f64).sqrt())
    } else if m == 0.0 {
        0.0
    } else {
        f64::INFINITY.copysign(m)
    }
}

/// [`MeanTest`] over one case's bands; None without pairs (different seed counts, or fewer than 2).
pub fn mean_test(bands: &[CycleBand], alpha: f64) -> Option<MeanTest> {
    use statrs::distribution::{ContinuousCDF, StudentsT};
    let paired: Vec<&CycleBand> = bands
        .iter()
        .filter(|b| b.yade.len() == b.ryade.len() && b.yade != b.ryade)
        .collect();
    let n = bands.first()?.yade.len();
    if n < 2 || bands.iter().any(|b| b.yade.len() != b.ryade.len()) {
        return None;
    }
    let m = paired.len().max(1);
    let t_crit = StudentsT::new(0.0, 1.0, (n - 1) as f64)
        .ok()?
        .inverse_cdf(1.0 - alpha / (2.0 * m as f64));
    let mut worst = (0.0f64, 0u32, METRICS[0], 0.0f64);
    for b in &paired {
        let (mean_d, sd_d) = mean_sd(&differences(&b.yade, &b.ryade));
        let t = t_of(mean_d, sd_d, n).abs();
        if t > worst.0 || worst.0 == 0.0 {
            let det = if b.yade_sd > 0.0 {
                t_crit * sd_d / (n as f64).sqrt() / b.yade_sd
            } else {
                f64::INFINITY
            };
            worst = (t, b.cycle, b.metric, det);
        }
    }
    Some(MeanTest {
        n,
        m: paired.len(),
        alpha,
        t_crit,
        t_max: worst.0,
        cycle: worst.1,
        metric: worst.2,
        detectable_sd: worst.3,
        pass: worst.0 <= t_crit,
    })
}

/// Metrics compared cycle by cycle.
pub const METRICS: [&str; 2] = ["rut_mm", "porosity_box"];

fn metric(r: &HistoryRow, m: &str) -> f64 {
    match m {
        "rut_mm" => r.rut_mm,
        "porosity_box" => r.porosity_box,
        _ => f64::NAN,
    }
}

/// The band comparison of one case over seeds: cycles present in every run are compared.
pub fn compare_case(
    yade: &[Vec<HistoryRow>],
    ryade: &[Vec<HistoryRow>],
    k: f64,
) -> Result<Vec<CycleBand>> {
    if yade.len() < 2 {
        bail!("the band rule needs at least 2 YADE runs (use --seeds 2 or more)");
    }
    let ncyc = yade
        .iter()
        .chain(ryade.iter())
        .map(|h| h.len())
        .min()
        .unwrap_or(0);
    let mut out = Vec::new();
    for c in 0..ncyc {
        for m in METRICS {
            let y: Vec<f64> = yade.iter().map(|h| metric(&h[c], m)).collect();
            let r: Vec<f64> = ryade.iter().map(|h| metric(&h[c], m)).collect();
            out.push(band(c as u32, m, &y, &r, k));
        }
    }
    Ok(out)
}

/// Surface displacement ratio (seed-paper.txt Eq 1): (d_G - d_N) / (d_F - d_N), per cycle.
pub fn sdr(n: &[HistoryRow], g: &[HistoryRow], f: &[HistoryRow]) -> Vec<(u32, f64)> {
    let k = n.len().min(g.len()).min(f.len());
    (1..k)
        .map(|c| {
            let (dn, dg, df) = (n[c].rut_mm, g[c].rut_mm, f[c].rut_mm);
            (c as u32, (dg - dn) / (df - dn))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scenario_and_case_names() {
        assert_eq!(parse_scenario("r05").unwrap(), 5);
        let e = parse_scenario("r04").unwrap_err().to_string();
        assert!(e.contains("r03, r05 and r07"), "{}", e);
        assert!(parse_scenario("r050").is_err());
        assert_eq!(parse_cases("all").unwrap(), vec!['N', 'G', 'F']);
        assert!(parse_cases("X")
            .unwrap_err()
            .to_string()
            .contains("unknown case 'X'"));
        let c = CaseSpec {
            ratio: 3,
            case: 'G',
            size: "tiny".into(),
            seed: 2,
        };
        assert_eq!(c.name(), "r03_G_tiny_s2");
        assert_eq!(c.study_args()[1], "0.3");
    }

    /// The paired mean test: t of the differences, Student's quantile with Bonferroni's correction
    /// (t(4) at 1 - 0.01/22 is 8.827, as tables give), a constant offset of every seed fails it.
    #[test]
    fn paired_mean_test() {
        assert!(
            (paired_t(&[1.0, 2.0, 3.0], &[2.0, 2.0, 5.0]) - 1.0 / (1.0 / 3f64.sqrt())).abs()
                < 1e-12
        );
        assert_eq!(paired_t(&[1.0, 2.0], &[1.0, 2.0]), 0.0);
        assert_eq!(paired_t(&[1.0, 2.0], &[2.0, 3.0]), f64::INFINITY);
        let y: Vec<Vec<f64>> = (0..11)
            .map(|c| {
                [1.0, 2.0, 3.5, 4.0, 6.0]
                    .iter()
                    .map(|x| x + c as f64)
                    .collect()
            })
            .collect();
        let bands = |shift: f64, noise: f64| -> Vec<CycleBand> {
            y.iter()
                .enumerate()
                .map(|(c, v)| {
                    let r: Vec<f64> = v
                        .iter()
                        .enumerate()
                        .map(|(s, x)| x + shift + noise * (s as f64 - 2.0))
                        .collect();
                    band(c as u32, "rut_mm", v, &r, 3.0)
                })
                .collect()
        };
        let t = mean_test(&bands(0.0, 0.1), 0.01).unwrap();
        assert_eq!((t.n, t.m), (5, 11));
        assert!((t.t_crit - 8.827).abs() < 2e-3, "{}", t.t_crit);
        assert!(t.pass && t.t_max < 1e-9);
        let t = mean_test(&bands(1.0, 0.1), 0.01).unwrap();
        assert!(!t.pass && (t.t_max - 14.142).abs() < 1e-3, "{:?}", t);
    }

    /// The band rule: inside within k sd, outside beyond; exact equality passes with zero spread.
    #[test]
    fn band_rule() {
        let y = [10.0, 12.0, 14.0]; // mean 12, sd 2
        let b = band(1, "rut_mm", &y, &[12.0, 17.9], 3.0);
        assert!(b.inside);
        assert!((b.z_max_run - 2.95).abs() < 1e-12);
        let b = band(1, "rut_mm", &y, &[18.5], 3.0);
        assert!(!b.inside);
        let b = band(0, "rut_mm", &[0.0, 0.0, 0.0], &[0.0, 0.0], 3.0);
        assert!(b.inside && b.z_mean == 0.0);
        let b = band(0, "rut_mm", &[0.0, 0.0, 0.0], &[1e-3], 3.0);
        assert!(!b.inside);
    }

    #[test]
    fn surface_displacement_ratio() {
        let row = HistoryRow::with_rut;
        let n = vec![row(0, 0.0), row(1, 10.0)];
        let g = vec![row(0, 0.0), row(1, 8.0)];
        let f = vec![row(0, 0.0), row(1, 6.0)];
        assert_eq!(sdr(&n, &g, &f), vec![(1, 0.5)]);
    }

    #[test]
    fn malformed_history_is_a_clear_error() {
        let d = std::env::temp_dir().join(format!("ryade_hist_{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        let p = d.join("history.csv");
        std::fs::write(&p, "cycle,complete\n0,1\n").unwrap();
        let e = format!("{:#}", read_history(&p).unwrap_err());
        assert!(e.contains("history.csv: record 1 is malformed"), "{}", e);
        std::fs::remove_dir_all(&d).ok();
    }
}
