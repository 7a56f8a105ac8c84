//! Clumps: rigid aggregates of spheres (YADE `core/Clump.{hpp,cpp}`).
//!
//! A clump is a body of its own (shape `Clump`, never bounded, never in contact) that owns member
//! bodies. Members keep their shape, material and contacts; `NewtonIntegrator` skips them, sums
//! their forces and torques onto the clump, integrates the clump as a rigid (generally aspherical)
//! body and then places the members from the clump's state (`integrator`). Members of one clump
//! never interact (`collider::Collider::may_collide`).

use crate::body::Bodies;
use crate::material::FrictMat;
use crate::math::{cross, dot, Mat3, Quat, Vec3};
use crate::shape::Shape;

/// One member: its body id and its pose in the clump's principal frame (YADE's `Se3r` in
/// `Clump::members`).
#[derive(Clone, Debug, PartialEq)]
pub struct ClumpMember {
    pub id: u32,
    pub rel_pos: Vec3,
    pub rel_ori: Quat,
}

/// The `Clump` shape: members in ascending id order (YADE's `std::map` iteration order, which sets
/// every summation order below).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Clump {
    pub members: Vec<ClumpMember>,
}

/// `Clump::inertiaTensorTranslate`: `I + m·((off·off)·1 − off offᵀ)`, evaluated entry by entry as
/// Eigen does (the outer product is exact per entry, the dot product is `a0 + (a1 + a2)`).
pub fn inertia_translate(i: &Mat3, m: f64, off: &Vec3) -> Mat3 {
    let d = dot(off, off);
    Mat3::from_fn(|r, c| {
        let id = if r == c { d * 1.0 } else { d * 0.0 };
        i[(r, c)] + m * (id - off[r] * off[c])
    })
}

/// Eigen 3.4 `JacobiRotation::makeGivens(p, q)` for reals: returns (c, s).
fn make_givens(p: f64, q: f64) -> (f64, f64) {
    if q == 0.0 {
        (if p < 0.0 { -1.0 } else { 1.0 }, 0.0)
    } else if p == 0.0 {
        (0.0, if q < 0.0 { 1.0 } else { -1.0 })
    } else if p.abs() > q.abs() {
        let t = q / p;
        let mut u = (1.0 + t * t).sqrt();
        if p < 0.0 {
            u = -u;
        }
        let c = 1.0 / u;
        (c, -t * c)
    } else {
        let t = p / q;
        let mut u = (1.0 + t * t).sqrt();
        if q < 0.0 {
            u = -u;
        }
        let s = -1.0 / u;
        (-t * s, s)
    }
}

/// Eigen's `numext::hypot` for reals (`positive_real_hypot` on the absolute values).
fn eigen_hypot(a: f64, b: f64) -> f64 {
    let (x, y) = (a.abs(), b.abs());
    if x.is_infinite() || y.is_infinite() {
        return f64::INFINITY;
    }
    if x.is_nan() || y.is_nan() {
        return f64::NAN;
    }
    let p = if x < y { y } else { x };
    if p == 0.0 {
        return 0.0;
    }
    let qp = (if x < y { x } else { y }) / p;
    p * (1.0 + qp * qp).sqrt()
}

/// Eigen 3.4 `SelfAdjointEigenSolver<Matrix3d>(m)` (the iterative `compute`, not `computeDirect`):
/// scale by the largest |entry| of the lower triangle, Householder tridiagonalisation (the 3x3
/// special case), implicit symmetric QR steps with Wilkinson shift and Givens rotations, then a
/// selection sort into ascending eigenvalues. Returns (eigenvectors as columns, eigenvalues).
/// Only the lower triangle of `m` is read, as Eigen does.
pub fn self_adjoint_eigen(m: &Mat3) -> Result<(Mat3, Vec3), String> {
    let mut scale = 0.0f64;
    for c in 0..3 {
        for r in c..3 {
            let a = m[(r, c)].abs();
            if a > scale {
                scale = a;
            }
        }
    }
    if scale == 0.0 {
        scale = 1.0;
    }
    let l = |r: usize, c: usize| m[(r, c)] / scale;
    // tridiagonalization_inplace_selector<MatrixType,3,false>
    let mut diag = [l(0, 0), 0.0, 0.0];
    let mut sub = [0.0; 2];
    let mut q = Mat3::identity();
    let v1norm2 = l(2, 0) * l(2, 0);
    if v1norm2 <= f64::MIN_POSITIVE {
        diag[1] = l(1, 1);
        diag[2] = l(2, 2);
        sub[0] = l(1, 0);
        sub[1] = l(2, 1);
    } else {
        let beta = (l(1, 0) * l(1, 0) + v1norm2).sqrt();
        let inv_beta = 1.0 / beta;
        let m01 = l(1, 0) * inv_beta;
        let m02 = l(2, 0) * inv_beta;
        let qq = 2.0 * m01 * l(2, 1) + m02 * (l(2, 2) - l(1, 1));
        diag[1] = l(1, 1) + m02 * qq;
        diag[2] = l(2, 2) - m02 * qq;
        sub[0] = beta;
        sub[1] = l(2, 1) - m01 * qq;
        q = Mat3::new(1.0, 0.0, 0.0, 0.0, m01, m02, 0.0, m02, -m01);
    }
    // computeFromTridiagonal_impl
    let n = 3usize;
    let max_iterations = 30usize;
    let consider_as_zero = f64::MIN_POSITIVE;
    let precision_inv = 1.0 / f64::EPSILON;
    let mut end = n - 1;
    let mut start = 0usize;
    let mut iter = 0usize;
    while end > 0 {
        for i in start..end {
            if sub[i].abs() < consider_as_zero {
                sub[i] = 0.0;
            } else {
                let s = precision_inv * sub[i];
                if s * s <= diag[i].abs() + diag[i + 1].abs() {
                    sub[i] = 0.0;
                }
            }
        }
        while end > 0 && sub[end - 1] == 0.0 {
            end -= 1;
        }
        if end == 0 {
            break;
        }
        iter += 1;
        if iter > max_iterations * n {
            break;
        }
        start = end - 1;
        while start > 0 && sub[start - 1] != 0.0 {
            start -= 1;
        }
        tridiagonal_qr_step(&mut diag, &mut sub, start, end, &mut q);
    }
    if iter > max_iterations * n {
        return Err(
            "the eigen decomposition of the clump's inertia tensor did not converge".into(),
        );
    }
    for i in 0..n - 1 {
        let mut k = i;
        for j in i + 1..n {
            if diag[j] < diag[k] {
                k = j;
            }
        }
        if k > i {
            diag.swap(i, k);
            for r in 0..3 {
                let t = q[(r, i)];
                q[(r, i)] = q[(r, k)];
                q[(r, k)] = t;
            }
        }
    }
    Ok((
        q,
        Vec3::new(diag[0] * scale, diag[1] * scale, diag[2] * scale),
    ))
}

/// Eigen's `tridiagonal_qr_step` (Francis implicit QR step with Wilkinson shift), accumulating the
/// rotations into the columns of `q` (`applyOnTheRight(k, k+1, rot)`).
fn tridiagonal_qr_step(
    diag: &mut [f64; 3],
    sub: &mut [f64; 2],
    start: usize,
    end: usize,
    q: &mut Mat3,
) {
    let td = (diag[end - 1] - diag[end]) * 0.5;
    let e = sub[end - 1];
    let mut mu = diag[end];
    if td == 0.0 {
        mu -= e.abs();
    } else if e != 0.0 {
        let e2 = e * e;
        let h = eigen_hypot(td, e);
        let sh = if td > 0.0 { h } else { -h };
        if e2 == 0.0 {
            mu -= e / ((td + sh) / e);
        } else {
            mu -= e2 / (td + sh);
        }
    }
    let mut x = diag[start] - mu;
    let mut z = sub[start];
    let mut k = start;
    while k < end && z != 0.0 {
        let (c, s) = make_givens(x, z);
        let sdk = s * diag[k] + c * sub[k];
        let dkp1 = s * sub[k] + c * diag[k + 1];
        diag[k] = c * (c * diag[k] - s * sub[k]) - s * (c * sub[k] - s * diag[k + 1]);
        diag[k + 1] = s * sdk + c * dkp1;
        sub[k] = c * sdk - s * dkp1;
        if k > start {
            sub[k - 1] = c * sub[k - 1] - s * z;
        }
        x = sub[k];
        if k < end - 1 {
            z = -s * sub[k + 1];
            sub[k + 1] *= c;
        }
        // Q = Q * G: columns k and k+1 rotated by the transposed rotation (c, -s)
        if !(c == 1.0 && s == 0.0) {
            for r in 0..3 {
                let xi = q[(r, k)];
                let yi = q[(r, k + 1)];
                q[(r, k)] = c * xi + -s * yi;
                q[(r, k + 1)] = s * xi + c * yi;
            }
        }
        k += 1;
    }
}

/// Eigen's 3x3 determinant (`determinant_impl<Derived, 3>`); only its sign is used.
fn det3(m: &Mat3) -> f64 {
    let h =
        |a: usize, b: usize, c: usize| m[(a, 0)] * (m[(b, 1)] * m[(c, 2)] - m[(b, 2)] * m[(c, 1)]);
    h(0, 1, 2) - h(1, 0, 2) + h(2, 0, 1)
}

/// `Clump::updateProperties(clump, discretization=0)` (core/Clump.cpp), spheres only: mass, centre of
/// mass, principal inertia and orientation from the members (no volume discretisation, so overlaps
/// count twice, as in YADE), then the members' poses in the principal frame. Velocities are zeroed.
pub fn update_properties(bodies: &mut Bodies, mats: &[FrictMat], cid: usize) -> Result<(), String> {
    let members: Vec<u32> = match &bodies.shape[cid] {
        Shape::Clump(c) => c.members.iter().map(|m| m.id).collect(),
        _ => return Err(format!("body #{} is not a clump", cid)),
    };
    if members.is_empty() {
        return Err("Clump::updateProperties: clump has zero members.".into());
    }
    let mut rel = Vec::with_capacity(members.len());
    if members.len() == 1 {
        // a clump of one takes the member's state as it is
        let s = members[0] as usize;
        bodies.pos[cid] = bodies.pos[s];
        bodies.ori[cid] = bodies.ori[s];
        bodies.inertia[cid] = bodies.inertia[s];
        bodies.mass[cid] = bodies.mass[s];
        bodies.vel[cid] = Vec3::zeros();
        bodies.ang_vel[cid] = Vec3::zeros();
        rel.push((Vec3::zeros(), Quat::IDENTITY));
    } else {
        let mut mass = 0.0;
        let mut sg = Vec3::zeros();
        let mut ig = Mat3::zeros();
        for &s in &members {
            let s = s as usize;
            let Some(r) = bodies.shape[s].plain_sphere_radius() else {
                return Err(format!(
                    "clump member #{} is a {}: ryade clumps support Sphere members only",
                    s,
                    bodies.shape[s].class_name()
                ));
            };
            let dens = mats[bodies.material[s]].density;
            let vol = (4.0 / 3.0) * std::f64::consts::PI * r.powf(3.0);
            let m = dens * vol;
            mass += m;
            let p = bodies.pos[s];
            sg += Vec3::new(m * p[0], m * p[1], m * p[2]);
            let ii = 2.0 / 5.0 * m * (r * r);
            let own = Mat3::from_diagonal(&Vec3::new(ii, ii, ii));
            let off = Vec3::new(-p[0], -p[1], -p[2]);
            ig += inertia_translate(&own, m, &off);
        }
        if mass.is_nan() || mass <= 0.0 {
            return Err(format!(
                "clump #{}: total mass {} is not positive",
                cid, mass
            ));
        }
        let pos = Vec3::new(sg[0] / mass, sg[1] / mass, sg[2] / mass);
        let mut ic = inertia_translate(&ig, -mass, &pos);
        ic[(1, 0)] = ic[(0, 1)];
        ic[(2, 0)] = ic[(0, 2)];
        ic[(2, 1)] = ic[(1, 2)];
        let (mut rot, eig) = self_adjoint_eigen(&ic)?;
        if det3(&rot) < 0.0 {
            for r in 0..3 {
                rot[(r, 2)] = -rot[(r, 2)];
            }
        }
        let mut ori = Quat::from_rotation_matrix(&rot);
        ori.normalize();
        bodies.pos[cid] = pos;
        bodies.ori[cid] = ori;
        bodies.inertia[cid] = eig;
        bodies.mass[cid] = mass;
        bodies.vel[cid] = Vec3::zeros();
        bodies.ang_vel[cid] = Vec3::zeros();
        bodies.aspherical[cid] = eig[0] != eig[1] || eig[0] != eig[2];
        let inv = ori.conjugate();
        for &s in &members {
            let s = s as usize;
            rel.push((inv.rotate(&(bodies.pos[s] - pos)), inv.mul(&bodies.ori[s])));
        }
    }
    if let Shape::Clump(c) = &mut bodies.shape[cid] {
        for (m, (p, o)) in c.members.iter_mut().zip(rel) {
            m.rel_pos = p;
            m.rel_ori = o;
        }
    }
    Ok(())
}

/// `O.bodies.clump(ids, discretization)` (py/wrapper/yadeWrapper.cpp `BodyContainer::clump` with
/// `Clump::add` and `Clump::updateProperties`): append an unbounded clump body and make `ids` its
/// members. `material` is the index the clump body records (YADE leaves it empty; nothing reads it).
/// Only standalone spheres can be clumped, with discretization 0.
pub fn make_clump(
    bodies: &mut Bodies,
    mats: &[FrictMat],
    ids: &[usize],
    discretization: u32,
) -> Result<usize, String> {
    if discretization > 0 {
        return Err(format!(
            "clump discretization={} (inertia by volume integration of overlapping members) is not \
             supported by ryade; use discretization=0 (the default)",
            discretization
        ));
    }
    if ids.is_empty() {
        return Err("Clump::updateProperties: clump has zero members.".into());
    }
    let n = bodies.len();
    let mut sorted: Vec<usize> = ids.to_vec();
    sorted.sort_unstable();
    for (k, &id) in sorted.iter().enumerate() {
        if id >= n {
            return Err(format!("No body #{} (there are {} bodies)", id, n));
        }
        if k > 0 && sorted[k - 1] == id {
            return Err(format!("Body #{} is already part of this clump #{}", id, n));
        }
        if bodies.is_clump(id) {
            return Err(format!(
                "body #{} is a clump: merging clumps into a new clump is not supported by ryade",
                id
            ));
        }
        if bodies.is_clump_member(id) {
            return Err(format!(
                "body #{} is already a member of clump #{}: moving members between clumps is not \
                 supported by ryade",
                id,
                bodies.clump_id[id].unwrap()
            ));
        }
        if bodies.shape[id].plain_sphere_radius().is_none() {
            return Err(format!(
                "body #{} is a {}: ryade clumps support Sphere members only",
                id,
                bodies.shape[id].class_name()
            ));
        }
    }
    let material = bodies.material[sorted[0]];
    let cid = bodies.push(crate::body::BodySpec {
        shape: Shape::Clump(Box::new(Clump {
            members: sorted
                .iter()
                .map(|&id| ClumpMember {
                    id: id as u32,
                    rel_pos: Vec3::zeros(),
                    rel_ori: Quat::IDENTITY,
                })
                .collect(),
        })),
        material,
        mask: 1,
        bounded: false,
        pos: Vec3::zeros(),
        vel: Vec3::zeros(),
        ang_vel: Vec3::zeros(),
        ori: Quat::IDENTITY,
        mass: 0.0,
        inertia: Vec3::zeros(),
        blocked: 0,
        is_damped: true,
    });
    for &id in &sorted {
        bodies.clump_id[id] = Some(cid as u32);
    }
    bodies.clump_id[cid] = Some(cid as u32);
    if let Err(e) = update_properties(bodies, mats, cid) {
        // leave no half-made clump behind
        for &id in &sorted {
            bodies.clump_id[id] = None;
        }
        bodies.truncate(cid);
        return Err(e);
    }
    Ok(cid)
}

/// `Clump::addForceTorqueFromMembers`: `F = Σ f_i`, `T = Σ (t_i + (x_i − x_c) × f_i)`, from zero, in
/// member order.
pub fn force_torque_from_members(
    c: &Clump,
    bodies: &Bodies,
    forces: &crate::forces::Forces,
    cpos: &Vec3,
) -> (Vec3, Vec3) {
    let mut f = Vec3::zeros();
    let mut t = Vec3::zeros();
    for m in &c.members {
        let id = m.id as usize;
        let fi = *forces.force(id);
        f += fi;
        t += forces.torque(id) + cross(&(bodies.pos[id] - cpos), &fi);
    }
    (f, t)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A diagonal matrix is already tridiagonal with zero off-diagonals: eigenvalues sorted
    /// ascending, eigenvectors the permuted axes.
    #[test]
    fn eigen_of_diagonal_matrix_sorts_ascending() {
        let m = Mat3::from_diagonal(&Vec3::new(3.0, 1.0, 2.0));
        let (v, e) = self_adjoint_eigen(&m).unwrap();
        assert_eq!(e, Vec3::new(1.0, 2.0, 3.0));
        assert_eq!(v.column(0).into_owned(), Vec3::new(0.0, 1.0, 0.0));
        assert_eq!(v.column(1).into_owned(), Vec3::new(0.0, 0.0, 1.0));
        assert_eq!(v.column(2).into_owned(), Vec3::new(1.0, 0.0, 0.0));
    }

    /// A full symmetric matrix: A·v = λ·v to round-off and orthonormal eigenvectors.
    #[test]
    fn eigen_of_full_matrix_satisfies_definition() {
        let m = Mat3::new(4.0, 1.0, -2.0, 1.0, 3.0, 0.5, -2.0, 0.5, 5.0);
        let (v, e) = self_adjoint_eigen(&m).unwrap();
        for k in 0..3 {
            let x = v.column(k).into_owned();
            let r = m * x - x * e[k];
            assert!(r.norm() < 1e-13, "residual {}", r.norm());
            assert!((x.norm() - 1.0).abs() < 1e-14);
        }
        assert!(e[0] <= e[1] && e[1] <= e[2]);
    }

    #[test]
    fn quaternion_round_trips_through_its_matrix() {
        let mut q = Quat::new(0.3, -0.5, 0.7, 0.1);
        q.normalize();
        let p = Quat::from_rotation_matrix(&q.to_rotation_matrix());
        let s = if p.w * q.w < 0.0 { -1.0 } else { 1.0 };
        assert!((p.w - s * q.w).abs() < 1e-15 && (p.x - s * q.x).abs() < 1e-15);
        assert!((p.y - s * q.y).abs() < 1e-15 && (p.z - s * q.z).abs() < 1e-15);
        let v = Vec3::new(0.2, -1.0, 3.0);
        let a = q.rotate(&v);
        let b = crate::math::mat_vec(&q.to_rotation_matrix(), &v);
        assert!((a - b).norm() < 1e-14);
    }
}
