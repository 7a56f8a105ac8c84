//! Materials. `FrictMat` mirrors YADE `pkg/common/ElastMat.hpp` (young, poisson, frictionAngle) on top
//! of `core/Material.hpp` (density).

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
}
