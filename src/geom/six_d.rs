//! `ScGeom6D` (pkg/dem/ScGeom.cpp): the relative rotation of the two bodies since the contact was
//! initialised, split into twist (about the normal) and bending, as YADE evaluates it through Eigen's
//! quaternion algebra and its `AngleAxis(Quaternion)` conversion.

use crate::math::{Quat, Real, Vec3};

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
        let q = |o: &Quat| [o.w, o.x, o.y, o.z];
        let creep_q = creep.then(|| q(&self.twist_creep));
        let d = relative_delta(
            &q(ori1),
            &q(ori2),
            &q(&self.initial_orientation1),
            &q(&self.initial_orientation2),
            creep_q.as_ref(),
        );
        let (angle, axis) = angle_axis(&Quat::new(d[0], d[1], d[2], d[3]));
        let n = [normal[0], normal[1], normal[2]];
        let (twist, bending) = twist_bending(angle, [axis[0], axis[1], axis[2]], &n);
        self.twist = twist;
        self.bending = Vec3::new(bending[0], bending[1], bending[2]);
    }
}

/// A quaternion (w, x, y, z) in any arithmetic.
pub type Q<R> = [R; 4];

/// `Quat::mul` (Eigen's Hamilton product) in any arithmetic.
#[inline(always)]
fn qmul<R: Real>(a: &Q<R>, b: &Q<R>) -> Q<R> {
    let ([aw, ax, ay, az], [bw, bx, by, bz]) = (*a, *b);
    [
        aw * bw - ax * bx - ay * by - az * bz,
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by + ay * bw + az * bx - ax * bz,
        aw * bz + az * bw + ax * by - ay * bx,
    ]
}

#[inline(always)]
fn qconj<R: Real>(a: &Q<R>) -> Q<R> {
    [a[0], -a[1], -a[2], -a[3]]
}

/// The first part of `ScGeom6D::precomputeRotations` on a contact that was real, in any
/// arithmetic: the relative rotation `(ori1 init1*) (init2 ori2*)`, normalised as Eigen's
/// `normalize()` (divided by its norm when that is positive), times the twist creep when on.
#[inline(always)]
pub fn relative_delta<R: Real>(
    ori1: &Q<R>,
    ori2: &Q<R>,
    init1: &Q<R>,
    init2: &Q<R>,
    creep: Option<&Q<R>>,
) -> Q<R> {
    let a = qmul(ori1, &qconj(init1));
    let b = qmul(init2, &qconj(ori2));
    let d = qmul(&a, &b);
    // `Quat::norm2`'s order: (x² + y²) + (z² + w²)
    let z = (d[1] * d[1] + d[2] * d[2]) + (d[3] * d[3] + d[0] * d[0]);
    let pos = z.gt(R::splat(0.0));
    let n = z.sqrt();
    let d = d.map(|c| R::select(pos, c / n, c));
    match creep {
        Some(c) => qmul(&d, c),
        None => d,
    }
}

/// `AngleAxis` of quaternion `d` (see `angle_axis`) when the norm `n` of its vector part is not
/// zero (`angle_axis` gives `n`, the stable norm below machine epsilon), in any arithmetic.
#[inline(always)]
pub fn angle_axis_of<R: Real>(d: &Q<R>, n: R) -> (R, [R; 3]) {
    let angle = R::splat(2.0) * n.atan2(d[0].abs());
    let n = R::select(d[0].lt(R::splat(0.0)), -n, n);
    (angle, [d[1] / n, d[2] / n, d[3] / n])
}

/// The norm of a quaternion's vector part (`norm`'s order).
#[inline(always)]
pub fn vec_norm<R: Real>(d: &Q<R>) -> R {
    (d[1] * d[1] + (d[2] * d[2] + d[3] * d[3])).sqrt()
}

/// The end of `ScGeom6D::precomputeRotations`: twist about the normal and bending, from the
/// rotation's angle and axis, in any arithmetic. Eigen can return NaN close to the identity; YADE
/// zeroes it (the > pi branch never fires because the angle comes from 2*atan2(|v|, |w|), kept for
/// the record).
#[inline(always)]
pub fn twist_bending<R: Real>(angle: R, axis: [R; 3], normal: &[R; 3]) -> (R, [R; 3]) {
    let angle = R::select(angle.is_nan(), R::splat(0.0), angle);
    let pi = R::splat(std::f64::consts::PI);
    let angle = R::select(
        angle.gt(pi),
        angle - R::splat(2.0 * std::f64::consts::PI),
        angle,
    );
    let twist = angle * (axis[0] * normal[0] + (axis[1] * normal[1] + axis[2] * normal[2]));
    let bending = [
        angle * axis[0] - twist * normal[0],
        angle * axis[1] - twist * normal[1],
        angle * axis[2] - twist * normal[2],
    ];
    (twist, bending)
}

/// Eigen 3.4 `AngleAxis<double>::operator=(const QuaternionBase&)`: `n = |vec|` (the stable norm when
/// below machine epsilon), angle `2·atan2(n, |w|)`, axis `vec/n` with the sign of w folded into n;
/// the identity gives angle 0 about x.
pub fn angle_axis(q: &Quat) -> (f64, Vec3) {
    let d = [q.w, q.x, q.y, q.z];
    let mut n = vec_norm(&d);
    if n < f64::EPSILON {
        n = stable_norm(&Vec3::new(q.x, q.y, q.z));
    }
    if n != 0.0 {
        let (angle, a) = angle_axis_of(&d, n);
        (angle, Vec3::new(a[0], a[1], a[2]))
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
