//! Engines adding a prescribed force to listed bodies (YADE `pkg/common/ForceEngine.cpp`):
//! `ForceEngine` (a constant force) and `HarmonicForceEngine` (a sinusoidal force per axis).

use crate::forces::Forces;
use crate::math::Vec3;

/// YADE `ForceEngine`: every step, `force` is added to each listed body (ids past the container are
/// skipped, as `bodies->exists` does).
#[derive(Clone, Debug, Default)]
pub struct ForceEngine {
    pub ids: Vec<usize>,
    pub force: Vec3,
}

impl ForceEngine {
    /// `ForceEngine::action`.
    pub fn action(&self, forces: &mut Forces, n_bodies: usize) {
        forces.resize(n_bodies);
        for &id in &self.ids {
            if id < n_bodies {
                forces.add_force(id, &self.force);
            }
        }
    }
}

/// YADE `InterpolatingDirectedForceEngine`: a ForceEngine whose magnitude is interpolated in time
/// (`times`, `magnitudes`, optionally wrapped) along `direction` (normalised at every step).
#[derive(Clone, Debug, Default)]
pub struct InterpolatingDirectedForceEngine {
    pub base: ForceEngine,
    pub times: Vec<f64>,
    pub magnitudes: Vec<f64>,
    pub direction: Vec3,
    pub wrap: bool,
    pub pos: usize,
}

impl InterpolatingDirectedForceEngine {
    /// `InterpolatingDirectedForceEngine::action` (ForceEngine.cpp).
    pub fn action(
        &mut self,
        forces: &mut Forces,
        n_bodies: usize,
        time: f64,
    ) -> Result<(), String> {
        if self.times.len() < 2 || self.times.len() != self.magnitudes.len() {
            return Err(format!(
                "InterpolatingDirectedForceEngine: times ({}) and magnitudes ({}) must have the same length, at least 2",
                self.times.len(),
                self.magnitudes.len()
            ));
        }
        let virt = if self.wrap {
            crate::kinematic::periodic_wrap(time, self.times[0], self.times[self.times.len() - 1])
        } else {
            time
        };
        self.direction = crate::math::normalized(&self.direction);
        let m = crate::kinematic::linear_interpolate(
            virt,
            &self.times,
            &self.magnitudes,
            &mut self.pos,
        );
        self.base.force = self.direction * m;
        self.base.action(forces, n_bodies);
        Ok(())
    }
}

/// YADE `HarmonicForceEngine`: adds `A_i sin(2 pi f_i t + fi_i)` per axis to each listed body.
#[derive(Clone, Debug, Default)]
pub struct HarmonicForceEngine {
    pub ids: Vec<usize>,
    /// Amplitude [N].
    pub a: Vec3,
    /// Frequency [Hz].
    pub f: Vec3,
    /// Initial phase [rad].
    pub fi: Vec3,
}

impl HarmonicForceEngine {
    /// `HarmonicForceEngine::action` (ForceEngine.cpp): the same operation order, `(f * 2) * pi`, then
    /// `sin(w * time + fi)` times `A` coefficient-wise.
    pub fn action(&self, forces: &mut Forces, n_bodies: usize, time: f64) {
        if self.ids.is_empty() {
            return; // YADE: "The list of ids is empty! Can't apply any forces."
        }
        let mut force = Vec3::zeros();
        for k in 0..3 {
            let w = self.f[k] * 2.0 * std::f64::consts::PI;
            force[k] = (w * time + self.fi[k]).sin() * self.a[k];
        }
        forces.resize(n_bodies);
        for &id in &self.ids {
            if id < n_bodies {
                forces.add_force(id, &force);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn harmonic_force_by_hand() {
        let e = HarmonicForceEngine {
            ids: vec![1],
            a: Vec3::new(2.0, 3.0, 0.0),
            f: Vec3::new(0.25, 0.5, 1.0),
            fi: Vec3::new(0.0, std::f64::consts::FRAC_PI_2, 0.0),
        };
        let mut forces = Forces::default();
        e.action(&mut forces, 2, 1.0);
        // x: 2 sin(pi/2) = 2; y: 3 sin(pi + pi/2) = -3; z: amplitude 0
        assert_eq!(forces.force(1)[0], 2.0);
        assert_eq!(forces.force(1)[1], -3.0);
        assert_eq!(forces.force(1)[2], 0.0);
        assert_eq!(*forces.force(0), Vec3::zeros());
    }
}
