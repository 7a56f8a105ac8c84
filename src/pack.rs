//! Sphere packings: YADE's `SpherePack` and its random loose generator `makeCloud`.
//!
//! [`SpherePack::make_cloud`] reproduces YADE 2023.02a `SpherePack.makeCloud`
//! (`preprocessing/dem/SpherePack.cpp`) bit for bit for `seed >= 0`: the same `std::mt19937`
//! stream, the same libstdc++ `uniform_real_distribution<double>(0,1)` (two 32-bit draws per
//! number), the same radius rules, placement order, overlap test, 1000-try rule and restart rule,
//! and the same floating-point evaluation order (core.md §11–12). It is checked against YADE's
//! own output by `tests/pack_makecloud.rs` (goldens from `yade_ref/pack/clouds.py`).
//!
//! `seed < 0` draws a fresh seed from the operating system, like YADE's `std::random_device`, so
//! such clouds are **not reproducible** (neither in YADE nor here).
//!
//! Deviations from YADE, all on inputs where YADE produces garbage or undefined behaviour:
//! ryade returns an error instead (see [`SpherePack::make_cloud`]).

use crate::math::{mat_vec, norm2, sign, Mat3, Vec3};
use anyhow::{bail, Result};
use rand_mt::Mt;
use std::f64::consts::PI;

/// The 1000-try rule of `makeCloud`: a sphere that cannot be placed in this many tries ends
/// (or restarts) the generation.
pub const MAX_TRY: usize = 1000;

/// Arguments of `SpherePack.makeCloud`, with YADE's Python defaults ([`Default`]).
#[derive(Clone, Debug, PartialEq)]
pub struct CloudParams {
    /// `minCorner` (default 0).
    pub min_corner: Vec3,
    /// `maxCorner` (default 0).
    pub max_corner: Vec3,
    /// `rMean` (default -1: derived from `num` and `porosity`).
    pub r_mean: f64,
    /// `rRelFuzz` (default 0): radii uniform in `rMean·(1 ± rRelFuzz)`.
    pub r_rel_fuzz: f64,
    /// `num` (default -1: as many as fit, stochastic radii).
    pub num: i32,
    /// `periodic` (default false).
    pub periodic: bool,
    /// `porosity` (default 0.65): first guess when `rMean` is derived from `num`.
    pub porosity: f64,
    /// `psdSizes`: sieve sizes (diameters), empty by default.
    pub psd_sizes: Vec<f64>,
    /// `psdCumm`: cumulative fractions passing, same length as `psd_sizes`.
    pub psd_cumm: Vec<f64>,
    /// `distributeMass` (default false).
    pub distribute_mass: bool,
    /// `seed` (default -1: random seed from the OS, non-reproducible).
    pub seed: i32,
    /// `hSize`: base vectors (columns) of a sheared periodic cell; `None` (YADE's zero matrix)
    /// means the axis-aligned box `min_corner..max_corner`.
    pub h_size: Option<Mat3>,
}

impl Default for CloudParams {
    fn default() -> Self {
        CloudParams {
            min_corner: Vec3::zeros(),
            max_corner: Vec3::zeros(),
            r_mean: -1.0,
            r_rel_fuzz: 0.0,
            num: -1,
            periodic: false,
            porosity: 0.65,
            psd_sizes: Vec::new(),
            psd_cumm: Vec::new(),
            distribute_mass: false,
            seed: -1,
            h_size: None,
        }
    }
}

/// A list of spheres, as YADE's `SpherePack`.
#[derive(Clone, Debug, PartialEq)]
pub struct SpherePack {
    /// `(center, radius)` in insertion order.
    pub spheres: Vec<(Vec3, f64)>,
    /// Period of an axis-aligned periodic packing (`SpherePack.cellSize`); `None` when YADE's
    /// cellSize is zero. `make_cloud` sets it only for `periodic` without `h_size`, and leaves it
    /// untouched otherwise, as YADE does.
    pub cell_size: Option<Vec3>,
    /// `SpherePack.isPeriodic`: the `periodic` argument of the last `make_cloud`.
    pub is_periodic: bool,
    /// `SpherePack.appliedPsdScaling`: factor (<= 1) applied to the PSD radii by the last
    /// `make_cloud` with a PSD and `num > 1` (kept from before otherwise, as in YADE).
    pub applied_psd_scaling: f64,
    /// The warnings YADE would have logged during the last `make_cloud`.
    pub warnings: Vec<String>,
}

impl Default for SpherePack {
    fn default() -> Self {
        SpherePack {
            spheres: Vec::new(),
            cell_size: None,
            is_periodic: false,
            applied_psd_scaling: 1.0,
            warnings: Vec::new(),
        }
    }
}

/// libstdc++ `<random>` `uniform_real_distribution<double>(0,1)` over `std::mt19937` (YADE `SpherePack::makeCloud`).
struct Canonical {
    mt: Mt,
}

impl Canonical {
    fn new(seed: u32) -> Self {
        // rand_mt's Mt::new is MT19937's init_genrand, as std::mt19937(seed).
        Canonical { mt: Mt::new(seed) }
    }

    /// libstdc++ `generate_canonical<double,53>` on a 32-bit engine: two draws,
    /// `(g1 + g2·2^32) / 2^64`, clamped below 1.
    fn next(&mut self) -> f64 {
        const R: f64 = 4_294_967_296.0; // 2^32
        let mut sum = 0.0;
        let mut tmp = 1.0;
        for _ in 0..2 {
            sum += self.mt.next_u32() as f64 * tmp;
            tmp *= R;
        }
        let u = sum / tmp;
        // uniform_real_distribution then returns u*(1-0)+0, which is u.
        if u >= 1.0 {
            1.0 - f64::EPSILON / 2.0 // nextafter(1, 0)
        } else {
            u
        }
    }
}

/// A seed from the OS (YADE uses `std::random_device` for `seed < 0`): non-reproducible.
fn os_random_seed() -> u32 {
    use std::hash::{BuildHasher, Hasher};
    let mut h = std::collections::hash_map::RandomState::new().build_hasher();
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_nanos())
        .unwrap_or(0);
    h.write_u128(nanos);
    h.finish() as u32
}

/// glibc `pow` for the exponents YADE passes to `pow` as a library call (GCC without fast-math
/// only inlines exponents -1..2). The exponent goes through `black_box` so that LLVM cannot
/// rewrite e.g. `pow(x, 0.5)` into `sqrt(x)`, which may round differently.
#[inline(never)]
fn libm_pow(x: f64, y: f64) -> f64 {
    x.powf(std::hint::black_box(y))
}

/// Eigen 3.4 `Matrix3d::determinant()` (`Determinant.h`, 3x3 brute force).
fn eigen_det3(m: &Mat3) -> f64 {
    let h =
        |a: usize, b: usize, c: usize| m[(0, a)] * (m[(1, b)] * m[(2, c)] - m[(1, c)] * m[(2, b)]);
    h(0, 1, 2) - h(1, 0, 2) + h(2, 0, 1)
}

/// Eigen 3.4 `Matrix3d::inverse()` (`InverseImpl.h`, cofactors, `det = Σ cof_k0·m_k0` as `a0+(a1+a2)`).
fn eigen_inverse3(m: &Mat3) -> Mat3 {
    let cof = |i: usize, j: usize| {
        let (i1, i2, j1, j2) = ((i + 1) % 3, (i + 2) % 3, (j + 1) % 3, (j + 2) % 3);
        m[(i1, j1)] * m[(i2, j2)] - m[(i1, j2)] * m[(i2, j1)]
    };
    let c0 = [cof(0, 0), cof(1, 0), cof(2, 0)];
    let det = c0[0] * m[(0, 0)] + (c0[1] * m[(1, 0)] + c0[2] * m[(2, 0)]);
    let invdet = 1.0 / det;
    let mut r = Mat3::zeros();
    for (k, c) in c0.iter().enumerate() {
        r[(0, k)] = c * invdet;
    }
    for i in 1..3 {
        for j in 0..3 {
            r[(i, j)] = cof(j, i) * invdet;
        }
    }
    r
}

/// YADE `preprocessing/dem/SpherePack.cpp` `SpherePack::cellWrapRel`: `x` wrapped into
/// `[x0, x1)`, relative to `x0`.
fn cell_wrap_rel(x: f64, x0: f64, x1: f64) -> f64 {
    let x_norm = (x - x0) / (x1 - x0);
    (x_norm - x_norm.floor()) * (x1 - x0)
}

/// `std::min(a, b)`: `b < a ? b : a`.
fn std_min(a: f64, b: f64) -> f64 {
    if b < a {
        b
    } else {
        a
    }
}

/// YADE `preprocessing/dem/SpherePack.cpp` `SpherePack::pow3Interp`: radius between `a` and `b`
/// with a power -3 distribution.
fn pow3_interp(x: f64, a: f64, b: f64) -> f64 {
    libm_pow(
        x * (libm_pow(b, -2.0) - libm_pow(a, -2.0)) + libm_pow(a, -2.0),
        -1.0 / 2.0,
    )
}

/// YADE `preprocessing/dem/SpherePack.cpp` `SpherePack::psdGetPiece`: the piece of the
/// piecewise-linear cumulative curve `cumm` holding `x`, and the normalized position of `x` in it. Cases where YADE reads out of
/// bounds (x below the first or above the last value) are errors here.
fn psd_get_piece(x: f64, cumm: &[f64]) -> Result<(usize, f64)> {
    let sz = cumm.len();
    let mut i = 0;
    while i < sz && cumm[i] <= x {
        i += 1;
    }
    // (YADE's "i == sz-1 && cumm[i] <= x" branch can never be taken after that loop.)
    if i == 0 || i == sz {
        bail!(
            "SpherePack.makeCloud: drew {x} outside the cumulative curve [{}, {}]: psdCumm must \
             start at exactly 0 and end at exactly 1",
            cumm[0],
            cumm[sz - 1]
        );
    }
    let i = i - 1;
    let norm = (x - cumm[i]) / (cumm[i + 1] - cumm[i]);
    Ok((i, norm))
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Mode {
    RMean,
    Num,
    Psd,
}

/// Result of one pass of the generator.
enum Pass {
    Done(usize),
    /// 1000 tries exceeded in num mode: start over with this porosity.
    Restart(f64),
}

impl SpherePack {
    pub fn new() -> Self {
        Self::default()
    }

    /// YADE `SpherePack::add`.
    pub fn add(&mut self, center: Vec3, radius: f64) {
        self.spheres.push((center, radius));
    }

    pub fn len(&self) -> usize {
        self.spheres.len()
    }

    pub fn is_empty(&self) -> bool {
        self.spheres.is_empty()
    }

    /// YADE `preprocessing/dem/SpherePack.cpp` `SpherePack::makeCloud`: add a random loose cloud of non-overlapping spheres.
    ///
    /// Returns what YADE returns: `pack.len()` when all requested spheres were placed (or the
    /// cloud filled up), else the number placed by the final pass before 1000 tries failed.
    /// Spheres already in the pack are kept and avoided, and are dropped by a restart (as in YADE).
    ///
    /// Radius modes: `r_mean > 0` (radii `r_mean·(1 ± r_rel_fuzz)`), `num > 0` without PSD (r_mean
    /// derived from `porosity`, restarted with `porosity += (1-porosity)/10` when a sphere does not
    /// fit), or a PSD (`psd_sizes`/`psd_cumm`, optionally `distribute_mass`). With `num > 0`
    /// radii are deterministic and decreasing; otherwise each costs one random draw.
    ///
    /// Errors (YADE's, with its wording where it has one): psd arrays of different lengths or
    /// shorter than 2, psdCumm not from 0 to 1, non-monotonic PSD, rMean combined with a PSD,
    /// nothing to size the spheres by, a null-volume `h_size`, a num-mode box with zero volume
    /// and area. ryade-only errors, where YADE would produce garbage or undefined behaviour:
    /// non-finite arguments, a box of zero volume and
    /// zero area (no `h_size`), `r_rel_fuzz` outside [0, 1], `porosity >= 1` without `r_mean`, a random draw
    /// outside the PSD's cumulative curve.
    pub fn make_cloud(&mut self, p: &CloudParams) -> Result<usize> {
        self.warnings.clear();
        validate(p)?;
        let mut r_mean = p.r_mean;
        let mut porosity = p.porosity;
        loop {
            match self.cloud_pass(p, r_mean, porosity)? {
                Pass::Done(n) => return Ok(n),
                Pass::Restart(next) => {
                    // YADE recurses with rMean=-1, the new porosity and the same seed.
                    r_mean = -1.0;
                    porosity = next;
                }
            }
        }
    }

    /// One call of YADE `preprocessing/dem/SpherePack.cpp` `SpherePack::makeCloud` (the restart is the caller's loop).
    fn cloud_pass(&mut self, p: &CloudParams, mut r_mean: f64, mut porosity: f64) -> Result<Pass> {
        self.is_periodic = p.periodic;
        let seed = if p.seed >= 0 {
            p.seed as u32
        } else {
            os_random_seed()
        };
        let mut rng = Canonical::new(seed);

        let mn = p.min_corner;
        let size: Vec3 = p.max_corner - p.min_corner;
        let h_found = p.h_size.is_some_and(|h| h != Mat3::zeros());
        let h: Mat3 = match p.h_size {
            Some(h) if h_found => h,
            _ => Mat3::from_diagonal(&size),
        };
        if h_found && !p.periodic {
            self.warnings
                .push("hSize can be defined only for periodic cells.".into());
        }
        let volume = eigen_det3(&h);
        let inv_h = if h_found {
            eigen_inverse3(&h)
        } else {
            Mat3::zeros()
        };
        let area = (size[0] * size[2] + size[0] * size[1] + size[1] * size[2]).abs();
        if volume == 0.0 {
            if h_found {
                bail!(
                    "The period defined by hSize has null length in at least one direction, this is \
                     not supported. Define flat boxes via min-max and keep hSize undefined if you \
                     want a 2D packing."
                );
            }
            self.warnings.push(
                "The volume of the min-max box is null, we will assume that the packing is 2D."
                    .into(),
            );
        }

        if porosity <= 0.0 && r_mean <= 0.0 {
            self.warnings
                .push("porosity or rMean must be >0, setting porosity=0.5 for you.".into());
            porosity = 0.5;
        }
        let fuzz = p.r_rel_fuzz;
        let num = p.num;
        let mut mode = None;
        if r_mean > 0.0 {
            mode = Some(Mode::RMean);
        } else if num > 0 && p.psd_sizes.is_empty() {
            mode = Some(Mode::Num);
            if volume != 0.0 {
                r_mean = libm_pow(
                    volume * (1.0 - porosity)
                        / (PI * (4.0 / 3.0) * (1.0 + fuzz * fuzz) * num as f64),
                    1.0 / 3.0,
                );
            } else {
                if area == 0.0 {
                    bail!(
                        "The box defined has null volume AND null surface. Define at least maxCorner \
                         of the box, or hSize if periodic."
                    );
                }
                r_mean = libm_pow(
                    area * (1.0 - porosity) / (PI * (1.0 + fuzz * fuzz) * num as f64),
                    0.5,
                );
            }
        }

        let mut psd_radii: Vec<f64> = Vec::new();
        let mut psd_cumm2: Vec<f64> = Vec::new();
        let mut err = false;
        if !p.psd_sizes.is_empty() {
            err = mode.is_some();
            mode = Some(Mode::Psd);
            let sizes = &p.psd_sizes;
            let cumm = &p.psd_cumm;
            if sizes.len() != cumm.len() {
                bail!(
                    "SpherePack.makeCloud: psdSizes and psdCumm must have same dimensions ({}!={})",
                    sizes.len(),
                    cumm.len()
                );
            }
            if sizes.len() <= 1 {
                bail!("SpherePack.makeCloud: psdSizes must have at least 2 items");
            }
            let last = sizes.len() - 1;
            if cumm[0] != 0.0 && cumm[last] != 1.0 {
                bail!("SpherePack.makeCloud: first and last items of psdCumm *must* be exactly 0 and 1.");
            }
            // volume for the PSD bookkeeping: the box volume, or area × largest size in 2D
            let v_psd = if volume != 0.0 {
                volume
            } else {
                area * sizes[last]
            };
            for i in 0..sizes.len() {
                psd_radii.push(0.5 * sizes[i]);
                if p.distribute_mass {
                    if i == 0 {
                        psd_cumm2.push(0.0);
                    } else {
                        let inc = 3.0 * v_psd * (1.0 - porosity) / PI * (cumm[i] - cumm[i - 1])
                            / (sizes[i] - sizes[i - 1])
                            * (libm_pow(sizes[i - 1], -2.0) - libm_pow(sizes[i], -2.0));
                        psd_cumm2.push(psd_cumm2[i - 1] + inc);
                    }
                }
                if i > 0 && (sizes[i - 1] > sizes[i] || cumm[i - 1] > cumm[i]) {
                    bail!(
                        "SpherePack:makeCloud: psdSizes and psdCumm must be both non-decreasing."
                    );
                }
            }
            if num > 1 {
                self.applied_psd_scaling = 1.0;
                if p.distribute_mass {
                    if psd_cumm2[last] < num as f64 {
                        self.applied_psd_scaling =
                            libm_pow(psd_cumm2[last] / num as f64, 1.0 / 3.0);
                    }
                } else {
                    let mut tot_vol = 0.0;
                    for i in 1..sizes.len() {
                        // YADE writes `4 / 3 * PI`: integer 4/3 is 1, so the factor is just PI.
                        let mid = 0.5 * (sizes[i] + sizes[i - 1]);
                        let half = 0.5 * (sizes[i] - sizes[i - 1]);
                        tot_vol += PI
                            * (cumm[i] - cumm[i - 1])
                            * num as f64
                            * libm_pow(mid, 3.0)
                            * (1.0 + half * half);
                    }
                    let volume_ratio = tot_vol / ((1.0 - porosity) * v_psd);
                    if volume_ratio > 1.0 {
                        self.applied_psd_scaling = libm_pow(volume_ratio, -1.0 / 3.0);
                    }
                }
                if self.applied_psd_scaling < 1.0 {
                    for r in psd_radii.iter_mut() {
                        *r *= self.applied_psd_scaling;
                    }
                }
            }
            if p.distribute_mass {
                for i in 1..sizes.len() {
                    psd_cumm2[i] /= psd_cumm2[last];
                }
            }
        }
        let mode = match mode {
            Some(m) if !err => m,
            _ => bail!(
                "SpherePack.makeCloud: at least one of rMean, porosity, psdSizes & psdCumm arguments \
                 must be specified. rMean can't be combined with psdSizes."
            ),
        };

        if p.periodic && volume != 0.0 && !h_found {
            self.cell_size = Some(size);
        }
        let mut i: i32 = 0;
        while i < num || num < 0 {
            let rand = if num > 0 {
                (num as f64 - i as f64 + 0.5) / (num as f64 + 1.0)
            } else {
                rng.next()
            };
            let r = match mode {
                Mode::RMean | Mode::Num => {
                    if p.distribute_mass {
                        pow3_interp(rand, r_mean * (1.0 - fuzz), r_mean * (1.0 + fuzz))
                    } else {
                        r_mean * (2.0 * (rand - 0.5) * fuzz + 1.0)
                    }
                }
                Mode::Psd => {
                    if p.distribute_mass {
                        let (k, t) = psd_get_piece(rand, &psd_cumm2)?;
                        pow3_interp(t, psd_radii[k], psd_radii[k + 1])
                    } else {
                        let (k, t) = psd_get_piece(rand, &p.psd_cumm)?;
                        psd_radii[k] + t * (psd_radii[k + 1] - psd_radii[k])
                    }
                }
            };
            if !self.try_place(&mut rng, p.periodic, h_found, &mn, &size, &h, &inv_h, r) {
                if num > 0 {
                    if mode != Mode::RMean {
                        let next = porosity + (1.0 - porosity) / 10.0;
                        self.warnings.push(format!(
                            "Exceeded {MAX_TRY} tries to insert non-overlapping sphere to packing. Only \
                             {i} spheres were added, although you requested {num}. Trying again with \
                             porosity {next}. The size distribution is being scaled down"
                        ));
                        self.spheres.clear();
                        return Ok(Pass::Restart(next));
                    }
                    self.warnings.push(format!(
                        "Exceeded {MAX_TRY} tries to insert non-overlapping sphere to packing. Only {i} \
                         spheres were added, although you requested {num}."
                    ));
                }
                return Ok(Pass::Done(i as usize));
            }
            i += 1;
        }
        if self.applied_psd_scaling < 1.0 {
            self.warnings.push(format!(
                "The size distribution has been scaled down by a factor pack.appliedPsdScaling={}",
                self.applied_psd_scaling
            ));
        }
        Ok(Pass::Done(self.spheres.len()))
    }

    /// The try loop of YADE `preprocessing/dem/SpherePack.cpp` `SpherePack::makeCloud`: up to 1000 random positions for a sphere of
    /// radius `r`; the first free one is appended. Returns false if none was free.
    #[allow(clippy::too_many_arguments)]
    fn try_place(
        &mut self,
        rng: &mut Canonical,
        periodic: bool,
        h_found: bool,
        mn: &Vec3,
        size: &Vec3,
        h: &Mat3,
        inv_h: &Mat3,
        r: f64,
    ) -> bool {
        for _ in 0..MAX_TRY {
            let mut c = Vec3::zeros();
            if !periodic {
                // a zero-size axis (2-D packing) takes no draw
                for axis in 0..3 {
                    c[axis] = mn[axis]
                        + if size[axis] != 0.0 {
                            (size[axis] - 2.0 * r) * rng.next() + r
                        } else {
                            0.0
                        };
                }
            } else {
                for axis in 0..3 {
                    c[axis] = rng.next();
                }
                c = mat_vec(h, &c) + mn;
            }
            let overlap = if !periodic {
                self.spheres.iter().any(|(cj, rj)| {
                    let s = rj + r;
                    s * s >= norm2(&(cj - c))
                })
            } else {
                self.spheres.iter().any(|(cj, rj)| {
                    let mut dr = Vec3::zeros();
                    if !h_found {
                        for axis in 0..3 {
                            if size[axis] != 0.0 {
                                dr[axis] = std_min(
                                    cell_wrap_rel(c[axis], cj[axis], cj[axis] + size[axis]),
                                    cell_wrap_rel(cj[axis], c[axis], c[axis] + size[axis]),
                                );
                            }
                        }
                    } else {
                        // minimum image in reduced coordinates, then back to cartesian
                        let c1c2 = mat_vec(inv_h, &(cj - c));
                        for axis in 0..3 {
                            let x = c1c2[axis];
                            dr[axis] = if x.abs() < (x - sign(x)).abs() {
                                x
                            } else {
                                x - sign(x)
                            };
                        }
                        dr = mat_vec(h, &dr);
                    }
                    let s = rj + r;
                    s * s >= norm2(&dr)
                })
            };
            if !overlap {
                self.spheres.push((c, r));
                return true;
            }
        }
        false
    }
}

/// Argument checks that YADE does not make (it would produce garbage or undefined behaviour).
fn validate(p: &CloudParams) -> Result<()> {
    let finite_vec = |v: &Vec3| v.iter().all(|x| x.is_finite());
    if !finite_vec(&p.min_corner) || !finite_vec(&p.max_corner) {
        bail!("makeCloud: minCorner and maxCorner must be finite");
    }
    if !p.r_mean.is_finite() || !p.r_rel_fuzz.is_finite() || !p.porosity.is_finite() {
        bail!("makeCloud: rMean, rRelFuzz and porosity must be finite");
    }
    if let Some(h) = &p.h_size {
        if !h.iter().all(|x| x.is_finite()) {
            bail!("makeCloud: hSize must be finite");
        }
    }
    let h_found = p.h_size.is_some_and(|h| h != Mat3::zeros());
    let size = p.max_corner - p.min_corner;
    if !h_found {
        // maxCorner below minCorner on an axis is accepted, as YADE does (SpherePack::makeCloud
        // draws minCorner + u * (maxCorner - minCorner): the box is the same, walked the other way;
        // YADE's examples/funnel.py relies on it)
        let nonzero = size.iter().filter(|&&s| s != 0.0).count();
        if nonzero < 2 {
            bail!(
                "makeCloud: the box minCorner {:?} .. maxCorner {:?} has zero volume and zero area; \
                 give maxCorner > minCorner on at least two axes (or hSize for a periodic cell)",
                p.min_corner.as_slice(),
                p.max_corner.as_slice()
            );
        }
    }
    if !(0.0..=1.0).contains(&p.r_rel_fuzz) {
        bail!(
            "makeCloud: rRelFuzz must be in [0, 1], got {}",
            p.r_rel_fuzz
        );
    }
    if p.r_mean <= 0.0 && p.porosity >= 1.0 {
        bail!(
            "makeCloud: porosity must be < 1 when rMean is not given, got {}",
            p.porosity
        );
    }
    if p.psd_sizes
        .iter()
        .chain(p.psd_cumm.iter())
        .any(|x| !x.is_finite())
    {
        bail!("makeCloud: psdSizes and psdCumm must be finite");
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// std::mt19937 with seed 5489 (the default): the C++ standard requires the 10000th output
    /// to be 4123659995.
    #[test]
    fn mt_matches_std_mt19937() {
        let mut mt = Mt::new(5489);
        let mut x = 0;
        for _ in 0..10000 {
            x = mt.next_u32();
        }
        assert_eq!(x, 4_123_659_995);
    }

    #[test]
    fn canonical_is_in_unit_interval() {
        let mut g = Canonical::new(1);
        for _ in 0..1000 {
            let u = g.next();
            assert!((0.0..1.0).contains(&u));
        }
    }

    #[test]
    fn eigen_det_and_inverse() {
        let m = Mat3::new(1.0, 0.2, 0.0, 0.0, 0.9, 0.15, 0.1, 0.0, 1.1);
        let inv = eigen_inverse3(&m);
        let id = m * inv;
        assert!((id - Mat3::identity()).abs().max() < 1e-15);
        assert!((eigen_det3(&m) - m.determinant()).abs() < 1e-15);
    }

    #[test]
    fn psd_piece() {
        let c = [0.0, 0.3, 0.3, 1.0];
        assert_eq!(psd_get_piece(0.1, &c).unwrap().0, 0);
        assert_eq!(psd_get_piece(0.3, &c).unwrap().0, 2);
        assert!(psd_get_piece(1.0, &c).is_err());
    }
}
