//! Contact geometry: `ScGeom` and the Ig2 functors that create and update it.
//!
//! Each functor mirrors its YADE file (named in the submodule) in floating-point evaluation order.

pub mod box_sphere;
pub mod facet_sphere;
pub mod grid;
pub mod six_d;
pub mod sphere_sphere;
pub mod wall_sphere;

use crate::math::r3::{self, R3};
use crate::math::{Quat, Real, Vec3};
pub use six_d::Rot6D;

/// A fictitious body state at a point of a grid connection (the C++-only `fictiousState` of
/// `ScGridCoGeom`/`GridCoGridCoGeom`): position, interpolated velocity and angular velocity.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Fict {
    pub pos: Vec3,
    pub vel: Vec3,
    pub ang_vel: Vec3,
}

impl Fict {
    pub fn kin(&self) -> Kin {
        Kin {
            pos: self.pos,
            vel: self.vel,
            ang_vel: self.ang_vel,
            ori: Quat::IDENTITY,
        }
    }
}

/// What `ScGridCoGeom` (pkg/common/Grid.hpp) adds to `ScGeom6D`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScGridCo {
    pub rot: Rot6D,
    pub is_duplicate: i32,
    pub true_int: i32,
    pub id3: i32,
    pub id4: i32,
    pub id5: i32,
    pub weight: Vec3,
    pub rel_pos: f64,
    pub fict: Fict,
    /// Identity of the geometry object when YADE shares it between two interactions (the hand-over
    /// of a sliding sphere to the next connection): interactions holding copies with the same
    /// non-zero `share` stand for one C++ object (see `Interactions::sync_shared`).
    pub share: u32,
}

impl Default for ScGridCo {
    /// The C++ defaults: isDuplicate 0, trueInt -1, id3 = id4 = 0, id5 -1, weight 0, relPos 0.
    fn default() -> Self {
        ScGridCo {
            rot: Rot6D::default(),
            is_duplicate: 0,
            true_int: -1,
            id3: 0,
            id4: 0,
            id5: -1,
            weight: Vec3::zeros(),
            rel_pos: 0.0,
            fict: Fict::default(),
            share: 0,
        }
    }
}

/// What `GridCoGridCoGeom` (pkg/common/Grid.hpp) adds to `ScGeom`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GridCoGridCo {
    pub rel_pos1: f64,
    pub rel_pos2: f64,
    pub fict1: Fict,
    pub fict2: Fict,
}

/// The geometry classes beyond plain `ScGeom`; only interactions made by the 6-D and grid functors
/// carry one (boxed in the interaction's extension, allocated when the contact is created).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GeomExt {
    /// `ScGeom6D`
    Sc6D(Rot6D),
    /// `GridNodeGeom6D`: `connection_body` is the GridConnection body whose position follows node 1.
    GridNode {
        rot: Rot6D,
        connection_body: Option<u32>,
    },
    ScGridCo(ScGridCo),
    GridCoGridCo(GridCoGridCo),
}

impl GeomExt {
    /// The rotational part of the ScGeom6D-derived classes.
    pub fn rot(&self) -> Option<&Rot6D> {
        match self {
            GeomExt::Sc6D(r) => Some(r),
            GeomExt::GridNode { rot, .. } => Some(rot),
            GeomExt::ScGridCo(g) => Some(&g.rot),
            GeomExt::GridCoGridCo(_) => None,
        }
    }

    pub fn rot_mut(&mut self) -> Option<&mut Rot6D> {
        match self {
            GeomExt::Sc6D(r) => Some(r),
            GeomExt::GridNode { rot, .. } => Some(rot),
            GeomExt::ScGridCo(g) => Some(&mut g.rot),
            GeomExt::GridCoGridCo(_) => None,
        }
    }

    pub fn class(&self) -> GeomClass {
        match self {
            GeomExt::Sc6D(_) => GeomClass::ScGeom6D,
            GeomExt::GridNode { .. } => GeomClass::GridNodeGeom6D,
            GeomExt::ScGridCo(_) => GeomClass::ScGridCoGeom,
            GeomExt::GridCoGridCo(_) => GeomClass::GridCoGridCoGeom,
        }
    }
}

/// YADE's geometry classes that ryade builds (for law dispatch and the records), with their bases.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum GeomClass {
    IGeom,
    GenericSpheresContact,
    ScGeom,
    ScGeom6D,
    GridNodeGeom6D,
    ScGridCoGeom,
    GridCoGridCoGeom,
}

impl GeomClass {
    pub fn name(&self) -> &'static str {
        match self {
            GeomClass::IGeom => "IGeom",
            GeomClass::GenericSpheresContact => "GenericSpheresContact",
            GeomClass::ScGeom => "ScGeom",
            GeomClass::ScGeom6D => "ScGeom6D",
            GeomClass::GridNodeGeom6D => "GridNodeGeom6D",
            GeomClass::ScGridCoGeom => "ScGridCoGeom",
            GeomClass::GridCoGridCoGeom => "GridCoGridCoGeom",
        }
    }
}

impl crate::dispatch::Hierarchy for GeomClass {
    fn parent(self) -> Option<Self> {
        use GeomClass::*;
        match self {
            IGeom => None,
            GenericSpheresContact => Some(IGeom),
            ScGeom => Some(GenericSpheresContact),
            ScGeom6D | GridCoGridCoGeom => Some(ScGeom),
            GridNodeGeom6D | ScGridCoGeom => Some(ScGeom6D),
        }
    }
}

/// Kinematic state of one body as the geometry functors see it.
#[derive(Clone, Copy, Debug)]
pub struct Kin {
    pub pos: Vec3,
    pub vel: Vec3,
    pub ang_vel: Vec3,
    pub ori: Quat,
}

/// Scene-level inputs of the geometry step.
#[derive(Clone, Copy, Debug)]
pub struct GeomCtx {
    pub dt: f64,
    /// `cell.intrShiftVel(cellDist)` in a periodic scene, zero otherwise (YADE adds it even then).
    pub shift_vel: Vec3,
}

/// One pair as a geometry functor sees it: both bodies' kinematics (body 1 first, after the swap),
/// the periodic shift of body 2, and whether the interaction is already real.
#[derive(Clone, Copy, Debug)]
pub struct Pair {
    pub s1: Kin,
    pub s2: Kin,
    pub shift2: Vec3,
    pub is_real: bool,
    pub ctx: GeomCtx,
}

impl Kin {
    /// Body `id`'s kinematics.
    #[inline(always)]
    pub fn of(b: &crate::body::Bodies, id: usize) -> Kin {
        Kin {
            pos: b.pos[id],
            vel: b.vel[id],
            ang_vel: b.ang_vel[id],
            ori: b.ori[id],
        }
    }
}

impl Pair {
    /// Bodies `id1` and `id2` as a geometry functor sees them.
    #[inline(always)]
    pub fn of(
        b: &crate::body::Bodies,
        id1: usize,
        id2: usize,
        shift2: Vec3,
        is_real: bool,
        ctx: GeomCtx,
    ) -> Pair {
        Pair {
            s1: Kin::of(b, id1),
            s2: Kin::of(b, id2),
            shift2,
            is_real,
            ctx,
        }
    }
}

/// Sphere-contact geometry (YADE `pkg/dem/ScGeom.hpp`, with `GenericSpheresContact`'s refR1/refR2,
/// which are `radius1`/`radius2` here).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ScGeom {
    pub contact_point: Vec3,
    pub pen: f64,
    pub normal: Vec3,
    pub shear_inc: Vec3,
    pub orthonormal_axis: Vec3,
    pub twist_axis: Vec3,
    pub radius1: f64,
    pub radius2: f64,
}

impl ScGeom {
    /// The radii the Ip2 functors use (`GenericSpheresContact::refR1/refR2`), each standing in for the
    /// other when not positive (a facet's or wall's side).
    #[inline]
    pub fn ref_radii(&self) -> (f64, f64) {
        let r1 = if self.radius1 > 0.0 {
            self.radius1
        } else {
            self.radius2
        };
        let r2 = if self.radius2 > 0.0 {
            self.radius2
        } else {
            self.radius1
        };
        (r1, r2)
    }

    /// `ScGeom::precompute` (pkg/dem/ScGeom.cpp): rotation of the contact frame since the last step,
    /// then the tangential relative velocity times dt (`precompute`, the formula in any arithmetic).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub fn precompute(
        &mut self,
        s1: &Kin,
        s2: &Kin,
        ctx: &GeomCtx,
        current_normal: &Vec3,
        is_new: bool,
        shift2: &Vec3,
        avoid_ratcheting: bool,
    ) {
        let [orth, twist, normal, shear_inc] = precompute(
            &self.at(),
            &KinOf::of(s1),
            &KinOf::of(s2),
            ctx.dt,
            &r3::of(&ctx.shift_vel),
            &r3::of(current_normal),
            is_new,
            &r3::of(shift2),
            avoid_ratcheting,
        );
        self.orthonormal_axis = Vec3::from(orth);
        self.twist_axis = Vec3::from(twist);
        self.normal = Vec3::from(normal);
        self.shear_inc = Vec3::from(shear_inc);
    }

    /// What `precompute` reads of the contact.
    #[inline(always)]
    fn at(&self) -> At<f64> {
        At {
            normal: r3::of(&self.normal),
            contact_point: r3::of(&self.contact_point),
            pen: self.pen,
            radius1: self.radius1,
            radius2: self.radius2,
        }
    }

    /// `ScGeom::getIncidentVel` (pkg/dem/ScGeom.cpp; `incident_vel`, the formula in any
    /// arithmetic).
    #[inline(always)]
    pub fn incident_vel(
        &self,
        s1: &Kin,
        s2: &Kin,
        shift2: &Vec3,
        shift_vel: &Vec3,
        avoid_ratcheting: bool,
    ) -> Vec3 {
        Vec3::from(incident_vel(
            &self.at(),
            &KinOf::of(s1),
            &KinOf::of(s2),
            &r3::of(shift2),
            &r3::of(shift_vel),
            avoid_ratcheting,
        ))
    }

    /// `ScGeom::rotate` (`rotate`, the formula in any arithmetic).
    #[inline(always)]
    pub fn rotate(&self, fs: &mut Vec3) {
        let (orth, twist) = (r3::of(&self.orthonormal_axis), r3::of(&self.twist_axis));
        *fs = Vec3::from(rotate(&orth, &twist, &r3::of(fs)));
    }
}

/// What `precompute` and `incident_vel` read of a contact (the normal: the last step's for the
/// first, the new one for the second), in arithmetic `R`.
#[derive(Clone, Copy)]
pub struct At<R> {
    pub normal: R3<R>,
    pub contact_point: R3<R>,
    pub pen: R,
    pub radius1: R,
    pub radius2: R,
}

/// `ScGeom::precompute` (pkg/dem/ScGeom.cpp) in any arithmetic (f64 for `ScGeom`, a contact per
/// lane in the fast path's boundary loop): the rotation of the contact frame since the last step
/// and the tangential relative velocity times dt. Returns the orthonormal axis, twist axis, normal
/// and shear increment it sets.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub fn precompute<R: Real>(
    at: &At<R>,
    s1: &KinOf<R>,
    s2: &KinOf<R>,
    dt: R,
    shift_vel: &R3<R>,
    current_normal: &R3<R>,
    is_new: bool,
    shift2: &R3<R>,
    avoid_ratcheting: bool,
) -> [R3<R>; 4] {
    let (orth, twist) = if !is_new {
        let w = r3::add(&s1.ang_vel, &s2.ang_vel);
        let angle = dt * R::splat(0.5) * r3::dot(&at.normal, &w);
        (
            r3::cross(&at.normal, current_normal),
            r3::scale(&at.normal, angle),
        )
    } else {
        ([R::splat(0.0); 3], [R::splat(0.0); 3])
    };
    let now = At {
        normal: *current_normal,
        ..*at
    };
    let rv = incident_vel(&now, s1, s2, shift2, shift_vel, avoid_ratcheting);
    let dn = r3::dot(current_normal, &rv);
    let rv = r3::sub(&rv, &r3::scale(current_normal, dn));
    [orth, twist, *current_normal, r3::scale(&rv, dt)]
}

/// `ScGeom::getIncidentVel` (pkg/dem/ScGeom.cpp) in any arithmetic, `at` with the new normal.
#[inline(always)]
pub fn incident_vel<R: Real>(
    at: &At<R>,
    s1: &KinOf<R>,
    s2: &KinOf<R>,
    shift2: &R3<R>,
    shift_vel: &R3<R>,
    avoid_ratcheting: bool,
) -> R3<R> {
    if avoid_ratcheting {
        // McNamara's fixed branch lengths, translational part scaled by alpha
        let alpha = (at.radius1 + at.radius2) / (at.radius1 + at.radius2 - at.pen);
        let a2 = r3::cross(&s2.ang_vel, &r3::scale(&at.normal, -at.radius2));
        let a1 = r3::cross(&s1.ang_vel, &r3::scale(&at.normal, at.radius1));
        let rv = r3::scale(&r3::sub(&s2.vel, &s1.vel), alpha);
        let rv = r3::sub(&r3::add(&rv, &a2), &a1);
        r3::add(&rv, &r3::scale(shift_vel, alpha))
    } else {
        let c1x = r3::sub(&at.contact_point, &s1.pos);
        let c2x = r3::sub(&at.contact_point, &r3::add(&s2.pos, shift2));
        let rv = r3::sub(
            &r3::add(&s2.vel, &r3::cross(&s2.ang_vel, &c2x)),
            &r3::add(&s1.vel, &r3::cross(&s1.ang_vel, &c1x)),
        );
        r3::add(&rv, shift_vel)
    }
}

/// `ScGeom::rotate` in any arithmetic: carry shear force `fs` along with the contact frame (first
/// order, the second term uses the already-updated force; no re-projection, as YADE).
#[inline(always)]
pub fn rotate<R: Real>(orth: &R3<R>, twist: &R3<R>, fs: &R3<R>) -> R3<R> {
    let fs = r3::sub(fs, &r3::cross(fs, orth));
    r3::sub(&fs, &r3::cross(&fs, twist))
}

/// A body's kinematics as `precompute` reads them, in arithmetic `R`.
#[derive(Clone, Copy)]
pub struct KinOf<R> {
    pub pos: R3<R>,
    pub vel: R3<R>,
    pub ang_vel: R3<R>,
}

impl KinOf<f64> {
    #[inline(always)]
    pub fn of(k: &Kin) -> KinOf<f64> {
        KinOf {
            pos: r3::of(&k.pos),
            vel: r3::of(&k.vel),
            ang_vel: r3::of(&k.ang_vel),
        }
    }
}
