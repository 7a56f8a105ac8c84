//! Kinematic engines: prescribed velocities on a list of bodies (YADE `pkg/common/KinematicEngines.cpp`);
//! `HelixEngine` and `CombinedKinematicEngine` (the `+` of kinematic engines) are mirrored too.
//!
//! `KinematicEngine::action` zeroes `vel` and `angVel` of every listed body, then `apply` adds the
//! engine's contribution. Three engines are mirrored: `TranslationEngine` (constant `velocity` along
//! `translationAxis`), `RotationEngine` (constant `angularVelocity` about `rotationAxis`, optionally
//! carrying the bodies round `zeroPoint`) and `ServoPIDController` (a PID law on the summed force of the
//! bodies, which then acts as a `TranslationEngine`).

use crate::body::Bodies;
use crate::forces::Forces;
use crate::math::{norm, normalized, Quat, Vec3};

/// `KinematicEngine::action`: reset the velocities of the listed bodies (ids past the container are
/// skipped, as YADE's `Body::byId` returns null for erased bodies).
fn reset_velocities(ids: &[usize], bodies: &mut Bodies) {
    for &id in ids {
        if id < bodies.len() {
            bodies.vel[id] = Vec3::zeros();
            bodies.ang_vel[id] = Vec3::zeros();
        }
    }
}

/// `TranslationEngine::apply`: `vel += velocity * translationAxis` for each listed body.
fn translate(ids: &[usize], bodies: &mut Bodies, velocity: f64, axis: &Vec3) {
    let dv = axis * velocity;
    for &id in ids {
        if id < bodies.len() {
            bodies.vel[id] += dv;
        }
    }
}

/// YADE `TranslationEngine`: every step, the listed bodies move at `velocity` along `translation_axis`
/// (normalised when set, as its postLoad does).
#[derive(Clone, Debug, Default)]
pub struct TranslationEngine {
    pub ids: Vec<usize>,
    pub velocity: f64,
    pub translation_axis: Vec3,
}

impl TranslationEngine {
    /// `KinematicEngine::action` + `TranslationEngine::apply`. Returns false when `ids` is empty
    /// (YADE logs "The list of ids is empty!" and moves nothing).
    pub fn action(&self, bodies: &mut Bodies) -> bool {
        if self.ids.is_empty() {
            return false;
        }
        reset_velocities(&self.ids, bodies);
        self.apply(&self.ids, bodies);
        true
    }

    /// `TranslationEngine::apply` on `ids` (the engine's own or a combination's).
    pub fn apply(&self, ids: &[usize], bodies: &mut Bodies) {
        translate(ids, bodies, self.velocity, &self.translation_axis);
    }
}

/// YADE `RotationEngine`: every step, the listed bodies spin at `angular_velocity` about
/// `rotation_axis` (normalised when set, as its postLoad does) and, with `rotate_around_zero`, also move
/// round `zero_point` at the velocity that takes them to their rotated place in one step.
#[derive(Clone, Debug)]
pub struct RotationEngine {
    pub ids: Vec<usize>,
    pub angular_velocity: f64,
    pub rotation_axis: Vec3,
    pub rotate_around_zero: bool,
    pub zero_point: Vec3,
}

impl Default for RotationEngine {
    /// YADE's defaults: axis x, no angular velocity, no displacement about the zero point.
    fn default() -> Self {
        RotationEngine {
            ids: Vec::new(),
            angular_velocity: 0.0,
            rotation_axis: Vec3::new(1.0, 0.0, 0.0),
            rotate_around_zero: false,
            zero_point: Vec3::zeros(),
        }
    }
}

impl RotationEngine {
    /// `KinematicEngine::action` + `RotationEngine::apply` (pkg/common/KinematicEngines.cpp). Returns
    /// false when `ids` is empty (YADE logs "The list of ids is empty!" and moves nothing).
    pub fn action(&self, bodies: &mut Bodies, dt: f64) -> bool {
        if self.ids.is_empty() {
            return false;
        }
        reset_velocities(&self.ids, bodies);
        self.apply(&self.ids, bodies, dt);
        true
    }

    /// `RotationEngine::apply` on `ids` (the engine's own or a combination's).
    pub fn apply(&self, ids: &[usize], bodies: &mut Bodies, dt: f64) {
        let spin = self.rotation_axis * self.angular_velocity;
        for &id in ids {
            if id >= bodies.len() {
                continue;
            }
            bodies.ang_vel[id] += spin;
            if self.rotate_around_zero {
                let arm = bodies.pos[id] - self.zero_point;
                let q = Quat::from_angle_axis(self.angular_velocity * dt, &self.rotation_axis);
                let new_pos = q.rotate(&arm) + self.zero_point;
                bodies.vel[id] += (new_pos - bodies.pos[id]) / dt;
            }
        }
    }
}

/// YADE `HelixEngine`: a `RotationEngine` that also moves the bodies at `linear_velocity` along the
/// axis; it always turns about `zeroPoint` (its apply sets `rotateAroundZero`) and counts `angleTurned`.
#[derive(Clone, Debug, Default)]
pub struct HelixEngine {
    pub rot: RotationEngine,
    pub linear_velocity: f64,
    pub angle_turned: f64,
}

impl HelixEngine {
    /// `KinematicEngine::action` + `HelixEngine::apply`.
    pub fn action(&mut self, bodies: &mut Bodies, dt: f64) -> bool {
        if self.rot.ids.is_empty() {
            return false;
        }
        reset_velocities(&self.rot.ids, bodies);
        let ids = std::mem::take(&mut self.rot.ids);
        self.apply(&ids, bodies, dt);
        self.rot.ids = ids;
        true
    }

    /// `HelixEngine::apply` (KinematicEngines.cpp): angle, axial velocity, then the rotation about zero.
    pub fn apply(&mut self, ids: &[usize], bodies: &mut Bodies, dt: f64) {
        if ids.is_empty() {
            return;
        }
        self.angle_turned += self.rot.angular_velocity * dt;
        let dv = self.rot.rotation_axis * self.linear_velocity;
        for &id in ids {
            if id < bodies.len() {
                bodies.vel[id] += dv;
            }
        }
        self.rot.rotate_around_zero = true;
        self.rot.apply(ids, bodies, dt);
    }
}

/// `linearInterpolate` (lib/smoothing/LinearInterpolate.hpp): the value at `t` of the piecewise linear
/// function through (`tt`, `values`), the end values outside; `pos` is the lookup state it keeps.
pub fn linear_interpolate(t: f64, tt: &[f64], values: &[f64], pos: &mut usize) -> f64 {
    if t <= tt[0] {
        *pos = 0;
        return values[0];
    }
    if t >= tt[tt.len() - 1] {
        *pos = tt.len() - 2;
        return values[values.len() - 1];
    }
    *pos = (*pos).min(tt.len() - 2);
    while tt[*pos] > t || tt[*pos + 1] < t {
        if tt[*pos] > t {
            *pos -= 1;
        } else {
            *pos += 1;
        }
    }
    let (t0, t1) = (tt[*pos], tt[*pos + 1]);
    let (v0, v1) = (values[*pos], values[*pos + 1]);
    v0 + (v1 - v0) * ((t - t0) / (t1 - t0))
}

/// `Shop::periodicWrap` (preprocessing/dem/Shop_02.cpp): `x` wrapped into [x0, x1).
pub fn periodic_wrap(x: f64, x0: f64, x1: f64) -> f64 {
    let x_norm = (x - x0) / (x1 - x0);
    let xx_norm = x_norm - x_norm.floor();
    x0 + xx_norm * (x1 - x0)
}

/// YADE `InterpolatingHelixEngine`: a HelixEngine whose angular velocity is interpolated in time
/// (`times`, `angularVelocities`, optionally wrapped) and whose axial velocity is `slope` times it.
#[derive(Clone, Debug, Default)]
pub struct InterpolatingHelixEngine {
    pub helix: HelixEngine,
    pub times: Vec<f64>,
    pub angular_velocities: Vec<f64>,
    pub wrap: bool,
    pub slope: f64,
    /// `_pos`, the interpolation's lookup state.
    pub pos: usize,
}

impl InterpolatingHelixEngine {
    /// `InterpolatingHelixEngine::apply` (KinematicEngines.cpp).
    pub fn apply(
        &mut self,
        ids: &[usize],
        bodies: &mut Bodies,
        dt: f64,
        time: f64,
    ) -> Result<(), String> {
        if self.times.len() < 2 || self.times.len() != self.angular_velocities.len() {
            return Err(format!(
                "InterpolatingHelixEngine: times ({}) and angularVelocities ({}) must have the same length, at least 2",
                self.times.len(),
                self.angular_velocities.len()
            ));
        }
        let virt = if self.wrap {
            periodic_wrap(time, self.times[0], self.times[self.times.len() - 1])
        } else {
            time
        };
        let w = linear_interpolate(virt, &self.times, &self.angular_velocities, &mut self.pos);
        self.helix.rot.angular_velocity = w;
        self.helix.linear_velocity = w * self.slope;
        self.helix.apply(ids, bodies, dt);
        Ok(())
    }
}

/// Eigen's `Quaternion::setFromTwoVectors` for the non-opposite case (the opposite one takes an SVD:
/// refused).
fn quat_from_two_vectors(a: &Vec3, b: &Vec3) -> Result<Quat, String> {
    let v0 = normalized(a);
    let v1 = normalized(b);
    let c = crate::math::dot(&v1, &v0);
    if c < -1.0 + 1e-12 {
        return Err(
            "BicyclePedalEngine with rotationAxis opposite to z is not supported by ryade yet"
                .into(),
        );
    }
    let axis = crate::math::cross(&v0, &v1);
    let s = ((1.0 + c) * 2.0).sqrt();
    let invs = 1.0 / s;
    Ok(Quat::new(
        s * 0.5,
        axis[0] * invs,
        axis[1] * invs,
        axis[2] * invs,
    ))
}

/// YADE `BicyclePedalEngine`: the bodies move on a circle of `radius` about `rotationAxis` without
/// turning (a pedal), at `angularVelocity`; `fi` is the phase.
#[derive(Clone, Debug)]
pub struct BicyclePedalEngine {
    pub ids: Vec<usize>,
    pub angular_velocity: f64,
    pub rotation_axis: Vec3,
    pub radius: f64,
    pub fi: f64,
}

impl Default for BicyclePedalEngine {
    fn default() -> Self {
        BicyclePedalEngine {
            ids: Vec::new(),
            angular_velocity: 0.0,
            rotation_axis: Vec3::new(1.0, 0.0, 0.0),
            radius: -1.0,
            fi: std::f64::consts::PI / 2.0,
        }
    }
}

impl BicyclePedalEngine {
    /// `BicyclePedalEngine::apply` (KinematicEngines.cpp).
    pub fn apply(&mut self, ids: &[usize], bodies: &mut Bodies, dt: f64) -> Result<(), String> {
        if ids.is_empty() {
            return Ok(());
        }
        let q = quat_from_two_vectors(&Vec3::new(0.0, 0.0, 1.0), &self.rotation_axis)?;
        let a = self.fi + self.angular_velocity * dt;
        let new_pos = Vec3::new(a.cos() * self.radius, a.sin() * self.radius, 0.0);
        let old_pos = Vec3::new(
            self.fi.cos() * self.radius,
            self.fi.sin() * self.radius,
            0.0,
        );
        let v = (old_pos - new_pos) / dt;
        self.fi += self.angular_velocity * dt;
        let v = q.rotate(&v);
        for &id in ids {
            if id < bodies.len() {
                bodies.vel[id] += v;
            }
        }
        Ok(())
    }
}

/// One member of a `CombinedKinematicEngine` (and the kinematic engines run alone as
/// `Engine::Kinematic`).
#[derive(Clone, Debug)]
pub enum KinematicPart {
    Translation(TranslationEngine),
    Rotation(RotationEngine),
    Helix(HelixEngine),
    ServoPid(ServoPid),
    InterpolatingHelix(InterpolatingHelixEngine),
    BicyclePedal(BicyclePedalEngine),
}

impl KinematicPart {
    pub fn class_name(&self) -> &'static str {
        match self {
            KinematicPart::Translation(_) => "TranslationEngine",
            KinematicPart::Rotation(_) => "RotationEngine",
            KinematicPart::Helix(_) => "HelixEngine",
            KinematicPart::ServoPid(_) => "ServoPIDController",
            KinematicPart::InterpolatingHelix(_) => "InterpolatingHelixEngine",
            KinematicPart::BicyclePedal(_) => "BicyclePedalEngine",
        }
    }

    /// The engine's own `ids`.
    pub fn ids(&self) -> &[usize] {
        match self {
            KinematicPart::Translation(t) => &t.ids,
            KinematicPart::Rotation(r) => &r.ids,
            KinematicPart::Helix(h) => &h.rot.ids,
            KinematicPart::ServoPid(s) => &s.ids,
            KinematicPart::InterpolatingHelix(h) => &h.helix.rot.ids,
            KinematicPart::BicyclePedal(b) => &b.ids,
        }
    }

    /// The member's `apply` on the combination's `ids`.
    #[allow(clippy::too_many_arguments)]
    pub fn apply(
        &mut self,
        ids: &[usize],
        bodies: &mut Bodies,
        forces: &Forces,
        dt: f64,
        iter: i64,
        time: f64,
    ) -> Result<(), String> {
        match self {
            KinematicPart::Translation(t) => t.apply(ids, bodies),
            KinematicPart::Rotation(r) => r.apply(ids, bodies, dt),
            KinematicPart::Helix(h) => h.apply(ids, bodies, dt),
            KinematicPart::ServoPid(s) => s.apply(ids, bodies, forces, iter),
            KinematicPart::InterpolatingHelix(h) => h.apply(ids, bodies, dt, time)?,
            KinematicPart::BicyclePedal(b) => b.apply(ids, bodies, dt)?,
        }
        Ok(())
    }

    /// `KinematicEngine::action` for an engine run alone: reset its bodies' velocities, then apply.
    pub fn action(
        &mut self,
        bodies: &mut Bodies,
        forces: &Forces,
        dt: f64,
        iter: i64,
        time: f64,
    ) -> Result<(), String> {
        let ids = self.ids().to_vec();
        if ids.is_empty() {
            return Ok(());
        }
        reset_velocities(&ids, bodies);
        self.apply(&ids, bodies, forces, dt, iter, time)
    }
}

/// YADE `CombinedKinematicEngine` (made by `+` on kinematic engines; `ids` are the first engine's):
/// `CombinedKinematicEngine::action` resets the listed bodies' velocities once, then runs the `apply`
/// of every member that is not dead, in order, on these ids.
#[derive(Clone, Debug, Default)]
pub struct CombinedKinematicEngine {
    pub ids: Vec<usize>,
    pub comb: Vec<KinematicPart>,
    /// `dead` of each member (checked at every step, as YADE does).
    pub comb_dead: Vec<bool>,
}

impl CombinedKinematicEngine {
    pub fn action(
        &mut self,
        bodies: &mut Bodies,
        forces: &Forces,
        dt: f64,
        iter: i64,
        time: f64,
    ) -> Result<bool, String> {
        if self.ids.is_empty() {
            return Ok(false);
        }
        reset_velocities(&self.ids, bodies);
        for (k, part) in self.comb.iter_mut().enumerate() {
            if self.comb_dead.get(k).copied().unwrap_or(false) {
                continue;
            }
            part.apply(&self.ids, bodies, forces, dt, iter, time)?;
        }
        Ok(true)
    }
}

/// YADE `ServoPIDController` (attribute names and defaults of 2023.02a; `iterPeriod` 100,
/// `maxVelocity` 0 = always clamped to rest).
#[derive(Clone, Debug)]
pub struct ServoPid {
    pub ids: Vec<usize>,
    pub axis: Vec3,
    /// Target force magnitude along `axis` [N].
    pub target: f64,
    pub current: Vec3,
    pub kp: f64,
    pub ki: f64,
    pub kd: f64,
    pub i_term: f64,
    pub cur_vel: f64,
    pub error_cur: f64,
    pub error_prev: f64,
    pub max_velocity: f64,
    pub iter_period: i64,
    pub iter_prev_start: i64,
    /// Inherited from TranslationEngine; overwritten on every call.
    pub velocity: f64,
    pub translation_axis: Vec3,
}

impl Default for ServoPid {
    fn default() -> Self {
        ServoPid {
            ids: Vec::new(),
            axis: Vec3::zeros(),
            target: 0.0,
            current: Vec3::zeros(),
            kp: 0.0,
            ki: 0.0,
            kd: 0.0,
            i_term: 0.0,
            cur_vel: 0.0,
            error_cur: 0.0,
            error_prev: 0.0,
            max_velocity: 0.0,
            iter_period: 100,
            iter_prev_start: -1,
            velocity: 0.0,
            translation_axis: Vec3::zeros(),
        }
    }
}

impl ServoPid {
    /// `KinematicEngine::action` + `ServoPIDController::apply` (KinematicEngines.cpp). The forces must
    /// be this step's synced ones (the servo normally follows NewtonIntegrator). Quirks kept on purpose:
    /// the error uses the *magnitude* of the axial force (its sign is ignored), the integral term
    /// accumulates `kI * error` without dt, and `axis` is normalised in place at every update.
    pub fn action(&mut self, bodies: &mut Bodies, forces: &Forces, iter: i64) -> bool {
        if self.ids.is_empty() {
            return false;
        }
        reset_velocities(&self.ids, bodies);
        let ids = std::mem::take(&mut self.ids);
        self.apply(&ids, bodies, forces, iter);
        self.ids = ids;
        true
    }

    /// `ServoPIDController::apply` on `ids` (the engine's own or a combination's).
    pub fn apply(&mut self, ids: &[usize], bodies: &mut Bodies, forces: &Forces, iter: i64) {
        if self.iter_prev_start < 0 || iter - self.iter_prev_start >= self.iter_period {
            let mut f = Vec3::zeros();
            for &id in ids {
                if let Some(fi) = forces.ft.get(id).map(|w| &w.f) {
                    f += fi;
                }
            }
            self.axis = normalized(&self.axis);
            let fa = f.component_mul(&self.axis);
            self.error_cur = norm(&fa) - self.target;
            let p_term = self.error_cur * self.kp;
            self.i_term += self.error_cur * self.ki;
            let d_term = (self.error_cur - self.error_prev) * self.kd;
            self.error_prev = self.error_cur;
            self.cur_vel = p_term + self.i_term + d_term;
            if self.cur_vel.abs() > self.max_velocity.abs() {
                self.cur_vel *= self.max_velocity.abs() / self.cur_vel.abs();
            }
            self.iter_prev_start = iter;
            self.current = fa;
        }
        self.translation_axis = self.axis;
        self.velocity = self.cur_vel;
        translate(ids, bodies, self.velocity, &self.translation_axis);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::body::Bodies;

    fn two_bodies() -> Bodies {
        let mut b = Bodies::default();
        for _ in 0..2 {
            b.push(crate::utils::sphere(Vec3::zeros(), 0.1, 0, 1000.0, true));
        }
        b
    }

    /// The PID arithmetic of KinematicEngines.cpp by hand: error from |F·axis|, clamp to maxVelocity,
    /// integral without dt, and the update only every iterPeriod steps.
    #[test]
    fn servo_pid_update_and_clamp() {
        let mut bodies = two_bodies();
        bodies.vel[0] = Vec3::new(5.0, 5.0, 5.0);
        let mut forces = Forces::default();
        forces.resize(2);
        *forces.force_mut(0) = Vec3::new(1.0, 2.0, -30.0);
        *forces.force_mut(1) = Vec3::new(0.0, 0.0, -20.0);
        let mut s = ServoPid {
            ids: vec![0, 1],
            axis: Vec3::new(0.0, 0.0, 2.0),
            target: 40.0,
            kp: 0.01,
            ki: 0.001,
            kd: 0.1,
            max_velocity: 1.0,
            iter_period: 2,
            ..Default::default()
        };
        assert!(s.action(&mut bodies, &forces, 10));
        // |(0, 0, -50)| - 40 = 10; v = 0.1 + 0.01 + 1.0 = 1.11 -> clamped to 1
        assert_eq!(s.error_cur, 10.0);
        assert_eq!(s.axis, Vec3::new(0.0, 0.0, 1.0));
        assert_eq!(s.cur_vel, 1.0);
        assert_eq!(bodies.vel[0], Vec3::new(0.0, 0.0, 1.0));
        assert_eq!(bodies.ang_vel[0], Vec3::zeros());
        // next step: no update (iterPeriod 2), the velocity is held
        *forces.force_mut(1) = Vec3::zeros();
        s.action(&mut bodies, &forces, 11);
        assert_eq!(s.error_cur, 10.0);
        assert_eq!(bodies.vel[1], Vec3::new(0.0, 0.0, 1.0));
        // step 12: |(0,0,-30)| - 40 = -10; v = -0.1 + 0.02 + 0.1*(-20) -> clamped to -1
        s.action(&mut bodies, &forces, 12);
        assert_eq!(s.error_cur, -10.0);
        assert_eq!(s.i_term, 0.0);
        assert_eq!(s.cur_vel, -1.0);
        assert_eq!(s.iter_prev_start, 12);
    }

    /// maxVelocity's default 0 keeps the bodies at rest whatever the error (grid-pid-api.md 3.1).
    #[test]
    fn servo_pid_default_max_velocity_is_rest() {
        let mut bodies = two_bodies();
        let mut forces = Forces::default();
        forces.resize(2);
        *forces.force_mut(0) = Vec3::new(0.0, 0.0, 7.0);
        let mut s = ServoPid {
            ids: vec![0],
            axis: Vec3::new(0.0, 0.0, 1.0),
            kp: 1.0,
            ..Default::default()
        };
        s.action(&mut bodies, &forces, 0);
        assert_eq!(s.cur_vel, 0.0);
        assert_eq!(bodies.vel[0], Vec3::zeros());
    }
}
