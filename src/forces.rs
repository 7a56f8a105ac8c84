//! Per-body force and torque accumulators (YADE `core/ForceContainerParallel.cpp`, one thread).
//!
//! A body's force after a step is `0 + c1 + c2 + ...` in interaction-container order; permanent
//! forces (`O.forces.setPermF`) are added after that sum, as `ForceContainer::sync` does.
//!
//! Layout: a body's force and torque sit together in one 64-byte `Wrench`, because every contact
//! adds both to each of its two bodies: one cache line per body instead of two (the interaction
//! loop visits bodies in container order, not in memory order). The sums are the same.

use crate::math::Vec3;

/// One body's force and torque accumulators, one cache line.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(64))]
pub struct Wrench {
    pub f: Vec3,
    pub t: Vec3,
}

impl Default for Wrench {
    fn default() -> Self {
        Wrench {
            f: Vec3::zeros(),
            t: Vec3::zeros(),
        }
    }
}

#[derive(Clone, Debug, Default)]
pub struct Forces {
    pub ft: Vec<Wrench>,
    pub perm_force: Vec<Vec3>,
    pub perm_torque: Vec<Vec3>,
    pub perm_used: bool,
    /// Iteration of the last ForceResetter run (Newton warns when it is stale, as YADE does).
    pub last_reset: i64,
}

impl Forces {
    /// Bodies covered.
    pub fn len(&self) -> usize {
        self.ft.len()
    }

    pub fn is_empty(&self) -> bool {
        self.ft.is_empty()
    }

    pub fn resize(&mut self, n: usize) {
        if self.ft.len() < n {
            self.ft.resize(n, Wrench::default());
            self.perm_force.resize(n, Vec3::zeros());
            self.perm_torque.resize(n, Vec3::zeros());
        }
    }

    /// `ForceResetter`: zero everything, then re-add permanent forces (YADE adds them at sync; the sum
    /// order is the same because the contributions are added to a separate zeroed accumulator).
    pub fn reset(&mut self, n: usize, iter: i64) {
        self.resize(n);
        for w in self.ft.iter_mut() {
            *w = Wrench::default();
        }
        self.last_reset = iter;
    }

    #[inline(always)]
    pub fn force(&self, id: usize) -> &Vec3 {
        &self.ft[id].f
    }

    #[inline(always)]
    pub fn torque(&self, id: usize) -> &Vec3 {
        &self.ft[id].t
    }

    #[inline(always)]
    pub fn force_mut(&mut self, id: usize) -> &mut Vec3 {
        &mut self.ft[id].f
    }

    #[inline(always)]
    pub fn torque_mut(&mut self, id: usize) -> &mut Vec3 {
        &mut self.ft[id].t
    }

    #[inline(always)]
    pub fn add_force(&mut self, id: usize, f: &Vec3) {
        self.ft[id].f += f;
    }

    #[inline(always)]
    pub fn add_torque(&mut self, id: usize, t: &Vec3) {
        self.ft[id].t += t;
    }

    /// The sync step of YADE: permanent forces are added after the contact sum.
    pub fn sync(&mut self) {
        if self.perm_used {
            for (i, w) in self.ft.iter_mut().enumerate() {
                w.f += self.perm_force[i];
                w.t += self.perm_torque[i];
            }
        }
    }
}
