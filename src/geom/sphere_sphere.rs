//! `Ig2_Sphere_Sphere_ScGeom` (pkg/dem/Ig2_Sphere_Sphere_ScGeom.cpp).

use super::{Pair, ScGeom};
use crate::math::{norm, Real, Vec3};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Params {
    pub interaction_detection_factor: f64,
    pub avoid_granular_ratcheting: bool,
}

impl Default for Params {
    fn default() -> Self {
        Params {
            interaction_detection_factor: 1.0,
            avoid_granular_ratcheting: true,
        }
    }
}

/// The distance pre-check of `go` for a potential interaction, from positions alone (lets the
/// interaction loop skip gathering both bodies' kinematics for pairs that do not touch).
#[inline(always)]
pub fn within_reach(p: &Params, r1: f64, r2: f64, pos1: &Vec3, pos2: &Vec3, shift2: &Vec3) -> bool {
    !apart(p, r1, r2, &((pos2 + shift2) - pos1))
}

/// The test that leaves a potential pair potential: `d` (sphere 1 to sphere 2) longer than the
/// detection distance (NaN: not apart, as `go` goes on).
#[inline(always)]
pub fn apart(p: &Params, r1: f64, r2: f64, d: &Vec3) -> bool {
    apart_of(p.interaction_detection_factor, r1, r2, [d[0], d[1], d[2]])
}

/// `apart` in any arithmetic of the same operations (`f64`, or four pairs in lanes: the fast
/// path's first pass, `fast::six_simd`), so every caller decides to the same bit.
#[inline(always)]
pub fn apart_of<R: Real>(factor: R, r1: R, r2: R, d: [R; 3]) -> R::Mask {
    let f = factor * (r1 + r2);
    // pow(x, 2) is x*x in glibc for every finite x; |d|² in `math::norm2`'s (Eigen's) order
    (f * f - (d[0] * d[0] + (d[1] * d[1] + d[2] * d[2]))).lt(R::splat(0.0))
}

/// Returns false (no contact) only for a potential interaction whose spheres do not touch; a real
/// interaction always gets its geometry updated, even when the spheres have separated.
#[inline(always)]
pub fn go(p: &Params, r1: f64, r2: f64, pr: &Pair, geom: &mut Option<ScGeom>) -> bool {
    let (s1, s2, shift2) = (&pr.s1, &pr.s2, &pr.shift2);
    let d = (s2.pos + shift2) - s1.pos;
    if !pr.is_real && apart(p, r1, r2, &d) {
        return false;
    }
    let is_new = geom.is_none();
    let g = geom.get_or_insert_with(ScGeom::default);
    let dist = norm(&d);
    let n = Vec3::new(d[0] / dist, d[1] / dist, d[2] / dist);
    let pen = r1 + r2 - dist;
    g.contact_point = s1.pos + n * (r1 - 0.5 * pen);
    g.pen = pen;
    g.radius1 = r1;
    g.radius2 = r2;
    g.precompute(
        s1,
        s2,
        &pr.ctx,
        &n,
        is_new,
        shift2,
        p.avoid_granular_ratcheting,
    );
    true
}
