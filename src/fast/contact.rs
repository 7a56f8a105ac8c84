//! The fast path's contact kernel: `Ig2_Sphere_Sphere_ScGeom` + `ScGeom::precompute`
//! (pkg/dem/Ig2_Sphere_Sphere_ScGeom.cpp, pkg/dem/ScGeom.cpp), `Ip2_FrictMat_FrictMat_FrictPhys`
//! (pkg/dem/FrictPhys.cpp) and `Law2_ScGeom_FrictPhys_CundallStrack` (pkg/dem/ElasticContactLaw.cpp)
//! fused into one function per pair. Same physics as the YADE-order path; the floating-point
//! evaluation order is free (reciprocals, regrouped cross products), so results agree with YADE to
//! round-off, not bit for bit.

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

#[inline(always)]
pub fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
#[inline(always)]
pub fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
#[inline(always)]
pub fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}
#[inline(always)]
pub fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
#[inline(always)]
pub fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
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

/// Both bodies of a pair as the kernel sees them.
pub struct Two {
    pub xi: V3,
    /// Body j's position plus its periodic shift.
    pub xj: V3,
    pub vi: V3,
    pub vj: V3,
    pub wi: V3,
    pub wj: V3,
    pub ri: f64,
    pub rj: f64,
}

/// What one contact adds to its bodies: `f` on i (j gets `-f`), torques on i and j.
pub struct Load {
    pub f: V3,
    pub ti: V3,
    pub tj: V3,
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
    let d = sub(b.xj, b.xi);
    let d2 = dot(d, d);
    let rs = b.ri + b.rj;
    let is_new = !c.active;
    if is_new {
        if d2 > rs * rs {
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
    let inv = 1.0 / dist;
    let n = scale(d, inv);
    let mut fs = c.fs;
    if !is_new {
        // ScGeom::rotate with the frame rotation since the last step
        let n0 = c.normal;
        let orth = cross(n0, n);
        let angle = dt * 0.5 * dot(n0, add(b.wi, b.wj));
        let twist = scale(n0, angle);
        fs = sub(fs, cross(fs, orth));
        fs = sub(fs, cross(fs, twist));
    }
    // ScGeom::getIncidentVel with avoidGranularRatcheting: alpha (vj - vi) - (ri wi + rj wj) x n
    let alpha = rs * inv;
    let spin = add(scale(b.wi, b.ri), scale(b.wj, b.rj));
    let vrel = sub(scale(sub(b.vj, b.vi), alpha), cross(spin, n));
    let vt = sub(vrel, scale(n, dot(n, vrel)));
    fs = sub(fs, scale(vt, dt * c.ks));
    // Law2_ScGeom_FrictPhys_CundallStrack: Coulomb cap on |Fs| against |Fn| tan(phi)
    let fn_mag = c.kn * pen.max(0.0);
    let max_fs2 = (fn_mag * fn_mag) * (c.tan_phi * c.tan_phi);
    let fs2 = dot(fs, fs);
    if fs2 > max_fs2 {
        fs = scale(fs, (max_fs2 / fs2).sqrt());
    }
    c.normal = n;
    c.fs = fs;
    c.pen = pen;
    let f = [
        -n[0] * fn_mag - fs[0],
        -n[1] * fn_mag - fs[1],
        -n[2] * fn_mag - fs[2],
    ];
    let nf = cross(n, f);
    Some(Load {
        f,
        ti: scale(nf, b.ri - 0.5 * pen),
        tj: scale(nf, b.rj - 0.5 * pen),
    })
}
