//! `PeriTriaxController` (pkg/dem/PeriIsoCompressor.{hpp,cpp}, YADE 2023.02a): drives the periodic
//! cell's velocity gradient so that each diagonal component reaches a goal stress (bit `i` of
//! `stressMask` set) or a goal logarithmic strain (bit clear).
//!
//! The engine writes `Cell::velGrad` directly (not `nextVelGrad`), in the middle of the step; the
//! next step's `Cell::integrateAndUpdate` deforms the cell with it and NewtonIntegrator adds the
//! homothetic terms (`integrator`). Quirks of 2023.02a reproduced on purpose:
//! * the stiffness used by the stress servo is a mean *contact* stiffness divided by a cell face
//!   area (YADE's own "FIXME: this is wrong"), so the servo saturates at `maxStrainRate` with few
//!   contacts;
//! * between two `globUpdate` steps `stress` is a prediction (the last measured value plus
//!   `velGrad·dt/size·stiff/area` per step), and `strain` is advanced by `velGrad·dt` inside the
//!   loop before it is compared with the goal;
//! * `maxBodySpan` is measured once, from the swept bounds of the first call;
//! * the doneHook runs every step while the goal holds, until the hook changes something.
//!
//! `doneHook` is a Python string: under `compat run` the Python side runs it (`Scene::step_with`
//! hands it over); a scene file carries the effect each firing had in YADE (`HookEvent`), applied
//! when the hook fires at the same iteration.

use crate::math::{cxx_max, cxx_min, mat_mul, mat_vec_i, sign, Mat3, Vec3};
use crate::scene::Scene;
use crate::shape::Shape;
use std::collections::VecDeque;

/// What one firing of the doneHook did in YADE (recorded by yade_ref/lib/ryade_record.py): the
/// iteration it fired at, the hook string, and the controller attributes it set.
#[derive(Clone, Debug, PartialEq)]
pub struct HookEvent {
    pub iter: i64,
    pub hook: String,
    pub set: Vec<HookSet>,
}

/// One attribute assignment of a recorded doneHook.
#[derive(Clone, Debug, PartialEq)]
pub enum HookSet {
    Goal(Vec3),
    StressMask(i32),
    MaxStrainRate(Vec3),
    MaxUnbalanced(f64),
    AbsStressTol(f64),
    RelStressTol(f64),
    GrowDamping(f64),
    GlobUpdate(i32),
    DoneHook(String),
    DynCell(bool),
    Mass(f64),
    Dead(bool),
}

/// YADE `PeriTriaxController` with its 2023.02a attributes and defaults.
#[derive(Clone, Debug)]
pub struct PeriTriax {
    pub dyn_cell: bool,
    pub goal: Vec3,
    pub stress_mask: i32,
    pub max_strain_rate: Vec3,
    pub max_unbalanced: f64,
    pub abs_stress_tol: f64,
    pub rel_stress_tol: f64,
    pub grow_damping: f64,
    pub glob_update: i32,
    pub done_hook: String,
    pub max_body_span: Vec3,
    pub stress_tensor: Mat3,
    pub stress: Vec3,
    pub strain: Vec3,
    pub strain_rate: Vec3,
    pub stiff: Vec3,
    pub curr_unbalanced: f64,
    pub prev_grow: Vec3,
    pub mass: f64,
    pub external_work: f64,
    /// Recorded doneHook firings still to come (scene files only; empty under `compat run`).
    pub hook_events: VecDeque<HookEvent>,
    /// Whether this controller was loaded with recorded firings (then every firing must match one).
    pub replay_hooks: bool,
    /// Cached `O.energy` index (`velGradWorkIx`).
    pub energy_cache: crate::energy::IdCache,
}

impl Default for PeriTriax {
    fn default() -> Self {
        PeriTriax {
            dyn_cell: false,
            goal: Vec3::zeros(),
            stress_mask: 0,
            max_strain_rate: Vec3::new(1.0, 1.0, 1.0),
            max_unbalanced: 1e-4,
            abs_stress_tol: 1e3,
            rel_stress_tol: 3e-5,
            grow_damping: 0.25,
            glob_update: 5,
            done_hook: String::new(),
            max_body_span: Vec3::zeros(),
            stress_tensor: Mat3::zeros(),
            stress: Vec3::zeros(),
            strain: Vec3::zeros(),
            strain_rate: Vec3::zeros(),
            stiff: Vec3::zeros(),
            curr_unbalanced: f64::NAN,
            prev_grow: Vec3::zeros(),
            mass: f64::NAN,
            external_work: 0.0,
            hook_events: VecDeque::new(),
            replay_hooks: false,
            energy_cache: Default::default(),
        }
    }
}

/// `Matrix3r::trace()`: Eigen's unrolled sum of the diagonal, `d0 + (d1 + d2)`.
#[inline(always)]
fn trace(m: &Mat3) -> f64 {
    m[(0, 0)] + (m[(1, 1)] + m[(2, 2)])
}

/// `Matrix3r::determinant()` as Eigen 3 expands it along the first row.
pub fn det3(m: &Mat3) -> f64 {
    m[(0, 0)] * (m[(1, 1)] * m[(2, 2)] - m[(1, 2)] * m[(2, 1)])
        - m[(0, 1)] * (m[(1, 0)] * m[(2, 2)] - m[(1, 2)] * m[(2, 0)])
        + m[(0, 2)] * (m[(1, 0)] * m[(2, 1)] - m[(1, 1)] * m[(2, 0)])
}

/// `Shop::getStress(volume)` (preprocessing/dem/Shop_02.cpp): Love-Weber stress
/// `Σ (Fn + Fs) ⊗ (x1 - x2 - hSize·cellDist) / V` over real interactions in container order, clump
/// members replaced by their clump, GridNode-GridNode bonds skipped. `volume == 0`: the cell volume
/// (periodic) or the spheres' bounding box.
pub fn get_stress(scene: &Scene, volume: f64) -> Result<Mat3, String> {
    let b = &scene.bodies;
    let volume = if volume != 0.0 {
        volume
    } else {
        match &scene.cell {
            Some(c) => det3(&c.hsize),
            None => {
                let (lo, hi) = crate::utils::aabb_extrema(scene)
                    .ok_or("getStress: no spheres to size the default volume")?;
                (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2])
            }
        }
    };
    let owner = |id: usize| match b.clump_id[id] {
        Some(c) if b.is_clump_member(id) => c as usize,
        _ => id,
    };
    let mut s = Mat3::zeros();
    for it in &scene.interactions.list {
        let (Some(_), Some(ph)) = (&it.geom, &it.phys) else {
            continue;
        };
        let (b1, b2) = (owner(it.id1 as usize), owner(it.id2 as usize));
        if matches!(b.shape[b1], Shape::GridNode(_)) {
            continue;
        }
        let mut branch = b.pos[b1] - b.pos[b2];
        if let Some(c) = &scene.cell {
            branch -= mat_vec_i(&c.hsize, &it.cell_dist);
        }
        let f = ph.normal_force + ph.shear_force;
        for i in 0..3 {
            for j in 0..3 {
                s[(i, j)] += f[i] * branch[j];
            }
        }
    }
    // a true division per entry, as Eigen's `Matrix3r / Real`
    Ok(Mat3::from_fn(|i, j| s[(i, j)] / volume))
}

impl PeriTriax {
    /// Whether bit `axis` of `stressMask` asks for stress control.
    #[inline(always)]
    fn stress_controlled(&self, axis: usize) -> bool {
        self.stress_mask & (1 << axis) != 0
    }

    /// `PeriTriaxController::strainStressStiffUpdate`: logarithmic strain from `trsf`, the mean
    /// contact stiffness per axis (stress servo only) and the stress tensor from `Shop::getStress`.
    fn strain_stress_stiff_update(&mut self, scene: &Scene) -> Result<(), String> {
        let cell = scene.cell.as_ref().ok_or("no periodic cell")?;
        for i in 0..3 {
            self.strain[i] = cell.trsf[(i, i)].ln();
        }
        let mut sum = Vec3::zeros();
        let mut n: i32 = 0;
        if !self.dyn_cell {
            for it in &scene.interactions.list {
                let (Some(g), Some(ph)) = (&it.geom, &it.phys) else {
                    continue;
                };
                for i in 0..3 {
                    sum[i] += g.normal[i].abs() * ph.kn + (1.0 - g.normal[i].abs()) * ph.ks;
                }
                n += 1;
            }
        }
        self.stress_tensor = get_stress(scene, 0.0)?;
        for axis in 0..3 {
            self.stress[axis] = self.stress_tensor[(axis, axis)];
        }
        self.stiff = if n > 0 {
            sum * (1.0 / n as f64)
        } else {
            Vec3::zeros()
        };
        Ok(())
    }

    /// `PeriTriaxController::action` (pkg/dem/PeriIsoCompressor.cpp). Returns whether the doneHook
    /// must run now (goal reached, packing stable, hook not empty).
    pub fn action(&mut self, scene: &mut Scene) -> Result<bool, String> {
        let cell = scene
            .cell
            .as_ref()
            .ok_or("PeriTriaxController run on aperiodic simulation.")?;
        let dt = scene.dt;
        let cell_size = cell.size();
        let cell_area = Vec3::new(
            cell_size[1] * cell_size[2],
            cell_size[0] * cell_size[2],
            cell_size[0] * cell_size[1],
        );
        if self.max_body_span[0] <= 0.0 {
            for bd in scene.bodies.bound.iter().flatten() {
                for i in 0..3 {
                    let span = bd.max[i] - bd.min[i];
                    if span < cell_size[i] {
                        self.max_body_span[i] = cxx_max(self.max_body_span[i], span);
                    }
                }
            }
        }
        if 2.1 * self.max_body_span[0] > cell_size[0]
            || 2.1 * self.max_body_span[1] > cell_size[1]
            || 2.1 * self.max_body_span[2] > cell_size[2]
        {
            return Err(
                "Minimum cell size is smaller than 2.1*maxBodySpan (periodic collider requirement)"
                    .into(),
            );
        }
        if self.glob_update == 0 {
            return Err("PeriTriaxController.globUpdate must not be 0".into());
        }
        let do_update = scene.iter % self.glob_update as i64 == 0;
        if do_update
            || cxx_min(self.stiff[0], cxx_min(self.stiff[1], self.stiff[2])) <= 0.0
            || self.dyn_cell
        {
            self.strain_stress_stiff_update(scene)?;
        }
        if self.dyn_cell && self.mass.is_nan() {
            // every body's State::mass, clumps and fixed bodies included
            self.mass = 0.0;
            for m in &scene.bodies.mass {
                self.mass += m;
            }
        }
        let mut all_ok = true;
        let cell = scene.cell.as_mut().expect("checked above");
        for axis in 0..3 {
            let mut sr = cell.vel_grad[(axis, axis)];
            let d = self.goal[axis] - self.stress[axis];
            if self.stress_controlled(axis) {
                if !self.dyn_cell {
                    let k = if self.stiff[axis] > 0.0 {
                        self.stiff[axis]
                    } else {
                        1.0
                    };
                    sr = 1.0 / dt * d * cell_area[axis] / k;
                } else {
                    // cell inertia with Cundall's damping
                    let damp = 1.0 - self.grow_damping * sign(sr * d);
                    sr += damp * dt * d / self.mass;
                }
            } else {
                sr = ((self.goal[axis] - self.strain[axis]).exp() - 1.0) / dt;
            }
            if !self.dyn_cell {
                sr = (1.0 - self.grow_damping) * sr + 0.8 * self.prev_grow[axis];
            }
            if sr.abs() > self.max_strain_rate[axis] {
                sr = sign(sr) * self.max_strain_rate[axis];
            }
            // never shrink below the periodic collider's minimum cell size
            sr = cxx_max(sr, -(cell_size[axis] - 2.1 * self.max_body_span[axis]) / dt);
            cell.vel_grad[(axis, axis)] = sr;
            self.strain[axis] += sr * dt;
            if self.stress_controlled(axis) {
                let (cur, g) = (self.stress[axis], self.goal[axis]);
                if (g != 0.0 && ((cur - g) / g).abs() > self.rel_stress_tol)
                    || (cur - g).abs() > self.abs_stress_tol
                {
                    all_ok = false;
                }
            } else {
                // the strain is prescribed exactly: the tolerances only absorb round-off
                let (cur, g) = (self.strain[axis], self.goal[axis]);
                if (g != 0.0 && ((cur - g) / g).abs() > 1e-6) || (cur - g).abs() > 1e-6 {
                    all_ok = false;
                }
            }
        }
        if !self.dyn_cell {
            // predicted stress until the next measurement
            for axis in 0..3 {
                if self.stiff[axis] > 0.0 {
                    self.stress[axis] += (cell.vel_grad[(axis, axis)] * dt / cell_size[axis])
                        * (self.stiff[axis] / cell_area[axis]);
                }
            }
        }
        for k in 0..3 {
            self.strain_rate[k] = cell.vel_grad[(k, k)];
        }
        let mean_vg = (cell.prev_vel_grad + cell.vel_grad) * 0.5;
        let dw = trace(&mat_mul(&mean_vg, &self.stress_tensor)) * dt * det3(&cell.hsize);
        self.external_work += dw;
        if scene.track_energy {
            scene
                .energy
                .add(-dw, "velGradWork", &mut self.energy_cache, false);
        }
        self.prev_grow = self.strain_rate;
        if all_ok {
            if do_update || self.curr_unbalanced < 0.0 {
                if scene.forces.perm_used {
                    // Shop::unbalancedForce syncs, which adds the permanent forces before Newton
                    // does; ryade's force container cannot sync twice
                    return Err(
                        "PeriTriaxController with permanent forces (O.forces.setPermF) is not supported by ryade yet"
                            .into(),
                    );
                }
                self.curr_unbalanced = crate::utils::unbalanced_force(scene, false);
            }
            if self.curr_unbalanced < self.max_unbalanced && !self.done_hook.is_empty() {
                return Ok(true);
            }
        }
        Ok(false)
    }

    /// Apply the next recorded doneHook firing (scene files), checking it fired at the same
    /// iteration with the same hook string in YADE. Returns whether the engine is now dead.
    pub fn replay_hook(&mut self, iter: i64) -> Result<bool, String> {
        let ev = self.hook_events.pop_front().ok_or_else(|| {
            format!(
                "PeriTriaxController.doneHook '{}' fired at iteration {}, but YADE recorded no further firing",
                self.done_hook, iter
            )
        })?;
        if ev.iter != iter || ev.hook != self.done_hook {
            return Err(format!(
                "PeriTriaxController.doneHook '{}' fired at iteration {}; YADE fired '{}' at iteration {}",
                self.done_hook, iter, ev.hook, ev.iter
            ));
        }
        let mut dead = false;
        for s in ev.set {
            match s {
                HookSet::Goal(v) => self.goal = v,
                HookSet::StressMask(m) => self.stress_mask = m,
                HookSet::MaxStrainRate(v) => self.max_strain_rate = v,
                HookSet::MaxUnbalanced(x) => self.max_unbalanced = x,
                HookSet::AbsStressTol(x) => self.abs_stress_tol = x,
                HookSet::RelStressTol(x) => self.rel_stress_tol = x,
                HookSet::GrowDamping(x) => self.grow_damping = x,
                HookSet::GlobUpdate(n) => self.glob_update = n,
                HookSet::DoneHook(h) => self.done_hook = h,
                HookSet::DynCell(b) => self.dyn_cell = b,
                HookSet::Mass(m) => self.mass = m,
                HookSet::Dead(d) => dead = d,
            }
        }
        Ok(dead)
    }

    /// The doubles of this controller's state in the order of the golden digest (FORMAT.md,
    /// `peri_triax`): stressTensor (row-major), stress, strain, strainRate, stiff, currUnbalanced,
    /// prevGrow, goal, mass, externalWork, maxBodySpan, stressMask, dynCell.
    pub fn digest_values(&self) -> Vec<f64> {
        let mut v = Vec::with_capacity(37);
        for i in 0..3 {
            for j in 0..3 {
                v.push(self.stress_tensor[(i, j)]);
            }
        }
        for x in [&self.stress, &self.strain, &self.strain_rate, &self.stiff] {
            v.extend(x.iter());
        }
        v.push(self.curr_unbalanced);
        v.extend(self.prev_grow.iter());
        v.extend(self.goal.iter());
        v.push(self.mass);
        v.push(self.external_work);
        v.extend(self.max_body_span.iter());
        v.push(self.stress_mask as f64);
        v.push(if self.dyn_cell { 1.0 } else { 0.0 });
        v
    }
}
