//! `ScGeom6D` (pkg/dem/ScGeom.cpp): the relative rotation of the two bodies since the contact was
//! initialised, split into twist (about the normal) and bending, as YADE evaluates it through Eigen's
//! quaternion algebra and its `AngleAxis(Quaternion)` conversion.

use crate::math::{dot, norm, Quat, Vec3};

/// The rotational part of `ScGeom6D` (the `ScGeom` part lives in the interaction's `ScGeom`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rot6D {
    pub initial_orientation1: Quat,
    pub initial_orientation2: Quat,
    pub twist_creep: Quat,
    pub twist: f64,
    pub bending: Vec3,
}

impl Default for Rot6D {
    /// The C++ defaults of `ScGeom6D`: identity orientations and creep, no twist or bending.
    fn default() -> Self {
        Rot6D {
            initial_orientation1: Quat::IDENTITY,
            initial_orientation2: Quat::IDENTITY,
            twist_creep: Quat::IDENTITY,
            twist: 0.0,
            bending: Vec3::zeros(),
        }
    }
}

impl Rot6D {
    /// `ScGeom6D::initRotations` (pkg/dem/ScGeom.cpp): current orientations become the reference.
    pub fn init_rotations(&mut self, ori1: &Quat, ori2: &Quat) {
        self.initial_orientation1 = *ori1;
        self.initial_orientation2 = *ori2;
        self.twist = 0.0;
        self.bending = Vec3::zeros();
        self.twist_creep = Quat::IDENTITY;
    }

    /// `ScGeom6D::precomputeRotations` (pkg/dem/ScGeom.cpp); `normal` is the already-updated contact
    /// normal.
    pub fn precompute_rotations(
        &mut self,
        ori1: &Quat,
        ori2: &Quat,
        normal: &Vec3,
        is_new: bool,
        creep: bool,
    ) {
        if is_new {
            self.init_rotations(ori1, ori2);
            return;
        }
        let a = ori1.mul(&self.initial_orientation1.conjugate());
        let b = self.initial_orientation2.mul(&ori2.conjugate());
        let mut delta = a.mul(&b);
        delta.normalize();
        if creep {
            delta = delta.mul(&self.twist_creep);
        }
        let (mut angle, axis) = angle_axis(&delta);
        // Eigen can return NaN close to the identity; YADE zeroes it (the > pi branch never fires
        // because the angle comes from 2*atan2(|v|, |w|), kept for the record)
        if angle.is_nan() {
            angle = 0.0;
        }
        if angle > std::f64::consts::PI {
            angle -= 2.0 * std::f64::consts::PI;
        }
        self.twist = angle * dot(&axis, normal);
        self.bending = Vec3::new(
            angle * axis[0] - self.twist * normal[0],
            angle * axis[1] - self.twist * normal[1],
            angle * axis[2] - self.twist * normal[2],
        );
    }
}

/// Eigen 3.4 `AngleAxis<double>::operator=(const QuaternionBase&)`: `n = |vec|` (the stable norm when
/// below machine epsilon), angle `2·atan2(n, |w|)`, axis `vec/n` with the sign of w folded into n;
/// the identity gives angle 0 about x.
pub fn angle_axis(q: &Quat) -> (f64, Vec3) {
    let v = Vec3::new(q.x, q.y, q.z);
    let mut n = norm(&v);
    if n < f64::EPSILON {
        n = stable_norm(&v);
    }
    if n != 0.0 {
        let angle = 2.0 * n.atan2(q.w.abs());
        if q.w < 0.0 {
            n = -n;
        }
        (angle, Vec3::new(v[0] / n, v[1] / n, v[2] / n))
    } else {
        (0.0, Vec3::new(1.0, 0.0, 0.0))
    }
}

/// Eigen 3.4 `stableNorm()` of a 3-vector built without alignment (one dynamic-size block): scale
/// by the largest magnitude through its reciprocal, sum the squares left to right, `scale*sqrt`.
pub fn stable_norm(v: &Vec3) -> f64 {
    let max_coeff = v[0].abs().max(v[1].abs()).max(v[2].abs());
    let mut scale = 0.0f64;
    let mut inv_scale = 1.0f64;
    let mut ssq = 0.0f64;
    if max_coeff > scale {
        ssq *= (scale / max_coeff) * (scale / max_coeff);
        let tmp = 1.0 / max_coeff;
        if tmp > f64::MAX {
            inv_scale = f64::MAX;
            scale = 1.0 / inv_scale;
        } else if max_coeff > f64::MAX {
            inv_scale = 1.0;
            scale = max_coeff;
        } else {
            scale = max_coeff;
            inv_scale = tmp;
        }
    } else if max_coeff.is_nan() {
        scale = max_coeff;
    }
    if scale > 0.0 {
        let a = v[0] * inv_scale;
        let b = v[1] * inv_scale;
        let c = v[2] * inv_scale;
        ssq += (a * a + b * b) + c * c;
    }
    scale * ssq.sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identity_is_zero_angle_about_x() {
        let (a, ax) = angle_axis(&Quat::IDENTITY);
        assert_eq!(a, 0.0);
        assert_eq!(ax, Vec3::new(1.0, 0.0, 0.0));
    }

    #[test]
    fn quarter_turn() {
        let q = Quat::from_angle_axis(0.5, &Vec3::new(0.0, 0.0, 1.0));
        let (a, ax) = angle_axis(&q);
        assert!((a - 0.5).abs() < 1e-15);
        assert_eq!(ax, Vec3::new(0.0, 0.0, 1.0));
        // negative w: same rotation, the axis keeps its direction
        let q2 = Quat::new(-q.w, -q.x, -q.y, -q.z);
        let (a2, ax2) = angle_axis(&q2);
        assert_eq!(a2, a);
        assert_eq!(ax2, ax);
    }

    #[test]
    fn stable_norm_of_tiny_vectors() {
        let v = Vec3::new(3e-20, 4e-20, 0.0);
        assert!((stable_norm(&v) - 5e-20).abs() < 1e-34);
        assert_eq!(stable_norm(&Vec3::zeros()), 0.0);
    }
}
