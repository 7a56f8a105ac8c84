//! Bodies, stored per quantity in contiguous arrays (structure of arrays).
//!
//! YADE keeps one heap object per body (`core/Body.hpp`, `core/State.hpp`); we keep one `Vec` per
//! quantity so the integrator and the collider stream through memory. Fields mirror YADE's `State`.

use crate::math::{Quat, Vec3};
use crate::shape::Shape;

/// `State.blockedDOFs` bits as YADE defines them: x=1, y=2, z=4, X=8, Y=16, Z=32.
pub const DOF_X: u8 = 1;
pub const DOF_ALL: u8 = 63;

/// Parse YADE's `blockedDOFs` string ('xyzXYZ' letters in any order).
pub fn parse_blocked_dofs(s: &str) -> Result<u8, String> {
    let mut bits = 0u8;
    for c in s.chars() {
        bits |= match c {
            'x' => 1,
            'y' => 2,
            'z' => 4,
            'X' => 8,
            'Y' => 16,
            'Z' => 32,
            _ => {
                return Err(format!(
                    "invalid character '{}' in blockedDOFs '{}': use letters from 'xyzXYZ'",
                    c, s
                ))
            }
        };
    }
    Ok(bits)
}

/// Axis-aligned bound of one body, as `core/Bound.hpp` (Aabb) plus the striding data.
#[derive(Clone, Copy, Debug)]
pub struct Bound {
    pub min: Vec3,
    pub max: Vec3,
    pub ref_pos: Vec3,
    pub sweep_length: f64,
    pub last_update_iter: i64,
}

impl Default for Bound {
    fn default() -> Self {
        Bound {
            min: Vec3::repeat(f64::NAN),
            max: Vec3::repeat(f64::NAN),
            ref_pos: Vec3::repeat(f64::NAN),
            sweep_length: 0.0,
            last_update_iter: 0,
        }
    }
}

/// Everything needed to add one body.
#[derive(Clone, Debug)]
pub struct BodySpec {
    pub shape: Shape,
    pub material: usize,
    pub mask: i32,
    pub bounded: bool,
    pub pos: Vec3,
    pub vel: Vec3,
    pub ang_vel: Vec3,
    pub ori: Quat,
    pub mass: f64,
    pub inertia: Vec3,
    pub blocked: u8,
    pub is_damped: bool,
}

#[derive(Clone, Debug, Default)]
pub struct Bodies {
    pub shape: Vec<Shape>,
    /// Index into `Scene::materials`.
    pub material: Vec<usize>,
    pub mask: Vec<i32>,
    pub bounded: Vec<bool>,
    pub pos: Vec<Vec3>,
    pub vel: Vec<Vec3>,
    pub ang_vel: Vec<Vec3>,
    pub ori: Vec<Quat>,
    pub mass: Vec<f64>,
    pub inertia: Vec<Vec3>,
    pub blocked: Vec<u8>,
    pub is_damped: Vec<bool>,
    /// `None` until the bound dispatcher first gives the body a bound (or never, for unbounded
    /// bodies and shapes without a bound functor).
    pub bound: Vec<Option<Bound>>,
    /// `Body::clumpId`: `None` for a standalone body, the clump's id for a clump member and for the
    /// clump itself (core/Body.hpp).
    pub clump_id: Vec<Option<u32>>,
    /// `State::angMom`, the state of the aspherical rotation integrator (clumps).
    pub ang_mom: Vec<Vec3>,
    /// `Body::aspherical`: rotation integrated with `leapfrogAsphericalRotate` when unblocked.
    pub aspherical: Vec<bool>,
}

impl Bodies {
    pub fn len(&self) -> usize {
        self.pos.len()
    }

    pub fn is_empty(&self) -> bool {
        self.pos.is_empty()
    }

    /// Append a body and return its id (ids are consecutive, as YADE's `O.bodies.append`).
    pub fn push(&mut self, b: BodySpec) -> usize {
        let id = self.len();
        self.shape.push(b.shape);
        self.material.push(b.material);
        self.mask.push(b.mask);
        self.bounded.push(b.bounded);
        self.pos.push(b.pos);
        self.vel.push(b.vel);
        self.ang_vel.push(b.ang_vel);
        self.ori.push(b.ori);
        self.mass.push(b.mass);
        self.inertia.push(b.inertia);
        self.blocked.push(b.blocked);
        self.is_damped.push(b.is_damped);
        self.bound.push(None);
        self.clump_id.push(None);
        self.ang_mom.push(Vec3::zeros());
        self.aspherical.push(false);
        id
    }

    /// Drop the bodies from id `n` on (undoes a failed append).
    pub fn truncate(&mut self, n: usize) {
        self.shape.truncate(n);
        self.material.truncate(n);
        self.mask.truncate(n);
        self.bounded.truncate(n);
        self.pos.truncate(n);
        self.vel.truncate(n);
        self.ang_vel.truncate(n);
        self.ori.truncate(n);
        self.mass.truncate(n);
        self.inertia.truncate(n);
        self.blocked.truncate(n);
        self.is_damped.truncate(n);
        self.bound.truncate(n);
        self.clump_id.truncate(n);
        self.ang_mom.truncate(n);
        self.aspherical.truncate(n);
    }

    /// `Body::isClump()`: the body holds a `Clump` shape.
    pub fn is_clump(&self, id: usize) -> bool {
        matches!(self.shape[id], Shape::Clump(_))
    }

    /// `Body::isClumpMember()`: `clumpId` set and different from the body's own id.
    pub fn is_clump_member(&self, id: usize) -> bool {
        matches!(self.clump_id[id], Some(c) if c as usize != id)
    }

    /// `Body::isDynamic()`: not all DOFs blocked.
    pub fn is_dynamic(&self, id: usize) -> bool {
        self.blocked[id] != DOF_ALL
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn blocked_dofs_bits() {
        assert_eq!(parse_blocked_dofs("xyzXYZ").unwrap(), DOF_ALL);
        assert_eq!(parse_blocked_dofs("xy").unwrap(), 3);
        assert_eq!(parse_blocked_dofs("").unwrap(), 0);
        assert!(parse_blocked_dofs("q").is_err());
    }
}
