//! Constitutive laws (Law2 functors). This file: `Law2_ScGeom_FrictPhys_CundallStrack`
//! (pkg/dem/ElasticContactLaw.cpp): linear normal spring, incremental shear spring with a Coulomb
//! cap. `cohesion_moment`: the cohesive law with moments (grid bonds, rolling resistance); `grid`:
//! the sphere-connection and connection-connection laws that put the force on the grid nodes; `viscel`:
//! the viscoelastic law of ViscElMat; `mindlin`: Hertz-Mindlin.

pub mod bubble;
pub mod cohesion_moment;
pub mod cpm;
pub mod grid;
pub mod luding;
pub mod mindlin;
pub mod viscel;

use crate::energy::{EnergyTracker, IdCache};
use crate::forces::Forces;
use crate::geom::ScGeom;
use crate::math::r3::{self, R3};
use crate::math::{norm2, Real, Vec3};
use crate::phys::FrictPhys;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Params {
    pub never_erase: bool,
    pub spherical_bodies: bool,
}

impl Default for Params {
    fn default() -> Self {
        Params {
            never_erase: false,
            spherical_bodies: true,
        }
    }
}

/// Where a law adds its energy terms while `O.trackEnergy` (YADE `scene->energy->add`): the scene's
/// tracker and the index caches of the InteractionLoop's law functors (one per `LawFunctor`, as each
/// YADE functor instance caches its own `plastDissipIx`, `elastPotentialIx`, ...).
pub struct LawEnergy<'a> {
    pub tracker: &'a mut EnergyTracker,
    pub caches: &'a mut [IdCache; LawFunctor::COUNT],
    /// The functor running now (set by the dispatch before it calls the law).
    pub functor: LawFunctor,
    /// Its `traceEnergy` (GridCoGridCo only): slip dissipation to the functor's own counter.
    pub trace: bool,
}

impl LawEnergy<'_> {
    #[inline]
    pub fn add(&mut self, val: f64, name: &'static str, reset: bool) {
        let c = &mut self.caches[self.functor as usize];
        self.tracker.add(val, name, c, reset);
    }
}

/// Which Law2 functor handles an interaction (resolved from its geometry and physics classes).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LawFunctor {
    /// `Law2_ScGeom_FrictPhys_CundallStrack`
    CundallStrack,
    /// `Law2_ScGeom6D_CohFrictPhys_CohesionMoment`
    CohesionMoment,
    /// `Law2_ScGridCoGeom_FrictPhys_CundallStrack`
    ScGridCoFrict,
    /// `Law2_ScGridCoGeom_CohFrictPhys_CundallStrack`
    ScGridCoCohFrict,
    /// `Law2_GridCoGridCoGeom_FrictPhys_CundallStrack`
    GridCoGridCoFrict,
    /// `Law2_ScGeom_ViscElPhys_Basic`
    ViscElBasic,
    /// `Law2_ScGeom_MindlinPhys_Mindlin`
    Mindlin,
    /// `Law2_ScGeom_LudingPhys_Basic`
    LudingBasic,
    /// `Law2_ScGeom_BubblePhys_Bubble`
    Bubble,
    /// `Law2_ScGeom_CpmPhys_Cpm`
    Cpm,
}

impl LawFunctor {
    /// Number of law functors (the size of `LawEnergy::caches`).
    pub const COUNT: usize = 10;

    pub fn class_name(&self) -> &'static str {
        match self {
            LawFunctor::CundallStrack => "Law2_ScGeom_FrictPhys_CundallStrack",
            LawFunctor::CohesionMoment => "Law2_ScGeom6D_CohFrictPhys_CohesionMoment",
            LawFunctor::ScGridCoFrict => "Law2_ScGridCoGeom_FrictPhys_CundallStrack",
            LawFunctor::ScGridCoCohFrict => "Law2_ScGridCoGeom_CohFrictPhys_CundallStrack",
            LawFunctor::GridCoGridCoFrict => "Law2_GridCoGridCoGeom_FrictPhys_CundallStrack",
            LawFunctor::ViscElBasic => "Law2_ScGeom_ViscElPhys_Basic",
            LawFunctor::Mindlin => "Law2_ScGeom_MindlinPhys_Mindlin",
            LawFunctor::LudingBasic => "Law2_ScGeom_LudingPhys_Basic",
            LawFunctor::Bubble => "Law2_ScGeom_BubblePhys_Bubble",
            LawFunctor::Cpm => "Law2_ScGeom_CpmPhys_Cpm",
        }
    }
}

/// `std::max(a, b)`: `a < b ? b : a`.
#[inline(always)]
pub(crate) fn cxx_max(a: f64, b: f64) -> f64 {
    if a < b {
        b
    } else {
        a
    }
}

/// Body data the law needs for the torque arm in the general (non-spherical) branch.
pub struct LawBodies<'a> {
    pub pos1: &'a Vec3,
    pub pos2_shifted: Vec3,
}

/// What one contact puts on its bodies: `force` on body 1 (body 2 gets `-force`) and the torques.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Load {
    pub force: Vec3,
    pub torque1: Vec3,
    pub torque2: Vec3,
}

/// Returns false when the contact must be erased (separated and `never_erase` off).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub fn go(
    p: &Params,
    g: &ScGeom,
    ph: &mut FrictPhys,
    id1: usize,
    id2: usize,
    bodies: &LawBodies,
    forces: &mut Forces,
    energy: Option<&mut LawEnergy<'_>>,
) -> bool {
    match load(p, g, ph, bodies, energy) {
        Some(l) => {
            apply(forces, id1, id2, &l);
            true
        }
        None => false,
    }
}

/// The arithmetic of `Law2_ScGeom_FrictPhys_CundallStrack::go` up to the forces it adds (None: the
/// contact must be erased). Touches only the contact's own physics, so contacts can be evaluated
/// in any order (or in parallel) as long as `apply` runs in container order.
#[inline(always)]
pub fn load(
    p: &Params,
    g: &ScGeom,
    ph: &mut FrictPhys,
    bodies: &LawBodies,
    energy: Option<&mut LawEnergy<'_>>,
) -> Option<Load> {
    if g.pen < 0.0 {
        if p.never_erase {
            ph.shear_force = Vec3::zeros();
            ph.normal_force = Vec3::zeros();
        } else {
            return None;
        }
    }
    let (normal, cp) = (r3::of(&g.normal), r3::of(&g.contact_point));
    let nf = normal_force(&normal, g.pen, ph.kn);
    ph.normal_force = Vec3::from(nf);
    cundall_shear(g, ph, energy);
    let at = (&normal, g.pen, (g.radius1, g.radius2), &cp);
    let (pos1, pos2) = (r3::of(bodies.pos1), r3::of(&bodies.pos2_shifted));
    let l = loads(
        p.spherical_bodies,
        at,
        &nf,
        &r3::of(&ph.shear_force),
        &pos1,
        &pos2,
    );
    Some(Load {
        force: Vec3::from(l[0]),
        torque1: Vec3::from(l[1]),
        torque2: Vec3::from(l[2]),
    })
}

/// Cundall-Strack's normal force, `normal * (kn * max(pen, 0))`, in any arithmetic (f64 here,
/// one contact per lane in the fast path's boundary loop).
#[inline(always)]
pub fn normal_force<R: Real>(normal: &R3<R>, pen: R, kn: R) -> R3<R> {
    r3::scale(normal, kn * pen.max(R::splat(0.0)))
}

/// Cundall-Strack's trial shear force, in any arithmetic: the last one `fs` carried along with the
/// contact frame (`geom::rotate` about the orthonormal and twist axes), minus ks times the shear
/// increment.
#[inline(always)]
pub fn shear_trial<R: Real>(
    (orth, twist, shear_inc): (&R3<R>, &R3<R>, &R3<R>),
    fs: &R3<R>,
    ks: R,
) -> R3<R> {
    r3::sub(
        &crate::geom::rotate(orth, twist, fs),
        &r3::scale(shear_inc, ks),
    )
}

/// The Coulomb cap on shear force `fs` in any arithmetic: where |fs|² > `max_fs2`, `fs` scaled by
/// sqrt(max_fs2) / |fs|.
#[inline(always)]
pub fn coulomb_cap<R: Real>(fs: R3<R>, max_fs2: R) -> R3<R> {
    let n2 = r3::norm2(&fs);
    let over = n2.gt(max_fs2);
    if !R::any(over) {
        return fs;
    }
    let ratio = max_fs2.sqrt() / n2.sqrt();
    fs.map(|c| R::select(over, c * ratio, c))
}

/// The loads of a Cundall-Strack contact (force on body 1, torques on bodies 1 and 2) from its
/// normal and shear forces, in any arithmetic: lever arms radius - pen/2 along the normal
/// (`sphericalBodies`), else from the contact point (Law2::applyForceAtContactPoint,
/// pkg/common/Dispatching.cpp).
#[inline(always)]
pub fn loads<R: Real>(
    spherical_bodies: bool,
    (normal, pen, (radius1, radius2), contact_point): (&R3<R>, R, (R, R), &R3<R>),
    normal_force: &R3<R>,
    fs: &R3<R>,
    pos1: &R3<R>,
    pos2_shifted: &R3<R>,
) -> [R3<R>; 3] {
    let force = r3::sub(&r3::neg(normal_force), fs);
    if spherical_bodies {
        let nf = r3::cross(normal, &force);
        let half = R::splat(0.5);
        [
            force,
            r3::scale(&nf, radius1 - half * pen),
            r3::scale(&nf, radius2 - half * pen),
        ]
    } else {
        [
            force,
            r3::cross(&r3::sub(contact_point, pos1), &force),
            r3::neg(&r3::cross(&r3::sub(contact_point, pos2_shifted), &force)),
        ]
    }
}

/// Add a contact's load to its bodies in YADE's order: force 1, force 2, torque 1, torque 2.
#[inline(always)]
pub fn apply(forces: &mut Forces, id1: usize, id2: usize, l: &Load) {
    forces.add_force(id1, &l.force);
    forces.add_force(id2, &(-l.force));
    forces.add_torque(id1, &l.torque1);
    forces.add_torque(id2, &l.torque2);
}

/// The Coulomb-capped shear update shared by the frictional laws, with their energy terms.
#[inline(always)]
pub(crate) fn cundall_shear(g: &ScGeom, ph: &mut FrictPhys, energy: Option<&mut LawEnergy<'_>>) {
    let axes = (
        &r3::of(&g.orthonormal_axis),
        &r3::of(&g.twist_axis),
        &r3::of(&g.shear_inc),
    );
    let trial = shear_trial(axes, &r3::of(&ph.shear_force), ph.ks);
    let max_fs = norm2(&ph.normal_force) * (ph.tan_phi * ph.tan_phi);
    let fs = Vec3::from(coulomb_cap(trial, max_fs));
    match energy {
        None => ph.shear_force = fs,
        Some(e) => {
            // Law2_ScGeom_FrictPhys_CundallStrack::go (ElasticContactLaw.cpp), trackEnergy branch
            let trial = Vec3::from(trial);
            if norm2(&trial) > max_fs {
                let dissip = crate::math::dot(&((trial - fs) * (1.0 / ph.ks)), &fs);
                // (traceEnergy: to the functor's plasticDissipation, which ryade does not expose)
                if !e.trace && dissip > 0.0 {
                    e.add(dissip, "plastDissip", false);
                }
            }
            ph.shear_force = fs;
            e.add(
                0.5 * (norm2(&ph.normal_force) / ph.kn + norm2(&ph.shear_force) / ph.ks),
                "elastPotential",
                true,
            );
        }
    }
}
