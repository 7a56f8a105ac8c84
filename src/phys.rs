//! Contact physics: `Ip2_FrictMat_FrictMat_FrictPhys` (pkg/dem/FrictPhys.cpp) and
//! `Ip2_CohFrictMat_CohFrictMat_CohFrictPhys` (pkg/dem/CohesiveFrictionalContactLaw.cpp),
//! `Ip2_ViscElMat_ViscElMat_ViscElPhys` (pkg/dem/ViscoelasticPM.cpp), `Ip2_FrictMat_FrictMat_MindlinPhys`
//! (pkg/dem/HertzMindlin.cpp).

use crate::geom::ScGeom;
use crate::material::FrictMat;
use crate::math::Vec3;

/// Physics classes for law dispatch (IPhys <- NormPhys <- NormShearPhys <- FrictPhys <-
/// RotStiffFrictPhys <- CohFrictPhys, MindlinPhys; FrictPhys <- ViscElPhys).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PhysClass {
    IPhys,
    NormPhys,
    NormShearPhys,
    FrictPhys,
    RotStiffFrictPhys,
    CohFrictPhys,
    ViscElPhys,
    MindlinPhys,
    LudingPhys,
    BubblePhys,
    CpmPhys,
}

impl crate::dispatch::Hierarchy for PhysClass {
    fn parent(self) -> Option<Self> {
        use PhysClass::*;
        match self {
            IPhys => None,
            NormPhys => Some(IPhys),
            NormShearPhys => Some(NormPhys),
            CpmPhys => Some(NormShearPhys),
            FrictPhys => Some(NormShearPhys),
            ViscElPhys | LudingPhys => Some(FrictPhys),
            BubblePhys => Some(IPhys),
            RotStiffFrictPhys => Some(FrictPhys),
            CohFrictPhys => Some(RotStiffFrictPhys),
            MindlinPhys => Some(RotStiffFrictPhys),
        }
    }
}

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

/// The FrictMat constants a contact's creation needs (what the fast path keeps per material).
#[derive(Clone, Copy, Debug)]
pub struct FrictConsts {
    pub young: f64,
    pub poisson: f64,
    pub friction_angle: f64,
}

impl FrictMat {
    pub fn consts(&self) -> FrictConsts {
        FrictConsts {
            young: self.young,
            poisson: self.poisson,
            friction_angle: self.friction_angle,
        }
    }
}

/// The numbers of `Ip2_FrictMat_FrictMat_FrictPhys::go` (pkg/dem/FrictPhys.cpp) for radii ra, rb: harmonic
/// means of E·R and E·R·ν, tan of the weaker friction angle. Both paths (YADE-order and fast) use this.
#[inline]
pub fn frict_stiffness(m1: &FrictConsts, m2: &FrictConsts, ra: f64, rb: f64) -> (f64, f64, f64) {
    let kna = m1.young * ra;
    let knb = m2.young * rb;
    let ksa = kna * m1.poisson;
    let ksb = knb * m2.poisson;
    let kn = 2.0 * kna * knb / (kna + knb);
    let ks = 2.0 * ksa * ksb / (ksa + ksb);
    (kn, ks, m1.friction_angle.min(m2.friction_angle).tan())
}

/// `Ip2_FrictMat_FrictMat_FrictPhys::go`: harmonic means of E·R and E·R·ν, friction of the weaker.
pub fn ip2_frict(m1: &FrictMat, m2: &FrictMat, g: &ScGeom) -> FrictPhys {
    let (ra, rb) = g.ref_radii();
    let (kn, ks, tan_phi) = frict_stiffness(&m1.consts(), &m2.consts(), ra, rb);
    FrictPhys {
        kn,
        ks,
        tan_phi,
        normal_force: Vec3::zeros(),
        shear_force: Vec3::zeros(),
    }
}

/// What `CohFrictPhys` (pkg/dem/CohesiveFrictionalContactLaw.hpp) adds to `FrictPhys`, including the
/// rotational stiffnesses of its base `RotStiffFrictPhys`. Defaults are the C++ class defaults.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CohFrictPhys {
    pub kr: f64,
    pub ktw: f64,
    pub cohesion_disables_friction: bool,
    pub cohesion_broken: bool,
    pub fragile: bool,
    pub init_cohesion: bool,
    pub max_roll_pl: f64,
    pub max_twist_pl: f64,
    pub normal_adhesion: f64,
    pub shear_adhesion: f64,
    pub unp: f64,
    pub unp_max: f64,
    pub moment_rotation_law: bool,
    pub creep_viscosity: f64,
    pub moment_twist: Vec3,
    pub moment_bending: Vec3,
}

impl Default for CohFrictPhys {
    fn default() -> Self {
        CohFrictPhys {
            kr: 0.0,
            ktw: 0.0,
            cohesion_disables_friction: false,
            cohesion_broken: true,
            fragile: true,
            init_cohesion: false,
            max_roll_pl: 0.0,
            max_twist_pl: 0.0,
            normal_adhesion: 0.0,
            shear_adhesion: 0.0,
            unp: 0.0,
            unp_max: 0.0,
            moment_rotation_law: false,
            creep_viscosity: -1.0,
            moment_twist: Vec3::zeros(),
            moment_bending: Vec3::zeros(),
        }
    }
}

impl CohFrictPhys {
    /// `CohFrictPhys::SetBreakingState`.
    pub fn set_breaking_state(&mut self) {
        self.cohesion_broken = true;
        self.normal_adhesion = 0.0;
        self.shear_adhesion = 0.0;
    }
}

/// The state of an `Ip2_CohFrictMat_CohFrictMat_CohFrictPhys` functor (its flags change while the
/// simulation runs: `setCohesionNow` switches itself off one iteration after it was first used).
#[derive(Clone, Debug, PartialEq)]
pub struct CohFrictIp2 {
    pub set_cohesion_now: bool,
    pub set_cohesion_on_new_contacts: bool,
    /// The C++-only `cohesionDefinitionIteration` (-1: none).
    pub cohesion_definition_iteration: i64,
}

impl Default for CohFrictIp2 {
    fn default() -> Self {
        CohFrictIp2 {
            set_cohesion_now: false,
            set_cohesion_on_new_contacts: false,
            cohesion_definition_iteration: -1,
        }
    }
}

/// What the cohesive Ip2 must do to the interaction's geometry besides creating/updating physics.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CohAction {
    Nothing,
    /// `geom->initRotations(state1, state2)`
    InitRotations,
}

impl CohFrictIp2 {
    /// `Ip2_CohFrictMat_CohFrictMat_CohFrictPhys::go` (pkg/dem/CohesiveFrictionalContactLaw.cpp):
    /// the `setCohesionNow` bookkeeping on every call, then either new physics (harmonic stiffnesses,
    /// rotational stiffnesses, cohesion if requested) or, on existing physics, a cohesion reset when
    /// `setCohesionNow` or `initCohesion` asks for it (stiffnesses and `unp` untouched).
    #[allow(clippy::too_many_arguments)]
    pub fn go(
        &mut self,
        iter: i64,
        m1: &FrictMat,
        m2: &FrictMat,
        radius1: f64,
        radius2: f64,
        phys: &mut Option<FrictPhys>,
        coh: &mut Option<CohFrictPhys>,
    ) -> CohAction {
        if self.set_cohesion_now && self.cohesion_definition_iteration == -1 {
            self.cohesion_definition_iteration = iter;
        }
        if self.set_cohesion_now
            && self.cohesion_definition_iteration != -1
            && self.cohesion_definition_iteration != iter
        {
            self.cohesion_definition_iteration = -1;
            self.set_cohesion_now = false;
        }
        let (c1, c2) = (
            m1.coh.as_deref().expect("CohFrictMat"),
            m2.coh.as_deref().expect("CohFrictMat"),
        );
        let normal_adh = cxx_min(c1.normal_cohesion, c2.normal_cohesion);
        let shear_adh = cxx_min(c1.shear_cohesion, c2.shear_cohesion);
        let mut action = CohAction::Nothing;
        if phys.is_none() {
            let (ea, eb, va, vb) = (m1.young, m2.young, m1.poisson, m2.poisson);
            let (da, db) = (radius1, radius2);
            let kn = 2.0 * ea * da * eb * db / (ea * da + eb * db);
            let friction_angle = cxx_min(m1.friction_angle, m2.friction_angle);
            let alpha_kr = if c1.alpha_kr != 0.0 && c2.alpha_kr != 0.0 {
                2.0 * c1.alpha_kr * c2.alpha_kr / (c1.alpha_kr + c2.alpha_kr)
            } else {
                0.0
            };
            let alpha_ktw = if c1.alpha_ktw != 0.0 && c2.alpha_ktw != 0.0 {
                2.0 * c1.alpha_ktw * c2.alpha_ktw / (c1.alpha_ktw + c2.alpha_ktw)
            } else {
                0.0
            };
            let ks = if va != 0.0 && vb != 0.0 {
                2.0 * ea * da * va * eb * db * vb / (ea * da * va + eb * db * vb)
            } else {
                0.0
            };
            let mut cp = CohFrictPhys {
                kr: da * db * ks * alpha_kr,
                ktw: da * db * ks * alpha_ktw,
                ..Default::default()
            };
            let tan_phi = friction_angle.tan();
            if (self.set_cohesion_on_new_contacts || self.set_cohesion_now)
                && c1.is_cohesive
                && c2.is_cohesive
            {
                cp.cohesion_broken = false;
                let m = cxx_min(db, da);
                cp.normal_adhesion = normal_adh * (m * m);
                cp.shear_adhesion = shear_adh * (m * m);
                action = CohAction::InitRotations;
                cp.fragile = c1.fragile || c2.fragile;
            }
            cp.max_roll_pl = cxx_min(c1.eta_roll * da, c2.eta_roll * db);
            cp.max_twist_pl = cxx_min(c1.eta_twist * da, c2.eta_twist * db);
            cp.moment_rotation_law = c1.moment_rotation_law && c2.moment_rotation_law;
            *phys = Some(FrictPhys {
                kn,
                ks,
                tan_phi,
                normal_force: Vec3::zeros(),
                shear_force: Vec3::zeros(),
            });
            *coh = Some(cp);
        } else if let Some(cp) = coh.as_mut() {
            if (self.set_cohesion_now && c1.is_cohesive && c2.is_cohesive) || cp.init_cohesion {
                cp.cohesion_broken = false;
                let m = cxx_min(radius2, radius1);
                cp.normal_adhesion = normal_adh * (m * m);
                cp.shear_adhesion = shear_adh * (m * m);
                action = CohAction::InitRotations;
                cp.fragile = c1.fragile || c2.fragile;
                cp.init_cohesion = false;
            }
        }
        action
    }
}

/// `std::min(a, b)`: `b < a ? b : a`.
#[inline(always)]
pub(crate) fn cxx_min(a: f64, b: f64) -> f64 {
    if b < a {
        b
    } else {
        a
    }
}

/// What `ViscElPhys` (pkg/dem/ViscoelasticPM.hpp) adds to `FrictPhys` (kn, ks, tanφ and the forces
/// are there): the viscous constants, the last normal force parts and the rolling resistance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViscElPhys {
    pub cn: f64,
    pub cs: f64,
    /// `Fn`: elastic part of the normal force.
    pub fn_el: f64,
    /// `Fv`: viscous part of the normal force.
    pub fv: f64,
    pub m_r: f64,
    pub m_r_type: u32,
}

/// `contactParameterCalculation` (pkg/dem/ViscoelasticPM.cpp): the two values in series (1 / (1/l1 +
/// 1/l2)), a zero value left out, 0 when both are zero.
pub fn viscel_series(l1: f64, l2: f64) -> f64 {
    let inv = |l: f64| if l != 0.0 { 1.0 / l } else { 0.0 };
    let a = inv(l1) + inv(l2);
    if a != 0.0 {
        1.0 / a
    } else {
        0.0
    }
}

/// `Ip2_ViscElMat_ViscElMat_ViscElPhys::epsilon` (pkg/dem/ViscoelasticPM.cpp).
const VISCEL_EPSILON: f64 = 1.0e-8;

/// `get_en_from_cn` (pkg/dem/ViscoelasticPM.cpp): the restitution coefficient of a damped oscillator
/// of mass m, stiffness kn and damping cn (under-, over- and critically damped branches).
pub fn viscel_en_from_cn(cn: f64, m: f64, kn: f64) -> f64 {
    let beta = 0.5 * cn / m;
    let omega0 = (kn / m).sqrt();
    let omega = (omega0 * omega0 - beta * beta).sqrt();
    let big_omega = (beta * beta - omega0 * omega0).sqrt();
    let half = omega0 / 2f64.sqrt();
    let pi = std::f64::consts::PI;
    if beta < half {
        (-beta / omega * (pi - (2. * beta * omega / (omega * omega - beta * beta)).atan())).exp()
    } else if beta > half && beta < omega0 {
        (-beta / omega * (-2. * beta * omega / (omega * omega - beta * beta)).atan()).exp()
    } else if beta > omega0 {
        (-beta / big_omega * ((beta + big_omega) / (beta - big_omega)).ln()).exp()
    } else if beta == half || beta == omega0 {
        viscel_en_from_cn(cn + VISCEL_EPSILON, m, kn)
    } else {
        0.0
    }
}

/// `find_cn_from_en` (pkg/dem/ViscoelasticPM.cpp): Newton-Raphson (central-difference slope) for the
/// damping cn whose restitution coefficient is `en`; gives up after 15 iterations with cn = 0.
pub fn viscel_cn_from_en(en: f64, m: f64, kn: f64, ids: (usize, usize)) -> f64 {
    let eps = VISCEL_EPSILON;
    let mut cn = eps;
    let mut en_now = viscel_en_from_cn(cn, m, kn);
    let mut i = 0;
    let mut error = 1.0 / eps;
    while error > 1.0e-2 || error.is_nan() {
        if i > 15 {
            cn = 0.;
            eprintln!(
                "Warning (Ip2_ViscElMat_ViscElMat_ViscElPhys): no convergence of cn for the restitution \
                 coefficient within 15 iterations, contact {}-{}: continuing with cn=0 en=1",
                ids.0, ids.1
            );
            break;
        }
        i += 1;
        let mut slope =
            (viscel_en_from_cn(cn - eps, m, kn) - viscel_en_from_cn(cn + eps, m, kn)) / (-2. * eps);
        // (a NaN slope is replaced too, as YADE's `fabs(deriv) > 1e-15 ? deriv : 1e-15`)
        slope = if slope.abs() > 1e-15 { slope } else { 1e-15 };
        cn -= (en_now - en) / slope;
        en_now = viscel_en_from_cn(cn, m, kn);
        error = (en_now - en).abs() / en;
    }
    cn
}

/// `Ip2_ViscElMat_ViscElMat_ViscElPhys::Calculate_ViscElMat_ViscElMat_ViscElPhys`
/// (pkg/dem/ViscoelasticPM.cpp) without lubrication: the per-body constants from contact
/// time and restitution (Pournin), or given kn/ks/cn/cs, or E·d and ν·kn with cn/cs given or cn from
/// the normal restitution; then the two bodies in series. `mass1/2` are the bodies' masses (a massless
/// body takes the other's), `ids` only name the contact in messages; `mm` the functor's MatchMakers
/// (tc, en, et, frictAngle), called with the two materials' ids.
#[allow(clippy::too_many_arguments)]
pub fn ip2_viscel(
    mm: &ViscElIp2,
    m1: &FrictMat,
    m2: &FrictMat,
    mass1: f64,
    mass2: f64,
    g: &ScGeom,
    ids: (usize, usize),
) -> Result<(FrictPhys, ViscElPhys), String> {
    let (v1, v2) = (
        m1.viscel.as_deref().ok_or("ViscElMat expected")?,
        m2.viscel.as_deref().ok_or("ViscElMat expected")?,
    );
    let same_set = [
        (v1.kn, v2.kn),
        (v1.ks, v2.ks),
        (v1.cn, v2.cn),
        (v1.cs, v2.cs),
        (v1.tc, v2.tc),
        (v1.en, v2.en),
        (v1.et, v2.et),
    ]
    .iter()
    .all(|(a, b)| a.is_finite() == b.is_finite());
    if !same_set {
        return Err(
            "Both materials should have the same defined set of variables e.g. tc, ks etc.!".into(),
        );
    }
    let (mut ma, mut mb) = (mass1, mass2);
    if ma == 0.0 && mb > 0.0 {
        ma = mb;
    } else if mb == 0.0 && ma > 0.0 {
        mb = ma;
    }
    let mass_r = ma * mb / (ma + mb);
    let (r1, r2) = g.ref_radii();
    let pi = std::f64::consts::PI;
    let (kn1, kn2, ks1, ks2, cn1, cn2, cs1, cs2);
    let nan = f64::NAN;
    let pick = |m: &Option<MatchMaker>, a: f64, b: f64| -> Result<f64, String> {
        match m {
            Some(m) => m.call(m1.id, m2.id, nan, nan),
            None => Ok((a + b) / 2.0),
        }
    };
    if (v1.tc.is_finite() && v1.en.is_finite() && v1.et.is_finite())
        || (mm.tc.is_some() && mm.en.is_some() && mm.et.is_some())
    {
        let tc = pick(&mm.tc, v1.tc, v2.tc)?;
        let ln_en = pick(&mm.en, v1.en, v2.en)?.ln();
        let ln_et = pick(&mm.et, v1.et, v2.et)?.ln();
        // per body twice the contact's value, so that the two in series give it
        let kn = 1. / tc / tc * (pi * pi + ln_en * ln_en) * mass_r * 2.;
        let ks = 2.0 / 7.0 / tc / tc * (pi * pi + ln_et * ln_et) * mass_r * 2.;
        let zero_small = |c: f64| if c.abs() <= 1e-20 { 0.0 } else { c };
        let cn = zero_small(-2.0 / tc * ln_en * mass_r * 2.);
        let cs = zero_small(-4.0 / 7.0 / tc * ln_et * mass_r * 2.);
        (kn1, kn2, ks1, ks2, cn1, cn2, cs1, cs2) = (kn, kn, ks, ks, cn, cn, cs, cs);
    } else if v1.kn.is_finite() && v1.ks.is_finite() && v1.cn.is_finite() && v1.cs.is_finite() {
        (kn1, kn2, ks1, ks2) = (v1.kn, v2.kn, v1.ks, v2.ks);
        (cn1, cn2, cs1, cs2) = (v1.cn, v2.cn, v1.cs, v2.cs);
    } else {
        kn1 = 2. * m1.young * r1;
        kn2 = 2. * m2.young * r2;
        ks1 = kn1 * m1.poisson;
        ks2 = kn2 * m2.poisson;
        if v1.cn.is_finite() && v1.cs.is_finite() {
            (cn1, cn2, cs1, cs2) = (v1.cn, v2.cn, v1.cs, v2.cs);
        } else if v1.en.is_finite() {
            let en = pick(&mm.en, v1.en, v2.en)?;
            let cn = 2.0 * viscel_cn_from_en(en, mass_r, viscel_series(kn1, kn2), ids);
            (cn1, cn2, cs1, cs2) = (cn, cn, 0.0, 0.0);
        } else {
            return Err(
                "Inconsistent material constants for ViscElMat's, please check input".into(),
            );
        }
    }
    let m_r = if v1.m_r > 0.0 || v2.m_r > 0.0 {
        let inv = |m: f64| if m > 0.0 { 1. / m } else { 0. };
        2.0 / (inv(v1.m_r) + inv(v2.m_r))
    } else {
        0.0
    };
    if v1.m_r_type != v2.m_r_type || !(1..=2).contains(&v1.m_r_type) {
        return Err("mRtype should be equal for both materials and have the values 1 or 2!".into());
    }
    Ok((
        FrictPhys {
            kn: viscel_series(kn1, kn2),
            ks: viscel_series(ks1, ks2),
            tan_phi: match &mm.frict_angle {
                Some(f) => f.call(m1.id, m2.id, nan, nan)?.tan(),
                None => cxx_min(m1.friction_angle, m2.friction_angle).tan(),
            },
            normal_force: Vec3::zeros(),
            shear_force: Vec3::zeros(),
        },
        ViscElPhys {
            cn: viscel_series(cn1, cn2),
            cs: viscel_series(cs1, cs2),
            fn_el: 0.0,
            fv: 0.0,
            m_r,
            m_r_type: v1.m_r_type,
        },
    ))
}

#[cfg(test)]
mod viscel_tests {
    use super::*;

    /// Springs (or dashpots) in series; a zero one is left out, as YADE's contactParameterCalculation.
    #[test]
    fn series_rule() {
        assert_eq!(viscel_series(2.0, 2.0), 1.0);
        assert_eq!(viscel_series(3.0, 6.0), 2.0);
        assert_eq!(viscel_series(2.0, 0.0), 2.0);
        assert_eq!(viscel_series(0.0, 0.0), 0.0);
    }

    /// Restitution of the damped oscillator: none lost without damping, less for more damping, and the
    /// Newton iteration finds a damping whose restitution is within its 1 % tolerance of the target.
    #[test]
    fn restitution_and_its_inverse() {
        let (m, k) = (0.01, 1e5);
        assert_eq!(viscel_en_from_cn(0.0, m, k), 1.0);
        let (e1, e2) = (viscel_en_from_cn(1.0, m, k), viscel_en_from_cn(5.0, m, k));
        assert!(1.0 > e1 && e1 > e2 && e2 > 0.0, "{} {}", e1, e2);
        // light damping: close to the linear dashpot's exp(-beta pi / omega)
        let (beta, omega) = (0.5 * 0.1 / m, (k / m - (0.5 * 0.1 / m).powi(2)).sqrt());
        let e = viscel_en_from_cn(0.1, m, k);
        assert!(
            (e - (-beta * std::f64::consts::PI / omega).exp()).abs() < 1e-3,
            "{}",
            e
        );
        for en in [0.3, 0.5, 0.9] {
            let cn = viscel_cn_from_en(en, m, k, (0, 1));
            assert!(cn > 0.0);
            assert!((viscel_en_from_cn(cn, m, k) - en).abs() / en <= 1e-2);
        }
    }
}

/// `Ip2_FrictMat_FrictMat_MindlinPhys`'s attributes (pkg/dem/HertzMindlin.hpp); the MatchMakers are
/// called with the two materials' ids.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MindlinIp2 {
    pub gamma: f64,
    pub eta: f64,
    pub krot: f64,
    pub ktwist: f64,
    pub en: Option<MatchMaker>,
    pub es: Option<MatchMaker>,
    pub betan: Option<MatchMaker>,
    pub betas: Option<MatchMaker>,
    pub frict_angle: Option<MatchMaker>,
}

/// What `MindlinPhys` (pkg/dem/HertzMindlin.hpp) adds to `FrictPhys` (kn, ks, tanφ and the forces are
/// there; kn and ks are recomputed by the law at every step), with `RotStiffFrictPhys`'s kr and ktw.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MindlinPhys {
    pub kno: f64,
    pub kso: f64,
    pub max_bend_pl: f64,
    pub normal_viscous: Vec3,
    pub shear_viscous: Vec3,
    pub shear_elastic: Vec3,
    pub us_elastic: Vec3,
    pub us_total: Vec3,
    pub moment_bend: Vec3,
    pub moment_twist: Vec3,
    pub radius: f64,
    pub adhesion_force: f64,
    pub is_adhesive: bool,
    pub is_sliding: bool,
    pub betan: f64,
    pub betas: f64,
    pub kr: f64,
    pub ktw: f64,
}

impl Default for MindlinPhys {
    fn default() -> Self {
        MindlinPhys {
            kno: 0.0,
            kso: 0.0,
            max_bend_pl: 0.0,
            normal_viscous: Vec3::zeros(),
            shear_viscous: Vec3::zeros(),
            shear_elastic: Vec3::zeros(),
            us_elastic: Vec3::zeros(),
            us_total: Vec3::zeros(),
            moment_bend: Vec3::zeros(),
            moment_twist: Vec3::zeros(),
            radius: f64::NAN,
            adhesion_force: 0.0,
            is_adhesive: false,
            is_sliding: false,
            betan: 0.0,
            betas: 0.0,
            kr: 0.0,
            ktw: 0.0,
        }
    }
}

/// `Ip2_FrictMat_FrictMat_MindlinPhys::go` (pkg/dem/HertzMindlin.cpp), same operation order. Errors as
/// YADE's `invalid_argument` when both en and betan (or es and betas) are given.
pub fn ip2_mindlin(
    p: &MindlinIp2,
    m1: &FrictMat,
    m2: &FrictMat,
    g: &ScGeom,
) -> Result<(FrictPhys, MindlinPhys), String> {
    let (ea, eb, va, vb) = (m1.young, m2.young, m1.poisson, m2.poisson);
    let (da, db) = g.ref_radii();
    let ga = ea / (2.0 * (1.0 + va));
    let gb = eb / (2.0 * (1.0 + vb));
    let g_eff = 1.0 / ((2.0 - va) / ga + (2.0 - vb) / gb);
    let e_eff = ea * eb / ((1. - va * va) * eb + (1. - vb * vb) * ea);
    let r = da * db / (da + db);
    let r_mean = (da + db) / 2.;
    let kno = 4. / 3. * e_eff * r.sqrt();
    let kso = 8.0 * r.sqrt() * g_eff;
    let nan = f64::NAN;
    let call = |m: &MatchMaker| m.call(m1.id, m2.id, nan, nan);
    // YADE: (*frictAngle)(id1, id2, fa1, fa2), with the materials' angles for the fallback
    let friction_angle = match &p.frict_angle {
        Some(f) => f.call(m1.id, m2.id, m1.friction_angle, m2.friction_angle)?,
        None => crate::math::cxx_min(m1.friction_angle, m2.friction_angle),
    };
    let adhesion = 4. * std::f64::consts::PI * r * p.gamma;
    let mut mp = MindlinPhys {
        kno,
        kso,
        adhesion_force: adhesion,
        kr: p.krot,
        ktw: p.ktwist,
        max_bend_pl: p.eta * r_mean,
        ..Default::default()
    };
    if p.en.is_some() && p.betan.is_some() {
        return Err(
            "Ip2_FrictMat_FrictMat_MindlinPhys: only one of en, betan can be specified.".into(),
        );
    }
    if p.es.is_some() && p.betas.is_some() {
        return Err(
            "Ip2_FrictMat_FrictMat_MindlinPhys: only one of es, betas can be specified.".into(),
        );
    }
    if p.en.is_some() || p.es.is_some() {
        // Thornton et al. (2013), eqs. (B6), (B7)
        let h = [
            -6.918798, -16.41105, 146.8049, -796.4559, 2928.711, -7206.864, 11494.29, -11342.18,
            6276.757, -1489.915,
        ];
        let en = call(p.en.as_ref().or(p.es.as_ref()).unwrap())?;
        let es = call(p.es.as_ref().or(p.en.as_ref()).unwrap())?;
        let alpha = |e: f64| {
            let mut acc = h[9];
            for k in (1..9).rev() {
                acc = h[k] + e * acc;
            }
            e * (h[0] + e * acc)
        };
        let beta = |e: f64, a: f64| {
            if e == 1.0 {
                0.0
            } else {
                let ope = 1.0 + e;
                (1.0 / (1.0 - (ope * ope) * a.exp()) - 1.0).sqrt()
            }
        };
        mp.betan = beta(en, alpha(en));
        mp.betas = beta(es, alpha(es));
    } else {
        mp.betan = match &p.betan {
            Some(m) => call(m)?,
            None => 0.0,
        };
        mp.betas = match &p.betas {
            Some(m) => call(m)?,
            None => mp.betan,
        };
    }
    let fp = FrictPhys {
        kn: 0.0,
        ks: 0.0,
        tan_phi: friction_angle.tan(),
        normal_force: Vec3::zeros(),
        shear_force: Vec3::zeros(),
    };
    Ok((fp, mp))
}

/// YADE's `MatchMaker` (pkg/common/MatchMaker.cpp): a value per pair of material ids (either order),
/// else a fallback computed from two values (`algo`).
#[derive(Clone, Debug, PartialEq)]
pub struct MatchMaker {
    /// (id1, id2, value) as given.
    pub matches: Vec<(i32, i32, f64)>,
    /// "val", "zero", "avg", "min", "max" or "harmAvg".
    pub algo: String,
    pub val: f64,
}

impl MatchMaker {
    /// `MatchMaker::operator()(id1, id2, val1, val2)`; the functors call it with the material ids only
    /// (NaN values), which an algo needing values refuses.
    pub fn call(&self, id1: i32, id2: i32, v1: f64, v2: f64) -> Result<f64, String> {
        let key = (id1.min(id2), id1.max(id2));
        // YADE's std::map keeps the first item of a repeated pair
        if let Some(m) = self
            .matches
            .iter()
            .find(|m| (m.0.min(m.1), m.0.max(m.1)) == key)
        {
            return Ok(m.2);
        }
        let needs = !matches!(self.algo.as_str(), "val" | "zero");
        if needs && (v1.is_nan() || v2.is_nan()) {
            return Err(format!(
                "MatchMaker: no match for ({},{}), and values required for algo computation '{}' not specified.",
                id1, id2, self.algo
            ));
        }
        Ok(match self.algo.as_str() {
            "val" => self.val,
            "zero" => 0.,
            "avg" => (v1 + v2) / 2.,
            "min" => crate::math::cxx_min(v1, v2),
            "max" => crate::math::cxx_max(v1, v2),
            _ => 2. * v1 * v2 / (v1 + v2),
        })
    }
}

/// The MatchMakers `Ip2_ViscElMat_ViscElMat_ViscElPhys` may be given (None: the materials' values).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ViscElIp2 {
    pub tc: Option<MatchMaker>,
    pub en: Option<MatchMaker>,
    pub et: Option<MatchMaker>,
    pub frict_angle: Option<MatchMaker>,
}

/// What `LudingPhys` (pkg/dem/LudingPM.hpp) adds to `FrictPhys` (ks, tanφ and the forces are there; kn
/// stays 0): the hysteretic spring's slopes and its overlap history.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LudingPhys {
    pub k1: f64,
    pub k2: f64,
    pub kp: f64,
    pub kc: f64,
    pub phi_f: f64,
    pub g0: f64,
    pub delt_min: f64,
    pub delt_max: f64,
    pub delt_p_max: f64,
    pub delt_null: f64,
    pub delt_p_null: f64,
    pub delt_prev: f64,
}

/// `Ip2_LudingMat_LudingMat_LudingPhys::reduced`: twice the two values in series (a zero left out).
fn luding_reduced(a1: f64, a2: f64) -> f64 {
    let inv = |x: f64| if x != 0.0 { 1.0 / x } else { 0.0 };
    let a = inv(a1) + inv(a2);
    let a = if a != 0.0 { 1.0 / a } else { 0.0 };
    2.0 * a
}

/// `Ip2_LudingMat_LudingMat_LudingPhys::go` (pkg/dem/LudingPM.cpp); `r1`, `r2` the bodies' sphere radii
/// (None for another shape).
pub fn ip2_luding(
    m1: &FrictMat,
    m2: &FrictMat,
    r1: Option<f64>,
    r2: Option<f64>,
) -> Result<(FrictPhys, LudingPhys), String> {
    let (l1, l2) = (
        m1.luding.as_deref().ok_or("LudingMat expected")?,
        m2.luding.as_deref().ok_or("LudingMat expected")?,
    );
    let mut lp = LudingPhys {
        k1: luding_reduced(l1.k1, l2.k1),
        k2: 0.0,
        kp: luding_reduced(l1.kp, l2.kp),
        kc: luding_reduced(l1.kc, l2.kc),
        phi_f: luding_reduced(l1.phi_f, l2.phi_f),
        g0: luding_reduced(l1.g0, l2.g0),
        delt_min: 0.0,
        delt_max: 0.0,
        delt_p_max: 0.0,
        delt_null: 0.0,
        delt_p_null: 0.0,
        delt_prev: 0.0,
    };
    let ks = luding_reduced(l1.ks, l2.ks);
    let (a1, a2) = match (r1, r2) {
        (Some(a), Some(b)) => (a, b),
        (Some(a), None) => (a, 0.0),
        (None, Some(b)) => (0.0, b),
        (None, None) => {
            return Err("Ip2_LudingMat_LudingMat_LudingPhys: neither body is a Sphere".into())
        }
    };
    if lp.k1 >= lp.kp {
        return Err("k1 have to be less as kp!".into());
    }
    lp.delt_p_max = lp.kp / (lp.kp - lp.k1) * lp.phi_f * 2.0 * a1 * a2 / (a1 + a2);
    lp.delt_p_null = lp.phi_f * 2.0 * a1 * a2 / (a1 + a2);
    Ok((
        FrictPhys {
            kn: 0.0,
            ks,
            tan_phi: cxx_min(m1.friction_angle, m2.friction_angle).tan(),
            normal_force: Vec3::zeros(),
            shear_force: Vec3::zeros(),
        },
        lp,
    ))
}

/// `BubblePhys` (pkg/dem/BubbleMat.hpp, an IPhys: its normal force is kept in the FrictPhys part, whose
/// kn, ks and shear force stay 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BubblePhys {
    pub fn_: f64,
    pub r_avg: f64,
    pub dmax: f64,
    pub newton_iter: i32,
    pub newton_tol: f64,
    pub coeff_a: f64,
    pub coeff_b: f64,
}

impl Default for BubblePhys {
    fn default() -> Self {
        BubblePhys {
            fn_: f64::NAN,
            r_avg: f64::NAN,
            dmax: f64::NAN,
            newton_iter: 50,
            newton_tol: 1e-6,
            coeff_a: f64::NAN,
            coeff_b: f64::NAN,
        }
    }
}

impl BubblePhys {
    /// `BubblePhys::computeCoeffs` (pkg/dem/BubbleMat.cpp): the threshold Dmax of Chan's law and the
    /// artificial exponential beyond it, and the starting force.
    pub fn compute_coeffs(&mut self, pct_max_force: f64, c1: f64) {
        let fmax = pct_max_force * c1 * self.r_avg;
        let log_pct = (pct_max_force / 4.0).ln();
        self.dmax = pct_max_force * self.r_avg * log_pct;
        let dfdd = c1 / (log_pct + 1.0);
        self.coeff_b = dfdd / fmax;
        self.coeff_a = fmax / (self.coeff_b * self.dmax).exp();
        self.fn_ = 0.1 * fmax;
    }

    /// `BubblePhys::computeForce`: Newton-Raphson on Chan's equation (25) for a separation at least
    /// Dmax, the exponential extension below it.
    pub fn compute_force(&self, separation: f64, c1: f64) -> Result<f64, String> {
        if separation >= self.dmax {
            let c2 = 1. / (4.0 * c1 * self.r_avg);
            let mut ret = self.fn_;
            let mut i = 0;
            loop {
                let ret_old = ret;
                let g = (ret * c2).ln();
                let f = separation * c1 - ret * g;
                let df = g + 1.0;
                ret += f / df;
                let residual = if ret <= 0.0 {
                    ret = 0.9 * ret.abs();
                    self.newton_tol * 2.0
                } else {
                    (ret - ret_old).abs() / ret_old
                };
                let over = i > self.newton_iter;
                i += 1;
                if over {
                    return Err("BubblePhys::computeForce: no convergence".into());
                }
                // `while (residual > newtonTol)`: a NaN residual ends the loop too
                #[allow(clippy::neg_cmp_op_on_partial_ord)]
                if !(residual > self.newton_tol) {
                    return Ok(ret);
                }
            }
        } else {
            Ok(self.coeff_a * (self.coeff_b * separation).exp())
        }
    }
}

/// What `CpmPhys` (pkg/dem/ConcretePM.hpp) adds to the normal/shear forces and stiffnesses kept in
/// `FrictPhys` (its `tan_phi` unused): the material constants averaged by the Ip2, the lengths set by
/// the law on the first step, and the damage/plasticity state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CpmPhys {
    pub e: f64,
    pub g: f64,
    pub tan_friction_angle: f64,
    pub undamaged_cohesion: f64,
    pub cross_section: f64,
    pub ref_length: f64,
    pub ref_pd: f64,
    pub eps_crack_onset: f64,
    pub rel_ductility: f64,
    pub eps_fracture: f64,
    pub equiv_strain_shear_contrib: f64,
    pub dmg_tau: f64,
    pub dmg_rate_exp: f64,
    pub pl_tau: f64,
    pub pl_rate_exp: f64,
    pub iso_prestress: f64,
    pub never_damage: bool,
    pub dam_law: i32,
    pub is_cohesive: bool,
    pub omega: f64,
    pub fn_: f64,
    pub sigma_n: f64,
    pub eps_n: f64,
    pub rel_residual_strength: f64,
    pub kappa_d: f64,
    pub eps_n_pl: f64,
    pub sigma_t: Vec3,
    pub fs: Vec3,
    pub eps_t_pl: Vec3,
    pub eps_t: Vec3,
}

impl Default for CpmPhys {
    /// The C++ defaults (NaN for the constants; sigmaN, sigmaT and relResidualStrength are left
    /// uninitialised by YADE and always written by the law before they are read: NaN here).
    fn default() -> Self {
        let nan = f64::NAN;
        CpmPhys {
            e: nan,
            g: nan,
            tan_friction_angle: nan,
            undamaged_cohesion: nan,
            cross_section: nan,
            ref_length: nan,
            ref_pd: nan,
            eps_crack_onset: nan,
            rel_ductility: nan,
            eps_fracture: nan,
            equiv_strain_shear_contrib: nan,
            dmg_tau: -1.0,
            dmg_rate_exp: 0.0,
            pl_tau: -1.0,
            pl_rate_exp: 0.0,
            iso_prestress: 0.0,
            never_damage: false,
            dam_law: 1,
            is_cohesive: false,
            omega: 0.0,
            fn_: 0.0,
            sigma_n: nan,
            eps_n: 0.0,
            rel_residual_strength: nan,
            kappa_d: 0.0,
            eps_n_pl: 0.0,
            sigma_t: Vec3::new(nan, nan, nan),
            fs: Vec3::zeros(),
            eps_t_pl: Vec3::zeros(),
            eps_t: Vec3::zeros(),
        }
    }
}

impl CpmPhys {
    /// `CpmPhys::funcG`: the damage ω of the largest strain κ (0 below the onset or never damaged).
    pub fn func_g(
        kappa_d: f64,
        eps_crack_onset: f64,
        eps_fracture: f64,
        never_damage: bool,
        dam_law: i32,
    ) -> Result<f64, String> {
        if kappa_d < eps_crack_onset || never_damage {
            return Ok(0.0);
        }
        match dam_law {
            0 => Ok((1.0 - eps_crack_onset / kappa_d) / (1.0 - eps_crack_onset / eps_fracture)),
            1 => Ok(1.0
                - (eps_crack_onset / kappa_d)
                    * (-(kappa_d - eps_crack_onset) / eps_fracture).exp()),
            _ => Err(format!("CpmPhys.damLaw {} is not 0 or 1", dam_law)),
        }
    }
}

/// `Ip2_CpmMat_CpmMat_CpmPhys::go` (pkg/dem/ConcretePM.cpp) for a new contact: a shared material is
/// copied, two materials are averaged (E, poisson·E, tan of the mean angle, ...; `damLaw` of the
/// first); contacts made before iteration `cohesive_threshold_iter` (or always, when negative) are
/// cohesive. kn and ks stay 0 until the law's first step sets them.
pub fn ip2_cpm(
    m1: &FrictMat,
    m2: &FrictMat,
    iter: i64,
    cohesive_threshold_iter: i64,
) -> Result<(FrictPhys, CpmPhys), String> {
    let (c1, c2) = (
        m1.cpm.as_deref().ok_or("CpmMat expected")?,
        m2.cpm.as_deref().ok_or("CpmMat expected")?,
    );
    let mut p = CpmPhys {
        dam_law: c1.dam_law,
        is_cohesive: cohesive_threshold_iter < 0 || iter < cohesive_threshold_iter,
        ..Default::default()
    };
    if m1.id >= 0 && m1.id == m2.id {
        p.e = m1.young;
        p.g = m1.young * m1.poisson;
        p.tan_friction_angle = m1.friction_angle.tan();
        p.undamaged_cohesion = c1.sigma_t;
        p.eps_crack_onset = c1.eps_crack_onset;
        p.rel_ductility = c1.rel_ductility;
        p.equiv_strain_shear_contrib = c1.equiv_strain_shear_contrib;
        p.never_damage = c1.never_damage;
        p.dmg_tau = c1.dmg_tau;
        p.dmg_rate_exp = c1.dmg_rate_exp;
        p.pl_tau = c1.pl_tau;
        p.pl_rate_exp = c1.pl_rate_exp;
        p.iso_prestress = c1.iso_prestress;
    } else {
        let avg = |a: f64, b: f64| 0.5 * (a + b);
        p.e = avg(m1.young, m2.young);
        p.g = avg(m1.poisson, m2.poisson) * p.e;
        p.tan_friction_angle = avg(m1.friction_angle, m2.friction_angle).tan();
        p.undamaged_cohesion = avg(c1.sigma_t, c2.sigma_t);
        p.eps_crack_onset = avg(c1.eps_crack_onset, c2.eps_crack_onset);
        p.rel_ductility = avg(c1.rel_ductility, c2.rel_ductility);
        p.equiv_strain_shear_contrib =
            avg(c1.equiv_strain_shear_contrib, c2.equiv_strain_shear_contrib);
        p.never_damage = c1.never_damage || c2.never_damage;
        p.dmg_tau = avg(c1.dmg_tau, c2.dmg_tau);
        p.dmg_rate_exp = avg(c1.dmg_rate_exp, c2.dmg_rate_exp);
        p.pl_tau = avg(c1.pl_tau, c2.pl_tau);
        p.pl_rate_exp = avg(c1.pl_rate_exp, c2.pl_rate_exp);
        p.iso_prestress = avg(c1.iso_prestress, c2.iso_prestress);
    }
    Ok((FrictPhys::default(), p))
}
