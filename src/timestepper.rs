//! `GlobalStiffnessTimeStepper` (pkg/dem/GlobalStiffnessTimeStepper.cpp): dt from the stiffest
//! translational or rotational eigen-period of each dynamic body, from its current contacts.

use crate::body::Bodies;
use crate::interaction::Interactions;
use crate::math::{norm2, Vec3};

#[derive(Clone, Debug, PartialEq)]
pub struct GlobalStiffnessTimeStepper {
    pub active: bool,
    pub time_step_update_interval: u32,
    /// Initial dt while no contact exists; negative: `timestepSafetyCoefficient * PWaveTimeStep()`.
    pub default_dt: f64,
    pub max_dt: f64,
    pub previous_dt: f64,
    pub timestep_safety_coefficient: f64,
    pub computed_once: bool,
    pub stiffness: Vec<Vec3>,
    pub rstiffness: Vec<Vec3>,
}

impl Default for GlobalStiffnessTimeStepper {
    fn default() -> Self {
        GlobalStiffnessTimeStepper {
            active: true,
            time_step_update_interval: 1,
            default_dt: -1.0,
            max_dt: f64::MAX,
            previous_dt: f64::MAX,
            timestep_safety_coefficient: 0.8,
            computed_once: false,
            stiffness: Vec::new(),
            rstiffness: Vec::new(),
        }
    }
}

/// `std::min` / `std::max` as C++ evaluates them (`b < a ? b : a`, `a < b ? b : a`).
fn cmin(a: f64, b: f64) -> f64 {
    if b < a {
        b
    } else {
        a
    }
}
fn cmax(a: f64, b: f64) -> f64 {
    if a < b {
        b
    } else {
        a
    }
}

impl GlobalStiffnessTimeStepper {
    /// `GlobalStiffnessTimeStepper::isActivated`.
    pub fn is_activated(&self, iter: i64) -> bool {
        self.active
            && (!self.computed_once
                || iter % self.time_step_update_interval.max(1) as i64 == 0
                || iter < 2)
    }

    /// `computeStiffnesses`: per-body diagonal stiffness from every real contact with a normal force.
    fn compute_stiffnesses(&mut self, n: usize, intrs: &Interactions) {
        self.stiffness.clear();
        self.stiffness.resize(n, Vec3::zeros());
        self.rstiffness.clear();
        self.rstiffness.resize(n, Vec3::zeros());
        for it in &intrs.list {
            let (Some(g), Some(p)) = (&it.geom, &it.phys) else {
                continue;
            };
            if norm2(&p.normal_force) == 0.0 {
                continue;
            }
            let nn = g.normal;
            let sq = Vec3::new(nn[0] * nn[0], nn[1] * nn[1], nn[2] * nn[2]);
            let d = sq * (p.kn - p.ks) + Vec3::repeat(1.0) * p.ks;
            let dr = Vec3::new(sq[1] + sq[2], sq[0] + sq[2], sq[0] + sq[1]) * p.ks;
            let (a, b) = (it.id1 as usize, it.id2 as usize);
            self.stiffness[a] += d;
            self.rstiffness[a] += dr * (g.radius1 * g.radius1) + Vec3::zeros();
            self.stiffness[b] += d;
            self.rstiffness[b] += dr * (g.radius2 * g.radius2) + Vec3::zeros();
        }
    }

    /// `computeTimeStep`: returns the new dt, or None to keep the current one.
    pub fn compute(&mut self, bodies: &Bodies, intrs: &Interactions, pwave: f64) -> Option<f64> {
        if self.default_dt < 0.0 {
            self.default_dt = self.timestep_safety_coefficient * pwave;
        }
        self.compute_stiffnesses(bodies.len(), intrs);
        let mut new_dt = f64::MAX;
        let mut computed = false;
        for id in 0..bodies.len() {
            if !bodies.is_dynamic(id) {
                continue;
            }
            let s = self.stiffness[id];
            let r = self.rstiffness[id];
            if s == Vec3::zeros() {
                continue;
            }
            let mut dt = cmax(cmax(s[0], s[1]), s[2]);
            if dt != 0.0 {
                dt = bodies.mass[id] / dt;
                computed = true;
            } else {
                dt = f64::MAX;
            }
            let mut rd = [f64::MAX; 3];
            for k in 0..3 {
                if r[k] != 0.0 {
                    rd[k] = bodies.inertia[id][k] / r[k];
                    computed = true;
                }
            }
            let rdt = cmin(cmin(rd[0], rd[1]), rd[2]);
            let dt = 1.41044 * self.timestep_safety_coefficient * cmin(dt, rdt).sqrt();
            new_dt = cmin(dt, new_dt);
        }
        if computed {
            self.previous_dt = cmin(cmin(new_dt, self.max_dt), 1.05 * self.previous_dt);
            self.computed_once = true;
            Some(self.previous_dt)
        } else if !self.computed_once {
            Some(self.default_dt)
        } else {
            None
        }
    }
}
