//! `NewtonIntegrator` (pkg/dem/NewtonIntegrator.cpp): leap-frog with Cundall's non-viscous damping.
//!
//! Forces were computed from x_n and v_{n-1/2}; this computes v_{n+1/2} then x_{n+1}. Fixed bodies
//! (all DOFs blocked) skip the acceleration but still move with their velocity. Clump members are
//! skipped; a clump takes its members' forces and torques (`Clump::addForceTorqueFromMembers`), is
//! integrated as a rigid body (aspherical rotation when its principal inertia differs) and then
//! places its members (`Clump::moveMembers`).

use crate::body::{Bodies, DOF_ALL};
use crate::cell::Cell;
use crate::energy::{EnergyTracker, IdCache};
use crate::forces::Forces;
use crate::math::{cross, dot, mat_mul, mat_vec, norm2, sign, Mat3, Quat, Vec3};
use crate::shape::Shape;

/// `State::DOF_RXRYRZ`: the three rotational DOF bits.
const DOF_ROT: u8 = 8 | 16 | 32;

#[derive(Clone, Debug)]
pub struct Newton {
    pub damping: f64,
    pub gravity: Vec3,
    pub damp_gravity: bool,
    /// `exactAsphericalRot`: integrate aspherical bodies (clumps) from their angular momentum.
    pub exact_aspherical_rot: bool,
    /// -1: every body; otherwise only bodies whose groupMask shares a bit.
    pub mask: i32,
    /// `kinSplit`: the kinetic energy as `kinTrans` and `kinRot` instead of one `kinetic` entry.
    pub kin_split: bool,
    /// YADE's `maxVelocitySq`, reused by the collider as a displacement indicator:
    /// 0 before any step, 0.5 when every body is still inside its swept bound, 2 otherwise.
    pub max_velocity_sq: f64,
    pub prev_vel_grad: Mat3,
    pub prev_cell_size: Option<Vec3>,
    /// Per-step work lists, kept to avoid an allocation per step (no state).
    pub scratch: Scratch,
    /// Cached `O.energy` indices (`nonviscDampIx`, `kinEnergyIx`, `fieldWorkIx`).
    pub energy_cache: IdCache,
}

/// The bodies whose orientation `leapfrogSphericalRotate` updates and the clumps whose members are
/// moved, in id order, filled by each `Newton::step`.
#[derive(Clone, Debug, Default)]
pub struct Scratch {
    spherical: Vec<u32>,
    clumps: Vec<u32>,
}

impl Default for Newton {
    fn default() -> Self {
        Newton {
            damping: 0.2,
            gravity: Vec3::zeros(),
            damp_gravity: true,
            exact_aspherical_rot: true,
            mask: -1,
            kin_split: false,
            max_velocity_sq: 0.0,
            prev_vel_grad: Mat3::zeros(),
            prev_cell_size: None,
            scratch: Scratch::default(),
            energy_cache: IdCache::default(),
        }
    }
}

/// Problems the integrator refuses to integrate through.
#[derive(Debug, Clone, PartialEq)]
pub enum NewtonError {
    NonFinite { id: usize, what: &'static str },
    BadMass { id: usize },
}

impl Newton {
    /// `NewtonIntegrator::cundallDamp2nd`: damp each acceleration component by the sign of its
    /// product with the mid-step velocity estimate `v + dt/2 a`.
    #[inline(always)]
    fn damp(&self, dt: f64, v: &Vec3, a: &mut Vec3) {
        for i in 0..3 {
            a[i] *= 1.0 - self.damping * sign(a[i] * (v[i] + 0.5 * dt * a[i]));
        }
    }

    /// `NewtonIntegrator::cundallDamp1st`: damp each torque component by the sign of its product
    /// with the current angular velocity (aspherical rotation).
    #[inline(always)]
    fn damp1st(&self, w: &Vec3, m: &mut Vec3) {
        for i in 0..3 {
            m[i] *= 1.0 - self.damping * sign(m[i] * w[i]);
        }
    }

    /// `saveMaximaDisplacement`: 0.5 while a bounded body is inside its swept bound, 2 otherwise.
    #[inline(always)]
    fn save_maxima_displacement(&mut self, bodies: &Bodies, id: usize) {
        if let Some(b) = &bodies.bound[id] {
            let d = bodies.pos[id] - b.ref_pos;
            let md = d[0].abs().max(d[1].abs().max(d[2].abs()));
            let ind = if md == 0.0 || md < b.sweep_length {
                0.5
            } else {
                2.0
            };
            self.max_velocity_sq = self.max_velocity_sq.max(ind);
        }
    }

    /// `NewtonIntegrator::updateEnergy`: body `id`'s damping dissipation, kinetic energy and
    /// gravity work, from the state before this step's update (`f`, `m`: its force and torque).
    #[allow(clippy::too_many_arguments)]
    fn update_energy(
        &mut self,
        e: &mut EnergyTracker,
        bodies: &Bodies,
        id: usize,
        fluct: &Vec3,
        f: &Vec3,
        m: &Vec3,
        dt: f64,
    ) {
        let abs = |v: &Vec3| Vec3::new(v[0].abs(), v[1].abs(), v[2].abs());
        let mass = bodies.mass[id];
        let w = bodies.ang_vel[id];
        let c = &mut self.energy_cache;
        if self.damping != 0.0 && bodies.is_damped[id] {
            let fg = f + self.gravity * mass;
            e.add(
                dot(&abs(fluct), &abs(&fg)) * self.damping * dt,
                "nonviscDamp",
                c,
                false,
            );
            e.add(
                dot(&abs(&w), &abs(m)) * self.damping * dt,
                "nonviscDamp",
                c,
                false,
            );
        }
        let e_trans = 0.5 * mass * norm2(fluct);
        let inertia = bodies.inertia[id];
        let e_rot = if bodies.aspherical[id] {
            // YADE 2023.02a: `T.transpose() * mI * T` with T = ori (the later `T * mI * T^T` is the
            // physically right one; ryade gives YADE's number)
            let t = bodies.ori[id].to_rotation_matrix();
            let tit = mat_mul(&mat_mul(&t.transpose(), &Mat3::from_diagonal(&inertia)), &t);
            0.5 * dot(&w, &mat_vec(&tit, &w))
        } else {
            0.5 * dot(&w, &inertia.component_mul(&w))
        };
        if self.kin_split {
            e.add(e_trans, "kinTrans", c, true);
            e.add(e_rot, "kinRot", c, true);
        } else {
            e.add(e_trans + e_rot, "kinetic", c, true);
        }
        e.add(
            -dot(&self.gravity, &bodies.vel[id]) * mass * dt,
            "gravWork",
            c,
            false,
        );
    }

    /// One `NewtonIntegrator::action` over all bodies (YADE order: forces already synced). Clumps
    /// add their members' forces to their own entry in `forces`, as YADE does. With `energy`
    /// (`O.trackEnergy`), each body's terms are added before its update.
    #[allow(clippy::too_many_arguments)]
    pub fn step(
        &mut self,
        bodies: &mut Bodies,
        forces: &mut Forces,
        cell: Option<&mut Cell>,
        dt: f64,
        pool: Option<&rayon::ThreadPool>,
        energy: Option<&mut EnergyTracker>,
    ) -> Result<(), NewtonError> {
        let mut energy = energy;
        let mut cell = cell;
        if let Some(c) = cell.as_deref_mut() {
            // a velGrad assigned by the user (`Cell::setVelGrad`) takes effect here, after the
            // interaction loop (NewtonIntegrator::action)
            if c.vel_grad_changed || c.next_vel_grad != Mat3::zeros() {
                c.vel_grad = c.next_vel_grad;
                c.vel_grad_changed = false;
                c.next_vel_grad = Mat3::zeros();
            }
        }
        let periodic = cell.is_some();
        let (homo_deform, dvel_grad, dspin) = if let Some(c) = cell.as_deref() {
            // velGrad update and the homothetic terms (zero for a static cell, still evaluated
            // because YADE adds them and the additions turn -0.0 into +0.0)
            let dvg = c.vel_grad - self.prev_vel_grad;
            let r = (dvg - dvg.transpose()) * 0.5;
            (
                c.homo_deform,
                dvg,
                Vec3::new(-r[(1, 2)], r[(0, 2)], -r[(0, 1)]),
            )
        } else {
            (0, Mat3::zeros(), Vec3::zeros())
        };
        self.max_velocity_sq = 0.0;
        if let Some(c) = cell.as_deref() {
            if let Some(prev) = self.prev_cell_size {
                if prev != c.size() {
                    self.max_velocity_sq = norm2(&(prev - c.size())) / (dt * dt);
                }
            }
        }
        let g = self.gravity;
        let Scratch {
            mut spherical,
            mut clumps,
        } = std::mem::take(&mut self.scratch);
        spherical.clear();
        clumps.clear();
        let mut failed = None;
        let n = bodies.len();
        let run_ctx = RunCtx {
            dt,
            damping: self.damping,
            gravity: g,
            damp_gravity: self.damp_gravity,
            periodic,
            homo_deform,
            prev_vel_grad: self.prev_vel_grad,
            dvel_grad,
            dspin,
        };
        let mut id = 0;
        while id < n {
            // a run of plain bodies: the same arithmetic over arrays (see `plain_run`)
            let run = if energy.is_some() {
                0
            } else {
                (id..n.min(id + RUN))
                    .take_while(|&j| self.is_plain(bodies, j))
                    .count()
            };
            if run >= 4 {
                let done = plain_run(&run_ctx, bodies, forces, id, run);
                for j in id..id + done {
                    spherical.push(j as u32);
                    self.save_maxima_displacement(bodies, j);
                }
                if done < run {
                    let j = id + done - 1;
                    failed = Some(non_finite(j, forces.force(j)));
                    break;
                }
                id += run;
                continue;
            }
            let this = id;
            id += 1;
            let id = this;
            // clump members are moved by their clump
            if bodies.is_clump_member(id) {
                continue;
            }
            // a clump carries its own id as `clumpId` (cheaper to read than the shape)
            let is_clump = bodies.clump_id[id].is_some();
            if self.mask > 0 && (bodies.mask[id] & self.mask) == 0 {
                continue;
            }
            if let (true, Shape::Clump(c)) = (is_clump, &bodies.shape[id]) {
                let (cf, ct) =
                    crate::clump::force_torque_from_members(c, bodies, forces, &bodies.pos[id]);
                *forces.torque_mut(id) += ct;
                *forces.force_mut(id) += cf;
            }
            let f = *forces.force(id);
            let mut m = *forces.torque(id);
            let blocked = bodies.blocked[id];
            let use_aspherical =
                self.exact_aspherical_rot && bodies.aspherical[id] && (blocked & DOF_ROT) == 0;
            let fluct = if periodic {
                bodies.vel[id] - mat_vec(&self.prev_vel_grad, &bodies.pos[id])
            } else {
                bodies.vel[id]
            };
            if let Some(e) = energy.as_deref_mut() {
                self.update_energy(e, bodies, id, &fluct, &f, &m, dt);
            }
            if blocked != DOF_ALL {
                let mass = bodies.mass[id];
                let mut a = Vec3::zeros();
                if self.damp_gravity {
                    if blocked == 0 {
                        a = Vec3::new(f[0] / mass + g[0], f[1] / mass + g[1], f[2] / mass + g[2]);
                    } else {
                        for i in 0..3 {
                            if blocked & (1 << i) == 0 {
                                a[i] += f[i] / mass + g[i];
                            }
                        }
                    }
                    if bodies.is_damped[id] {
                        self.damp(dt, &fluct, &mut a);
                    }
                } else {
                    if blocked == 0 {
                        a = Vec3::new(f[0] / mass, f[1] / mass, f[2] / mass);
                    } else {
                        for i in 0..3 {
                            if blocked & (1 << i) == 0 {
                                a[i] += f[i] / mass;
                            }
                        }
                    }
                    if bodies.is_damped[id] {
                        self.damp(dt, &fluct, &mut a);
                    }
                    let mut ga = Vec3::zeros();
                    if blocked == 0 {
                        ga = g;
                    } else {
                        for i in 0..3 {
                            if blocked & (1 << i) == 0 {
                                ga[i] = g[i];
                            }
                        }
                    }
                    a += ga;
                }
                if periodic && homo_deform > 1 {
                    a += mat_vec(&self.prev_vel_grad, &bodies.vel[id]);
                }
                bodies.vel[id] += a * dt;
                if use_aspherical {
                    // torque-driven: no DOF is blocked here, only the torque is damped
                    if bodies.is_damped[id] {
                        let w = bodies.ang_vel[id];
                        self.damp1st(&w, &mut m);
                    }
                } else {
                    let inertia = bodies.inertia[id];
                    let mut aa = Vec3::zeros();
                    if blocked == 0 {
                        aa = Vec3::new(m[0] / inertia[0], m[1] / inertia[1], m[2] / inertia[2]);
                    } else {
                        for i in 0..3 {
                            if blocked & (8 << i) == 0 {
                                aa[i] += m[i] / inertia[i];
                            }
                        }
                    }
                    if bodies.is_damped[id] {
                        let w = bodies.ang_vel[id];
                        self.damp(dt, &w, &mut aa);
                    }
                    bodies.ang_vel[id] += aa * dt;
                }
            } else if periodic && homo_deform > 1 {
                let v = bodies.vel[id];
                bodies.vel[id] += mat_vec(&(self.prev_vel_grad * dt), &v);
            }
            // leapfrogTranslate
            if periodic && homo_deform != 0 {
                let dv = mat_vec(&dvel_grad, &bodies.pos[id]);
                bodies.vel[id] += dv;
            }
            let v = bodies.vel[id];
            bodies.pos[id] += v * dt;
            if use_aspherical {
                leapfrog_aspherical_rotate(bodies, id, dt, &m);
            } else {
                // leapfrogSphericalRotate (the orientation update follows in `rotate_spherical`)
                if periodic && homo_deform != 0 {
                    bodies.ang_vel[id] += dspin;
                }
                spherical.push(id as u32);
            }
            self.save_maxima_displacement(bodies, id);
            if is_clump {
                clumps.push(id as u32);
            }
            if !moved_finite(bodies, id) {
                failed = Some(non_finite(id, &f));
                break;
            }
        }
        // Orientations, then the clump members (they take their clump's new orientation). Each
        // body's arithmetic is that of YADE's single loop; only the order between bodies differs,
        // and no body reads another's orientation. On a failure the bodies up to the failing one
        // are complete and the later ones untouched, as in YADE's loop.
        match pool {
            Some(pool) if spherical.len() >= 2 * ROTATE_CHUNK => {
                rotate_spherical_par(pool, bodies, &spherical, dt)
            }
            _ => rotate_spherical(&mut bodies.ori, &bodies.ang_vel, 0, &spherical, dt),
        }
        for &id in &clumps {
            self.move_members(bodies, id as usize);
        }
        self.scratch = Scratch { spherical, clumps };
        if let Some(e) = failed {
            return Err(e);
        }
        if let Some(c) = cell {
            self.prev_cell_size = Some(c.size());
            self.prev_vel_grad = c.vel_grad;
            c.prev_vel_grad = c.vel_grad;
        }
        Ok(())
    }

    /// A body `plain4` may integrate: standalone (no clump), selected by the mask, no blocked DOF,
    /// spherical rotation.
    #[inline(always)]
    fn is_plain(&self, bodies: &Bodies, id: usize) -> bool {
        bodies.clump_id[id].is_none()
            && (self.mask <= 0 || (bodies.mask[id] & self.mask) != 0)
            && bodies.blocked[id] == 0
            && !(self.exact_aspherical_rot && bodies.aspherical[id])
    }

    /// `Clump::moveMembers` (core/Clump.hpp): each member's pose and velocity from the clump's,
    /// then `saveMaximaDisplacement` for the member.
    fn move_members(&mut self, bodies: &mut Bodies, cid: usize) {
        let Shape::Clump(c) = &bodies.shape[cid] else {
            return;
        };
        let members: Vec<(usize, Vec3, Quat)> = c
            .members
            .iter()
            .map(|m| (m.id as usize, m.rel_pos, m.rel_ori))
            .collect();
        let (cp, co, cv, cw) = (
            bodies.pos[cid],
            bodies.ori[cid],
            bodies.vel[cid],
            bodies.ang_vel[cid],
        );
        for (id, rp, ro) in members {
            let p = cp + co.rotate(&rp);
            bodies.pos[id] = p;
            bodies.ori[id] = co.mul(&ro);
            bodies.vel[id] = cv + cross(&cw, &(p - cp));
            bodies.ang_vel[id] = cw;
            self.save_maxima_displacement(bodies, id);
        }
    }
}

/// Whether body `id`'s new position and velocity are finite (YADE stops the step at the first
/// body where they are not).
#[inline(always)]
fn moved_finite(bodies: &Bodies, id: usize) -> bool {
    bodies.pos[id].iter().all(|x| x.is_finite()) && bodies.vel[id].iter().all(|x| x.is_finite())
}

/// The error for body `id` whose motion came out non-finite, blaming the force `f` if it is.
fn non_finite(id: usize, f: &Vec3) -> NewtonError {
    NewtonError::NonFinite {
        id,
        what: if f.iter().all(|x| x.is_finite()) {
            "position/velocity"
        } else {
            "force"
        },
    }
}

/// Most bodies per `plain_run` call.
const RUN: usize = 64;
type F = [f64; RUN];

/// What `plain_run` needs of the step (the scalar loop's locals).
struct RunCtx {
    dt: f64,
    damping: f64,
    gravity: Vec3,
    damp_gravity: bool,
    periodic: bool,
    homo_deform: i32,
    prev_vel_grad: Mat3,
    dvel_grad: Mat3,
    dspin: Vec3,
}

/// `mat_vec` over the first `len` entries of arrays: row i is `m_i0 v0 + (m_i1 v1 + m_i2 v2)`.
#[inline(always)]
fn mat_vec_run(m: &Mat3, v: &[F; 3], len: usize) -> [F; 3] {
    let mut r = [[0.0; RUN]; 3];
    for (i, ri) in r.iter_mut().enumerate() {
        for j in 0..len {
            ri[j] = m[(i, 0)] * v[0][j] + (m[(i, 1)] * v[1][j] + m[(i, 2)] * v[2][j]);
        }
    }
    r
}

/// `cundallDamp2nd` over arrays, for the entries with `on` set.
#[inline(always)]
fn damp_run(damping: f64, dt: f64, v: &F, a: &mut F, on: &[bool; RUN], len: usize) {
    for j in 0..len {
        let d = a[j] * (1.0 - damping * sign(a[j] * (v[j] + 0.5 * dt * a[j])));
        a[j] = if on[j] { d } else { a[j] };
    }
}

avx2_dispatch! {
    /// The velocity, position and angular-velocity part of `NewtonIntegrator::action` for `len`
    /// (at most `RUN`) consecutive plain bodies (`Newton::is_plain`), component by component over
    /// arrays so that the divisions and matrix products run four wide. Each body gets exactly the
    /// scalar loop's operations (IEEE arithmetic is exact per element, and no FMA is formed), so the
    /// bits are the same. Returns how many bodies were integrated: `len`, or up to and including the
    /// first body whose position or velocity came out non-finite (the later ones untouched, as YADE's
    /// loop stops there).
    fn plain_run / plain_run_avx2 => plain_run_impl(
        c: &RunCtx,
        bodies: &mut Bodies,
        forces: &Forces,
        id0: usize,
        len: usize,
    ) -> usize
}

#[inline(always)]
fn plain_run_impl(
    c: &RunCtx,
    bodies: &mut Bodies,
    forces: &Forces,
    id0: usize,
    len: usize,
) -> usize {
    let ids = id0..id0 + len;
    let get = |a: &[Vec3]| -> [F; 3] {
        let mut r = [[0.0; RUN]; 3];
        for (j, x) in a.iter().enumerate() {
            for k in 0..3 {
                r[k][j] = x[k];
            }
        }
        r
    };
    let (mut f, mut m) = ([[0.0; RUN]; 3], [[0.0; RUN]; 3]);
    for (j, w) in forces.ft[ids.clone()].iter().enumerate() {
        for k in 0..3 {
            f[k][j] = w.f[k];
            m[k][j] = w.t[k];
        }
    }
    let mut vel = get(&bodies.vel[ids.clone()]);
    let pos = get(&bodies.pos[ids.clone()]);
    let mut w = get(&bodies.ang_vel[ids.clone()]);
    let inertia = get(&bodies.inertia[ids.clone()]);
    let mut mass = [1.0; RUN];
    mass[..len].copy_from_slice(&bodies.mass[ids.clone()]);
    let mut damped = [false; RUN];
    damped[..len].copy_from_slice(&bodies.is_damped[ids.clone()]);
    let (dt, g) = (c.dt, c.gravity);
    let fluct = if c.periodic {
        let mv = mat_vec_run(&c.prev_vel_grad, &pos, len);
        let mut r = vel;
        for k in 0..3 {
            for j in 0..len {
                r[k][j] = vel[k][j] - mv[k][j];
            }
        }
        r
    } else {
        vel
    };
    let mut a = [[0.0; RUN]; 3];
    for k in 0..3 {
        for j in 0..len {
            a[k][j] = if c.damp_gravity {
                f[k][j] / mass[j] + g[k]
            } else {
                f[k][j] / mass[j]
            };
        }
        damp_run(c.damping, dt, &fluct[k], &mut a[k], &damped, len);
        if !c.damp_gravity {
            for x in a[k][..len].iter_mut() {
                *x += g[k];
            }
        }
    }
    if c.periodic && c.homo_deform > 1 {
        let mv = mat_vec_run(&c.prev_vel_grad, &vel, len);
        for k in 0..3 {
            for j in 0..len {
                a[k][j] += mv[k][j];
            }
        }
    }
    for k in 0..3 {
        for j in 0..len {
            vel[k][j] += a[k][j] * dt;
        }
    }
    let mut aa = [[0.0; RUN]; 3];
    for k in 0..3 {
        for j in 0..len {
            aa[k][j] = m[k][j] / inertia[k][j];
        }
        damp_run(c.damping, dt, &w[k], &mut aa[k], &damped, len);
        for j in 0..len {
            w[k][j] += aa[k][j] * dt;
        }
    }
    if c.periodic && c.homo_deform != 0 {
        let dv = mat_vec_run(&c.dvel_grad, &pos, len);
        for k in 0..3 {
            for j in 0..len {
                vel[k][j] += dv[k][j];
                w[k][j] += c.dspin[k];
            }
        }
    }
    let mut new_pos = pos;
    for k in 0..3 {
        for j in 0..len {
            new_pos[k][j] = pos[k][j] + vel[k][j] * dt;
        }
    }
    for j in 0..len {
        let id = id0 + j;
        bodies.vel[id] = Vec3::new(vel[0][j], vel[1][j], vel[2][j]);
        bodies.ang_vel[id] = Vec3::new(w[0][j], w[1][j], w[2][j]);
        bodies.pos[id] = Vec3::new(new_pos[0][j], new_pos[1][j], new_pos[2][j]);
        if !moved_finite(bodies, id) {
            return j + 1;
        }
    }
    len
}

/// Bodies per task of the parallel orientation pass.
const ROTATE_CHUNK: usize = 1024;

/// `rotate_spherical` on the thread pool: the id list (ascending) is cut into runs and each run
/// gets the disjoint slice of orientations its ids fall in; per body the same arithmetic, so the
/// bits do not depend on the thread count.
fn rotate_spherical_par(pool: &rayon::ThreadPool, bodies: &mut Bodies, ids: &[u32], dt: f64) {
    let mut jobs = Vec::with_capacity(ids.len() / ROTATE_CHUNK + 1);
    let mut rest: &mut [Quat] = &mut bodies.ori;
    let mut base = 0usize;
    for run in ids.chunks(ROTATE_CHUNK) {
        let end = run[run.len() - 1] as usize + 1;
        let (mine, tail) = std::mem::take(&mut rest).split_at_mut(end - base);
        jobs.push((mine, base, run));
        rest = tail;
        base = end;
    }
    let ang_vel = &bodies.ang_vel;
    pool.install(|| {
        use rayon::prelude::*;
        jobs.into_par_iter()
            .for_each(|(ori, base, run)| rotate_spherical(ori, ang_vel, base, run, dt));
    });
}

avx2_dispatch! {
    /// The orientation half of `NewtonIntegrator::leapfrogSphericalRotate` for the listed bodies:
    /// `ori = AngleAxis(|w| dt, w/|w|) * ori` (skipped when `w = 0`), then `ori.normalize()`
    /// (`rotate_spherical_impl`), compiled for AVX2 when the CPU has it. `ori` holds the orientations
    /// of the bodies from id `base` on.
    fn rotate_spherical / rotate_spherical_avx2 => rotate_spherical_impl(
        ori: &mut [Quat],
        ang_vel: &[Vec3],
        base: usize,
        ids: &[u32],
        dt: f64,
    )
}

/// `rotate_spherical` in three passes per block, the first and last over arrays (component by
/// component, so that square roots and divisions run four wide; every body's values get the
/// operations of the one-pass form, so the same bits): |ω|, the axis ω/|ω| and the angle; the
/// quaternion product (sin/cos one body at a time); the normalisation.
#[inline(always)]
fn rotate_spherical_impl(ori: &mut [Quat], ang_vel: &[Vec3], base: usize, ids: &[u32], dt: f64) {
    const BLOCK: usize = 64;
    for block in ids.chunks(BLOCK) {
        let mut w = [[0.0; BLOCK]; 3];
        for (j, &id) in block.iter().enumerate() {
            for k in 0..3 {
                w[k][j] = ang_vel[id as usize][k];
            }
        }
        // w2 = 0: no rotation (the axis and angle computed for it are not used)
        let mut w2 = [0.0; BLOCK];
        let (mut angle, mut axis) = ([0.0; BLOCK], [[0.0; BLOCK]; 3]);
        for j in 0..BLOCK {
            w2[j] = w[0][j] * w[0][j] + (w[1][j] * w[1][j] + w[2][j] * w[2][j]);
            let wn = w2[j].sqrt();
            angle[j] = wn * dt;
            for k in 0..3 {
                axis[k][j] = w[k][j] / wn;
            }
        }
        let mut q = [[0.0; BLOCK]; 4];
        for (j, &id) in block.iter().enumerate() {
            let mut q0 = ori[id as usize - base];
            if w2[j] != 0.0 {
                let ax = Vec3::new(axis[0][j], axis[1][j], axis[2][j]);
                q0 = Quat::from_angle_axis(angle[j], &ax).mul(&q0);
            }
            (q[0][j], q[1][j], q[2][j], q[3][j]) = (q0.x, q0.y, q0.z, q0.w);
        }
        // Quat::normalize: divide by sqrt(squaredNorm) when it is positive
        for j in 0..BLOCK {
            let z =
                (q[0][j] * q[0][j] + q[1][j] * q[1][j]) + (q[2][j] * q[2][j] + q[3][j] * q[3][j]);
            let n = z.sqrt();
            for c in q.iter_mut() {
                c[j] = if z > 0.0 { c[j] / n } else { c[j] };
            }
        }
        for (j, &id) in block.iter().enumerate() {
            let o = &mut ori[id as usize - base];
            (o.x, o.y, o.z, o.w) = (q[0][j], q[1][j], q[2][j], q[3][j]);
        }
    }
}

/// `NewtonIntegrator::DotQ`: the quaternion derivative for a body-frame angular velocity `w`.
#[inline(always)]
fn dot_q(w: &Vec3, q: &Quat) -> Quat {
    Quat {
        w: (-q.x * w[0] - q.y * w[1] - q.z * w[2]) / 2.0,
        x: (q.w * w[0] - q.z * w[1] + q.y * w[2]) / 2.0,
        y: (q.z * w[0] + q.w * w[1] - q.x * w[2]) / 2.0,
        z: (-q.y * w[0] + q.x * w[1] + q.w * w[2]) / 2.0,
    }
}

/// `NewtonIntegrator::leapfrogAsphericalRotate`: angular momentum leap-frog with a mid-step
/// quaternion; `angVel` is recomputed from the momentum (the stored `angVel` of an aspherical body
/// is output only: YADE quirk, setting it by hand has no effect on the motion).
fn leapfrog_aspherical_rotate(bodies: &mut Bodies, id: usize, dt: f64, m: &Vec3) {
    let ori = bodies.ori[id];
    let inertia = bodies.inertia[id];
    let a = ori.conjugate().to_rotation_matrix();
    let half = dt / 2.0;
    let l_n = bodies.ang_mom[id] + Vec3::new(half * m[0], half * m[1], half * m[2]);
    let l_b_n = mat_vec(&a, &l_n);
    let w_b_n = Vec3::new(
        l_b_n[0] / inertia[0],
        l_b_n[1] / inertia[1],
        l_b_n[2] / inertia[2],
    );
    let dq_n = dot_q(&w_b_n, &ori);
    let q_half = Quat {
        x: ori.x + half * dq_n.x,
        y: ori.y + half * dq_n.y,
        z: ori.z + half * dq_n.z,
        w: ori.w + half * dq_n.w,
    };
    bodies.ang_mom[id] += Vec3::new(dt * m[0], dt * m[1], dt * m[2]);
    let l_b_half = mat_vec(&a, &bodies.ang_mom[id]);
    let w_b_half = Vec3::new(
        l_b_half[0] / inertia[0],
        l_b_half[1] / inertia[1],
        l_b_half[2] / inertia[2],
    );
    let dq_half = dot_q(&w_b_half, &q_half);
    let mut q = Quat {
        x: ori.x + dt * dq_half.x,
        y: ori.y + dt * dq_half.y,
        z: ori.z + dt * dq_half.z,
        w: ori.w + dt * dq_half.w,
    };
    bodies.ang_vel[id] = q.rotate(&w_b_half);
    q.normalize();
    bodies.ori[id] = q;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::body::BodySpec;

    fn ball(x: f64, w: f64) -> BodySpec {
        BodySpec {
            shape: Shape::Sphere { radius: 0.1 },
            material: 0,
            mask: 1,
            bounded: false,
            pos: Vec3::new(x, 0.0, 0.0),
            vel: Vec3::new(1.0, 0.0, 0.0),
            ang_vel: Vec3::new(0.0, 0.0, w),
            ori: Quat::IDENTITY,
            mass: 1.0,
            inertia: Vec3::repeat(0.004),
            blocked: 0,
            is_damped: true,
        }
    }

    /// The orientation pass runs after the translation pass; a body's new orientation must still be
    /// YADE's `AngleAxis(|w| dt, w/|w|) * ori` (a spin about z by 2 rad/s for 0.1 s turns it by
    /// 0.2 rad), and a failing body must leave the bodies before it complete and those after it
    /// untouched, as YADE's single loop does.
    #[test]
    fn orientation_pass_and_failure_keep_the_single_loop_semantics() {
        let mut bodies = Bodies::default();
        for (x, w) in [(0.0, 2.0), (1.0, 2.0), (2.0, 2.0)] {
            bodies.push(ball(x, w));
        }
        let mut forces = Forces::default();
        forces.reset(3, 0);
        forces.sync();
        let mut n = Newton {
            damping: 0.0,
            ..Default::default()
        };
        n.step(&mut bodies, &mut forces, None, 0.1, None, None)
            .unwrap();
        let half = 0.5 * (2.0f64 * 0.1);
        for id in 0..3 {
            let q = bodies.ori[id];
            assert!((q.w - half.cos()).abs() < 1e-15 && (q.z - half.sin()).abs() < 1e-15);
            assert_eq!((q.x, q.y), (0.0, 0.0));
            assert!((bodies.pos[id][0] - (id as f64 + 0.1)).abs() < 1e-15);
        }
        let before: Vec<(Vec3, Quat)> = (0..3).map(|i| (bodies.pos[i], bodies.ori[i])).collect();
        bodies.vel[1][1] = f64::NAN;
        let e = n
            .step(&mut bodies, &mut forces, None, 0.1, None, None)
            .unwrap_err();
        assert_eq!(
            e,
            NewtonError::NonFinite {
                id: 1,
                what: "position/velocity"
            }
        );
        // body 0 complete (moved and turned again), body 2 untouched
        assert!((bodies.pos[0][0] - 0.2).abs() < 1e-15);
        assert!((bodies.ori[0].z - (2.0 * half).sin()).abs() < 1e-15);
        assert_eq!((bodies.pos[2], bodies.ori[2]), before[2]);
    }

    /// Bodies with forces, torques and velocities of every sign, damped and undamped.
    fn varied(n: usize) -> (Bodies, Forces) {
        let mut bodies = Bodies::default();
        let mut forces = Forces::default();
        forces.reset(n, 0);
        for i in 0..n {
            let t = i as f64 + 1.0;
            let mut b = ball(0.3 * t, (-1.0f64).powi(i as i32) * 0.7 * t);
            b.vel = Vec3::new(0.1 * t.sin(), -0.2 * t.cos(), 0.05 * t);
            b.mass = 0.5 + 0.1 * t;
            b.inertia = Vec3::new(0.003, 0.004, 0.005) * t;
            b.is_damped = i % 3 != 0;
            bodies.push(b);
            *forces.force_mut(i) = Vec3::new((1.3 * t).sin(), -(0.7 * t).cos(), 0.2 * t - 1.0);
            *forces.torque_mut(i) = Vec3::new(0.01 * t.cos(), 0.02 * (2.0 * t).sin(), -0.003 * t);
        }
        (bodies, forces)
    }

    /// The array path for runs of plain bodies (`plain_run`) gives each body exactly the bits of
    /// the one-body loop: ten bodies integrated together equal each integrated alone (a run of
    /// one takes the scalar path), with damping, gravity inside and outside the damping, and a
    /// periodic cell whose velocity gradient brings in the homothetic terms.
    #[test]
    fn runs_of_plain_bodies_give_the_one_body_bits() {
        let mut cell = Cell::new(Mat3::identity() * 2.0).unwrap();
        cell.vel_grad = Mat3::new(0.1, 0.02, 0.0, -0.03, 0.05, 0.01, 0.0, 0.04, -0.2);
        for (damp_gravity, periodic) in [(true, false), (false, false), (true, true), (false, true)]
        {
            let newton = Newton {
                gravity: Vec3::new(0.0, -9.81, 1.5),
                damp_gravity,
                prev_vel_grad: Mat3::new(0.05, 0.0, 0.01, 0.0, -0.02, 0.0, 0.03, 0.0, 0.01),
                ..Default::default()
            };
            let (mut all, mut f_all) = varied(10);
            let mut c = cell.clone();
            newton
                .clone()
                .step(
                    &mut all,
                    &mut f_all,
                    periodic.then_some(&mut c),
                    1e-3,
                    None,
                    None,
                )
                .unwrap();
            let (reference, f_ref) = varied(10);
            for id in 0..10 {
                let mut one = Bodies::default();
                let mut f_one = Forces::default();
                f_one.reset(1, 0);
                one.push(ball(0.0, 0.0));
                for (dst, src) in [
                    (&mut one.pos, &reference.pos),
                    (&mut one.vel, &reference.vel),
                ] {
                    dst[0] = src[id];
                }
                one.ang_vel[0] = reference.ang_vel[id];
                one.mass[0] = reference.mass[id];
                one.inertia[0] = reference.inertia[id];
                one.is_damped[0] = reference.is_damped[id];
                f_one.ft[0] = f_ref.ft[id];
                let mut c = cell.clone();
                newton
                    .clone()
                    .step(
                        &mut one,
                        &mut f_one,
                        periodic.then_some(&mut c),
                        1e-3,
                        None,
                        None,
                    )
                    .unwrap();
                let same = |a: &Vec3, b: &Vec3| (0..3).all(|k| a[k].to_bits() == b[k].to_bits());
                assert!(
                    same(&one.pos[0], &all.pos[id]),
                    "pos {id} {damp_gravity} {periodic}"
                );
                assert!(
                    same(&one.vel[0], &all.vel[id]),
                    "vel {id} {damp_gravity} {periodic}"
                );
                assert!(same(&one.ang_vel[0], &all.ang_vel[id]), "angVel {id}");
                assert_eq!(one.ori[0], all.ori[id], "ori {id}");
            }
        }
    }

    /// A non-finite force in the middle of a run: the bodies before it complete, the failing one
    /// updated, the later ones untouched, and the error names it, as YADE's loop stops there.
    #[test]
    fn a_failure_inside_a_run_keeps_the_single_loop_semantics() {
        let (mut bodies, mut forces) = varied(10);
        let before = bodies.clone();
        forces.force_mut(6)[2] = f64::INFINITY;
        let e = Newton::default()
            .step(&mut bodies, &mut forces, None, 1e-3, None, None)
            .unwrap_err();
        assert_eq!(
            e,
            NewtonError::NonFinite {
                id: 6,
                what: "force"
            }
        );
        for id in 0..7 {
            assert_ne!(bodies.pos[id], before.pos[id], "body {id} integrated");
        }
        for id in 7..10 {
            assert_eq!(bodies.pos[id], before.pos[id], "body {id} untouched");
            assert_eq!(bodies.vel[id], before.vel[id], "body {id} untouched");
        }
    }
}
