//! Skipping YADE's distance pre-check for idle sphere-sphere pairs that provably stay apart.
//!
//! Every step YADE's `InteractionLoop` calls `Ig2_Sphere_Sphere_ScGeom::go` on each potential
//! pair, and the functor returns early when `(f (r1 + r2))² - |d|² < 0` (f the
//! `interactionDetectionFactor`). On a dense packing most slots are such idle pairs (scene (a):
//! 60,600 of 77,800), and their checks cost a fifth of the loop. This module proves, from quantities
//! read once per step, that a pair checked apart earlier is still apart, so its check can be
//! skipped with the same outcome: the results do not change by a single bit.
//!
//! The proof: `travel` adds up, step after step, an upper bound on how much any pair's gap
//! `|d| - f (r1 + r2)` can have shrunk: twice the largest displacement of any body since the
//! previous loop (measured against a snapshot of the positions, so every mover counts: Newton,
//! Python, kinematic engines, clumps) plus twice f times the largest radius change. A pair found
//! apart with gap `g` when `travel` was `T` gets the deadline `T + g - tol`; while `travel` stays
//! below it, its gap is still positive. `tol` (1e-9 of the magnitudes involved) and the factor
//! `1 + 1e-9` on each step's bound cover floating-point rounding (relative 1e-16 per operation)
//! many times over. Whatever the bound cannot follow resets all deadlines, so every idle pair is
//! checked again: a change in the number of bodies, in the periodic cell's `hSize`, or in the
//! detection factor, a body that stops or starts being a sphere, a changed `GridConnection`, or a
//! non-finite position.
//!
//! Potential sphere-`GridConnection` pairs (`Ig2_Sphere_GridConnection_ScGridCoGeom`) are skipped
//! the same way: a point's distance to a segment shrinks by at most the point's displacement plus
//! the larger of the two ends' (every point of the segment is a convex combination of its ends), so
//! the same `travel` bounds it. That functor can also make a potential pair real without any
//! distance check, by taking over the contact of a neighbouring connection; it does so only when
//! the sphere has a real interaction with that neighbour. `grid_real` marks every body seen in a
//! real interaction with a connection during the current and the previous loop (and by
//! `createInteraction`): a real interaction is visited by every loop, so a sphere with a real
//! connection contact now is marked, and its potential connection pairs are never skipped.

use crate::body::Bodies;
use crate::cell::Cell;
use crate::interaction::ScanEntry;
use crate::math::{norm2, Mat3, Vec3};
use crate::shape::{GridConnection, Shape};

/// The snapshot and the accumulated bound (see the module doc); owned by the scene, used only by
/// the interaction loop.
#[derive(Clone, Debug, Default)]
pub struct IdleSkip {
    pos: Vec<Vec3>,
    /// Sphere radius, -1 for any other shape (a shape change is then a large radius change).
    radius: Vec<f64>,
    hsize: Option<Mat3>,
    factor: f64,
    /// Every `GridConnection` body and its shape at the snapshot (a change resets).
    conns: Vec<(u32, GridConnection)>,
    /// Per body: bit 1 set when seen in a real interaction with a connection during the current
    /// loop, bit 0 during the previous one (see the module doc); empty until the first mark.
    grid_real: Vec<u8>,
    /// Upper bound on how much any pair's gap has shrunk since the last reset.
    pub travel: f64,
}

fn radius_of(s: &Shape) -> f64 {
    match s {
        Shape::Sphere { radius } => *radius,
        _ => -1.0,
    }
}

impl IdleSkip {
    /// At the start of the interaction loop: advance `travel` by this step's bound and take the
    /// new snapshot, or reset (all deadlines of `scan` cleared, so every idle pair is checked).
    pub fn prepare(
        &mut self,
        bodies: &Bodies,
        cell: Option<&Cell>,
        factor: f64,
        scan: &mut [ScanEntry],
    ) {
        let hsize = cell.map(|c| c.hsize);
        let n = bodies.len();
        let mut reset = n != self.pos.len() || hsize != self.hsize || factor != self.factor;
        if !reset {
            let (mut d2max, mut drmax, mut nan, mut kind) = (0.0f64, 0.0f64, false, false);
            for id in 0..n {
                let p = bodies.pos[id];
                let r = radius_of(&bodies.shape[id]);
                let d2 = norm2(&(p - self.pos[id]));
                let dr = (r - self.radius[id]).abs();
                nan |= (d2 + dr).is_nan();
                kind |= (r < 0.0) != (self.radius[id] < 0.0);
                d2max = d2max.max(d2);
                drmax = drmax.max(dr);
                self.pos[id] = p;
                self.radius[id] = r;
            }
            let conns_changed =
                self.conns
                    .iter()
                    .any(|(id, c)| match &bodies.shape[*id as usize] {
                        Shape::GridConnection(now) => **now != *c,
                        _ => true,
                    });
            // a sphere-connection reach is r + R whatever the detection factor
            let step = 2.0 * (d2max.sqrt() + factor.abs().max(1.0) * drmax) * (1.0 + 1e-9);
            self.travel += step;
            reset = nan || kind || conns_changed || !self.travel.is_finite();
        }
        if reset {
            self.pos.clear();
            self.pos.extend_from_slice(&bodies.pos);
            self.radius.clear();
            self.radius.extend(bodies.shape.iter().map(radius_of));
            self.conns.clear();
            for (id, s) in bodies.shape.iter().enumerate() {
                if let Shape::GridConnection(c) = s {
                    self.conns.push((id as u32, (**c).clone()));
                }
            }
            self.hsize = hsize;
            self.factor = factor;
            self.travel = 0.0;
            for e in scan.iter_mut() {
                e.deadline = f64::NEG_INFINITY;
            }
        }
        // the current loop's marks become the previous loop's
        for m in self.grid_real.iter_mut() {
            *m >>= 1;
        }
    }

    /// Bodies `a` and `b` are in a real interaction that involves a `GridConnection` (or may be):
    /// their potential connection pairs are not skipped during this loop and the next.
    #[inline]
    pub fn mark_grid_real(&mut self, a: u32, b: u32) {
        let hi = a.max(b) as usize;
        if hi >= self.grid_real.len() {
            self.grid_real.resize(hi + 1, 0);
        }
        self.grid_real[a as usize] |= 2;
        self.grid_real[b as usize] |= 2;
    }

    /// True when the idle sphere-connection pair of `e` (sphere `e.id1`) is still apart by the
    /// bound and no take-over of a neighbour's contact is possible (see the module doc).
    #[inline(always)]
    pub fn skips_gridco(&self, e: &ScanEntry) -> bool {
        self.travel < e.deadline && self.grid_real.get(e.id1 as usize).copied().unwrap_or(0) == 0
    }

    /// The radius of body `id` when it was a sphere at the snapshot.
    #[inline(always)]
    pub fn sphere_radius(&self, id: u32) -> Option<f64> {
        let r = self.radius[id as usize];
        (r >= 0.0).then_some(r)
    }

    /// Both radii when both bodies are spheres (from the snapshot, which equals the shapes during
    /// the interaction loop: nothing in the loop changes a shape).
    #[inline(always)]
    pub fn sphere_radii(&self, a: u32, b: u32) -> Option<(f64, f64)> {
        let (r1, r2) = (self.radius[a as usize], self.radius[b as usize]);
        (r1 >= 0.0 && r2 >= 0.0).then_some((r1, r2))
    }

    /// True when the idle pair of `e` is still apart by the bound (its check can be skipped).
    #[inline(always)]
    pub fn skips(&self, e: &ScanEntry) -> bool {
        self.travel < e.deadline
    }

    /// The deadline of a pair just checked apart: `p1` and `p2s` (body 2's position plus the
    /// period shift) and `reach = f (r1 + r2)` as in the check.
    #[inline(always)]
    pub fn deadline(&self, p1: &Vec3, p2s: &Vec3, reach: f64) -> f64 {
        let d = p2s - p1;
        let gap = norm2(&d).sqrt() - reach;
        let scale = p1.amax() + p2s.amax() + reach.abs();
        self.travel + gap - 1e-9 * scale
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::utils;

    fn two_spheres(x2: f64) -> Bodies {
        let mut b = Bodies::default();
        for x in [0.0, x2] {
            b.push(utils::sphere(Vec3::new(x, 0.0, 0.0), 0.5, 0, 1000.0, false));
        }
        b
    }

    fn entry() -> ScanEntry {
        ScanEntry {
            id2: 1,
            idle: true,
            ..ScanEntry::default()
        }
    }

    /// A pair 0.5 apart stays skipped while the bodies creep together, and is checked again as
    /// soon as the accumulated travel could have closed the gap, however the body moved.
    #[test]
    fn skips_only_while_the_gap_cannot_have_closed() {
        let mut b = two_spheres(1.5);
        let mut s = IdleSkip::default();
        let mut scan = vec![entry()];
        s.prepare(&b, None, 1.0, &mut scan);
        assert!(!s.skips(&scan[0]), "a new idle pair is checked");
        scan[0].deadline = s.deadline(&b.pos[0], &b.pos[1], 1.0);
        // each step both spheres move 0.1 towards each other: the gap shrinks by 0.2 per step and
        // the bound by exactly as much (largest displacement 0.1, counted for both bodies)
        let mut skipped = 0;
        for _ in 0..5 {
            b.pos[0][0] += 0.1;
            b.pos[1][0] -= 0.1;
            s.prepare(&b, None, 1.0, &mut scan);
            if s.skips(&scan[0]) {
                skipped += 1;
            }
        }
        // gaps after each step 0.3, 0.1, -0.1...: skipped at the first two steps only
        assert_eq!(skipped, 2);
        // a teleport (Python writing `state.pos`) is a displacement like any other
        let mut b = two_spheres(10.0);
        let mut scan = vec![entry()];
        let mut s = IdleSkip::default();
        s.prepare(&b, None, 1.0, &mut scan);
        scan[0].deadline = s.deadline(&b.pos[0], &b.pos[1], 1.0);
        s.prepare(&b, None, 1.0, &mut scan);
        assert!(s.skips(&scan[0]));
        b.pos[1][0] = 1.0;
        s.prepare(&b, None, 1.0, &mut scan);
        assert!(!s.skips(&scan[0]));
    }

    /// Growing radii, a changed detection factor, a new body or a NaN position make every idle
    /// pair be checked again.
    #[test]
    fn radius_factor_body_count_and_nan_end_the_skipping() {
        let setups: [fn(&mut Bodies, &mut f64); 4] = [
            |b, _| {
                if let Shape::Sphere { radius } = &mut b.shape[1] {
                    *radius = 4.0
                }
            },
            |_, f| *f = 1.5,
            |b, _| {
                b.push(utils::sphere(
                    Vec3::new(20.0, 0.0, 0.0),
                    0.5,
                    0,
                    1000.0,
                    false,
                ));
            },
            |b, _| b.pos[0][1] = f64::NAN,
        ];
        for change in setups {
            let mut b = two_spheres(4.0);
            let mut f = 1.0;
            let mut s = IdleSkip::default();
            let mut scan = vec![entry()];
            s.prepare(&b, None, f, &mut scan);
            scan[0].deadline = s.deadline(&b.pos[0], &b.pos[1], f);
            s.prepare(&b, None, f, &mut scan);
            assert!(s.skips(&scan[0]));
            change(&mut b, &mut f);
            s.prepare(&b, None, f, &mut scan);
            assert!(!s.skips(&scan[0]));
        }
    }

    /// A mark blocks the sphere's connection pairs during the loop that set it and the next one;
    /// a connection whose nodes or radius change, or a sphere that becomes another shape, ends
    /// every skip.
    #[test]
    fn marks_last_two_loops_and_shape_changes_reset() {
        let mut b = two_spheres(4.0);
        let mut s = IdleSkip::default();
        let mut scan = vec![ScanEntry {
            idle: false,
            idle_gc: true,
            ..entry()
        }];
        s.prepare(&b, None, 1.0, &mut scan);
        scan[0].deadline = s.deadline(&b.pos[0], &b.pos[1], 1.0);
        s.prepare(&b, None, 1.0, &mut scan);
        assert!(s.skips_gridco(&scan[0]));
        s.mark_grid_real(0, 1);
        assert!(!s.skips_gridco(&scan[0]), "marked during this loop");
        s.prepare(&b, None, 1.0, &mut scan);
        assert!(!s.skips_gridco(&scan[0]), "marked during the previous loop");
        s.prepare(&b, None, 1.0, &mut scan);
        assert!(s.skips_gridco(&scan[0]), "no mark for two loops");
        // body 1 becomes a connection: kind change, reset
        b.shape[1] = Shape::GridConnection(Box::new(GridConnection {
            radius: 0.1,
            node1: 0,
            node2: 0,
            periodic: false,
            cell_dist: [0; 3],
        }));
        s.prepare(&b, None, 1.0, &mut scan);
        assert!(!s.skips_gridco(&scan[0]));
        scan[0].deadline = s.deadline(&b.pos[0], &b.pos[1], 1.0);
        s.prepare(&b, None, 1.0, &mut scan);
        assert!(s.skips_gridco(&scan[0]));
        // a thicker connection: reset
        if let Shape::GridConnection(c) = &mut b.shape[1] {
            c.radius = 0.2;
        }
        s.prepare(&b, None, 1.0, &mut scan);
        assert!(!s.skips_gridco(&scan[0]));
    }
}
