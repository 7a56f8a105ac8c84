//! The fast path's broad phase: a cell list builds a Verlet list of sphere pairs closer than
//! `r_i + r_j + skin`; the list stays valid until some body has moved more than `skin/2` since the
//! build. Bodies are renumbered in cell order (spatial sorting) at every build, so that neighbours
//! are near each other in memory. Takes the place of YADE's `InsertionSortCollider`; which pairs
//! interact is decided by the contact kernel's distance test, as in YADE.

use super::contact::{Pair, V3};
use rayon::prelude::*;
use rustc_hash::FxHashMap;

/// Bodies per block of the pair search (the unit of parallel work).
const BLOCK: usize = 256;

/// The cell grid over the (wrapped) positions.
struct Grid {
    origin: V3,
    inv_cs: V3,
    nc: [usize; 3],
    /// The periodic cell size per axis (None: an open domain).
    period: Option<V3>,
}

impl Grid {
    fn new(pos: &[V3], period: Option<V3>, reach: f64) -> Grid {
        let (origin, extent) = match period {
            Some(l) => ([0.0; 3], l),
            None => {
                let mut lo = [f64::INFINITY; 3];
                let mut hi = [f64::NEG_INFINITY; 3];
                for p in pos {
                    for k in 0..3 {
                        lo[k] = lo[k].min(p[k]);
                        hi[k] = hi[k].max(p[k]);
                    }
                }
                if pos.is_empty() {
                    lo = [0.0; 3];
                    hi = [0.0; 3];
                }
                (lo, [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]])
            }
        };
        let mut nc = [1usize; 3];
        let mut inv_cs = [0.0; 3];
        for k in 0..3 {
            // cells at least `reach` wide, at most ~2^20 in all
            let n = (extent[k] / reach).floor();
            nc[k] = if n.is_finite() && n >= 1.0 {
                (n as usize).min(128)
            } else {
                1
            };
            inv_cs[k] = if extent[k] > 0.0 {
                nc[k] as f64 / extent[k]
            } else {
                0.0
            };
        }
        Grid {
            origin,
            inv_cs,
            nc,
            period,
        }
    }

    /// The position wrapped into the period (unchanged in an open domain).
    #[inline]
    fn wrap(&self, p: &V3) -> V3 {
        match self.period {
            Some(l) => std::array::from_fn(|k| super::contact::wrap_into(p[k], l[k])),
            None => *p,
        }
    }

    #[inline]
    fn cell_of(&self, w: &V3) -> [usize; 3] {
        let mut c = [0usize; 3];
        for k in 0..3 {
            let x = ((w[k] - self.origin[k]) * self.inv_cs[k]).floor();
            c[k] = if x > 0.0 {
                (x as usize).min(self.nc[k] - 1)
            } else {
                0
            };
        }
        c
    }

    #[inline]
    fn linear(&self, c: [usize; 3]) -> usize {
        (c[0] * self.nc[1] + c[1]) * self.nc[2] + c[2]
    }

    /// The distinct neighbour cells along one axis (periodic wrap; fewer than 3 on a small grid).
    fn around(&self, k: usize, c: usize) -> ([usize; 3], usize) {
        let n = self.nc[k];
        let mut out = [c; 3];
        let mut m = 1;
        let cand: [Option<usize>; 2] = if self.period.is_some() {
            [Some((c + n - 1) % n), Some((c + 1) % n)]
        } else {
            [c.checked_sub(1), (c + 1 < n).then_some(c + 1)]
        };
        for x in cand.into_iter().flatten() {
            if !out[..m].contains(&x) {
                out[m] = x;
                m += 1;
            }
        }
        (out, m)
    }
}

/// The result of a build: body order, pairs and the periodic shifts they use.
pub struct Built {
    /// `order[new] = old`: the spatial order of the bodies.
    pub order: Vec<u32>,
    /// Pairs in the new numbering, sorted by i.
    pub pairs: Vec<Pair>,
    /// Shift vectors (index 0 is zero).
    pub shifts: Vec<V3>,
    /// The integer period of each shift (for exchanging contacts with the YADE-order path).
    pub shift_cells: Vec<[i32; 3]>,
    /// The positions in the new order, wrapped into the periodic cell (as given without one).
    pub wrapped: Vec<V3>,
    /// The cell list of the new order.
    pub cells: Cells,
}

/// The cell list of a build: the bodies are numbered in cell order, so the bodies of cell `c` are
/// `start[c]..start[c + 1]` (positions wrapped into the periodic cell, clamped into the grid).
pub struct Cells {
    grid: Grid,
    start: Vec<usize>,
}

impl Cells {
    /// The cells along axis `k` that may hold a body within `half` of `at` on that axis (nearest
    /// image on a periodic axis): the cells of `at - half` to `at + half`, the interval widened by
    /// far more than the rounding of wrapped positions and offsets; as two ascending, disjoint
    /// ranges (wrapped: `0..=b`, then `a..n`).
    fn span(&self, k: usize, at: f64, half: f64) -> [std::ops::Range<usize>; 2] {
        let g = &self.grid;
        let n = g.nc[k];
        let idx = |x: f64| ((x - g.origin[k]) * g.inv_cs[k]).floor();
        let eps = 1e-9 * (half + at.abs() + g.origin[k].abs() + 1.0 / g.inv_cs[k]);
        let (lo, hi) = (idx(at - half - eps), idx(at + half + eps));
        if !(lo.is_finite() && hi.is_finite()) || (g.period.is_some() && hi - lo + 1.0 >= n as f64)
        {
            return [0..n, n..n];
        }
        if g.period.is_some() {
            // fewer than n cells: lo..=hi shifted into the period wraps at most once
            let (lo, hi) = (lo as i64, hi as i64);
            let (a, b) = (
                lo.rem_euclid(n as i64) as usize,
                hi.rem_euclid(n as i64) as usize,
            );
            if a <= b {
                [a..b + 1, n..n]
            } else {
                [0..b + 1, a..n]
            }
        } else {
            let clamp = |x: f64| if x > 0.0 { (x as usize).min(n - 1) } else { 0 };
            [clamp(lo)..clamp(hi) + 1, n..n]
        }
    }

    /// Calls `f` with ascending, disjoint runs of bodies that hold every body whose wrapped position
    /// is within `half[k]` of `at[k]` on each axis k (nearest image on a periodic axis; an
    /// infinite `half` takes the whole axis).
    pub fn runs_near(&self, at: &V3, half: &V3, mut f: impl FnMut(std::ops::Range<usize>)) {
        let [sx, sy, sz] = std::array::from_fn(|k| self.span(k, at[k], half[k]));
        let mut runs = Vec::with_capacity(9);
        for x in sx.into_iter().flatten() {
            for y in sy.iter().cloned().flatten() {
                for z in sz.iter().cloned().flatten() {
                    add_cell(&mut runs, self.grid.linear([x, y, z]));
                }
            }
        }
        for (c0, c1) in runs {
            f(self.start[c0]..self.start[c1]);
        }
    }
}

/// Cell `c` (past the last run's cells) added to the runs of consecutive cells.
#[inline]
fn add_cell(runs: &mut Vec<(usize, usize)>, c: usize) {
    match runs.last_mut() {
        Some(r) if r.1 == c => r.1 = c + 1,
        _ => runs.push((c, c + 1)),
    }
}

/// Sort the bodies by cell and list every pair closer than `r_i + r_j + skin` (minimum image in a
/// periodic cell, which needs spheres smaller than half the cell, as YADE's collider does). With
/// `par` the search runs on the current rayon pool; the result does not depend on it.
pub fn build(pos: &[V3], radius: &[f64], period: Option<V3>, skin: f64, par: bool) -> Built {
    let n = pos.len();
    let rmax = radius.iter().cloned().fold(0.0, f64::max);
    let reach = 2.0 * rmax + skin;
    let grid = Grid::new(pos, period, reach);
    let wrapped: Vec<V3> = pos.iter().map(|p| grid.wrap(p)).collect();
    let cells: Vec<usize> = wrapped
        .iter()
        .map(|w| grid.linear(grid.cell_of(w)))
        .collect();
    let ncell = grid.nc[0] * grid.nc[1] * grid.nc[2];
    // counting sort by cell: the new order and each cell's range
    let mut start = vec![0usize; ncell + 1];
    for &c in &cells {
        start[c + 1] += 1;
    }
    for c in 0..ncell {
        start[c + 1] += start[c];
    }
    let mut fill = start.clone();
    let mut order = vec![0u32; n];
    for (old, &c) in cells.iter().enumerate() {
        order[fill[c]] = old as u32;
        fill[c] += 1;
    }
    // positions and radii in the new order: a cell's bodies side by side
    let ws: Vec<V3> = order.iter().map(|&o| wrapped[o as usize]).collect();
    let rs: Vec<f64> = order.iter().map(|&o| radius[o as usize]).collect();
    // the pair search, in blocks of bodies (in parallel when `par`: the blocks are concatenated in
    // order, so the list is the same for any thread count); periodic images are numbered after
    let search = |b: usize| -> Vec<(Pair, [i32; 3])> {
        let mut out = Vec::with_capacity(BLOCK * 8);
        // the neighbour cells of the current body's cell that hold later bodies (the bodies are
        // numbered in cell order: cells before its own hold only earlier ones), ascending, and
        // merged into runs of consecutive cells (the bodies of a run are consecutive)
        let mut runs: Vec<(usize, usize)> = Vec::with_capacity(27);
        let mut near: Vec<u32> = Vec::new();
        let mut neigh_of = usize::MAX;
        for ni in b * BLOCK..((b + 1) * BLOCK).min(n) {
            let i = order[ni] as usize;
            let own = cells[i];
            if own != neigh_of {
                let c = grid.cell_of(&wrapped[i]);
                runs.clear();
                let (mut ax, mx) = grid.around(0, c[0]);
                let (mut ay, my) = grid.around(1, c[1]);
                let (mut az, mz) = grid.around(2, c[2]);
                // (each axis ascending: the linear indices then come out ascending)
                ax[..mx].sort_unstable();
                ay[..my].sort_unstable();
                az[..mz].sort_unstable();
                for &x in &ax[..mx] {
                    for &y in &ay[..my] {
                        for &z in &az[..mz] {
                            let cell = grid.linear([x, y, z]);
                            if cell >= own {
                                add_cell(&mut runs, cell);
                            }
                        }
                    }
                }
                neigh_of = own;
            }
            // the distance test over the runs (no branch on its outcome: the bodies within reach
            // are written to `near` and counted), then the listed pairs' periods
            let minimum_image = |wi: &V3, wj: &V3| {
                let mut d = [wj[0] - wi[0], wj[1] - wi[1], wj[2] - wi[2]];
                if let Some(l) = period {
                    // minimum image of the wrapped difference (|d| < l). At |d| = l/2 either
                    // image is beyond reach (refused: 2 rmax + skin < l/2), so the plain
                    // comparison lists the pairs a rounding of d/l would
                    for k in 0..3 {
                        d[k] = super::contact::nearest_image(d[k], l[k]);
                    }
                }
                d
            };
            let mut m = 0;
            for &(c0, c1) in &runs {
                // (its own cell starts the first run: only the bodies after it)
                let from = if c0 == own { ni + 1 } else { start[c0] };
                let to = start[c1];
                if near.len() < m + (to - from) {
                    near.resize(m + (to - from), 0);
                }
                for nj in from..to {
                    let d = minimum_image(&ws[ni], &ws[nj]);
                    let lim = rs[ni] + rs[nj] + skin;
                    near[m] = nj as u32;
                    // (not beyond reach: a NaN distance is listed, as the kernel meets it)
                    let beyond = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > lim * lim;
                    m += !beyond as usize;
                }
            }
            for &nj in &near[..m] {
                let nj = nj as usize;
                // the period of the unwrapped difference
                let mut cd = [0i32; 3];
                if let Some(l) = period {
                    let d = minimum_image(&ws[ni], &ws[nj]);
                    let j = order[nj] as usize;
                    for k in 0..3 {
                        let s = d[k] - (pos[j][k] - pos[i][k]);
                        // (0, what the rounding gives, without its division and libm call: both
                        // bodies in the cell and no image taken, the common case)
                        cd[k] = if s == 0.0 {
                            0
                        } else {
                            (s / l[k]).round() as i32
                        };
                    }
                }
                let pair = Pair {
                    i: ni as u32,
                    j: nj as u32,
                    img: 0,
                };
                out.push((pair, cd));
            }
        }
        out
    };
    let nb = n.div_ceil(BLOCK);
    let found: Vec<Vec<(Pair, [i32; 3])>> = if par {
        (0..nb).into_par_iter().map(search).collect()
    } else {
        (0..nb).map(search).collect()
    };
    let mut shifts = vec![[0.0; 3]];
    let mut shift_cells = vec![[0i32; 3]];
    let mut shift_index: FxHashMap<[i32; 3], u32> = FxHashMap::default();
    shift_index.insert([0; 3], 0);
    let mut pairs = Vec::with_capacity(found.iter().map(Vec::len).sum());
    for (mut pair, cd) in found.into_iter().flatten() {
        if cd != [0; 3] {
            pair.img = *shift_index.entry(cd).or_insert_with(|| {
                let l = period.unwrap();
                shifts.push([
                    l[0] * cd[0] as f64,
                    l[1] * cd[1] as f64,
                    l[2] * cd[2] as f64,
                ]);
                shift_cells.push(cd);
                (shifts.len() - 1) as u32
            });
        }
        pairs.push(pair);
    }
    Built {
        order,
        pairs,
        shifts,
        shift_cells,
        wrapped: ws,
        cells: Cells { grid, start },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `Cells::runs_near` holds every body within the box (nearest image on a periodic axis), in
    /// ascending, disjoint runs: boxes of every size, centred anywhere (past the cell, at its
    /// faces, far away), an infinite one, open and periodic, grids of one or two cells per axis.
    /// Fails, checked, with the two ranges of a wrapped span swapped, or periodic axes taken as open.
    #[test]
    fn runs_near_holds_every_body_in_the_box() {
        let mut mt = rand_mt::Mt64::new(21);
        let mut rnd = move || (mt.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        for (l, period) in [
            ([1.0, 0.8, 1.3], true),
            ([1.0, 0.8, 1.3], false),
            ([0.09, 0.13, 1.3], true),
        ] {
            let n = 3000;
            // (every third body on a cell boundary of the periodic grid: cells of l / nc)
            let nc = l.map(|x| (x / 0.045f64).floor().min(128.0));
            let pos: Vec<V3> = (0..n)
                .map(|i| {
                    std::array::from_fn(|k| match i % 3 {
                        0 => (nc[k] * rnd()).floor() * (l[k] / nc[k]),
                        _ => l[k] * (1.4 * rnd() - 0.2),
                    })
                })
                .collect();
            let radius = vec![0.02; n];
            let b = build(&pos, &radius, period.then_some(l), 0.005, false);
            let mut seen = 0;
            for t in 0..600 {
                let mut half: V3 = std::array::from_fn(|_| 0.02 + 0.2 * rnd());
                // (a box with a body on one of its faces)
                let w = b.wrapped[(n as f64 * rnd()) as usize];
                let at: V3 = std::array::from_fn(|k| match t % 4 {
                    0 => l[k] * (1.6 * rnd() - 0.3),
                    1 => [0.0, l[k], -3.0 * l[k]][(3.0 * rnd()) as usize],
                    2 => [w[k] - half[k], w[k] + half[k]][t / 4 % 2],
                    _ => l[k] * 7.3,
                });
                if t % 50 == 5 {
                    half[t % 3] = f64::INFINITY;
                }
                let mut got = vec![false; n];
                let mut last = 0;
                b.cells.runs_near(&at, &half, |r| {
                    assert!(r.start >= last, "ascending, disjoint");
                    last = r.end;
                    for k in r {
                        got[k] = true;
                    }
                });
                for (k, w) in b.wrapped.iter().enumerate() {
                    let inside = (0..3).all(|a| {
                        let d = w[a] - at[a];
                        let d = if period {
                            d - l[a] * (d / l[a]).round()
                        } else {
                            d
                        };
                        d.abs() <= half[a]
                    });
                    if inside {
                        seen += 1;
                        assert!(got[k], "body {k} at {w:?}, box {at:?} +- {half:?}");
                    }
                }
            }
            assert!(seen > 1000, "{seen}");
        }
    }

    /// A body at a NaN position is listed with the bodies of the cells around its cell (a NaN
    /// distance is not beyond reach: the kernel then meets it, as it met it before the distance
    /// test was branch-free). Fails, checked, with the test written as `d² <= lim²`.
    #[test]
    fn a_nan_position_is_listed_with_its_neighbours() {
        for period in [None, Some([1.0, 1.0, 1.0])] {
            let mut pos: Vec<V3> = (0..4).map(|i| [0.001 * i as f64, 0.0, 0.0]).collect();
            pos[2] = [f64::NAN, 0.0, 0.0];
            let b = build(&pos, &[0.01; 4], period, 0.001, false);
            assert_eq!(b.pairs.len(), 6, "{period:?}");
        }
    }

    /// Every pair closer than r_i + r_j + skin is listed once, with the right image, whatever the
    /// grid (brute force over the 27 images).
    #[test]
    fn lists_exactly_the_pairs_within_reach() {
        let l = [1.0, 0.9, 1.1];
        let mut s: u64 = 12345;
        let mut rnd = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        let n = 300;
        let pos: Vec<V3> = (0..n)
            .map(|_| [3.0 * rnd() - 1.0, 3.0 * rnd() - 1.0, 3.0 * rnd() - 1.0])
            .collect();
        let radius: Vec<f64> = (0..n).map(|_| 0.03 + 0.04 * rnd()).collect();
        let skin = 0.02;
        for period in [Some(l), None] {
            let b = build(&pos, &radius, period, skin, false);
            let bp = build(&pos, &radius, period, skin, true);
            assert_eq!(b.pairs.len(), bp.pairs.len());
            assert!(b
                .pairs
                .iter()
                .zip(&bp.pairs)
                .all(|(x, y)| (x.i, x.j, x.img) == (y.i, y.j, y.img)));
            assert_eq!(b.shift_cells, bp.shift_cells);
            let mut got: Vec<(u32, u32, [i32; 3])> = b
                .pairs
                .iter()
                .map(|p| {
                    let (a, c) = (b.order[p.i as usize], b.order[p.j as usize]);
                    let cd = b.shift_cells[p.img as usize];
                    if a < c {
                        (a, c, cd)
                    } else {
                        (c, a, [-cd[0], -cd[1], -cd[2]])
                    }
                })
                .collect();
            got.sort();
            let mut want = Vec::new();
            let imgs: Vec<i32> = if period.is_some() {
                (-4..=4).collect()
            } else {
                vec![0]
            };
            for a in 0..n {
                for c in a + 1..n {
                    for &x in &imgs {
                        for &y in &imgs {
                            for &z in &imgs {
                                let cd = [x, y, z];
                                let d: Vec<f64> = (0..3)
                                    .map(|k| pos[c][k] + l[k] * cd[k] as f64 - pos[a][k])
                                    .collect();
                                let lim = radius[a] + radius[c] + skin;
                                if d.iter().map(|v| v * v).sum::<f64>() <= lim * lim {
                                    want.push((a as u32, c as u32, cd));
                                }
                            }
                        }
                    }
                }
            }
            want.sort();
            assert_eq!(got, want, "period {:?}", period);
        }
    }
}
