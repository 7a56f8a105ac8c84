//! YADE `TriaxialCompressionEngine` (pkg/dem/TriaxialCompressionEngine.cpp): a
//! `TriaxialStressController` driven by a state machine: isotropic compaction to
//! `sigmaIsoCompaction`, optional unloading to `sigmaLateralConfinement`, then confined loading by
//! moving the top and bottom walls at a strain rate until `epsilonMax` (or a compaction at fixed
//! porosity). It lives in the controller (`TriaxialStressController::compression`).

use crate::math::{cxx_max, cxx_min, Vec3};
use crate::scene::Scene;
use crate::triax::{TriaxialStressController, BACK, BOTTOM, FRONT, LEFT, RIGHT, TOP};

pub const STATE_UNINITIALIZED: i32 = 0;
pub const STATE_ISO_COMPACTION: i32 = 1;
pub const STATE_ISO_UNLOADING: i32 = 2;
pub const STATE_TRIAX_LOADING: i32 = 3;
pub const STATE_FIXED_POROSITY_COMPACTION: i32 = 4;
pub const STATE_LIMBO: i32 = 5;

/// The attributes and state `TriaxialCompressionEngine` adds (names as in YADE, defaults of its
/// constructor: `currentState` uninitialised, `isAxisymetric` true, `previousSigmaIso` = sigma_iso).
#[derive(Clone, Debug, PartialEq)]
pub struct Compression {
    pub strain_rate: f64,
    pub current_strain_rate: f64,
    pub unbalanced_force: f64,
    pub stability_criterion: f64,
    pub translation_axis: Vec3,
    pub auto_compression_activation: bool,
    pub auto_unload: bool,
    pub auto_stop_simulation: bool,
    pub test_equilibrium_interval: i64,
    pub current_state: i32,
    pub previous_state: i32,
    pub sigma_iso_compaction: f64,
    pub previous_sigma_iso: f64,
    pub sigma_lateral_confinement: f64,
    pub no_files: bool,
    pub friction_angle_degree: f64,
    pub epsilon_max: f64,
    pub fixed_poro_compaction: bool,
    pub fixed_porosity: f64,
    pub max_stress: f64,
    pub sigma_iso: f64,
    pub is_axisymetric: bool,
    pub first_run: bool,
    pub save_simulation: bool,
    /// `Key`: appended to the snapshot file names.
    pub key: String,
    /// `Phase1End` (private in YADE): "Compacted", "Unloaded", ... in the snapshot names.
    pub phase1_end: String,
    /// Files YADE would write during this step, in its order (`.spheres`: Shop::saveSpheresToFile;
    /// `.xml`: Omega::saveSimulation); the compat layer writes them right after the engine
    /// (`scene.done_hook_pending`) and clears the list.
    pub pending_files: Vec<String>,
}

impl Default for Compression {
    fn default() -> Self {
        Compression {
            strain_rate: 0.0,
            current_strain_rate: 0.0,
            unbalanced_force: 1.0,
            stability_criterion: 0.001,
            translation_axis: Vec3::new(0.0, 1.0, 0.0),
            auto_compression_activation: true,
            auto_unload: true,
            auto_stop_simulation: false,
            test_equilibrium_interval: 20,
            current_state: STATE_UNINITIALIZED,
            previous_state: STATE_UNINITIALIZED,
            sigma_iso_compaction: 1.0,
            previous_sigma_iso: 0.0,
            sigma_lateral_confinement: 1.0,
            no_files: false,
            friction_angle_degree: -1.0,
            epsilon_max: 0.5,
            fixed_poro_compaction: false,
            fixed_porosity: 0.0,
            max_stress: 0.0,
            sigma_iso: 0.0,
            is_axisymetric: true,
            first_run: true,
            save_simulation: false,
            key: String::new(),
            phase1_end: "Compacted".into(),
            pending_files: Vec::new(),
        }
    }
}

/// `Shop::setContactFriction` (preprocessing/dem/Shop_02.cpp): the friction angle of every dynamic
/// body's material (the material object itself, shared with whatever else uses it; clumps skipped
/// when `skip_clumps`, as Shop does and ThreeDTriaxialEngine does not), then tan(min(φ1, φ2)) on every
/// real contact.
pub fn set_contact_friction(scene: &mut Scene, angle_rad: f64, skip_clumps: bool) {
    let b = &scene.bodies;
    for id in 0..b.len() {
        if skip_clumps && b.is_clump(id) {
            continue;
        }
        if b.is_dynamic(id) {
            scene.materials[b.material[id]].friction_angle = angle_rad;
        }
    }
    for it in scene.interactions.list.iter_mut().filter(|it| it.is_real()) {
        let fa = scene.materials[scene.bodies.material[it.id1 as usize]].friction_angle;
        let fb = scene.materials[scene.bodies.material[it.id2 as usize]].friction_angle;
        if let Some(ph) = it.phys.as_mut() {
            ph.tan_phi = cxx_min(fa, fb).tan();
        }
    }
}

impl Compression {
    /// `doStateTransition`.
    fn transition(
        &mut self,
        t: &mut TriaxialStressController,
        scene: &mut Scene,
        next: i32,
    ) -> Result<(), String> {
        let cur = self.current_state;
        if next == STATE_ISO_COMPACTION {
            self.sigma_iso = self.sigma_iso_compaction;
            self.previous_sigma_iso = self.sigma_iso;
        } else if next == STATE_TRIAX_LOADING {
            self.sigma_iso = self.sigma_lateral_confinement;
            self.previous_sigma_iso = self.sigma_iso;
            t.internal_compaction = false;
            if self.friction_angle_degree > 0.0 {
                set_contact_friction(
                    scene,
                    self.friction_angle_degree * std::f64::consts::PI / 180.0,
                    true,
                );
            }
            t.height0 = t.height;
            t.depth0 = t.depth;
            t.width0 = t.width;
            t.wall_activated[BOTTOM] = false;
            t.wall_activated[TOP] = false;
            if cur == STATE_ISO_UNLOADING && !self.no_files {
                self.pending_files.push("/tmp/unloaded.spheres".into());
            }
            if !self.first_run && !self.no_files {
                self.save_simulation = true;
            }
            self.phase1_end = "Unloaded".into();
        } else if cur == STATE_ISO_COMPACTION && next == STATE_ISO_UNLOADING {
            self.sigma_iso = self.sigma_lateral_confinement;
            self.sigma_iso_compaction = self.sigma_lateral_confinement;
            self.previous_sigma_iso = self.sigma_iso;
            t.internal_compaction = false;
            if self.friction_angle_degree > 0.0 {
                set_contact_friction(
                    scene,
                    self.friction_angle_degree * std::f64::consts::PI / 180.0,
                    true,
                );
            }
            if !self.first_run && !self.no_files {
                self.save_simulation = true;
            }
            self.phase1_end = "Compacted".into();
        } else if (cur == STATE_ISO_COMPACTION || cur == STATE_ISO_UNLOADING) && next == STATE_LIMBO
        {
            return Err(
                "TriaxialCompressionEngine's STATE_LIMBO is not supported by ryade yet".into(),
            );
        } else if next == STATE_FIXED_POROSITY_COMPACTION {
            t.internal_compaction = false;
            t.wall_activated = [false; 6];
        } else {
            // YADE logs the undefined transition and ignores it
            return Ok(());
        }
        self.current_state = next;
        self.previous_state = self.current_state;
        Ok(())
    }

    /// `updateParameters`.
    fn update_parameters(
        &mut self,
        t: &mut TriaxialStressController,
        scene: &mut Scene,
    ) -> Result<(), String> {
        self.unbalanced_force = crate::utils::unbalanced_force(scene, false);
        let s = self.current_state;
        // YADE's two nested conditions (the porosity branch of its `else` only returns)
        let checked = (s != STATE_TRIAX_LOADING && s == STATE_ISO_COMPACTION)
            || s == STATE_ISO_UNLOADING
            || s == STATE_FIXED_POROSITY_COMPACTION
            || self.auto_compression_activation;
        if checked
            && self.unbalanced_force <= self.stability_criterion
            && ((t.mean_stress - self.sigma_iso) / self.sigma_iso).abs() < 0.005
            && !self.fixed_poro_compaction
        {
            if s == STATE_ISO_COMPACTION
                && self.auto_unload
                && self.sigma_lateral_confinement != self.sigma_iso_compaction
            {
                self.transition(t, scene, STATE_ISO_UNLOADING)?;
                t.compute_stress_strain(scene)?;
            } else if (s == STATE_ISO_COMPACTION || s == STATE_ISO_UNLOADING || s == STATE_LIMBO)
                && self.auto_compression_activation
            {
                self.transition(t, scene, STATE_TRIAX_LOADING)?;
                t.compute_stress_strain(scene)?;
            }
        }
        Ok(())
    }

    /// `TriaxialCompressionEngine::action` around the controller's own action.
    pub fn action(
        &mut self,
        t: &mut TriaxialStressController,
        scene: &mut Scene,
    ) -> Result<(), String> {
        if self.first_run {
            if (self.sigma_iso_compaction != self.previous_sigma_iso
                || self.current_state == STATE_UNINITIALIZED
                || self.current_state == STATE_LIMBO)
                && self.current_state != STATE_TRIAX_LOADING
                && !self.fixed_poro_compaction
            {
                self.transition(t, scene, STATE_ISO_COMPACTION)?;
            }
            if self.previous_state != STATE_TRIAX_LOADING
                && self.current_state == STATE_TRIAX_LOADING
            {
                self.transition(t, scene, STATE_TRIAX_LOADING)?;
            }
            if self.fixed_porosity < 1.0
                && self.current_state == STATE_UNINITIALIZED
                && self.fixed_poro_compaction
            {
                self.transition(t, scene, STATE_FIXED_POROSITY_COMPACTION)?;
            }
            self.previous_state = self.current_state;
            self.previous_sigma_iso = self.sigma_iso;
            self.first_run = false;
        }
        if scene.iter % self.test_equilibrium_interval == 0 {
            self.update_parameters(t, scene)?;
            self.max_stress = cxx_max(self.max_stress, -t.stress[TOP][1]);
        }
        if self.save_simulation {
            if !self.no_files {
                let base = format!(
                    "./{}_{}_{}_{}",
                    self.key, self.phase1_end, scene.iter, self.current_state
                );
                self.pending_files.push(format!("{}.xml", base));
                self.pending_files.push(format!("{}.spheres", base));
            }
            self.save_simulation = false;
        }
        if self.is_axisymetric || t.internal_compaction {
            if t.stress_mask & 1 != 0 {
                t.goal1 = self.sigma_iso;
            }
            if t.stress_mask & 2 != 0 {
                t.goal2 = self.sigma_iso;
            }
            // `stressMask & 3` in YADE (not 4): kept
            if t.stress_mask & 3 != 0 {
                t.goal3 = self.sigma_iso;
            }
        }
        t.controller_action(scene)?;
        if self.current_state == STATE_LIMBO && self.auto_stop_simulation {
            return Err("TriaxialCompressionEngine.autoStopSimulation in STATE_LIMBO is not supported by ryade yet".into());
        }
        let dt = scene.dt;
        let id = |w: usize| t.wall_ids[w] as usize;
        if self.current_state == STATE_TRIAX_LOADING && self.epsilon_max.abs() > t.strain[1].abs() {
            if self.current_strain_rate != self.strain_rate {
                self.current_strain_rate += (self.strain_rate - self.current_strain_rate) * 0.0003;
            }
            let d = self.translation_axis * (0.5 * self.current_strain_rate * t.height) * dt;
            scene.bodies.pos[id(BOTTOM)] += d;
            scene.bodies.pos[id(TOP)] -= d;
        }
        if self.current_state == STATE_FIXED_POROSITY_COMPACTION {
            let sr = self.strain_rate;
            let ax = self.translation_axis;
            let (x, z) = (Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0));
            let dy = ax * (0.5 * sr * t.height) * dt;
            let dz = z * (0.5 * sr * t.depth) * dt;
            let dx = x * (0.5 * sr * t.width) * dt;
            scene.bodies.pos[id(BOTTOM)] += dy;
            scene.bodies.pos[id(TOP)] -= dy;
            scene.bodies.pos[id(BACK)] += dz;
            scene.bodies.pos[id(FRONT)] -= dz;
            scene.bodies.pos[id(LEFT)] += dx;
            scene.bodies.pos[id(RIGHT)] -= dx;
        }
        Ok(())
    }

    /// Set one attribute from JSON; Err(None) for a name it does not have.
    pub fn set(&mut self, k: &str, v: &serde_json::Value) -> Result<(), Option<String>> {
        let num = || crate::utils::attr_f64(k, v);
        let boolean = || crate::utils::attr_bool(k, v);
        match k {
            "strainRate" => self.strain_rate = num()?,
            "currentStrainRate" => self.current_strain_rate = num()?,
            "UnbalancedForce" => self.unbalanced_force = num()?,
            "StabilityCriterion" => self.stability_criterion = num()?,
            "translationAxis" => {
                let a: [f64; 3] = serde_json::from_value(v.clone())
                    .map_err(|_| Some("translationAxis must be a Vector3".to_string()))?;
                self.translation_axis = Vec3::new(a[0], a[1], a[2]);
            }
            "autoCompressionActivation" => self.auto_compression_activation = boolean()?,
            "autoUnload" => self.auto_unload = boolean()?,
            "autoStopSimulation" => self.auto_stop_simulation = boolean()?,
            "testEquilibriumInterval" => self.test_equilibrium_interval = num()? as i64,
            "currentState" => self.current_state = num()? as i32,
            "previousState" => self.previous_state = num()? as i32,
            "sigmaIsoCompaction" => self.sigma_iso_compaction = num()?,
            "previousSigmaIso" => self.previous_sigma_iso = num()?,
            "sigmaLateralConfinement" => self.sigma_lateral_confinement = num()?,
            "noFiles" => self.no_files = boolean()?,
            "frictionAngleDegree" => self.friction_angle_degree = num()?,
            "epsilonMax" => self.epsilon_max = num()?,
            "fixedPoroCompaction" => self.fixed_poro_compaction = boolean()?,
            "fixedPorosity" => self.fixed_porosity = num()?,
            "maxStress" => self.max_stress = num()?,
            "sigma_iso" => self.sigma_iso = num()?,
            "isAxisymetric" => self.is_axisymetric = boolean()?,
            "_firstRun" => self.first_run = boolean()?,
            "Key" => {
                self.key = v
                    .as_str()
                    .ok_or_else(|| Some("Key must be a string".to_string()))?
                    .to_string()
            }
            "_phase1End" => {
                self.phase1_end = v
                    .as_str()
                    .ok_or_else(|| Some("_phase1End must be a string".to_string()))?
                    .to_string()
            }
            "_pendingFiles" => {
                self.pending_files = serde_json::from_value(v.clone())
                    .map_err(|_| Some("_pendingFiles must be a list of names".to_string()))?
            }
            _ => return Err(None),
        }
        Ok(())
    }

    /// One attribute as JSON (None: no such name).
    pub fn get(&self, k: &str) -> Option<serde_json::Value> {
        use serde_json::json;
        Some(match k {
            "strainRate" => json!(self.strain_rate),
            "currentStrainRate" => json!(self.current_strain_rate),
            "UnbalancedForce" => json!(self.unbalanced_force),
            "StabilityCriterion" => json!(self.stability_criterion),
            "translationAxis" => {
                let a = self.translation_axis;
                json!([a[0], a[1], a[2]])
            }
            "autoCompressionActivation" => json!(self.auto_compression_activation),
            "autoUnload" => json!(self.auto_unload),
            "autoStopSimulation" => json!(self.auto_stop_simulation),
            "testEquilibriumInterval" => json!(self.test_equilibrium_interval),
            "currentState" => json!(self.current_state),
            "previousState" => json!(self.previous_state),
            "sigmaIsoCompaction" => json!(self.sigma_iso_compaction),
            "previousSigmaIso" => json!(self.previous_sigma_iso),
            "sigmaLateralConfinement" => json!(self.sigma_lateral_confinement),
            "noFiles" => json!(self.no_files),
            "frictionAngleDegree" => json!(self.friction_angle_degree),
            "epsilonMax" => json!(self.epsilon_max),
            "fixedPoroCompaction" => json!(self.fixed_poro_compaction),
            "fixedPorosity" => json!(self.fixed_porosity),
            "maxStress" => json!(self.max_stress),
            "sigma_iso" => json!(self.sigma_iso),
            "isAxisymetric" => json!(self.is_axisymetric),
            "_firstRun" => json!(self.first_run),
            "Key" => json!(self.key),
            "_phase1End" => json!(self.phase1_end),
            "_pendingFiles" => json!(self.pending_files),
            _ => return None,
        })
    }

    /// The attribute names `to_json` writes.
    pub const ATTRS: &'static [&'static str] = &[
        "strainRate",
        "currentStrainRate",
        "UnbalancedForce",
        "StabilityCriterion",
        "translationAxis",
        "autoCompressionActivation",
        "autoUnload",
        "autoStopSimulation",
        "testEquilibriumInterval",
        "currentState",
        "previousState",
        "sigmaIsoCompaction",
        "previousSigmaIso",
        "sigmaLateralConfinement",
        "noFiles",
        "frictionAngleDegree",
        "epsilonMax",
        "fixedPoroCompaction",
        "fixedPorosity",
        "maxStress",
        "sigma_iso",
        "isAxisymetric",
        "_firstRun",
        "Key",
        "_phase1End",
    ];
}

/// What YADE's `ThreeDTriaxialEngine` (pkg/dem/ThreeDTriaxialEngine.cpp) adds to the controller: per
/// axis, stress control (the controller's servo) or strain control (both walls moved at a strain rate
/// converging to `strainRate_i`). Its own `strainDamping` (0.9997) shadows the controller's, as in YADE.
#[derive(Clone, Debug, PartialEq)]
pub struct ThreeD {
    pub strain_rate: [f64; 3],
    pub current_strain_rate: [f64; 3],
    pub unbalanced_force: f64,
    pub friction_angle_degree: f64,
    pub update_friction_angle: bool,
    pub stress_control: [bool; 3],
    pub strain_damping: f64,
    pub key: String,
    pub first_run: bool,
}

impl Default for ThreeD {
    fn default() -> Self {
        ThreeD {
            strain_rate: [0.0; 3],
            current_strain_rate: [0.0; 3],
            unbalanced_force: 1.0,
            friction_angle_degree: -1.0,
            update_friction_angle: false,
            stress_control: [true; 3],
            strain_damping: 0.9997,
            key: String::new(),
            first_run: true,
        }
    }
}

impl ThreeD {
    /// `ThreeDTriaxialEngine::action` around the controller's own action.
    pub fn action(
        &mut self,
        t: &mut TriaxialStressController,
        scene: &mut Scene,
    ) -> Result<(), String> {
        // (axis walls: negative side, positive side)
        const WALLS: [(usize, usize); 3] = [(LEFT, RIGHT), (BOTTOM, TOP), (BACK, FRONT)];
        if self.first_run {
            if self.update_friction_angle {
                // ThreeDTriaxialEngine::setContactProperties: clumps not skipped
                set_contact_friction(
                    scene,
                    self.friction_angle_degree * std::f64::consts::PI / 180.0,
                    false,
                );
            }
            t.height0 = t.height;
            t.depth0 = t.depth;
            t.width0 = t.width;
            for (i, (lo, hi)) in WALLS.iter().enumerate() {
                t.wall_activated[*lo] = self.stress_control[i];
                t.wall_activated[*hi] = self.stress_control[i];
            }
            self.first_run = false;
        }
        let dt = scene.dt;
        for (i, (lo, hi)) in WALLS.iter().enumerate() {
            if self.current_strain_rate[i] != self.strain_rate[i] {
                self.current_strain_rate[i] += (self.strain_rate[i] - self.current_strain_rate[i])
                    * (1.0 - self.strain_damping);
            }
            let size = [t.width, t.height, t.depth][i];
            if !self.stress_control[i] {
                let mut axis = Vec3::zeros();
                axis[i] = 1.0;
                let d = axis * (0.5 * self.current_strain_rate[i] * size) * dt;
                scene.bodies.pos[t.wall_ids[*lo] as usize] += d;
                scene.bodies.pos[t.wall_ids[*hi] as usize] -= d;
            } else {
                // max_vel_i (the controller's action overwrites it from max_vel right after: kept)
                let v = 0.5 * self.current_strain_rate[i] * size;
                match i {
                    0 => t.max_vel1 = v,
                    1 => t.max_vel2 = v,
                    _ => t.max_vel3 = v,
                }
            }
        }
        t.controller_action(scene)
    }

    /// Set one attribute from JSON; Err(None) for a name it does not have.
    pub fn set(&mut self, k: &str, v: &serde_json::Value) -> Result<(), Option<String>> {
        let num = || crate::utils::attr_f64(k, v);
        let boolean = || crate::utils::attr_bool(k, v);
        let axis = |p: &str| -> Option<usize> {
            k.strip_prefix(p)
                .and_then(|n| n.parse::<usize>().ok())
                .filter(|n| (1..=3).contains(n))
                .map(|n| n - 1)
        };
        if let Some(i) = axis("strainRate") {
            self.strain_rate[i] = num()?;
        } else if let Some(i) = axis("currentStrainRate") {
            self.current_strain_rate[i] = num()?;
        } else if let Some(i) = axis("stressControl_") {
            self.stress_control[i] = boolean()?;
        } else {
            match k {
                "UnbalancedForce" => self.unbalanced_force = num()?,
                "frictionAngleDegree" => self.friction_angle_degree = num()?,
                "updateFrictionAngle" => self.update_friction_angle = boolean()?,
                "strainDamping" => self.strain_damping = num()?,
                "Key" => {
                    self.key = v
                        .as_str()
                        .ok_or_else(|| Some("Key must be a string".to_string()))?
                        .to_string()
                }
                "_firstRun" => self.first_run = boolean()?,
                _ => return Err(None),
            }
        }
        Ok(())
    }

    /// One attribute as JSON (None: no such name).
    pub fn get(&self, k: &str) -> Option<serde_json::Value> {
        use serde_json::json;
        let axis = |p: &str| -> Option<usize> {
            k.strip_prefix(p)
                .and_then(|n| n.parse::<usize>().ok())
                .filter(|n| (1..=3).contains(n))
                .map(|n| n - 1)
        };
        if let Some(i) = axis("strainRate") {
            return Some(json!(self.strain_rate[i]));
        }
        if let Some(i) = axis("currentStrainRate") {
            return Some(json!(self.current_strain_rate[i]));
        }
        if let Some(i) = axis("stressControl_") {
            return Some(json!(self.stress_control[i]));
        }
        Some(match k {
            "UnbalancedForce" => json!(self.unbalanced_force),
            "frictionAngleDegree" => json!(self.friction_angle_degree),
            "updateFrictionAngle" => json!(self.update_friction_angle),
            "strainDamping" => json!(self.strain_damping),
            "Key" => json!(self.key),
            "_firstRun" => json!(self.first_run),
            _ => return None,
        })
    }

    /// The attribute names `to_json` writes.
    pub const ATTRS: &'static [&'static str] = &[
        "strainRate1",
        "strainRate2",
        "strainRate3",
        "currentStrainRate1",
        "currentStrainRate2",
        "currentStrainRate3",
        "stressControl_1",
        "stressControl_2",
        "stressControl_3",
        "UnbalancedForce",
        "frictionAngleDegree",
        "updateFrictionAngle",
        "strainDamping",
        "Key",
        "_firstRun",
    ];
}
