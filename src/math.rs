//! Vector algebra evaluated in YADE's floating-point order.
//!
//! YADE 2023.02a builds Eigen with `EIGEN_DONT_VECTORIZE`; Eigen's unrolled reductions then evaluate a
//! three-term sum as `a0 + (a1 + a2)` and a four-term one as `(a0 + a1) + (a2 + a3)` (core.md §12).
//! Element-wise operations (add, sub, scale) are exact per component and need no care; every
//! *reduction* in the engine goes through this module. No FMA, no fast-math: Rust never contracts
//! `a*b + c` on its own, and we never call `mul_add`.

use nalgebra::{Matrix3, Vector3};
use std::ops::{Add, Div, Mul, Neg, Sub};

pub type Vec3 = Vector3<f64>;
pub type Mat3 = Matrix3<f64>;

/// `a·b` as Eigen evaluates it: `a0*b0 + (a1*b1 + a2*b2)`.
#[inline(always)]
pub fn dot(a: &Vec3, b: &Vec3) -> f64 {
    r3::dot(&r3::of(a), &r3::of(b))
}

/// `|a|²` as Eigen evaluates it: `a0² + (a1² + a2²)`.
#[inline(always)]
pub fn norm2(a: &Vec3) -> f64 {
    r3::norm2(&r3::of(a))
}

/// `|a|` = `sqrt(squaredNorm)`.
#[inline(always)]
pub fn norm(a: &Vec3) -> f64 {
    norm2(a).sqrt()
}

/// Eigen's `cross`: `(a1b2 − a2b1, a2b0 − a0b2, a0b1 − a1b0)`.
#[inline(always)]
pub fn cross(a: &Vec3, b: &Vec3) -> Vec3 {
    Vec3::from(r3::cross(&r3::of(a), &r3::of(b)))
}

/// Eigen's `normalize()` on a 3-vector: divide each component by `sqrt(squaredNorm)` (a true
/// division, no reciprocal), and leave a zero vector untouched.
#[inline(always)]
pub fn normalized(a: &Vec3) -> Vec3 {
    Vec3::from(r3::normalized(&r3::of(a)))
}

/// `M * v`, row i evaluated `m_i0*v0 + (m_i1*v1 + m_i2*v2)`.
#[inline(always)]
pub fn mat_vec(m: &Mat3, v: &Vec3) -> Vec3 {
    Vec3::from(r3::mat_vec(m, &r3::of(v)))
}

/// `Mᵀ * v` with the same per-row evaluation order.
#[inline(always)]
pub fn mat_t_vec(m: &Mat3, v: &Vec3) -> Vec3 {
    Vec3::from(r3::mat_t_vec(m, &r3::of(v)))
}

/// `M * (integer vector)`, as YADE's `hSize * cellDist.cast<Real>()`.
#[inline(always)]
pub fn mat_vec_i(m: &Mat3, v: &[i32; 3]) -> Vec3 {
    mat_vec(m, &Vec3::new(v[0] as f64, v[1] as f64, v[2] as f64))
}

/// `A * B` for 3x3 matrices, each entry `a_i0*b_0j + (a_i1*b_1j + a_i2*b_2j)`.
pub fn mat_mul(a: &Mat3, b: &Mat3) -> Mat3 {
    Mat3::from_fn(|i, j| a[(i, 0)] * b[(0, j)] + (a[(i, 1)] * b[(1, j)] + a[(i, 2)] * b[(2, j)]))
}

/// `std::max(a, b)` as YADE calls it: `a < b ? b : a` (keeps `a` when either is NaN).
#[inline(always)]
pub fn cxx_max(a: f64, b: f64) -> f64 {
    if a < b {
        b
    } else {
        a
    }
}

/// `std::min(a, b)`: `b < a ? b : a`.
#[inline(always)]
pub fn cxx_min(a: f64, b: f64) -> f64 {
    if b < a {
        b
    } else {
        a
    }
}

/// YADE's `math::sign`: `(0 < x) - (x < 0)`; 0 for 0 and for NaN.
#[inline(always)]
pub fn sign(x: f64) -> f64 {
    ((0.0 < x) as i32 - (x < 0.0) as i32) as f64
}

/// A unit quaternion stored as Eigen does (x, y, z, w), with Eigen's conventions. Laid out w, x, y,
/// z (`repr(C)`: the fast integrator loads four at a time).
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct Quat {
    pub w: f64,
    pub x: f64,
    pub y: f64,
    pub z: f64,
}

impl Default for Quat {
    fn default() -> Self {
        Quat::IDENTITY
    }
}

impl Quat {
    pub const IDENTITY: Quat = Quat {
        w: 1.0,
        x: 0.0,
        y: 0.0,
        z: 0.0,
    };

    pub fn new(w: f64, x: f64, y: f64, z: f64) -> Quat {
        Quat { w, x, y, z }
    }

    /// Eigen `Quaternion(AngleAxis(angle, axis))`: `w = cos(angle/2)`, `xyz = sin(angle/2)·axis`,
    /// the half angle computed as `0.5*angle`.
    pub fn from_angle_axis(angle: f64, axis: &Vec3) -> Quat {
        let ha = 0.5 * angle;
        let s = ha.sin();
        Quat {
            w: ha.cos(),
            x: s * axis[0],
            y: s * axis[1],
            z: s * axis[2],
        }
    }

    /// Hamilton product `self * b`, each component summed left to right as Eigen's scalar path does.
    #[inline(always)]
    pub fn mul(&self, b: &Quat) -> Quat {
        let a = self;
        Quat {
            w: a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z,
            x: a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
            y: a.w * b.y + a.y * b.w + a.z * b.x - a.x * b.z,
            z: a.w * b.z + a.z * b.w + a.x * b.y - a.y * b.x,
        }
    }

    /// Eigen's squaredNorm over the coefficient order (x, y, z, w): `(x²+y²) + (z²+w²)`.
    #[inline(always)]
    pub fn norm2(&self) -> f64 {
        (self.x * self.x + self.y * self.y) + (self.z * self.z + self.w * self.w)
    }

    /// Eigen's `normalize()`: divide by `sqrt(squaredNorm)` when it is positive.
    #[inline(always)]
    pub fn normalize(&mut self) {
        let z = self.norm2();
        if z > 0.0 {
            let n = z.sqrt();
            self.x /= n;
            self.y /= n;
            self.z /= n;
            self.w /= n;
        }
    }

    pub fn conjugate(&self) -> Quat {
        Quat {
            w: self.w,
            x: -self.x,
            y: -self.y,
            z: -self.z,
        }
    }

    /// Eigen `q * v` for a 3-vector (`QuaternionBase::_transformVector`, Geometry/Quaternion.h):
    /// `uv = q.vec × v; uv += uv; v + w·uv + q.vec × uv`, which assumes a unit quaternion (YADE also
    /// applies it to the not yet normalised quaternion in `leapfrogAsphericalRotate`).
    #[inline(always)]
    pub fn rotate(&self, v: &Vec3) -> Vec3 {
        let qv = Vec3::new(self.x, self.y, self.z);
        let mut uv = cross(&qv, v);
        uv += uv;
        let c = cross(&qv, &uv);
        Vec3::new(
            v[0] + self.w * uv[0] + c[0],
            v[1] + self.w * uv[1] + c[1],
            v[2] + self.w * uv[2] + c[2],
        )
    }

    /// Eigen `Quaternion(Matrix3)` (Shoemake's algorithm, `quaternionbase_assign_impl<Other,3,3>`):
    /// from the trace when it is positive, otherwise from the largest diagonal entry.
    pub fn from_rotation_matrix(m: &Mat3) -> Quat {
        let t = m[(0, 0)] + (m[(1, 1)] + m[(2, 2)]);
        if t > 0.0 {
            let t = (t + 1.0).sqrt();
            let h = 0.5 / t;
            Quat {
                w: 0.5 * t,
                x: (m[(2, 1)] - m[(1, 2)]) * h,
                y: (m[(0, 2)] - m[(2, 0)]) * h,
                z: (m[(1, 0)] - m[(0, 1)]) * h,
            }
        } else {
            let mut i = 0;
            if m[(1, 1)] > m[(0, 0)] {
                i = 1;
            }
            if m[(2, 2)] > m[(i, i)] {
                i = 2;
            }
            let j = (i + 1) % 3;
            let k = (j + 1) % 3;
            let t = (m[(i, i)] - m[(j, j)] - m[(k, k)] + 1.0).sqrt();
            let mut c = [0.0; 3];
            c[i] = 0.5 * t;
            let h = 0.5 / t;
            let w = (m[(k, j)] - m[(j, k)]) * h;
            c[j] = (m[(j, i)] + m[(i, j)]) * h;
            c[k] = (m[(k, i)] + m[(i, k)]) * h;
            Quat {
                w,
                x: c[0],
                y: c[1],
                z: c[2],
            }
        }
    }

    /// Eigen `toRotationMatrix()` (Quaternion.h): `tx = 2x`, `twx = tx*w`, ..., `R00 = 1-(tyy+tzz)`.
    pub fn to_rotation_matrix(&self) -> Mat3 {
        let (x, y, z, w) = (self.x, self.y, self.z, self.w);
        let tx = 2.0 * x;
        let ty = 2.0 * y;
        let tz = 2.0 * z;
        let twx = tx * w;
        let twy = ty * w;
        let twz = tz * w;
        let txx = tx * x;
        let txy = ty * x;
        let txz = tz * x;
        let tyy = ty * y;
        let tyz = tz * y;
        let tzz = tz * z;
        Mat3::new(
            1.0 - (tyy + tzz),
            txy - twz,
            txz + twy,
            txy + twz,
            1.0 - (txx + tzz),
            tyz - twx,
            txz - twy,
            tyz + twx,
            1.0 - (txx + tyy),
        )
    }
}

/// The arithmetic a formula written once runs in: one `f64` (the scalar kernels, the YADE-order
/// path) or four lanes (`fast::contact_simd::F4`, AVX2). The formula does the same operations in
/// the same order in either, so a lane's result is the scalar one to the bit.
pub trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// Which lanes a comparison holds in.
    type Mask: Copy;
    fn splat(x: f64) -> Self;
    fn sqrt(self) -> Self;
    /// `f64::max`'s result for a NaN `self` and a number `o`: `o`.
    fn max(self, o: Self) -> Self;
    fn gt(self, o: Self) -> Self::Mask;
    fn lt(self, o: Self) -> Self::Mask;
    /// The lanes holding NaN.
    fn is_nan(self) -> Self::Mask;
    fn abs(self) -> Self;
    /// libm's `atan2(self, x)`.
    fn atan2(self, x: Self) -> Self;
    /// Whether `m` holds in some lane.
    fn any(m: Self::Mask) -> bool;
    /// `a` where `m` holds, else `b`.
    fn select(m: Self::Mask, a: Self, b: Self) -> Self;
}

impl Real for f64 {
    type Mask = bool;
    #[inline(always)]
    fn splat(x: f64) -> f64 {
        x
    }
    #[inline(always)]
    fn sqrt(self) -> f64 {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn max(self, o: f64) -> f64 {
        f64::max(self, o)
    }
    #[inline(always)]
    fn gt(self, o: f64) -> bool {
        self > o
    }
    #[inline(always)]
    fn lt(self, o: f64) -> bool {
        self < o
    }
    #[inline(always)]
    fn is_nan(self) -> bool {
        f64::is_nan(self)
    }
    #[inline(always)]
    fn abs(self) -> f64 {
        f64::abs(self)
    }
    #[inline(always)]
    fn atan2(self, x: f64) -> f64 {
        f64::atan2(self, x)
    }
    #[inline(always)]
    fn any(m: bool) -> bool {
        m
    }
    #[inline(always)]
    fn select(m: bool, a: f64, b: f64) -> f64 {
        if m {
            a
        } else {
            b
        }
    }
}

/// The reductions above on 3-vectors of any arithmetic (`[R; 3]`: f64, or the fast path's lanes,
/// one vector per lane), with the same operations in the same order: lanes give f64's bits. The
/// f64 functions above are these.
pub mod r3 {
    use super::{Mat3, Real, Vec3};

    /// A 3-vector in arithmetic `R`.
    pub type R3<R> = [R; 3];

    #[inline(always)]
    pub fn of(v: &Vec3) -> R3<f64> {
        [v[0], v[1], v[2]]
    }
    #[inline(always)]
    pub fn splat<R: Real>(v: &Vec3) -> R3<R> {
        [R::splat(v[0]), R::splat(v[1]), R::splat(v[2])]
    }
    #[inline(always)]
    pub fn add<R: Real>(a: &R3<R>, b: &R3<R>) -> R3<R> {
        [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
    }
    #[inline(always)]
    pub fn sub<R: Real>(a: &R3<R>, b: &R3<R>) -> R3<R> {
        [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
    }
    #[inline(always)]
    pub fn scale<R: Real>(a: &R3<R>, s: R) -> R3<R> {
        [a[0] * s, a[1] * s, a[2] * s]
    }
    #[inline(always)]
    pub fn neg<R: Real>(a: &R3<R>) -> R3<R> {
        [-a[0], -a[1], -a[2]]
    }
    /// `a·b`: `a0*b0 + (a1*b1 + a2*b2)`.
    #[inline(always)]
    pub fn dot<R: Real>(a: &R3<R>, b: &R3<R>) -> R {
        a[0] * b[0] + (a[1] * b[1] + a[2] * b[2])
    }
    /// `|a|²`: `a0² + (a1² + a2²)`.
    #[inline(always)]
    pub fn norm2<R: Real>(a: &R3<R>) -> R {
        a[0] * a[0] + (a[1] * a[1] + a[2] * a[2])
    }
    /// Eigen's `cross`.
    #[inline(always)]
    pub fn cross<R: Real>(a: &R3<R>, b: &R3<R>) -> R3<R> {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    }
    /// Eigen's `normalize()`: each component divided by `sqrt(squaredNorm)` where it is
    /// positive, else left as it is.
    #[inline(always)]
    pub fn normalized<R: Real>(a: &R3<R>) -> R3<R> {
        let z = norm2(a);
        let pos = z.gt(R::splat(0.0));
        let n = z.sqrt();
        [
            R::select(pos, a[0] / n, a[0]),
            R::select(pos, a[1] / n, a[1]),
            R::select(pos, a[2] / n, a[2]),
        ]
    }
    /// `M * v`, row i `m_i0*v0 + (m_i1*v1 + m_i2*v2)` (M the same in every lane).
    #[inline(always)]
    pub fn mat_vec<R: Real>(m: &Mat3, v: &R3<R>) -> R3<R> {
        let e = |i, j| R::splat(m[(i, j)]);
        [
            e(0, 0) * v[0] + (e(0, 1) * v[1] + e(0, 2) * v[2]),
            e(1, 0) * v[0] + (e(1, 1) * v[1] + e(1, 2) * v[2]),
            e(2, 0) * v[0] + (e(2, 1) * v[1] + e(2, 2) * v[2]),
        ]
    }
    /// `Mᵀ * v`, row i `m_0i*v0 + (m_1i*v1 + m_2i*v2)` (M the same in every lane).
    #[inline(always)]
    pub fn mat_t_vec<R: Real>(m: &Mat3, v: &R3<R>) -> R3<R> {
        let e = |i, j| R::splat(m[(i, j)]);
        [
            e(0, 0) * v[0] + (e(1, 0) * v[1] + e(2, 0) * v[2]),
            e(0, 1) * v[0] + (e(1, 1) * v[1] + e(2, 1) * v[2]),
            e(0, 2) * v[0] + (e(1, 2) * v[1] + e(2, 2) * v[2]),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The three-term order matters: these inputs give different doubles left-to-right.
    #[test]
    fn dot_uses_eigen_pairing() {
        let a = Vec3::new(1e16, 1.0, -1e16);
        let b = Vec3::new(1.0, 1.0, 1.0);
        // Eigen: 1e16 + (1 + -1e16) = 1e16 + -1e16 (1 is absorbed) = 0
        assert_eq!(dot(&a, &b), 0.0);
        // left to right would give (1e16 + 1) - 1e16 = 0 too; use a case that differs:
        let c = Vec3::new(1.0, 1e16, -1e16);
        assert_eq!(dot(&c, &b), 1.0);
        assert_eq!((c[0] + c[1]) + c[2], 0.0);
    }

    #[test]
    fn sign_of_nan_and_zero_is_zero() {
        assert_eq!(sign(f64::NAN), 0.0);
        assert_eq!(sign(0.0), 0.0);
        assert_eq!(sign(-0.0), 0.0);
        assert_eq!(sign(-3.0), -1.0);
        assert_eq!(sign(2.0), 1.0);
    }

    #[test]
    fn rotation_of_identity_is_identity() {
        assert_eq!(Quat::IDENTITY.to_rotation_matrix(), Mat3::identity());
    }

    #[test]
    fn quarter_turn_about_z_maps_x_to_y() {
        let q = Quat::from_angle_axis(std::f64::consts::FRAC_PI_2, &Vec3::new(0.0, 0.0, 1.0));
        let r = q.to_rotation_matrix();
        let v = mat_vec(&r, &Vec3::new(1.0, 0.0, 0.0));
        assert!((v - Vec3::new(0.0, 1.0, 0.0)).norm() < 1e-15);
    }
}
