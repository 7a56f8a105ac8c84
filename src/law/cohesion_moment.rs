//! `Law2_ScGeom6D_CohFrictPhys_CohesionMoment` (pkg/dem/CohesiveFrictionalContactLaw.cpp): normal
//! spring with adhesion and plastic normal displacement `unp`, incremental shear with cohesion and
//! friction, and bending/twisting moments (total form from the ScGeom6D rotations, or incremental).

use super::{cxx_max, LawEnergy};
use crate::forces::Forces;
use crate::geom::{Rot6D, ScGeom};
use crate::math::{cross, dot, norm, Quat, Vec3};
use crate::phys::{CohFrictPhys, FrictPhys};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Params {
    /// Declared by YADE, not used by this law.
    pub never_erase: bool,
    pub always_use_moment_law: bool,
    pub shear_creep: bool,
    pub twist_creep: bool,
    pub trace_energy: bool,
    pub use_incremental_form: bool,
    pub creep_viscosity: f64,
}

impl Default for Params {
    fn default() -> Self {
        Params {
            never_erase: false,
            always_use_moment_law: false,
            shear_creep: false,
            twist_creep: false,
            trace_energy: false,
            use_incremental_form: false,
            creep_viscosity: 1.0,
        }
    }
}

/// Body data the law reads: positions (body 2 shifted by its period) and angular velocities.
pub struct Bodies2 {
    pub pos1: Vec3,
    pub pos2_shifted: Vec3,
    pub ang_vel1: Vec3,
    pub ang_vel2: Vec3,
}

/// What one contact adds to its two bodies, in the order `go` adds it: the force at the contact
/// point (with its torques), then, when the moment law acts, the moment (-moment on body 1, +moment
/// on body 2: a separate addition, so the torque sums keep YADE's rounding).
#[derive(Clone, Copy, Debug)]
pub struct CohLoad {
    pub force: Vec3,
    pub torque1: Vec3,
    pub torque2: Vec3,
    pub moment: Option<Vec3>,
}

/// Add a contact's load in `Law2_ScGeom6D_CohFrictPhys_CohesionMoment::go`'s order.
#[inline(always)]
pub fn apply(forces: &mut Forces, id1: usize, id2: usize, l: &CohLoad) {
    forces.add_force(id1, &l.force);
    forces.add_torque(id1, &l.torque1);
    forces.add_force(id2, &(-l.force));
    forces.add_torque(id2, &l.torque2);
    if let Some(m) = l.moment {
        forces.add_torque(id1, &(-m));
        forces.add_torque(id2, &m);
    }
}

/// Mirrors `Law2_ScGeom6D_CohFrictPhys_CohesionMoment::go` up to the loads it adds (`apply` adds
/// them in its order). `fresh` is `Interaction::isFresh` (made real this iteration). Ok(None) when
/// the bond breaks (or tension erases it).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub fn load(
    p: &Params,
    dt: f64,
    fresh: bool,
    g: &ScGeom,
    rot: &mut Rot6D,
    ph: &mut FrictPhys,
    cp: &mut CohFrictPhys,
    b: &Bodies2,
    energy: Option<&mut LawEnergy<'_>>,
) -> Result<Option<CohLoad>, String> {
    if fresh {
        ph.shear_force = Vec3::zeros();
    }
    let un = g.pen;
    let mut fn_ = ph.kn * (un - cp.unp);
    if cp.fragile && (-fn_) > cp.normal_adhesion {
        // tensile break
        return Ok(None);
    }
    if (-fn_) > cp.normal_adhesion {
        // normal plasticity
        fn_ = -cp.normal_adhesion;
        cp.unp = un + cp.normal_adhesion / ph.kn;
        if cp.unp_max >= 0.0 && -cp.unp > cp.unp_max {
            return Ok(None);
        }
    }
    ph.normal_force = g.normal * fn_;
    if p.shear_creep {
        let sf = ph.shear_force;
        let d = Vec3::new(
            ph.ks * ((sf[0] * dt) / p.creep_viscosity),
            ph.ks * ((sf[1] * dt) / p.creep_viscosity),
            ph.ks * ((sf[2] * dt) / p.creep_viscosity),
        );
        ph.shear_force -= d;
    }
    g.rotate(&mut ph.shear_force);
    ph.shear_force -= g.shear_inc * ph.ks;
    let fs = norm(&ph.shear_force);
    let mut max_fs = cp.shear_adhesion;
    if !cp.cohesion_disables_friction || max_fs == 0.0 {
        max_fs += fn_ * ph.tan_phi;
    }
    max_fs = cxx_max(0.0, max_fs);
    let mut energy = energy;
    if fs > max_fs {
        if cp.fragile && !cp.cohesion_broken {
            cp.set_breaking_state();
            max_fs = cxx_max(0.0, fn_ * ph.tan_phi);
        }
        max_fs /= fs;
        let trial = ph.shear_force;
        ph.shear_force *= max_fs;
        if let Some(e) = energy.as_mut() {
            let d = dot(&((trial - ph.shear_force) * (1.0 / ph.ks)), &ph.shear_force);
            if d > 0.0 {
                e.add(d, "shearDissip", false);
            }
        }
        if fn_ < 0.0 {
            ph.normal_force = Vec3::zeros();
        }
    }
    // LawFunctor::applyForceAtContactPoint
    let force = -ph.normal_force - ph.shear_force;
    let mut out = CohLoad {
        force,
        torque1: cross(&(g.contact_point - b.pos1), &force),
        torque2: -cross(&(g.contact_point - b.pos2_shifted), &force),
        moment: None,
    };

    if cp.moment_rotation_law && (!cp.cohesion_broken || p.always_use_moment_law) {
        if !p.use_incremental_form {
            if p.twist_creep {
                let m = if g.radius2 < g.radius1 {
                    g.radius2
                } else {
                    g.radius1
                };
                let viscosity_twist = p.creep_viscosity * ((2.0 * m) * (2.0 * m)) / 16.0;
                let creeped = rot.twist * (1.0 - dt / viscosity_twist);
                let q_twist = Quat::from_angle_axis(rot.twist, &g.normal);
                let q_creeped = Quat::from_angle_axis(creeped, &g.normal);
                let q_delta = q_creeped.mul(&q_twist.conjugate());
                rot.twist_creep = rot.twist_creep.mul(&q_delta);
            }
            cp.moment_twist = g.normal * (rot.twist * cp.ktw);
            cp.moment_bending = rot.bending * cp.kr;
        } else {
            if p.twist_creep {
                return Err("Law2_ScGeom6D_CohFrictPhys_CohesionMoment: no twis creep is included if the incremental form for the rotations is used.".into());
            }
            let rel = b.ang_vel2 - b.ang_vel1;
            let rel_bend = rel - g.normal * dot(&g.normal, &rel);
            let rot_bend = rel_bend * dt;
            g.rotate(&mut cp.moment_bending);
            cp.moment_bending -= rot_bend * cp.kr;
            let rel_twist = g.normal * dot(&g.normal, &rel);
            let rot_twist = rel_twist * dt;
            g.rotate(&mut cp.moment_twist);
            cp.moment_twist -= rot_twist * cp.ktw;
        }
        // (YADE logs a warning here on every call when a limit is active with the total form)
        if cp.max_roll_pl >= 0.0 {
            let roll_max = cp.max_roll_pl * norm(&ph.normal_force);
            let scalar_roll = norm(&cp.moment_bending);
            if scalar_roll > roll_max {
                let ratio = roll_max / scalar_roll;
                cp.moment_bending *= ratio;
                if let Some(e) = energy.as_mut() {
                    let d = (1.0 / cp.kr) * (scalar_roll - roll_max) * roll_max;
                    if d > 0.0 {
                        e.add(d, "bendingDissip", false);
                    }
                }
            }
        }
        if cp.max_twist_pl >= 0.0 {
            let twist_max = cp.max_twist_pl * norm(&ph.normal_force);
            let scalar_twist = norm(&cp.moment_twist);
            if scalar_twist > twist_max {
                let ratio = twist_max / scalar_twist;
                cp.moment_twist *= ratio;
                if let Some(e) = energy.as_mut() {
                    let d = (1.0 / cp.ktw) * (scalar_twist - twist_max) * twist_max;
                    if d > 0.0 {
                        e.add(d, "twistDissip", false);
                    }
                }
            }
        }
        out.moment = Some(cp.moment_twist + cp.moment_bending);
    }
    Ok(Some(out))
}
