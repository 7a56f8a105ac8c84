//! Contact geometry: `ScGeom` and the Ig2 functors that create and update it.
//!
//! Each functor mirrors its YADE file (named in the submodule) in floating-point evaluation order.

pub mod box_sphere;
pub mod facet_sphere;
pub mod grid;
pub mod six_d;
pub mod sphere_sphere;
pub mod wall_sphere;

use crate::math::{cross, dot, Quat, Vec3};
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
    /// then the tangential relative velocity times dt.
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
        if !is_new {
            self.orthonormal_axis = cross(&self.normal, current_normal);
            let w = s1.ang_vel + s2.ang_vel;
            let angle = ctx.dt * 0.5 * dot(&self.normal, &w);
            self.twist_axis = self.normal * angle;
        } else {
            self.orthonormal_axis = Vec3::zeros();
            self.twist_axis = Vec3::zeros();
        }
        self.normal = *current_normal;
        let rv = self.incident_vel(s1, s2, shift2, &ctx.shift_vel, avoid_ratcheting);
        let dn = dot(&self.normal, &rv);
        let rv = rv - self.normal * dn;
        self.shear_inc = rv * ctx.dt;
    }

    /// `ScGeom::getIncidentVel` (pkg/dem/ScGeom.cpp).
    #[inline(always)]
    pub fn incident_vel(
        &self,
        s1: &Kin,
        s2: &Kin,
        shift2: &Vec3,
        shift_vel: &Vec3,
        avoid_ratcheting: bool,
    ) -> Vec3 {
        if avoid_ratcheting {
            // McNamara's fixed branch lengths, translational part scaled by alpha
            let alpha = (self.radius1 + self.radius2) / (self.radius1 + self.radius2 - self.pen);
            let a2 = cross(&s2.ang_vel, &(self.normal * (-self.radius2)));
            let a1 = cross(&s1.ang_vel, &(self.normal * self.radius1));
            let mut rv = (s2.vel - s1.vel) * alpha + a2 - a1;
            rv += shift_vel * alpha;
            rv
        } else {
            let c1x = self.contact_point - s1.pos;
            let c2x = self.contact_point - (s2.pos + shift2);
            let mut rv = (s2.vel + cross(&s2.ang_vel, &c2x)) - (s1.vel + cross(&s1.ang_vel, &c1x));
            rv += shift_vel;
            rv
        }
    }

    /// `ScGeom::rotate`: carry the shear force along with the contact frame (first order, the
    /// second term uses the already-updated force; no re-projection, as YADE).
    #[inline(always)]
    pub fn rotate(&self, fs: &mut Vec3) {
        *fs -= cross(fs, &self.orthonormal_axis);
        *fs -= cross(fs, &self.twist_axis);
    }
}
