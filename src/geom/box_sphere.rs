//! `Ig2_Box_Sphere_ScGeom` and `Ig2_Box_Sphere_ScGeom6D` (pkg/dem/Ig2_Box_Sphere_ScGeom.cpp). Note
//! the YADE asymmetry kept on purpose: the centre-inside branch uses the ratcheting-free relative
//! velocity, the outside branch uses real lever arms.

use super::{GeomExt, Pair, Rot6D, ScGeom};
use crate::interaction::IntrExt;
use crate::math::{mat_t_vec, mat_vec, norm, normalized, Mat3, Vec3};

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
    let mut c = mat_t_vec(axis_t, &rel);
    let mut inside = true;
    for i in 0..3 {
        if c[i] < -ext[i] {
            c[i] = -ext[i];
            inside = false;
        }
        if c[i] > ext[i] {
            c[i] = ext[i];
            inside = false;
        }
    }
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
        let c_box = mat_vec(axis_t, &c);
        let c_sph = c_box - rel;
        let depth = r - norm(&c_sph);
        if -depth > r * (p.interaction_detection_factor - 1.0) && !is_real {
            return false;
        }
        let pt1 = c_box + bx.pos;
        let dir = normalized(&c_sph);
        let pt2 = sph.pos + shift2 + dir * r;
        let is_new = geom.is_none();
        let g = geom.get_or_insert_with(ScGeom::default);
        g.contact_point = (pt1 + pt2) * 0.5;
        g.pen = depth;
        g.radius1 = r;
        g.radius2 = r;
        g.precompute(bx, sph, &pr.ctx, &(-dir), is_new, shift2, false);
    }
    true
}
