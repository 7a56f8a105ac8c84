//! Contact physics: `Ip2_FrictMat_FrictMat_FrictPhys` (pkg/dem/FrictPhys.cpp) and
//! `Ip2_CohFrictMat_CohFrictMat_CohFrictPhys` (pkg/dem/CohesiveFrictionalContactLaw.cpp).

use crate::geom::ScGeom;
use crate::material::FrictMat;
use crate::math::Vec3;

/// Physics classes for law dispatch (IPhys <- NormPhys <- NormShearPhys <- FrictPhys <-
/// RotStiffFrictPhys <- CohFrictPhys).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PhysClass {
    IPhys,
    NormPhys,
    NormShearPhys,
    FrictPhys,
    RotStiffFrictPhys,
    CohFrictPhys,
}

impl crate::dispatch::Hierarchy for PhysClass {
    fn parent(self) -> Option<Self> {
        use PhysClass::*;
        match self {
            IPhys => None,
            NormPhys => Some(IPhys),
            NormShearPhys => Some(NormPhys),
            FrictPhys => Some(NormShearPhys),
            RotStiffFrictPhys => Some(FrictPhys),
            CohFrictPhys => Some(RotStiffFrictPhys),
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
