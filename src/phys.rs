//! Contact physics: `Ip2_FrictMat_FrictMat_FrictPhys` (pkg/dem/FrictPhys.cpp).

use crate::geom::ScGeom;
use crate::material::FrictMat;
use crate::math::Vec3;

/// `FrictPhys` (NormShearPhys + tangent of the friction angle). kn, ks and tanφ are frozen at creation.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FrictPhys {
    pub kn: f64,
    pub ks: f64,
    pub tan_phi: f64,
    /// Force on body 2 from body 1.
    pub normal_force: Vec3,
    pub shear_force: Vec3,
}

/// `Ip2_FrictMat_FrictMat_FrictPhys::go`: harmonic means of E·R and E·R·ν, friction of the weaker.
pub fn ip2_frict(m1: &FrictMat, m2: &FrictMat, g: &ScGeom) -> FrictPhys {
    let ra = if g.radius1 > 0.0 {
        g.radius1
    } else {
        g.radius2
    };
    let rb = if g.radius2 > 0.0 {
        g.radius2
    } else {
        g.radius1
    };
    let kna = m1.young * ra;
    let knb = m2.young * rb;
    let ksa = kna * m1.poisson;
    let ksb = knb * m2.poisson;
    let kn = 2.0 * kna * knb / (kna + knb);
    let ks = 2.0 * ksa * ksb / (ksa + ksb);
    let phi = m1.friction_angle.min(m2.friction_angle);
    FrictPhys {
        kn,
        ks,
        tan_phi: phi.tan(),
        normal_force: Vec3::zeros(),
        shear_force: Vec3::zeros(),
    }
}
