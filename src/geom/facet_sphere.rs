//! `Ig2_Facet_Sphere_ScGeom` (pkg/dem/Ig2_Facet_Sphere_ScGeom.cpp): face, edge and vertex branches.

use super::{Pair, ScGeom};
use crate::math::{dot, mat_t_vec, mat_vec, norm, normalized, Mat3, Vec3};
use crate::shape::Facet;

#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Params {
    pub shrink_factor: f64,
    /// `hertzian`: the facet's equivalent radius (refR1) is 1e8 times the sphere's instead of twice it.
    pub hertzian: bool,
}

/// Body 1 is the facet, body 2 the sphere of radius `r`. A new contact needs a strictly positive
/// penetration; a real one is always updated.
pub fn go(p: &mut Params, facet: &Facet, r: f64, pr: &Pair, geom: &mut Option<ScGeom>) -> bool {
    go_rotated(p, facet, r, pr, geom, &pr.s1.ori.to_rotation_matrix())
}

/// `go` given the facet's rotation matrix `axis_t` (`pr.s1.ori.to_rotation_matrix()`), for a
/// caller that keeps it while the facet does not turn.
pub fn go_rotated(
    p: &mut Params,
    facet: &Facet,
    r: f64,
    pr: &Pair,
    geom: &mut Option<ScGeom>,
    axis_t: &Mat3,
) -> bool {
    let (s1, s2, shift2, is_real) = (&pr.s1, &pr.s2, &pr.shift2, pr.is_real);
    // branch vector in facet-local coordinates: facetAxis = axis_t^T
    let cl = mat_t_vec(axis_t, &(s2.pos + shift2 - s1.pos));
    let mut normal = facet.normal;
    let mut l = dot(&normal, &cl);
    if l < 0.0 {
        normal = -normal;
        l = -l;
    }
    if l > r && !is_real {
        return false;
    }
    let mut cp = cl - normal * l;
    let ne = &facet.ne;
    let mut bm = dot(&ne[0], &cp);
    let mut m = 0usize;
    for (i, nei) in ne.iter().enumerate().skip(1) {
        let b = dot(nei, &cp);
        if bm < b {
            bm = b;
            m = i;
        }
    }
    let mut sh = r * p.shrink_factor;
    let mut icr = facet.icr - sh;
    if icr < 0.0 {
        // YADE resets an over-large shrinkFactor with a warning
        p.shrink_factor = 0.0;
        icr = facet.icr;
        sh = 0.0;
    }
    let pen;
    if bm < icr {
        pen = r - l;
        normal = normalized(&normal);
    } else {
        cp += ne[m] * (icr - bm);
        let prev = if m == 0 { 2 } else { m - 1 };
        if dot(&cp, &ne[prev]) > icr {
            cp = facet.vu[m] * (facet.vl[m] - sh);
        } else {
            m = if m + 1 > 2 { 0 } else { m + 1 };
            if dot(&cp, &ne[m]) > icr {
                cp = facet.vu[m] * (facet.vl[m] - sh);
            }
        }
        normal = cl - cp;
        let nn = norm(&normal);
        normal = Vec3::new(normal[0] / nn, normal[1] / nn, normal[2] / nn);
        pen = r - nn;
    }
    if pen > 0.0 || is_real {
        let is_new = geom.is_none();
        let g = geom.get_or_insert_with(ScGeom::default);
        let n_global = mat_vec(axis_t, &normal);
        g.contact_point = s2.pos + shift2 - n_global * (r - 0.5 * pen);
        g.pen = pen;
        g.radius1 = if p.hertzian { 1e8 * r } else { 2.0 * r };
        g.radius2 = r;
        g.precompute(s1, s2, &pr.ctx, &n_global, is_new, shift2, false);
        return true;
    }
    false
}
