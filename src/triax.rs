//! YADE `TriaxialStressController` (pkg/dem/TriaxialStressController.cpp): six walls (boxes) around a
//! packing, each driven to a target stress (servo on the wall's contact stiffness) or strain rate, or,
//! with `internalCompaction`, all held while the dynamic spheres grow (`Shop::growParticles`,
//! preprocessing/dem/Shop_02.cpp) until the mean wall stress reaches the goal. Walls are numbered as
//! YADE does: left, right, bottom, top, back, front.

use crate::math::{dot, Vec3};
use crate::scene::Scene;
use crate::shape::Shape;

pub const LEFT: usize = 0;
pub const RIGHT: usize = 1;
pub const BOTTOM: usize = 2;
pub const TOP: usize = 3;
pub const BACK: usize = 4;
pub const FRONT: usize = 5;

/// `pow` of the C library with the exponent hidden from the optimiser (YADE calls `std::pow(x, 3)`).
#[inline(always)]
fn libm_pow(x: f64, y: f64) -> f64 {
    x.powf(std::hint::black_box(y))
}

/// YADE's `math::sign`: -1, 0 or 1.
fn sign(x: f64) -> f64 {
    ((0.0 < x) as i32 - (x < 0.0) as i32) as f64
}

/// `std::min` (the first argument on a tie).
fn cxx_min(a: f64, b: f64) -> f64 {
    if b < a {
        b
    } else {
        a
    }
}

/// The attributes and state of a `TriaxialStressController` (names as in YADE, defaults of 2023.02a).
#[derive(Clone, Debug)]
pub struct TriaxialStressController {
    pub stiffness_update_interval: u32,
    pub radius_control_interval: u32,
    pub compute_stress_strain_interval: u32,
    pub stress_damping: f64,
    pub strain_damping: f64,
    pub thickness: f64,
    /// `wall_left_id`, `wall_right_id`, `wall_bottom_id`, `wall_top_id`, `wall_back_id`, `wall_front_id`.
    pub wall_ids: [i64; 6],
    /// `wall_*_activated`, same order.
    pub wall_activated: [bool; 6],
    pub height: f64,
    pub width: f64,
    pub depth: f64,
    pub height0: f64,
    pub width0: f64,
    pub depth0: f64,
    pub goal1: f64,
    pub goal2: f64,
    pub goal3: f64,
    pub stress_mask: u32,
    pub max_multiplier: f64,
    pub final_max_multiplier: f64,
    pub max_vel: f64,
    pub previous_stress: f64,
    pub previous_multiplier: f64,
    pub internal_compaction: bool,
    pub mean_stress: f64,
    pub volumetric_strain: f64,
    pub external_work: f64,
    pub update_porosity: bool,
    // state (not attributes in YADE, read-only from Python)
    pub first: bool,
    /// The wall ids synced from the attributes at the first run (`wall_id[]`).
    pub wall_id: [i64; 6],
    pub previous_translation: [Vec3; 6],
    pub stiffness: [f64; 6],
    pub strain: Vec3,
    pub normal: [Vec3; 6],
    pub stress: [Vec3; 6],
    pub force: [Vec3; 6],
    pub particles_volume: f64,
    pub box_volume: f64,
    pub porosity: f64,
    pub max_vel1: f64,
    pub max_vel2: f64,
    pub max_vel3: f64,
    /// `Some` for a `TriaxialCompressionEngine` (its state machine around this controller).
    pub compression: Option<Box<crate::triax_compression::Compression>>,
    /// `Some` for a `ThreeDTriaxialEngine`.
    pub three_d: Option<Box<crate::triax_compression::ThreeD>>,
}

impl Default for TriaxialStressController {
    fn default() -> Self {
        let mut normal = [Vec3::zeros(); 6];
        normal[BOTTOM][1] = 1.0;
        normal[TOP][1] = -1.0;
        normal[LEFT][0] = 1.0;
        normal[RIGHT][0] = -1.0;
        normal[FRONT][2] = -1.0;
        normal[BACK][2] = 1.0;
        TriaxialStressController {
            stiffness_update_interval: 10,
            radius_control_interval: 10,
            compute_stress_strain_interval: 10,
            stress_damping: 0.25,
            strain_damping: 0.99,
            thickness: -1.0,
            wall_ids: [0, 1, 2, 3, 4, 5],
            wall_activated: [true; 6],
            height: 0.0,
            width: 0.0,
            depth: 0.0,
            height0: 0.0,
            width0: 0.0,
            depth0: 0.0,
            goal1: 0.0,
            goal2: 0.0,
            goal3: 0.0,
            stress_mask: 7,
            max_multiplier: 1.001,
            final_max_multiplier: 1.00001,
            max_vel: 1.0,
            previous_stress: 0.0,
            previous_multiplier: 1.0,
            internal_compaction: true,
            mean_stress: 0.0,
            volumetric_strain: 0.0,
            external_work: 0.0,
            update_porosity: false,
            first: true,
            wall_id: [0; 6],
            previous_translation: [Vec3::zeros(); 6],
            stiffness: [0.0; 6],
            strain: Vec3::zeros(),
            normal,
            stress: [Vec3::zeros(); 6],
            force: [Vec3::zeros(); 6],
            particles_volume: 0.0,
            box_volume: 0.0,
            porosity: 1.0,
            max_vel1: 0.0,
            max_vel2: 0.0,
            max_vel3: 0.0,
            compression: None,
            three_d: None,
        }
    }
}

/// A body's force as YADE's synced container gives it: the summed contributions, then the permanent
/// force (`ForceContainer::sync`).
fn synced_force(scene: &Scene, id: i64) -> Vec3 {
    let id = id as usize;
    let f = &scene.forces;
    if id >= f.len() {
        return Vec3::zeros();
    }
    if f.perm_used {
        f.ft[id].f + f.perm_force[id]
    } else {
        f.ft[id].f
    }
}

impl TriaxialStressController {
    fn wall(&self, scene: &Scene, w: usize) -> Result<usize, String> {
        let id = self.wall_ids[w];
        if id < 0 || id as usize >= scene.bodies.len() {
            return Err(format!(
                "TriaxialStressController: wall id {} (wall {}) is not a body",
                id,
                ["left", "right", "bottom", "top", "back", "front"][w]
            ));
        }
        Ok(id as usize)
    }

    /// The engine's action: `TriaxialCompressionEngine::action` when it is one, else the
    /// controller's.
    pub fn action(&mut self, scene: &mut Scene) -> Result<(), String> {
        if let Some(mut c) = self.compression.take() {
            let r = c.action(self, scene);
            self.compression = Some(c);
            return r;
        }
        if let Some(mut c) = self.three_d.take() {
            let r = c.action(self, scene);
            self.three_d = Some(c);
            return r;
        }
        self.controller_action(scene)
    }

    /// YADE's class name of the engine.
    pub fn class_name(&self) -> &'static str {
        if self.compression.is_some() {
            "TriaxialCompressionEngine"
        } else if self.three_d.is_some() {
            "ThreeDTriaxialEngine"
        } else {
            "TriaxialStressController"
        }
    }

    /// `TriaxialStressController::action`.
    pub fn controller_action(&mut self, scene: &mut Scene) -> Result<(), String> {
        if self.first {
            self.wall_id = self.wall_ids;
        }
        let ids: Vec<usize> = (0..6)
            .map(|w| self.wall(scene, w))
            .collect::<Result<_, _>>()?;
        if self.thickness < 0.0 {
            match &scene.bodies.shape[ids[BOTTOM]] {
                Shape::Box { extents } => self.thickness = 2.0 * extents[1],
                s => {
                    return Err(format!(
                        "TriaxialStressController: the bottom wall #{} is a {}, not a Box",
                        ids[BOTTOM],
                        s.class_name()
                    ))
                }
            }
        }
        let pos = |w: usize| scene.bodies.pos[ids[w]];
        self.height = pos(TOP)[1] - pos(BOTTOM)[1] - self.thickness;
        self.width = pos(RIGHT)[0] - pos(LEFT)[0] - self.thickness;
        self.depth = pos(FRONT)[2] - pos(BACK)[2] - self.thickness;
        self.box_volume = self.height * self.width * self.depth;
        if self.first || self.update_porosity {
            self.particles_volume = 0.0;
            let b = &scene.bodies;
            for id in 0..b.len() {
                if b.is_clump(id) {
                    return Err(
                        "TriaxialStressController with clumps is not supported by ryade yet".into(),
                    );
                } else if b.is_dynamic(id) && !b.is_clump_member(id) {
                    let r = match &b.shape[id] {
                        Shape::Sphere { radius } => *radius,
                        s => {
                            return Err(format!(
                                "TriaxialStressController: dynamic body #{} is a {}, not a Sphere",
                                id,
                                s.class_name()
                            ))
                        }
                    };
                    self.particles_volume += 1.3333333 * std::f64::consts::PI * libm_pow(r, 3.0);
                }
            }
            self.first = false;
            self.update_porosity = false;
        }
        let hwd = self.height + self.width + self.depth;
        self.max_vel1 = 3.0 * self.width / hwd * self.max_vel;
        self.max_vel2 = 3.0 * self.height / hwd * self.max_vel;
        self.max_vel3 = 3.0 * self.depth / hwd * self.max_vel;
        self.porosity = (self.box_volume - self.particles_volume) / self.box_volume;

        let iter = scene.iter;
        if iter % self.stiffness_update_interval as i64 == 0 || iter < 100 {
            self.update_stiffness(scene);
        }
        let radius_iter = iter % self.radius_control_interval as i64 == 0;
        if iter % self.compute_stress_strain_interval as i64 == 0
            || (self.internal_compaction && radius_iter)
        {
            self.compute_stress_strain(scene)?;
        }

        if !self.internal_compaction {
            let (h, w, d) = (self.height, self.width, self.depth);
            // (wall, axis, goal, size along the axis, resultant force on the wall, max velocity, mask bit)
            let y_force = Vec3::new(0.0, self.goal2 * w * d, 0.0);
            let x_force = Vec3::new(self.goal1 * h * d, 0.0, 0.0);
            let z_force = Vec3::new(0.0, 0.0, self.goal3 * h * w);
            let plan = [
                (BOTTOM, 1, self.goal2, h, y_force, self.max_vel2, 2u32),
                (TOP, 1, self.goal2, h, -y_force, self.max_vel2, 2),
                (LEFT, 0, self.goal1, w, x_force, self.max_vel1, 1),
                (RIGHT, 0, self.goal1, w, -x_force, self.max_vel1, 1),
                (BACK, 2, self.goal3, d, z_force, self.max_vel3, 4),
                (FRONT, 2, self.goal3, d, -z_force, self.max_vel3, 4),
            ];
            for (wall, axis, goal, size, resultant, vmax, bit) in plan {
                let id = ids[wall];
                if self.wall_activated[wall] {
                    if self.stress_mask & bit != 0 {
                        self.control_external_stress(scene, wall, id, resultant, vmax);
                    } else {
                        let v = scene.bodies.vel[id][axis];
                        scene.bodies.vel[id][axis] +=
                            (-self.normal[wall][axis] * 0.5 * goal * size - v)
                                * (1.0 - self.strain_damping);
                        self.external_work +=
                            dot(&scene.bodies.vel[id], &synced_force(scene, id as i64)) * scene.dt;
                    }
                } else {
                    scene.bodies.vel[id] = Vec3::zeros();
                }
            }
        } else {
            for &id in &ids {
                scene.bodies.vel[id] = Vec3::zeros();
            }
            if radius_iter {
                let m = self.stress_mask;
                let on = |bit: u32| if m & bit != 0 { 1.0 } else { 0.0 };
                let mut sigma_iso = on(1) * self.goal1 + on(2) * self.goal2 + on(4) * self.goal3;
                sigma_iso /= on(1) + on(2) + on(4);
                if sigma_iso.abs() <= self.mean_stress.abs() {
                    self.max_multiplier = self.final_max_multiplier;
                }
                if self.mean_stress == 0.0 {
                    self.previous_multiplier = self.max_multiplier;
                } else if sigma_iso < 0.0 {
                    self.previous_multiplier = 1.
                        + (sigma_iso - self.mean_stress) / sigma_iso * (self.max_multiplier - 1.);
                } else {
                    self.previous_multiplier = 1.
                        + (self.mean_stress - sigma_iso) / sigma_iso * (self.max_multiplier - 1.);
                }
                self.previous_stress = self.mean_stress;
                self.control_internal_stress(scene, self.previous_multiplier)?;
            }
        }
        Ok(())
    }

    /// `updateStiffness`: the summed kn of each wall's contacts that carry a force.
    fn update_stiffness(&mut self, scene: &Scene) {
        self.stiffness = [0.0; 6];
        for it in &scene.interactions.list {
            if !it.is_real() {
                continue;
            }
            let Some(ph) = it.phys.as_ref() else { continue };
            let fn_ = crate::math::norm(&ph.normal_force);
            if fn_ != 0.0 {
                let (id1, id2) = (it.id1 as i64, it.id2 as i64);
                for index in 0..6 {
                    if self.wall_id[index] == id1 || self.wall_id[index] == id2 {
                        self.stiffness[index] += ph.kn;
                    }
                }
            }
        }
    }

    /// `controlExternalStress`: move the wall so that the force of the sample on it approaches
    /// `resultant`, by its stiffness, clamped to `max_v` dt, smoothed with `stressDamping`.
    fn control_external_stress(
        &mut self,
        scene: &mut Scene,
        wall: usize,
        id: usize,
        resultant: Vec3,
        max_v: f64,
    ) {
        let dt = scene.dt;
        let f = synced_force(scene, self.wall_id[wall]);
        let mut translation = dot(&self.normal[wall], &(f - resultant));
        if translation != 0.0 {
            if self.stiffness[wall] != 0.0 {
                translation /= self.stiffness[wall];
                translation = cxx_min(translation.abs(), max_v * dt) * sign(translation);
            } else {
                translation = max_v * sign(translation) * dt;
            }
        }
        self.previous_translation[wall] = self.normal[wall]
            * ((1.0 - self.stress_damping) * translation)
            + self.previous_translation[wall] * 0.8;
        self.external_work += dot(&self.previous_translation[wall], &f);
        scene.bodies.vel[id] = self.previous_translation[wall] / dt;
    }

    /// `computeStressStrain`: box sizes, logarithmic strains, the walls' forces and stresses, and the
    /// mean stress.
    pub fn compute_stress_strain(&mut self, scene: &Scene) -> Result<(), String> {
        let ids: Vec<usize> = (0..6)
            .map(|w| self.wall(scene, w))
            .collect::<Result<_, _>>()?;
        let pos = |w: usize| scene.bodies.pos[ids[w]];
        self.height = pos(TOP)[1] - pos(BOTTOM)[1] - self.thickness;
        self.width = pos(RIGHT)[0] - pos(LEFT)[0] - self.thickness;
        self.depth = pos(FRONT)[2] - pos(BACK)[2] - self.thickness;
        self.mean_stress = 0.0;
        if self.height0 == 0.0 {
            self.height0 = self.height;
        }
        if self.width0 == 0.0 {
            self.width0 = self.width;
        }
        if self.depth0 == 0.0 {
            self.depth0 = self.depth;
        }
        self.strain[0] = (self.width / self.width0).ln();
        self.strain[1] = (self.height / self.height0).ln();
        self.strain[2] = (self.depth / self.depth0).ln();
        self.volumetric_strain = self.strain[0] + self.strain[1] + self.strain[2];
        // YADE writes 1.f: a float one, exact in double
        let inv_x = 1.0 / (self.height * self.depth);
        let inv_y = 1.0 / (self.width * self.depth);
        let inv_z = 1.0 / (self.width * self.height);
        let f = |w: usize| synced_force(scene, self.wall_id[w]);
        self.force[BOTTOM] = f(BOTTOM);
        self.stress[BOTTOM] = self.force[BOTTOM] * inv_y;
        self.force[TOP] = f(TOP);
        self.stress[TOP] = -self.force[TOP] * inv_y;
        self.force[LEFT] = f(LEFT);
        self.stress[LEFT] = self.force[LEFT] * inv_x;
        self.force[RIGHT] = f(RIGHT);
        self.stress[RIGHT] = -self.force[RIGHT] * inv_x;
        self.force[FRONT] = f(FRONT);
        self.stress[FRONT] = -self.force[FRONT] * inv_z;
        self.force[BACK] = f(BACK);
        self.stress[BACK] = self.force[BACK] * inv_z;
        for i in 0..6 {
            let s = libm_pow(-1.0, i as f64);
            self.mean_stress += dot(&self.stress[i], &(self.normal[i] * s));
        }
        self.mean_stress /= 6.;
        Ok(())
    }

    /// `controlInternalStress` + `Shop::growParticles(multiplier, true, true)`.
    fn control_internal_stress(
        &mut self,
        scene: &mut Scene,
        multiplier: f64,
    ) -> Result<(), String> {
        self.particles_volume *= libm_pow(multiplier, 3.0);
        let m3 = libm_pow(multiplier, 3.0);
        let m5 = libm_pow(multiplier, 5.0);
        let b = &mut scene.bodies;
        for id in 0..b.len() {
            if !b.is_dynamic(id) {
                continue;
            }
            if b.is_clump(id) || b.is_clump_member(id) {
                return Err(
                    "TriaxialStressController growing clumps is not supported by ryade yet".into(),
                );
            }
            if let Shape::Sphere { radius } = &mut b.shape[id] {
                b.mass[id] *= m3;
                b.inertia[id] *= m5;
                *radius *= multiplier;
            }
        }
        let b = &scene.bodies;
        for it in scene.interactions.list.iter_mut() {
            if !it.is_real() {
                continue;
            }
            let (id1, id2) = (it.id1 as usize, it.id2 as usize);
            if let Some(g) = it.geom.as_mut() {
                if b.is_dynamic(id1) {
                    if let Shape::Sphere { radius } = &b.shape[id1] {
                        g.radius1 = *radius;
                    }
                }
                if b.is_dynamic(id2) {
                    if let Shape::Sphere { radius } = &b.shape[id2] {
                        g.radius2 = *radius;
                    }
                }
            }
            if let Some(ph) = it.phys.as_mut() {
                ph.kn *= multiplier;
                ph.ks *= multiplier;
            }
        }
        Ok(())
    }

    /// `getStrainRate`: the walls' relative velocities over the box sizes.
    pub fn strain_rate(&self, scene: &Scene) -> Vec3 {
        let v = |w: usize| {
            let id = self.wall_ids[w];
            if id >= 0 && (id as usize) < scene.bodies.len() {
                Some(scene.bodies.vel[id as usize])
            } else {
                None
            }
        };
        match (v(RIGHT), v(LEFT), v(TOP), v(BOTTOM), v(FRONT), v(BACK)) {
            (Some(r), Some(l), Some(t), Some(b), Some(f), Some(k)) => Vec3::new(
                (r[0] - l[0]) / self.width,
                (t[1] - b[1]) / self.height,
                (f[2] - k[2]) / self.depth,
            ),
            _ => Vec3::zeros(),
        }
    }
}

/// The attributes by YADE's names (scene files, the compat layer's `engine_set`/`engine_get`).
const F64_ATTRS: &[&str] = &[
    "stressDamping",
    "strainDamping",
    "thickness",
    "height",
    "width",
    "depth",
    "height0",
    "width0",
    "depth0",
    "goal1",
    "goal2",
    "goal3",
    "maxMultiplier",
    "finalMaxMultiplier",
    "max_vel",
    "previousStress",
    "previousMultiplier",
    "meanStress",
    "volumetricStrain",
    "externalWork",
];
const WALLS: [&str; 6] = ["left", "right", "bottom", "top", "back", "front"];

impl TriaxialStressController {
    fn f64_mut(&mut self, k: &str) -> Option<&mut f64> {
        Some(match k {
            "stressDamping" => &mut self.stress_damping,
            "strainDamping" => &mut self.strain_damping,
            "thickness" => &mut self.thickness,
            "height" => &mut self.height,
            "width" => &mut self.width,
            "depth" => &mut self.depth,
            "height0" => &mut self.height0,
            "width0" => &mut self.width0,
            "depth0" => &mut self.depth0,
            "goal1" => &mut self.goal1,
            "goal2" => &mut self.goal2,
            "goal3" => &mut self.goal3,
            "maxMultiplier" => &mut self.max_multiplier,
            "finalMaxMultiplier" => &mut self.final_max_multiplier,
            "max_vel" => &mut self.max_vel,
            "previousStress" => &mut self.previous_stress,
            "previousMultiplier" => &mut self.previous_multiplier,
            "meanStress" => &mut self.mean_stress,
            "volumetricStrain" => &mut self.volumetric_strain,
            "externalWork" => &mut self.external_work,
            _ => return None,
        })
    }

    /// Set one attribute from JSON; Err(None) for a name it does not have.
    pub fn set(&mut self, k: &str, v: &serde_json::Value) -> Result<(), Option<String>> {
        if let Some(c) = self.compression.as_mut() {
            match c.set(k, v) {
                Err(None) => {}
                r => return r,
            }
        }
        if let Some(c) = self.three_d.as_mut() {
            match c.set(k, v) {
                Err(None) => {}
                r => return r,
            }
        }
        let num = || crate::utils::attr_f64(k, v);
        let boolean = || crate::utils::attr_bool(k, v);
        if let Some(w) = k
            .strip_prefix("wall_")
            .and_then(|r| r.strip_suffix("_id"))
            .and_then(|n| WALLS.iter().position(|&x| x == n))
        {
            self.wall_ids[w] = num()? as i64;
            return Ok(());
        }
        if let Some(w) = k
            .strip_prefix("wall_")
            .and_then(|r| r.strip_suffix("_activated"))
            .and_then(|n| WALLS.iter().position(|&x| x == n))
        {
            self.wall_activated[w] = boolean()?;
            return Ok(());
        }
        match k {
            "stiffnessUpdateInterval" => self.stiffness_update_interval = num()? as u32,
            "radiusControlInterval" => self.radius_control_interval = num()? as u32,
            "computeStressStrainInterval" => self.compute_stress_strain_interval = num()? as u32,
            "stressMask" => self.stress_mask = num()? as u32,
            "internalCompaction" => self.internal_compaction = boolean()?,
            "updatePorosity" => self.update_porosity = boolean()?,
            _ => {
                let x = num()?;
                *self.f64_mut(k).ok_or(None)? = x;
            }
        }
        Ok(())
    }

    /// One attribute or read-only value as JSON (None: no such name).
    pub fn get(&self, k: &str) -> Option<serde_json::Value> {
        use serde_json::json;
        if let Some(v) = self.compression.as_ref().and_then(|c| c.get(k)) {
            return Some(v);
        }
        if let Some(v) = self.three_d.as_ref().and_then(|c| c.get(k)) {
            return Some(v);
        }
        let v3 = |v: &Vec3| json!([v[0], v[1], v[2]]);
        if let Some(w) = k
            .strip_prefix("wall_")
            .and_then(|r| r.strip_suffix("_id"))
            .and_then(|n| WALLS.iter().position(|&x| x == n))
        {
            return Some(json!(self.wall_ids[w]));
        }
        if let Some(w) = k
            .strip_prefix("wall_")
            .and_then(|r| r.strip_suffix("_activated"))
            .and_then(|n| WALLS.iter().position(|&x| x == n))
        {
            return Some(json!(self.wall_activated[w]));
        }
        if let Some(i) = k
            .strip_prefix("stress.")
            .and_then(|n| n.parse::<usize>().ok())
        {
            return self.stress.get(i).map(v3);
        }
        Some(match k {
            "stiffnessUpdateInterval" => json!(self.stiffness_update_interval),
            "radiusControlInterval" => json!(self.radius_control_interval),
            "computeStressStrainInterval" => json!(self.compute_stress_strain_interval),
            "stressMask" => json!(self.stress_mask),
            "internalCompaction" => json!(self.internal_compaction),
            "updatePorosity" => json!(self.update_porosity),
            "strain" => v3(&self.strain),
            "porosity" => json!(self.porosity),
            "boxVolume" => json!(self.box_volume),
            "particlesVolume" | "spheresVolume" => json!(self.particles_volume),
            "max_vel1" => json!(self.max_vel1),
            "max_vel2" => json!(self.max_vel2),
            "max_vel3" => json!(self.max_vel3),
            "stiffness" => json!(self.stiffness),
            _ => {
                let mut me = self.clone();
                return me.f64_mut(k).map(|x| json!(*x));
            }
        })
    }

    /// The scene-file object: every attribute (state included, so a saved run goes on as it was).
    pub fn to_json(&self) -> serde_json::Value {
        use serde_json::json;
        let mut o = json!({"class": self.class_name()});
        if let Some(c) = &self.compression {
            for k in crate::triax_compression::Compression::ATTRS {
                o[*k] = c.get(k).unwrap();
            }
        }
        if let Some(c) = &self.three_d {
            for k in crate::triax_compression::ThreeD::ATTRS {
                o[*k] = c.get(k).unwrap();
            }
        }
        for k in F64_ATTRS {
            o[*k] = self.get(k).unwrap();
        }
        for k in [
            "stiffnessUpdateInterval",
            "radiusControlInterval",
            "computeStressStrainInterval",
            "stressMask",
            "internalCompaction",
            "updatePorosity",
        ] {
            o[k] = self.get(k).unwrap();
        }
        for (w, n) in WALLS.iter().enumerate() {
            o[format!("wall_{}_id", n)] = json!(self.wall_ids[w]);
            o[format!("wall_{}_activated", n)] = json!(self.wall_activated[w]);
        }
        if !self.first {
            o["_state"] = json!({"wall_id": self.wall_id, "previousTranslation":
                self.previous_translation.iter().map(|v| [v[0], v[1], v[2]]).collect::<Vec<_>>(),
                "stiffness": self.stiffness, "strain": [self.strain[0], self.strain[1], self.strain[2]],
                "particlesVolume": self.particles_volume});
        }
        o
    }

    /// From a scene-file object (missing attributes: YADE's defaults).
    pub fn from_json(e: &serde_json::Value) -> Result<Self, String> {
        let mut t = TriaxialStressController::default();
        match e.get("class").and_then(|c| c.as_str()) {
            Some("TriaxialCompressionEngine") => t.compression = Some(Default::default()),
            Some("ThreeDTriaxialEngine") => t.three_d = Some(Default::default()),
            _ => {}
        }
        if let Some(o) = e.as_object() {
            for (k, v) in o {
                if k == "class" || k == "_state" || k == "label" || k == "dead" {
                    continue;
                }
                t.set(k, v).map_err(|e| {
                    e.unwrap_or_else(|| {
                        format!("TriaxialStressController has no attribute '{}'", k)
                    })
                })?;
            }
            if let Some(s) = o.get("_state") {
                let vec3 = |v: &serde_json::Value| -> Option<Vec3> {
                    let a = v.as_array()?;
                    Some(Vec3::new(
                        a.first()?.as_f64()?,
                        a.get(1)?.as_f64()?,
                        a.get(2)?.as_f64()?,
                    ))
                };
                t.first = false;
                if let Some(a) = s.get("wall_id").and_then(|v| v.as_array()) {
                    for (i, x) in a.iter().enumerate().take(6) {
                        t.wall_id[i] = x.as_i64().unwrap_or(0);
                    }
                }
                if let Some(a) = s.get("previousTranslation").and_then(|v| v.as_array()) {
                    for (i, x) in a.iter().enumerate().take(6) {
                        t.previous_translation[i] = vec3(x).unwrap_or_else(Vec3::zeros);
                    }
                }
                if let Some(a) = s.get("stiffness").and_then(|v| v.as_array()) {
                    for (i, x) in a.iter().enumerate().take(6) {
                        t.stiffness[i] = x.as_f64().unwrap_or(0.0);
                    }
                }
                if let Some(v) = s.get("strain").and_then(vec3) {
                    t.strain = v;
                }
                t.particles_volume = s
                    .get("particlesVolume")
                    .and_then(|v| v.as_f64())
                    .unwrap_or(0.0);
            }
        }
        Ok(t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sign_and_min_as_cxx() {
        assert_eq!(sign(-3.0), -1.0);
        assert_eq!(sign(0.0), 0.0);
        assert_eq!(sign(2.0), 1.0);
        assert_eq!(cxx_min(1.0, 1.0), 1.0);
        assert_eq!(cxx_min(2.0, 1.0), 1.0);
    }

    #[test]
    fn defaults_match_yade() {
        let t = TriaxialStressController::default();
        assert_eq!(t.normal[BOTTOM], Vec3::new(0.0, 1.0, 0.0));
        assert_eq!(t.normal[FRONT], Vec3::new(0.0, 0.0, -1.0));
        assert_eq!(t.wall_ids, [0, 1, 2, 3, 4, 5]);
        assert_eq!(t.stress_mask, 7);
        assert_eq!(t.porosity, 1.0);
    }
}
