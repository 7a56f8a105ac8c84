//! `Ig2_Wall_Sphere_ScGeom` (pkg/dem/Ig2_Facet_Sphere_ScGeom.cpp, second class in the file).

use super::{Pair, ScGeom};
use crate::math::Vec3;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Params {
    pub no_ratch: bool,
    /// `hertzian`: the wall's equivalent radius (refR1) is 1e8 times the sphere's instead of the sphere's.
    pub hertzian: bool,
}

impl Default for Params {
    fn default() -> Self {
        Params {
            no_ratch: true,
            hertzian: false,
        }
    }
}

/// Body 1 is the wall (axis, sense), body 2 the sphere of radius `r`.
pub fn go(
    p: &Params,
    axis: usize,
    sense: i32,
    r: f64,
    pr: &Pair,
    geom: &mut Option<ScGeom>,
) -> bool {
    let (wall, sph, shift2) = (&pr.s1, &pr.s2, &pr.shift2);
    let dist = sph.pos[axis] + shift2[axis] - wall.pos[axis];
    if !pr.is_real && dist.abs() > r {
        return false;
    }
    let mut cp = sph.pos + shift2;
    cp[axis] = wall.pos[axis];
    let mut n = Vec3::zeros();
    n[axis] = if sense == 0 {
        if dist > 0.0 {
            1.0
        } else {
            -1.0
        }
    } else if sense == 1 {
        1.0
    } else {
        -1.0
    };
    let is_new = geom.is_none();
    let g = geom.get_or_insert_with(ScGeom::default);
    // the wall's "radius" is the sphere's (non-Hertzian default)
    g.radius1 = if p.hertzian { 1e8 * r } else { r };
    g.radius2 = r;
    g.contact_point = cp;
    g.pen = -(dist.abs() - r);
    g.precompute(wall, sph, &pr.ctx, &n, is_new, shift2, p.no_ratch);
    true
}
