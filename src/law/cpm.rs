//! `Law2_ScGeom_CpmPhys_Cpm` (pkg/dem/ConcretePM.cpp), the public (reduced) concrete model Debian's
//! YADE is built with (no CPM_MATERIAL_MODEL): damage in tension driven by the largest equivalent
//! strain, Mohr-Coulomb shear plasticity reduced by damage, optional plastic softening in compression;
//! no rate dependence (dmgTau, plTau unused).

use super::Load;
use crate::geom::ScGeom;
use crate::math::{cross, cxx_max, norm, norm2, Vec3};
use crate::phys::{CpmPhys, FrictPhys};

/// The law functor's attributes the public model reads.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Params {
    pub omega_threshold: f64,
    pub eps_soft: f64,
    pub rel_kn_soft: f64,
    /// The yield surface attributes of the full model (read by nothing here; kept for the scene
    /// files): `yieldSurfType`, `yieldLogSpeed`, `yieldEllipseShift`.
    pub yield_surf_type: i32,
    pub yield_log_speed: f64,
    pub yield_ellipse_shift: f64,
}

impl Default for Params {
    fn default() -> Self {
        Params {
            omega_threshold: 1.0,
            eps_soft: 1.0,
            rel_kn_soft: 0.3,
            yield_surf_type: 2,
            yield_log_speed: 0.1,
            yield_ellipse_shift: f64::NAN,
        }
    }
}

/// What the first step of a contact sets from the two shapes (`isFresh` branch): two spheres
/// (their reference radii and centre distance) or a sphere against a facet, wall or box.
pub enum Fresh {
    Spheres {
        pos1: Vec3,
        pos2: Vec3,
        shift2: Vec3,
    },
    SphereOnPlane {
        radius: f64,
    },
}

/// How the forces reach the bodies: at the contact point (YADE's `applyForceAtContactPoint`), or, in
/// a periodic scene, with torques from the radii corrected by the initial overlap.
pub enum Arms {
    ContactPoint { pos1: Vec3, pos2: Vec3 },
    Periodic,
}

/// The outcome of one law call: the load to add, or the contact broken (erase it; YADE counts it in
/// both bodies' `CpmState.numBrokenCohesive`).
pub enum Outcome {
    Load(Load),
    Broken,
}

/// `Law2_ScGeom_CpmPhys_Cpm::go` up to the forces it adds.
pub fn load(
    p: &Params,
    fresh: Option<Fresh>,
    g: &ScGeom,
    ph: &mut FrictPhys,
    cp: &mut CpmPhys,
    arms: Arms,
) -> Result<Outcome, String> {
    if let Some(f) = fresh {
        match f {
            Fresh::Spheres { pos1, pos2, shift2 } => {
                let (r1, r2) = (g.radius1, g.radius2);
                let min_rad = if r1 <= 0.0 {
                    r2
                } else if r2 <= 0.0 {
                    r1
                } else {
                    crate::math::cxx_min(r1, r2)
                };
                cp.ref_length = norm(&((pos2 - pos1) + shift2));
                cp.cross_section = std::f64::consts::PI * (min_rad * min_rad);
                cp.ref_pd = r1 + r2 - cp.ref_length;
            }
            Fresh::SphereOnPlane { radius } => {
                cp.ref_length = radius;
                cp.cross_section = std::f64::consts::PI * (radius * radius);
                cp.ref_pd = 0.0;
            }
        }
        ph.kn = cp.cross_section * cp.e / cp.ref_length;
        ph.ks = cp.cross_section * cp.g / cp.ref_length;
        cp.eps_fracture = cp.eps_crack_onset * cp.rel_ductility;
    }
    let e = cp.e;
    let gm = cp.g;
    cp.eps_n = -(-cp.ref_pd + g.pen) / cp.ref_length;
    g.rotate(&mut cp.eps_t);
    cp.eps_t += g.shear_inc / cp.ref_length;
    if cp.eps_n.is_nan() || cp.eps_t[0].is_nan() {
        return Err(
            "Law2_ScGeom_CpmPhys_Cpm: the strain is NaN (YADE's verification fails too)".into(),
        );
    }
    // the simplified public model
    cp.eps_n += cp.iso_prestress / e;
    let xi2 = cp.equiv_strain_shear_contrib * cp.equiv_strain_shear_contrib;
    let en = cxx_max(cp.eps_n - cp.eps_n_pl, 0.0);
    let eps_norm = (en * en + xi2 * norm2(&cp.eps_t)).sqrt();
    cp.kappa_d = cxx_max(eps_norm, cp.kappa_d);
    cp.omega = if cp.is_cohesive {
        CpmPhys::func_g(
            cp.kappa_d,
            cp.eps_crack_onset,
            cp.eps_fracture,
            cp.never_damage,
            cp.dam_law,
        )?
    } else {
        1.0
    };
    let w = if cp.eps_n - cp.eps_n_pl > 0.0 {
        cp.omega
    } else {
        0.0
    };
    cp.sigma_n = (1.0 - w) * e * (cp.eps_n - cp.eps_n_pl);
    if p.eps_soft < 0.0 && cp.eps_n - cp.eps_n_pl < p.eps_soft {
        let sigma_n_soft = e * (p.eps_soft + p.rel_kn_soft * (cp.eps_n - cp.eps_n_pl - p.eps_soft));
        if sigma_n_soft > cp.sigma_n {
            cp.eps_n_pl += (cp.sigma_n - sigma_n_soft) / e;
            cp.sigma_n = sigma_n_soft;
        }
    }
    cp.sigma_t = (cp.eps_t - cp.eps_t_pl) * gm;
    let yield_sigma_t = cxx_max(
        0.0,
        cp.undamaged_cohesion * (1.0 - cp.omega) - cp.sigma_n * cp.tan_friction_angle,
    );
    if norm2(&cp.sigma_t) > yield_sigma_t * yield_sigma_t {
        let scale = yield_sigma_t / norm(&cp.sigma_t);
        cp.sigma_t *= scale;
        cp.eps_t_pl += cp.sigma_t * (1.0 - scale) / gm;
    }
    cp.rel_residual_strength = if cp.is_cohesive {
        if cp.kappa_d < cp.eps_crack_onset {
            1.0
        } else {
            (1.0 - cp.omega) * cp.kappa_d / cp.eps_crack_onset
        }
    } else {
        0.0
    };
    cp.sigma_n -= cp.iso_prestress;
    // YADE: epsN > 0 && ((isCohesive && omega > omegaThreshold) || !isCohesive)
    let breaks = if cp.is_cohesive {
        cp.omega > p.omega_threshold
    } else {
        true
    };
    if cp.eps_n > 0.0 && breaks {
        return Ok(Outcome::Broken);
    }
    cp.fn_ = cp.sigma_n * cp.cross_section;
    ph.normal_force = g.normal * -cp.fn_;
    cp.fs = cp.sigma_t * cp.cross_section;
    ph.shear_force = -cp.fs;
    let f = -ph.normal_force - ph.shear_force;
    Ok(Outcome::Load(match arms {
        Arms::ContactPoint { pos1, pos2 } => Load {
            force: f,
            torque1: cross(&(g.contact_point - pos1), &f),
            torque2: -cross(&(g.contact_point - pos2), &f),
        },
        Arms::Periodic => {
            let nf = cross(&g.normal, &f);
            Load {
                force: f,
                torque1: nf * (g.radius1 + 0.5 * (cp.ref_pd - g.pen)),
                torque2: nf * (g.radius2 + 0.5 * (cp.ref_pd - g.pen)),
            }
        }
    }))
}
