//! Materials. `FrictMat` mirrors YADE `pkg/common/ElastMat.hpp` (young, poisson, frictionAngle) on top
//! of `core/Material.hpp` (density). A `CohFrictMat` (pkg/dem/CohesiveFrictionalContactLaw.hpp) is a
//! FrictMat whose `coh` holds the cohesive and rotational parameters, a `ViscElMat`
//! (pkg/dem/ViscoelasticPM.hpp) one whose `viscel` holds the viscoelastic ones; plain FrictMat scenes
//! carry null pointers there and nothing else.

use serde::{Deserialize, Serialize};

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FrictMat {
    /// YADE's `Material.id` (index in `O.materials`, or -1 for a material not stored there).
    pub id: i32,
    pub label: String,
    pub young: f64,
    /// The ks/kn ratio in Ip2_FrictMat_FrictMat_FrictPhys (not a true Poisson ratio).
    pub poisson: f64,
    /// Radians.
    pub friction_angle: f64,
    pub density: f64,
    /// `Some` for a `CohFrictMat`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub coh: Option<Box<CohFrictParams>>,
    /// `Some` for a `ViscElMat`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub viscel: Option<Box<ViscElParams>>,
    /// `Some` for a `LudingMat` (pkg/dem/LudingPM.hpp: a `Material`, not an ElastMat; `young` and
    /// `poisson` unused, `friction_angle` its frictionAngle).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub luding: Option<Box<LudingParams>>,
    /// `Some(surfaceTension)` for a `BubbleMat` (pkg/dem/BubbleMat.hpp: a `Material`; only the density
    /// and this are used).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bubble: Option<f64>,
    /// `Some` for a `CpmMat` (pkg/dem/ConcretePM.hpp: a FrictMat with the concrete model's parameters).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cpm: Option<Box<CpmParams>>,
}

/// The fields `CpmMat` (pkg/dem/ConcretePM.hpp) adds to `FrictMat`, with YADE's defaults.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CpmParams {
    pub sigma_t: f64,
    pub never_damage: bool,
    pub eps_crack_onset: f64,
    pub rel_ductility: f64,
    pub equiv_strain_shear_contrib: f64,
    pub dam_law: i32,
    pub dmg_tau: f64,
    pub dmg_rate_exp: f64,
    pub pl_tau: f64,
    pub pl_rate_exp: f64,
    pub iso_prestress: f64,
}

impl Default for CpmParams {
    fn default() -> Self {
        CpmParams {
            sigma_t: f64::NAN,
            never_damage: false,
            eps_crack_onset: f64::NAN,
            rel_ductility: f64::NAN,
            equiv_strain_shear_contrib: 0.0,
            dam_law: 1,
            dmg_tau: -1.0,
            dmg_rate_exp: 0.0,
            pl_tau: -1.0,
            pl_rate_exp: 0.0,
            iso_prestress: 0.0,
        }
    }
}

/// The fields of a `LudingMat` besides density and frictionAngle (NaN: not given, YADE's default).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LudingParams {
    pub k1: f64,
    pub kp: f64,
    pub kc: f64,
    pub ks: f64,
    pub phi_f: f64,
    pub g0: f64,
}

impl Default for LudingParams {
    fn default() -> Self {
        LudingParams {
            k1: f64::NAN,
            kp: f64::NAN,
            kc: f64::NAN,
            ks: f64::NAN,
            phi_f: f64::NAN,
            g0: f64::NAN,
        }
    }
}

/// The fields `ViscElMat` adds to `FrictMat` (NaN: not given), with YADE's class defaults in `Default`.
/// Equality is bitwise, so that two copies of a material with NaN fields are equal.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ViscElParams {
    pub tc: f64,
    pub en: f64,
    pub et: f64,
    pub kn: f64,
    pub cn: f64,
    pub ks: f64,
    pub cs: f64,
    pub m_r: f64,
    pub m_r_type: u32,
}

impl PartialEq for ViscElParams {
    fn eq(&self, o: &Self) -> bool {
        let a = [
            self.tc, self.en, self.et, self.kn, self.cn, self.ks, self.cs, self.m_r,
        ];
        let b = [o.tc, o.en, o.et, o.kn, o.cn, o.ks, o.cs, o.m_r];
        a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()) && self.m_r_type == o.m_r_type
    }
}

impl Default for ViscElParams {
    fn default() -> Self {
        ViscElParams {
            tc: f64::NAN,
            en: f64::NAN,
            et: f64::NAN,
            kn: f64::NAN,
            cn: f64::NAN,
            ks: f64::NAN,
            cs: f64::NAN,
            m_r: 0.0,
            m_r_type: 1,
        }
    }
}

/// The fields `CohFrictMat` adds to `FrictMat`, with YADE's class defaults in `Default`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CohFrictParams {
    pub is_cohesive: bool,
    pub alpha_kr: f64,
    pub alpha_ktw: f64,
    pub eta_roll: f64,
    pub eta_twist: f64,
    pub normal_cohesion: f64,
    pub shear_cohesion: f64,
    pub fragile: bool,
    pub moment_rotation_law: bool,
}

impl Default for CohFrictParams {
    fn default() -> Self {
        CohFrictParams {
            is_cohesive: true,
            alpha_kr: 2.0,
            alpha_ktw: 2.0,
            eta_roll: -1.0,
            eta_twist: -1.0,
            normal_cohesion: -1.0,
            shear_cohesion: -1.0,
            fragile: true,
            moment_rotation_law: false,
        }
    }
}

impl Default for FrictMat {
    /// The C++ class defaults of `FrictMat()`: young 1e9, poisson 0.25, friction 0.5 rad, density 1000.
    fn default() -> Self {
        FrictMat {
            id: -1,
            label: String::new(),
            young: 1e9,
            poisson: 0.25,
            friction_angle: 0.5,
            density: 1000.0,
            coh: None,
            viscel: None,
            luding: None,
            bubble: None,
            cpm: None,
        }
    }
}

impl FrictMat {
    /// `utils.defaultMaterial()` (py/utils.py): young 1e7, poisson 0.3, friction 0.5, density 1000.
    pub fn yade_default_material() -> Self {
        FrictMat {
            young: 1e7,
            poisson: 0.3,
            ..FrictMat::default()
        }
    }

    /// `CohFrictMat()` with its C++ class defaults (those of FrictMat plus `CohFrictParams::default`).
    pub fn coh_frict_default() -> Self {
        FrictMat {
            coh: Some(Box::default()),
            ..FrictMat::default()
        }
    }

    pub fn class(&self) -> MatClass {
        if self.coh.is_some() {
            MatClass::CohFrictMat
        } else if self.viscel.is_some() {
            MatClass::ViscElMat
        } else if self.luding.is_some() {
            MatClass::LudingMat
        } else if self.bubble.is_some() {
            MatClass::BubbleMat
        } else if self.cpm.is_some() {
            MatClass::CpmMat
        } else {
            MatClass::FrictMat
        }
    }

    pub fn class_name(&self) -> &'static str {
        if self.coh.is_some() {
            "CohFrictMat"
        } else if self.viscel.is_some() {
            "ViscElMat"
        } else if self.luding.is_some() {
            "LudingMat"
        } else if self.bubble.is_some() {
            "BubbleMat"
        } else if self.cpm.is_some() {
            "CpmMat"
        } else {
            "FrictMat"
        }
    }
}

/// Material classes for physics dispatch (Material <- ElastMat <- FrictMat <- CohFrictMat, ViscElMat).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MatClass {
    Material,
    ElastMat,
    FrictMat,
    CohFrictMat,
    ViscElMat,
    LudingMat,
    BubbleMat,
    CpmMat,
}

impl crate::dispatch::Hierarchy for MatClass {
    fn parent(self) -> Option<Self> {
        match self {
            MatClass::Material => None,
            MatClass::LudingMat | MatClass::BubbleMat => Some(MatClass::Material),
            MatClass::ElastMat => Some(MatClass::Material),
            MatClass::FrictMat => Some(MatClass::ElastMat),
            MatClass::CohFrictMat | MatClass::ViscElMat | MatClass::CpmMat => {
                Some(MatClass::FrictMat)
            }
        }
    }
}
