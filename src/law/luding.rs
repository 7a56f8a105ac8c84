//! `Law2_ScGeom_LudingPhys_Basic` (pkg/dem/LudingPM.cpp): Luding's hysteretic normal spring (plastic
//! loading slope k1, unloading/reloading k2 growing with the largest overlap up to kp, adhesive branch
//! kc), viscous damping G0, an incremental shear spring capped by Coulomb friction with a shear dashpot
//! while sticking.

use super::Load;
use crate::geom::ScGeom;
use crate::math::{cross, norm, norm2, Vec3};
use crate::phys::{FrictPhys, LudingPhys};

/// `Law2_ScGeom_LudingPhys_Basic::go` up to the forces it adds (None: apart, erase). `b` as in the
/// viscoelastic law (body 2 unshifted, the period's shifts apart).
pub fn load(
    dt: f64,
    fresh: bool,
    g: &ScGeom,
    ph: &mut FrictPhys,
    lp: &mut LudingPhys,
    b: &super::viscel::Bodies,
) -> Option<Load> {
    let delt = g.pen;
    if delt < 0.0 {
        return None;
    }
    let mut force_hys = 0.0;
    if lp.delt_max / lp.delt_p_max >= 1.0 {
        lp.k2 = lp.kp;
    } else {
        lp.k2 = lp.k1 + (lp.kp - lp.k1) * lp.delt_max / lp.delt_p_max;
    }
    if lp.k2 > lp.kp {
        lp.k2 = lp.kp;
    }
    if lp.k1 > lp.k2 {
        lp.k1 = lp.k2;
    }
    lp.delt_min = (lp.k2 - lp.k1) / (lp.k2 + lp.kc);
    let null_of =
        |lp: &LudingPhys| crate::math::cxx_min((1.0 - lp.k1 / lp.k2) * lp.delt_max, lp.delt_p_null);
    if delt > lp.delt_max {
        lp.delt_max = delt;
        lp.delt_null = null_of(lp);
    }
    let k2_delt = lp.k2 * (delt - lp.delt_null);
    if k2_delt >= lp.k1 * delt {
        force_hys = if delt < lp.delt_p_max {
            lp.k1 * delt
        } else {
            k2_delt
        };
    } else if k2_delt > -lp.kc * delt && k2_delt < lp.k1 * delt {
        force_hys = k2_delt;
    } else if k2_delt <= -lp.kc * delt {
        if delt - lp.delt_prev < 0.0 {
            force_hys = -lp.kc * delt;
            lp.delt_max = delt * (lp.k2 + lp.kc) / (lp.k2 - lp.k1);
            lp.delt_null = null_of(lp);
        } else {
            force_hys = k2_delt;
        }
    }
    lp.delt_prev = delt;
    if fresh {
        ph.shear_force = Vec3::zeros();
    }
    g.rotate(&mut ph.shear_force);
    let (c1x, c2x, normal_vel, shear_vel) = super::viscel::contact_velocity(g, b);
    ph.shear_force += shear_vel * (ph.ks * dt);
    let mut shear_visc = Vec3::zeros();
    ph.normal_force = g.normal * (force_hys + lp.g0 * normal_vel);
    let max_fs = norm2(&ph.normal_force) * (ph.tan_phi * ph.tan_phi);
    if norm2(&ph.shear_force) > max_fs {
        let ratio = max_fs.sqrt() / norm(&ph.shear_force);
        ph.shear_force *= ratio;
    } else {
        shear_visc = shear_vel * lp.g0;
    }
    let f = ph.normal_force + ph.shear_force + shear_visc;
    Some(Load {
        force: -f,
        torque1: -cross(&c1x, &f),
        torque2: cross(&c2x, &f),
    })
}
