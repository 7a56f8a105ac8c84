//! Contact geometry: `ScGeom` and the Ig2 functors that create and update it.
//!
//! Each functor mirrors its YADE file (named in the submodule) in floating-point evaluation order.

pub mod box_sphere;
pub mod facet_sphere;
pub mod sphere_sphere;
pub mod wall_sphere;

use crate::math::{cross, dot, Quat, Vec3};

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
    /// `ScGeom::precompute` (pkg/dem/ScGeom.cpp): rotation of the contact frame since the last step,
    /// then the tangential relative velocity times dt.
    #[allow(clippy::too_many_arguments)]
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
