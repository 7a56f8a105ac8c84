//! YADE `HydroForceEngine` (pkg/common/HydroForceEngine.cpp), its `action`: on each listed sphere
//! inside the fluid mesh (cell p of height `deltaZ` above `zRef`), a drag force from the relative
//! velocity to the fluid (the cell's `vxFluid` plus the particle's fluctuation, Dallavalle's drag with
//! the Richardson-Zaki correction `(1-phi)^-expoRZ`), an optional lift from the fluid velocity
//! difference across the particle, the buoyancy, and an optional convective acceleration. The 1-D
//! fluid resolution and the averaging functions are not part of ryade (refused in the compat layer).

use crate::body::Bodies;
use crate::forces::Forces;
use crate::math::{norm, Vec3};

/// `pow` of the C library with the exponent hidden from the optimiser (YADE calls `pow(r, 3.0)`).
#[inline(always)]
fn libm_pow(x: f64, y: f64) -> f64 {
    x.powf(std::hint::black_box(y))
}

/// The attributes `action` reads (YADE's names in the compat layer and scene files).
#[derive(Clone, Debug, PartialEq)]
pub struct HydroForceEngine {
    pub ids: Vec<usize>,
    pub gravity: Vec3,
    pub dens_fluid: f64,
    pub visco_dyn: f64,
    pub z_ref: f64,
    pub delta_z: f64,
    pub n_cell: i64,
    pub expo_rz: f64,
    pub lift: bool,
    pub cl: f64,
    pub conv_acc_option: bool,
    pub steady_flow: bool,
    /// `vxFluid` (nCell + 1 values), `phiPart`, `convAcc` (nCell), and the per-body fluctuations.
    pub vx_fluid: Vec<f64>,
    pub phi_part: Vec<f64>,
    pub conv_acc: Vec<f64>,
    pub v_fluct_x: Vec<f64>,
    pub v_fluct_y: Vec<f64>,
    pub v_fluct_z: Vec<f64>,
}

impl Default for HydroForceEngine {
    fn default() -> Self {
        HydroForceEngine {
            ids: Vec::new(),
            gravity: Vec3::new(0.0, 0.0, -9.81),
            dens_fluid: 1000.0,
            visco_dyn: 1e-3,
            z_ref: 0.0,
            delta_z: f64::NAN,
            n_cell: 1,
            expo_rz: 3.1,
            lift: false,
            cl: 0.2,
            conv_acc_option: false,
            steady_flow: true,
            vx_fluid: Vec::new(),
            phi_part: Vec::new(),
            conv_acc: Vec::new(),
            v_fluct_x: Vec::new(),
            v_fluct_y: Vec::new(),
            v_fluct_z: Vec::new(),
        }
    }
}

impl HydroForceEngine {
    /// `HydroForceEngine::action` (without lubrication, which the compat layer refuses).
    pub fn action(&self, bodies: &Bodies, forces: &mut Forces) -> Result<(), String> {
        forces.resize(bodies.len());
        let mut gravity_buoyancy = self.gravity;
        if self.steady_flow {
            gravity_buoyancy[0] = 0.0;
        }
        let pi = std::f64::consts::PI;
        let short = |what: &str, len: usize, need: usize| {
            format!(
                "HydroForceEngine.{} has {} values, {} needed: call initialization() first (YADE reads past the end there)",
                what, len, need
            )
        };
        for &id in &self.ids {
            if id >= bodies.len() || bodies.is_clump(id) {
                continue;
            }
            let Some(r) = bodies.shape[id].sphere_radius() else {
                continue;
            };
            let pos = bodies.pos[id];
            let p = ((pos[2] - self.z_ref) / self.delta_z).floor() as i64;
            if !(p < self.n_cell && p >= 0) {
                continue;
            }
            let pu = p as usize;
            let at = |v: &Vec<f64>, i: usize, what: &str| -> Result<f64, String> {
                v.get(i).copied().ok_or_else(|| short(what, v.len(), i + 1))
            };
            let vel = bodies.vel[id];
            let mut lift_force = Vec3::zeros();
            let mut drag_force = Vec3::zeros();
            let mut conv_acc_force = Vec3::zeros();
            let v_rel = Vec3::new(
                at(&self.vx_fluid, pu + 1, "vxFluid")? + at(&self.v_fluct_x, id, "vFluctX")?,
                at(&self.v_fluct_y, id, "vFluctY")?,
                at(&self.v_fluct_z, id, "vFluctZ")?,
            ) - vel;
            if norm(&v_rel) != 0.0 {
                let phi = at(&self.phi_part, pu, "phiPart")?;
                let c = 0.5
                    * self.dens_fluid
                    * pi
                    * (r * r)
                    * (0.44 * norm(&v_rel) + 24.4 * self.visco_dyn / (self.dens_fluid * r * 2.0))
                    * libm_pow(1.0 - phi, -self.expo_rz);
                drag_force = v_rel * c;
            }
            let int_radius = (r / self.delta_z).floor() as i64;
            if p + int_radius < self.n_cell && p - int_radius > 0 && self.lift {
                let top = at(&self.vx_fluid, (p + 1 + int_radius) as usize, "vxFluid")?;
                let bottom = at(&self.vx_fluid, (p + 1 - int_radius) as usize, "vxFluid")?;
                let v_rel_top = top - vel[0];
                let v_rel_bottom = bottom - vel[0];
                lift_force[2] = 0.5
                    * self.dens_fluid
                    * pi
                    * (r * r)
                    * self.cl
                    * (v_rel_top * v_rel_top - v_rel_bottom * v_rel_bottom);
            }
            let buoyant_force =
                gravity_buoyancy * (-4.0 / 3.0 * pi * libm_pow(r, 3.0) * self.dens_fluid);
            if self.conv_acc_option {
                conv_acc_force[0] = -at(&self.conv_acc, pu, "convAcc")?;
            }
            forces.add_force(
                id,
                &(drag_force + lift_force + buoyant_force + conv_acc_force),
            );
        }
        Ok(())
    }

    /// Set one attribute from JSON (the scene files, the compat layer); Err(None) for a name it does
    /// not have.
    pub fn set(&mut self, k: &str, v: &serde_json::Value) -> Result<(), Option<String>> {
        let what = format!("HydroForceEngine.{}", k);
        let num = || crate::utils::attr_f64(&what, v);
        let boolean = || crate::utils::attr_bool(&what, v);
        let list = || -> Result<Vec<f64>, Option<String>> {
            serde_json::from_value(v.clone())
                .map_err(|_| Some(format!("HydroForceEngine.{} must be a list of numbers", k)))
        };
        match k {
            "ids" => {
                self.ids = serde_json::from_value(v.clone())
                    .map_err(|_| Some("HydroForceEngine.ids must be a list of ids".to_string()))?
            }
            "gravity" => {
                let a: [f64; 3] = serde_json::from_value(v.clone())
                    .map_err(|_| Some("HydroForceEngine.gravity must be a Vector3".to_string()))?;
                self.gravity = Vec3::new(a[0], a[1], a[2]);
            }
            "densFluid" => self.dens_fluid = num()?,
            "viscoDyn" => self.visco_dyn = num()?,
            "zRef" => self.z_ref = num()?,
            "deltaZ" => self.delta_z = v.as_f64().unwrap_or(f64::NAN),
            "nCell" => self.n_cell = num()? as i64,
            "expoRZ" => self.expo_rz = num()?,
            "lift" => self.lift = boolean()?,
            "Cl" => self.cl = num()?,
            "convAccOption" => self.conv_acc_option = boolean()?,
            "steadyFlow" => self.steady_flow = boolean()?,
            "vxFluid" => self.vx_fluid = list()?,
            "phiPart" => self.phi_part = list()?,
            "convAcc" => self.conv_acc = list()?,
            "vFluctX" => self.v_fluct_x = list()?,
            "vFluctY" => self.v_fluct_y = list()?,
            "vFluctZ" => self.v_fluct_z = list()?,
            _ => return Err(None),
        }
        Ok(())
    }

    /// The attributes as a scene-file object.
    pub fn to_json(&self) -> serde_json::Value {
        use serde_json::json;
        let g = self.gravity;
        json!({"class": "HydroForceEngine", "ids": self.ids, "gravity": [g[0], g[1], g[2]],
            "densFluid": self.dens_fluid, "viscoDyn": self.visco_dyn, "zRef": self.z_ref,
            "deltaZ": if self.delta_z.is_nan() { serde_json::Value::Null } else { json!(self.delta_z) },
            "nCell": self.n_cell, "expoRZ": self.expo_rz, "lift": self.lift, "Cl": self.cl,
            "convAccOption": self.conv_acc_option, "steadyFlow": self.steady_flow,
            "vxFluid": self.vx_fluid, "phiPart": self.phi_part, "convAcc": self.conv_acc,
            "vFluctX": self.v_fluct_x, "vFluctY": self.v_fluct_y, "vFluctZ": self.v_fluct_z})
    }

    /// From a scene-file object (missing attributes: YADE's defaults).
    pub fn from_json(e: &serde_json::Value) -> Result<Self, String> {
        let mut h = HydroForceEngine::default();
        if let Some(o) = e.as_object() {
            for (k, v) in o {
                if matches!(k.as_str(), "class" | "label" | "dead") {
                    continue;
                }
                h.set(k, v).map_err(|e| {
                    e.unwrap_or_else(|| {
                        format!("HydroForceEngine has no attribute '{}' in ryade", k)
                    })
                })?;
            }
        }
        Ok(h)
    }
}
