//! Per-body force and torque accumulators (YADE `core/ForceContainerParallel.cpp`, one thread).
//!
//! A body's force after a step is `0 + c1 + c2 + ...` in interaction-container order; permanent
//! forces (`O.forces.setPermF`) are added after that sum, as `ForceContainer::sync` does.

use crate::math::Vec3;

#[derive(Clone, Debug, Default)]
pub struct Forces {
    pub force: Vec<Vec3>,
    pub torque: Vec<Vec3>,
    pub perm_force: Vec<Vec3>,
    pub perm_torque: Vec<Vec3>,
    pub perm_used: bool,
    /// Iteration of the last ForceResetter run (Newton warns when it is stale, as YADE does).
    pub last_reset: i64,
}

impl Forces {
    pub fn resize(&mut self, n: usize) {
        if self.force.len() < n {
            self.force.resize(n, Vec3::zeros());
            self.torque.resize(n, Vec3::zeros());
            self.perm_force.resize(n, Vec3::zeros());
            self.perm_torque.resize(n, Vec3::zeros());
        }
    }

    /// `ForceResetter`: zero everything, then re-add permanent forces (YADE adds them at sync; the sum
    /// order is the same because the contributions are added to a separate zeroed accumulator).
    pub fn reset(&mut self, n: usize, iter: i64) {
        self.resize(n);
        for f in self.force.iter_mut() {
            *f = Vec3::zeros();
        }
        for t in self.torque.iter_mut() {
            *t = Vec3::zeros();
        }
        self.last_reset = iter;
    }

    #[inline(always)]
    pub fn add_force(&mut self, id: usize, f: &Vec3) {
        self.force[id] += f;
    }

    #[inline(always)]
    pub fn add_torque(&mut self, id: usize, t: &Vec3) {
        self.torque[id] += t;
    }

    /// The sync step of YADE: permanent forces are added after the contact sum.
    pub fn sync(&mut self) {
        if self.perm_used {
            for i in 0..self.force.len() {
                self.force[i] += self.perm_force[i];
                self.torque[i] += self.perm_torque[i];
            }
        }
    }
}
