//! `Law2_ScGeom_ViscElPhys_Basic` (pkg/dem/ViscoelasticPM.cpp, `computeForceTorqueViscEl`): a linear
//! spring-dashpot in the normal direction (no attraction), an incremental shear spring whose elastic
//! part is capped by Coulomb friction and a shear dashpot that acts only while sticking, and an optional
//! rolling resistance.

use super::Load;
use crate::geom::ScGeom;
use crate::math::{cross, dot, norm, norm2, Vec3};
use crate::phys::{FrictPhys, ViscElPhys};

/// The body data the law reads (body 2 unshifted; `shift2`/`shift_vel` are the period's shifts).
pub struct Bodies {
    pub pos1: Vec3,
    pub pos2: Vec3,
    pub vel1: Vec3,
    pub vel2: Vec3,
    pub ang_vel1: Vec3,
    pub ang_vel2: Vec3,
    pub shift2: Vec3,
    pub shift_vel: Vec3,
}

/// The branches from the two centres to the contact point and the relative velocity there, split
/// into its normal component and shear vector: (c1x, c2x, normal, shear) (ViscoelasticPM.cpp
/// `computeForceTorqueViscEl`; LudingPM.cpp computes them the same way).
#[inline(always)]
pub(crate) fn contact_velocity(g: &ScGeom, b: &Bodies) -> (Vec3, Vec3, f64, Vec3) {
    let c1x = g.contact_point - b.pos1;
    let c2x = g.contact_point - b.pos2 - b.shift2;
    let rel_vel =
        (b.vel1 + cross(&b.ang_vel1, &c1x)) - (b.vel2 + cross(&b.ang_vel2, &c2x)) + b.shift_vel;
    let normal_vel = dot(&g.normal, &rel_vel);
    (c1x, c2x, normal_vel, rel_vel - g.normal * normal_vel)
}

/// `computeForceTorqueViscEl` (pkg/dem/ViscoelasticPM.cpp): None when the bodies are apart (the contact
/// is erased), else the load (`force` on body 1, as `law::apply` adds it). `fresh`: the interaction
/// became real this step (`Interaction::isFresh`).
pub fn load(
    dt: f64,
    fresh: bool,
    g: &ScGeom,
    ph: &mut FrictPhys,
    vp: &mut ViscElPhys,
    b: &Bodies,
) -> Option<Load> {
    if g.pen < 0.0 {
        return None;
    }
    if fresh {
        ph.shear_force = Vec3::zeros();
    }
    g.rotate(&mut ph.shear_force);
    let (c1x, c2x, normal_vel, shear_vel) = contact_velocity(g, b);
    // the elastic shear force has a history; the viscous one is the present velocity's only
    ph.shear_force += shear_vel * (ph.ks * dt);
    let mut shear_visc = Vec3::zeros();
    vp.fn_el = ph.kn * g.pen;
    vp.fv = vp.cn * normal_vel;
    let normal = vp.fn_el + vp.fv;
    ph.normal_force = if normal < 0.0 {
        Vec3::zeros()
    } else {
        g.normal * normal
    };
    let mut moment = Vec3::zeros();
    if vp.m_r > 0.0 {
        // (YADE normalizes a copy of the relative angular velocity and uses the raw one)
        let rel_ang_vel = b.ang_vel1 - b.ang_vel2;
        if vp.m_r_type == 1 {
            moment = rel_ang_vel * (-vp.m_r * norm(&ph.normal_force));
        } else if vp.m_r_type == 2 {
            let arm = norm(&(cross(&c1x, &b.ang_vel1) - cross(&c2x, &b.ang_vel2)));
            moment = rel_ang_vel * (-vp.m_r * arm * norm(&ph.normal_force));
        }
    }
    let max_fs = norm2(&ph.normal_force) * (ph.tan_phi * ph.tan_phi);
    if norm2(&ph.shear_force) > max_fs {
        let ratio = max_fs.sqrt() / norm(&ph.shear_force);
        ph.shear_force *= ratio;
    } else {
        shear_visc = shear_vel * vp.cs;
    }
    let force = ph.normal_force + ph.shear_force + shear_visc;
    Some(Load {
        force: -force,
        torque1: -cross(&c1x, &force) + moment,
        torque2: cross(&c2x, &force) - moment,
    })
}
