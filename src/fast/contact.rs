//! The fast path's contact kernel: `Ig2_Sphere_Sphere_ScGeom` + `ScGeom::precompute`
//! (pkg/dem/Ig2_Sphere_Sphere_ScGeom.cpp, pkg/dem/ScGeom.cpp), `Ip2_FrictMat_FrictMat_FrictPhys`
//! (pkg/dem/FrictPhys.cpp) and `Law2_ScGeom_FrictPhys_CundallStrack` (pkg/dem/ElasticContactLaw.cpp)
//! fused into one function per pair. Same physics as the YADE-order path; the floating-point
//! evaluation order is free (reciprocals, regrouped cross products), so results agree with YADE to
//! round-off, not bit for bit.

use crate::math::r3;
pub use crate::math::Real;

pub type V3 = [f64; 3];

/// The coordinate `x` wrapped into the period [0, `l`).
#[inline(always)]
pub fn wrap_into(x: f64, l: f64) -> f64 {
    x - l * (x / l).floor()
}

/// The offset `d` (|d| < `l`, wrapped positions) brought to its nearest image in a period of `l`,
/// by comparison (no libm round).
#[inline(always)]
pub fn nearest_image(d: f64, l: f64) -> f64 {
    if d > 0.5 * l {
        d - l
    } else if d < -0.5 * l {
        d + l
    } else {
        d
    }
}

// (the kernel's vector operations by value: `math::r3`'s, except `dot`, whose order is free)
#[inline(always)]
pub fn add<R: Real>(a: [R; 3], b: [R; 3]) -> [R; 3] {
    r3::add(&a, &b)
}
#[inline(always)]
pub fn sub<R: Real>(a: [R; 3], b: [R; 3]) -> [R; 3] {
    r3::sub(&a, &b)
}
#[inline(always)]
pub fn scale<R: Real>(a: [R; 3], s: R) -> [R; 3] {
    r3::scale(&a, s)
}
#[inline(always)]
pub fn dot<R: Real>(a: [R; 3], b: [R; 3]) -> R {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
#[inline(always)]
pub fn cross<R: Real>(a: [R; 3], b: [R; 3]) -> [R; 3] {
    r3::cross(&a, &b)
}

/// One pair of the Verlet list: sorted body indices `i < j` and the index of body j's periodic
/// shift in the shift table (0: no shift).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Pair {
    pub i: u32,
    pub j: u32,
    pub img: u32,
}

/// The state a contact carries from step to step (what YADE keeps in ScGeom and FrictPhys).
/// `normal` points from i to j; `fs` is the shear force on j (YADE's `shearForce` on body 2).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Contact {
    pub active: bool,
    pub normal: V3,
    pub fs: V3,
    pub pen: f64,
    pub kn: f64,
    pub ks: f64,
    pub tan_phi: f64,
}

/// Material constants the contact creation needs (FrictMat).
pub type Mat = crate::phys::FrictConsts;

/// `Ip2_FrictMat_FrictMat_FrictPhys::go` (the one formula, `phys::frict_stiffness`) on a fresh contact.
#[inline(never)]
pub fn create(c: &mut Contact, m1: &Mat, m2: &Mat, r1: f64, r2: f64) {
    (c.kn, c.ks, c.tan_phi) = crate::phys::frict_stiffness(m1, m2, r1, r2);
    c.fs = [0.0; 3];
    c.active = true;
}

/// Both bodies of a pair (or of four pairs, one per lane) as the kernel sees them.
pub struct Two<R = f64> {
    pub xi: [R; 3],
    /// Body j's position plus its periodic shift.
    pub xj: [R; 3],
    pub vi: [R; 3],
    pub vj: [R; 3],
    pub wi: [R; 3],
    pub wj: [R; 3],
    pub ri: R,
    pub rj: R,
}

/// What one contact adds to its bodies: `f` on i (j gets `-f`), torques on i and j.
pub struct Load<R = f64> {
    pub f: [R; 3],
    pub ti: [R; 3],
    pub tj: [R; 3],
}

/// What the formula reads of a touching contact's state: the last step's normal, the shear force
/// and the stiffnesses.
pub struct Touch<R> {
    pub n0: [R; 3],
    pub fs: [R; 3],
    pub kn: R,
    pub ks: R,
    pub tan_phi: R,
}

/// A touching contact's new normal and shear force, and its loads.
pub struct Out<R> {
    pub n: [R; 3],
    pub fs: [R; 3],
    pub load: Load<R>,
}

/// Distance test, geometry, shear update and force of one pair. `new_contact` is called when the
/// spheres touch for the first time (YADE's `(r1+r2)² - |d|² >= 0` test) to create the physics.
/// Returns None when the pair is apart (an existing contact with `pen < 0` is erased, as the law
/// does).
#[inline(always)]
pub fn pair(
    c: &mut Contact,
    b: &Two,
    dt: f64,
    new_contact: impl FnOnce(&mut Contact),
) -> Option<Load> {
    let (d, d2, rs) = separation(b.xi, b.xj, b.ri, b.rj);
    let is_new = !c.active;
    if is_new {
        if apart(d2, rs) {
            return None;
        }
        new_contact(c);
    }
    let dist = d2.sqrt();
    let pen = rs - dist;
    if !is_new && pen < 0.0 {
        c.active = false;
        return None;
    }
    let s = Touch {
        n0: c.normal,
        fs: c.fs,
        kn: c.kn,
        ks: c.ks,
        tan_phi: c.tan_phi,
    };
    let o = law(&s, b, d, dist, pen, dt);
    c.normal = o.n;
    c.fs = o.fs;
    c.pen = pen;
    Some(o.load)
}

/// `d` = xj - xi, |d|² and ri + rj of a pair (or of four pairs, one per lane), in the operations
/// every kernel and pass uses for the distance test.
#[inline(always)]
pub fn separation<R: Real>(xi: [R; 3], xj: [R; 3], ri: R, rj: R) -> ([R; 3], R, R) {
    let d = sub(xj, xi);
    (d, dot(d, d), ri + rj)
}

/// Ig2_Sphere_Sphere_ScGeom's test on a pair that is no contact: apart when |d|² > (ri + rj)²
/// (NaN: not apart).
#[inline(always)]
pub fn apart<R: Real>(d2: R, rs: R) -> R::Mask {
    d2.gt(rs * rs)
}

/// The geometry, shear update and force of a touching contact (`d` from i to j, `dist` = |d|,
/// `pen` = ri + rj - dist): one formula for the scalar kernel and the lanes. A fresh contact
/// (`fs` zero, as `create` leaves it) comes out of the frame rotation unchanged, as YADE's first
/// step skips it.
#[inline(always)]
pub fn law<R: Real>(s: &Touch<R>, b: &Two<R>, d: [R; 3], dist: R, pen: R, dt: R) -> Out<R> {
    let inv = R::splat(1.0) / dist;
    let n = scale(d, inv);
    // ScGeom::rotate with the frame rotation since the last step
    let n0 = s.n0;
    let orth = cross(n0, n);
    let angle = dt * R::splat(0.5) * dot(n0, add(b.wi, b.wj));
    let twist = scale(n0, angle);
    let mut fs = s.fs;
    fs = sub(fs, cross(fs, orth));
    fs = sub(fs, cross(fs, twist));
    // ScGeom::getIncidentVel with avoidGranularRatcheting: alpha (vj - vi) - (ri wi + rj wj) x n
    let alpha = (b.ri + b.rj) * inv;
    let spin = add(scale(b.wi, b.ri), scale(b.wj, b.rj));
    let vrel = sub(scale(sub(b.vj, b.vi), alpha), cross(spin, n));
    let vt = sub(vrel, scale(n, dot(n, vrel)));
    fs = sub(fs, scale(vt, dt * s.ks));
    // Law2_ScGeom_FrictPhys_CundallStrack: Coulomb cap on |Fs| against |Fn| tan(phi)
    let fn_mag = s.kn * pen.max(R::splat(0.0));
    let max_fs2 = (fn_mag * fn_mag) * (s.tan_phi * s.tan_phi);
    let fs2 = dot(fs, fs);
    let over = fs2.gt(max_fs2);
    if R::any(over) {
        let capped = scale(fs, (max_fs2 / fs2).sqrt());
        fs = [
            R::select(over, capped[0], fs[0]),
            R::select(over, capped[1], fs[1]),
            R::select(over, capped[2], fs[2]),
        ];
    }
    let f = [
        -n[0] * fn_mag - fs[0],
        -n[1] * fn_mag - fs[1],
        -n[2] * fn_mag - fs[2],
    ];
    let nf = cross(n, f);
    let half = R::splat(0.5);
    Out {
        n,
        fs,
        load: Load {
            f,
            ti: scale(nf, b.ri - half * pen),
            tj: scale(nf, b.rj - half * pen),
        },
    }
}

/// Test pairs along a chain of `n` bodies: each with its next four, and (n > 2) body 0 with the
/// last through image 1 (the chain's far end brought back as a periodic image).
#[cfg(test)]
pub fn chain_pairs(n: usize) -> Vec<Pair> {
    let mut pairs = Vec::new();
    for i in 0..n {
        for dj in 1..5 {
            if i + dj < n {
                pairs.push(Pair {
                    i: i as u32,
                    j: (i + dj) as u32,
                    img: 0,
                });
            }
        }
        if i == 0 && n > 2 {
            pairs.push(Pair {
                i: 0,
                j: n as u32 - 1,
                img: 1,
            });
        }
    }
    pairs
}
