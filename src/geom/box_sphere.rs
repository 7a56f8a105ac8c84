//! `Ig2_Box_Sphere_ScGeom` and `Ig2_Box_Sphere_ScGeom6D` (pkg/dem/Ig2_Box_Sphere_ScGeom.cpp). Note
//! the YADE asymmetry kept on purpose: the centre-inside branch uses the ratcheting-free relative
//! velocity, the outside branch uses real lever arms.

use super::{GeomExt, Pair, Rot6D, ScGeom};
use crate::interaction::IntrExt;
use crate::math::r3::{self, R3};
use crate::math::{mat_vec, norm, normalized, Mat3, Real, Vec3};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Params {
    pub interaction_detection_factor: f64,
    /// `Ig2_Box_Sphere_ScGeom6D`: the ScGeom6D rotations on top of the ScGeom.
    pub six_d: bool,
}

impl Default for Params {
    fn default() -> Self {
        Params {
            interaction_detection_factor: 1.0,
            six_d: false,
        }
    }
}

/// `Ig2_Box_Sphere_ScGeom6D::go`: the ScGeom functor, then (when it made or kept a geometry) a new
/// contact becomes a ScGeom6D and the rotations are precomputed without creep.
pub fn go_6d(
    p: &Params,
    ext_half: &Vec3,
    r: f64,
    pr: &Pair,
    geom: &mut Option<ScGeom>,
    ext: &mut Option<Box<IntrExt>>,
) -> bool {
    let is_new = geom.is_none();
    if !go(p, ext_half, r, pr, geom) {
        return false;
    }
    let e = ext.get_or_insert_with(Default::default);
    if is_new || e.geom.is_none() {
        e.geom = Some(GeomExt::Sc6D(Rot6D::default()));
    }
    let normal = geom.as_ref().unwrap().normal;
    if let Some(rot) = e.geom.as_mut().and_then(|g| g.rot_mut()) {
        rot.precompute_rotations(&pr.s1.ori, &pr.s2.ori, &normal, is_new, false);
    }
    true
}

/// Body 1 is the box (half sizes `ext`), body 2 the sphere of radius `r`.
pub fn go(p: &Params, ext: &Vec3, r: f64, pr: &Pair, geom: &mut Option<ScGeom>) -> bool {
    go_rotated(p, ext, r, pr, geom, &pr.s1.ori.to_rotation_matrix())
}

/// `go` given the box's rotation matrix `axis_t` (`pr.s1.ori.to_rotation_matrix()`), for a caller
/// that keeps it while the box does not turn.
pub fn go_rotated(
    p: &Params,
    ext: &Vec3,
    r: f64,
    pr: &Pair,
    geom: &mut Option<ScGeom>,
    axis_t: &Mat3,
) -> bool {
    let (bx, sph, shift2, is_real) = (&pr.s1, &pr.s2, &pr.shift2, pr.is_real);
    let rel = sph.pos + shift2 - bx.pos;
    let c0 = r3::mat_t_vec(axis_t, &r3::of(&rel));
    let c = clamp_to_box(&c0, ext);
    // (bits unchanged: no component clamped; a NaN is not clamped either)
    let inside = (0..3).all(|i| c[i].to_bits() == c0[i].to_bits());
    let c = Vec3::from(c);
    if inside {
        let mut min_d = ext[0] - c[0].abs();
        let mut idx = 0;
        for i in 1..3 {
            let t = ext[i] - c[i].abs();
            if t < min_d {
                min_d = t;
                idx = i;
            }
        }
        let mut nl = Vec3::zeros();
        nl[idx] = if c[idx] > 0.0 { 1.0 } else { -1.0 };
        let normal = normalized(&mat_vec(axis_t, &nl));
        let pt1 = sph.pos + normal * min_d;
        let pt2 = sph.pos - normal * r;
        let normal2 = normalized(&(pt1 - pt2));
        let is_new = geom.is_none();
        let g = geom.get_or_insert_with(ScGeom::default);
        g.contact_point = (pt1 + pt2) * 0.5;
        g.pen = norm(&(pt1 - pt2));
        g.radius1 = r;
        g.radius2 = r;
        g.precompute(bx, sph, &pr.ctx, &normal2, is_new, shift2, true);
    } else {
        let (c_box, c_sph, depth) = outside_depth(axis_t, &r3::of(&c), &r3::of(&rel), r);
        if -depth > r * (p.interaction_detection_factor - 1.0) && !is_real {
            return false;
        }
        let sp = r3::of(&(sph.pos + shift2));
        let (cp, normal) = outside_contact(&c_box, &c_sph, &r3::of(&bx.pos), &sp, r);
        let is_new = geom.is_none();
        let g = geom.get_or_insert_with(ScGeom::default);
        g.contact_point = Vec3::from(cp);
        g.pen = depth;
        g.radius1 = r;
        g.radius2 = r;
        g.precompute(bx, sph, &pr.ctx, &Vec3::from(normal), is_new, shift2, false);
    }
    true
}

/// The sphere's centre `c` in the box's frame clamped into the box (half sizes `ext`), in any
/// arithmetic (f64 here, a contact per lane in the fast path's boundary loop).
#[inline(always)]
pub fn clamp_to_box<R: Real>(c: &R3<R>, ext: &Vec3) -> R3<R> {
    std::array::from_fn(|i| {
        let e = R::splat(ext[i]);
        let ci = R::select(c[i].lt(-e), -e, c[i]);
        R::select(ci.gt(e), e, ci)
    })
}

/// The centre-outside branch of `go_rotated` up to its distance test, in any arithmetic: the box's
/// point nearest the sphere's centre (`c` clamped, back in the world frame), the vector from the
/// centre (`rel` from the box's) to it, and the depth r - |that vector|.
#[inline(always)]
pub fn outside_depth<R: Real>(axis_t: &Mat3, c: &R3<R>, rel: &R3<R>, r: R) -> (R3<R>, R3<R>, R) {
    let c_box = r3::mat_vec(axis_t, c);
    let c_sph = r3::sub(&c_box, rel);
    let depth = r - r3::norm2(&c_sph).sqrt();
    (c_box, c_sph, depth)
}

/// The rest of the centre-outside branch, in any arithmetic: the contact point, halfway between
/// the box's point and the sphere's surface point along the same direction (the sphere's centre
/// `sphere` with its period's shift), and the normal (from the box to the sphere).
#[inline(always)]
pub fn outside_contact<R: Real>(
    c_box: &R3<R>,
    c_sph: &R3<R>,
    box_pos: &R3<R>,
    sphere: &R3<R>,
    r: R,
) -> (R3<R>, R3<R>) {
    let pt1 = r3::add(c_box, box_pos);
    let dir = r3::normalized(c_sph);
    let pt2 = r3::add(sphere, &r3::scale(&dir, r));
    (
        r3::scale(&r3::add(&pt1, &pt2), R::splat(0.5)),
        r3::neg(&dir),
    )
}
