//! `Law2_ScGeom_MindlinPhys_Mindlin` (pkg/dem/HertzMindlin.cpp, `Law2_ScGeom_MindlinPhys_Mindlin::go`):
//! Hertz normal force `kno uN^1.5` (optional DMT adhesion), tangent stiffnesses from the overlap, an
//! incremental shear force capped by Coulomb friction, viscous damping from the damping ratios, and an
//! optional bending/twisting moment.

use super::Load;
use crate::geom::{Kin, ScGeom};
use crate::math::{cross, dot, norm, norm2, Vec3};
use crate::phys::{FrictPhys, MindlinPhys};

/// The law's attributes (`calcEnergy` is refused where the scene is read).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Params {
    pub include_adhesion: bool,
    pub include_moment: bool,
    pub never_erase: bool,
}

/// The body data the law reads.
pub struct Bodies {
    pub s1: Kin,
    pub s2: Kin,
    pub mass1: f64,
    pub mass2: f64,
    pub dynamic1: bool,
    pub dynamic2: bool,
    /// Period shifts of body 2 (zero without a cell).
    pub shift2: Vec3,
    pub shift_vel: Vec3,
    pub periodic: bool,
}

/// `pow` of the C library, never rewritten by the compiler (YADE calls `std::pow(uN, 1.5)` and
/// `std::pow(uN, 0.5)`, which are not always the bits of `x * sqrt(x)` and `sqrt(x)`).
#[inline(always)]
fn libm_pow(x: f64, y: f64) -> f64 {
    x.powf(std::hint::black_box(y))
}

/// What the law does with a contact.
pub enum Outcome {
    /// Apart: erase the interaction.
    Erase,
    /// Apart but kept (`neverErase`): forces zeroed, nothing added to the bodies.
    Keep,
    /// The force's load, then (with `includeMoment`) the moment added as -moment to body 1 and
    /// +moment to body 2 (separate additions after the load's torques, as YADE makes them).
    Apply(Load, Option<Vec3>),
}

/// `Law2_ScGeom_MindlinPhys_Mindlin::go` up to the forces it adds.
pub fn load(
    p: &Params,
    dt: f64,
    g: &ScGeom,
    ph: &mut FrictPhys,
    mp: &mut MindlinPhys,
    b: &Bodies,
) -> Outcome {
    let use_damping = mp.betan != 0. || mp.betas != 0.;
    let (mut cn, mut cs) = (0.0, 0.0);
    let un = g.pen;
    if un < 0.0 {
        if p.never_erase {
            ph.shear_force = Vec3::zeros();
            ph.normal_force = Vec3::zeros();
            ph.kn = 0.0;
            ph.ks = 0.0;
            return Outcome::Keep;
        }
        return Outcome::Erase;
    }
    let mut fn_ = mp.kno * libm_pow(un, 1.5);
    if p.include_adhesion {
        fn_ -= mp.adhesion_force;
        mp.is_adhesive = fn_ < 0.0;
    }
    ph.normal_force = g.normal * fn_;
    ph.kn = 3. / 2. * mp.kno * libm_pow(un, 0.5);
    ph.ks = mp.kso * libm_pow(un, 0.5);
    if use_damping {
        let mbar = if !b.dynamic1 && b.dynamic2 {
            b.mass2
        } else if !b.dynamic2 && b.dynamic1 {
            b.mass1
        } else {
            b.mass1 * b.mass2 / (b.mass1 + b.mass2)
        };
        let cn_crit = 2. * (mbar * ph.kn).sqrt();
        let cs_crit = 2. * (mbar * ph.ks).sqrt();
        cn = cn_crit * mp.betan;
        cs = cs_crit * mp.betas;
    }
    // shear force, incrementally
    g.rotate(&mut mp.shear_elastic);
    let incident_v = g.incident_vel(&b.s1, &b.s2, &b.shift2, &b.shift_vel, false);
    let incident_vn = g.normal * dot(&g.normal, &incident_v);
    let incident_vs = g.shear_inc / dt;
    mp.shear_elastic -= (incident_vs * dt) * ph.ks;
    if use_damping {
        mp.normal_viscous = incident_vn * cn;
        let norm_temp = ph.normal_force - mp.normal_viscous;
        if mp.adhesion_force == 0.0 || !p.include_adhesion {
            if dot(&norm_temp, &g.normal) < 0.0 {
                ph.normal_force = Vec3::zeros();
                mp.normal_viscous += norm_temp;
            } else {
                ph.normal_force -= mp.normal_viscous;
            }
        } else if dot(&norm_temp, &g.normal) < 0.0 && norm(&mp.normal_viscous) > mp.adhesion_force {
            let norm_visc = norm(&mp.normal_viscous);
            let dir = mp.normal_viscous / norm_visc;
            mp.normal_viscous = dir * mp.adhesion_force;
            ph.normal_force -= mp.normal_viscous;
        } else {
            ph.normal_force -= mp.normal_viscous;
        }
    }
    // elastic and total shear displacements
    g.rotate(&mut mp.us_elastic);
    mp.us_elastic -= incident_vs * dt;
    g.rotate(&mut mp.us_total);
    mp.us_total -= incident_vs * dt;
    // Mohr-Coulomb
    mp.is_sliding = false;
    mp.shear_viscous = Vec3::zeros();
    let fn_now = norm(&ph.normal_force);
    let max_fs = if !p.include_adhesion {
        fn_now * ph.tan_phi
    } else {
        ph.tan_phi * (mp.adhesion_force + fn_now)
    };
    if norm2(&mp.shear_elastic) > max_fs * max_fs {
        mp.is_sliding = true;
        let ratio = max_fs / norm(&mp.shear_elastic);
        mp.shear_elastic *= ratio;
        ph.shear_force = mp.shear_elastic;
        mp.us_elastic *= ratio;
    } else if use_damping {
        mp.shear_viscous = incident_vs * cs;
        ph.shear_force = mp.shear_elastic - mp.shear_viscous;
    } else {
        ph.shear_force = mp.shear_elastic;
    }
    let force = -ph.normal_force - ph.shear_force;
    let l = if !b.periodic {
        // LawFunctor::applyForceAtContactPoint (core/Dispatching.hpp)
        Load {
            force,
            torque1: cross(&(g.contact_point - b.s1.pos), &force),
            torque2: -cross(&(g.contact_point - b.s2.pos), &force),
        }
    } else {
        let nf = cross(&g.normal, &force);
        Load {
            force,
            torque1: nf * (g.radius1 - 0.5 * g.pen),
            torque2: nf * (g.radius2 - 0.5 * g.pen),
        }
    };
    let mut moment = None;
    if p.include_moment {
        let rel_ang_vel = b.s2.ang_vel - b.s1.ang_vel;
        let bend = rel_ang_vel - g.normal * dot(&g.normal, &rel_ang_vel);
        let rel_rot = bend * dt;
        g.rotate(&mut mp.moment_bend);
        mp.moment_bend -= rel_rot * mp.kr;
        let twist = g.normal * dot(&g.normal, &rel_ang_vel);
        let rel_rot_twist = twist * dt;
        g.rotate(&mut mp.moment_twist);
        mp.moment_twist -= rel_rot_twist * mp.ktw;
        let moment_max = mp.max_bend_pl * norm(&ph.normal_force);
        let scalar_moment = norm(&mp.moment_bend);
        if moment_max > 0.0 && scalar_moment > moment_max {
            let ratio = moment_max / scalar_moment;
            mp.moment_bend *= ratio;
        }
        moment = Some(mp.moment_twist + mp.moment_bend);
    }
    Outcome::Apply(l, moment)
}
