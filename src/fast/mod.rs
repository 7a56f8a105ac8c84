//! The fast path (issue 6): a stepper for sphere scenes built from a `Scene`, free to reorder sums.
//!
//! Same physics as the YADE-order path (FrictMat, `Ig2_Sphere_Sphere_ScGeom` with
//! `avoidGranularRatcheting`, `Ip2_FrictMat_FrictMat_FrictPhys`, `Law2_ScGeom_FrictPhys_CundallStrack`,
//! `NewtonIntegrator` with damping and gravity, a static periodic cell or an open domain), laid out
//! for speed:
//!
//! * `neighbors`: a cell-list Verlet list with a skin (rebuilt only when some body has moved more
//!   than skin/2) instead of YADE's insertion-sort collider; bodies renumbered in cell order;
//! * `contact`: pair list and contact state in flat arrays, one fused kernel per pair;
//! * `newton`: the integrator with reciprocal masses;
//! * threads (rayon): the pair list is cut at body boundaries into one chunk per thread; a chunk
//!   owns the bodies whose pairs it holds and sums their forces in place, and queues the forces on
//!   other chunks' bodies, which are added after the parallel phase in chunk order. The result
//!   depends on the thread count only through the chunk boundaries: the same thread count gives
//!   the same bits on every run (one thread: no queue, the serial sums).
//!
//! Results agree with YADE (and the YADE-order path) to round-off at first, statistically after
//! the chaotic growth of differences in a dense packing. `write_back` returns the state to the
//! `Scene`, contacts included, so both paths can be mixed.

mod boundary;
pub mod contact;
#[cfg(target_arch = "x86_64")]
mod contact_simd;
mod grid;
pub mod neighbors;
pub mod newton;
#[cfg(target_arch = "x86_64")]
pub mod newton_simd;
mod six;
#[cfg(target_arch = "x86_64")]
mod six_simd;
#[cfg(target_arch = "x86_64")]
pub(crate) use six_simd::{rotations_lanes, RotOf};

/// Whether the lanes of this module can run here (AVX2).
pub(crate) fn lanes_available() -> bool {
    #[cfg(target_arch = "x86_64")]
    return std::is_x86_feature_detected!("avx2");
    #[cfg(not(target_arch = "x86_64"))]
    false
}

use crate::body::DOF_ALL;
use crate::geom::ScGeom;
use crate::interaction::{GeomFunctor, Interaction};
use crate::math::{Quat, Vec3};
use crate::phys::FrictPhys;
use crate::scene::{Engine, Scene};
use crate::shape::Shape;
use contact::{Contact, Mat, Pair, Two, V3};
use rayon::prelude::*;
use rustc_hash::FxHashMap;

/// Options of the fast path.
#[derive(Clone, Copy, Debug)]
pub struct FastOptions {
    /// Worker threads (1: no thread pool).
    pub threads: usize,
    /// Verlet skin as a fraction of the smallest radius.
    pub skin: f64,
}

impl Default for FastOptions {
    fn default() -> Self {
        FastOptions {
            threads: 1,
            skin: 0.3,
        }
    }
}

/// One thread's share: a run of the pair list and the bodies it owns (every body i of its pairs;
/// the owned ranges partition the bodies). It writes forces of owned bodies in place and queues
/// those of other chunks' bodies (`ghosts`), added after the parallel phase in chunk order.
struct Chunk {
    pairs: std::ops::Range<usize>,
    lo: usize,
    hi: usize,
    ghosts: Vec<Ghost>,
}

/// A force and torque for a body owned by another chunk.
#[derive(Clone, Copy)]
struct Ghost {
    j: u32,
    f: V3,
    t: V3,
}

/// Contact states kept over a Verlet rebuild, by scene ids (lower id first).
struct Known {
    plain: FxHashMap<(u32, u32), Contact>,
    six: FxHashMap<(u32, u32), six::C6>,
}

/// Memory held by the fast path, in bytes.
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct Memory {
    pub per_particle: f64,
    pub per_contact: f64,
    pub per_pair: f64,
}

pub struct FastSim {
    pub iter: i64,
    pub time: f64,
    cfg: newton::Cfg,
    period: Option<V3>,
    skin: f64,
    /// `ids[k]`: the scene id of body k (bodies are kept in spatial order).
    ids: Vec<u32>,
    pos: Vec<V3>,
    vel: Vec<V3>,
    ang_vel: Vec<V3>,
    ori: Vec<Quat>,
    radius: Vec<f64>,
    inert: Vec<newton::Inert>,
    mat: Vec<u32>,
    x_ref: Vec<V3>,
    force: Vec<V3>,
    torque: Vec<V3>,
    mats: Vec<Mat>,
    pairs: Vec<Pair>,
    contacts: Vec<Contact>,
    /// `contacts[q].active` as a byte: the lanes' first pass reads these 29 kB for the dense
    /// script's 29,000 pairs instead of one cache line per contact. Set at each list build, kept
    /// equal by the pair loops (`chunk_forces`).
    flags: Vec<u8>,
    shifts: Vec<V3>,
    shift_cells: Vec<[i32; 3]>,
    chunks: Vec<Chunk>,
    /// Fixed walls, boxes and facets and their contacts with the spheres.
    bnd: boundary::Boundaries,
    /// The study's piston engine (its index in the scene's engines), run after the integration.
    piston: Option<(usize, crate::piston::PistonController)>,
    /// An engine asked to end the run after this step (the piston's stops).
    stop: bool,
    /// Rolling-resistance contacts (ScGeom6D + CohFrictPhys) instead of `contacts`.
    six: Option<six::SixCfg>,
    /// The geogrid: nodes, bonds, sphere-connection contacts.
    grid: Option<grid::GridPart>,
    /// An error of the grid's interaction loop (the run stops; `take_error`).
    error: Option<String>,
    contacts6: Vec<six::C6>,
    /// With `SixCfg::defer_rotations`: the orientations at the last step's contact phase (the
    /// operands of its rotations), empty before the first step.
    ori_prev: Vec<Quat>,
    fmats: Vec<crate::material::FrictMat>,
    pool: Option<rayon::ThreadPool>,
    threads: usize,
    max_disp2: f64,
    /// Number of Verlet list builds so far.
    pub rebuilds: u64,
    /// Seconds spent so far in list builds, contact forces and integration.
    pub timing: Timing,
}

/// The spheres as a list build leaves them (the fast path's slots, spatially sorted), for the
/// boundaries' and the grid's candidate lists.
pub(super) struct Listing<'a> {
    pub ids: &'a [u32],
    /// Scene id -> slot (u32::MAX: no sphere of the fast path).
    pub slot: Vec<u32>,
    pub pos: &'a [V3],
    /// `pos` wrapped into the periodic cell (`neighbors::Built::wrapped`).
    pub wrapped: &'a [V3],
    pub rad: &'a [f64],
    /// The list build's cells (`neighbors::Built::cells`).
    pub cells: &'a neighbors::Cells,
}

impl<'a> Listing<'a> {
    pub fn new(
        ids: &'a [u32],
        pos: &'a [V3],
        wrapped: &'a [V3],
        rad: &'a [f64],
        cells: &'a neighbors::Cells,
    ) -> Listing<'a> {
        let mut slot = vec![u32::MAX; ids.iter().map(|&id| id as usize + 1).max().unwrap_or(0)];
        for (k, &id) in ids.iter().enumerate() {
            slot[id as usize] = k as u32;
        }
        Listing {
            ids,
            slot,
            pos,
            wrapped,
            rad,
            cells,
        }
    }

    /// The slot of scene body `id`, when it is one of the fast path's spheres.
    pub fn slot_of(&self, id: u32) -> Option<u32> {
        self.slot
            .get(id as usize)
            .copied()
            .filter(|&k| k != u32::MAX)
    }
}

/// Where the fast path's time goes (wall clock, summed over steps).
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct Timing {
    pub rebuild: f64,
    pub contacts: f64,
    /// The geogrid's part of `contacts`.
    pub grid: f64,
    pub newton: f64,
}

/// What the contact kernel reads of the bodies.
struct View<'a> {
    pos: &'a [V3],
    vel: &'a [V3],
    w: &'a [V3],
    rad: &'a [f64],
    mats: &'a [Mat],
    mat: &'a [u32],
    shifts: &'a [V3],
    dt: f64,
}

impl View<'_> {
    /// Panics unless the body arrays have one length; in debug builds also unless every pair's
    /// bodies and shift are in the view (release builds check the pairs after each list build).
    #[inline(always)]
    fn check(&self, pairs: &[Pair]) {
        let n = self.pos.len();
        assert!(
            self.vel.len() == n && self.w.len() == n && self.rad.len() == n,
            "the fast path's body arrays differ in length"
        );
        debug_assert!(pairs_in_range(pairs, n, self.shifts.len()));
    }
}

/// Whether every pair has `i < j < n` and `img < shifts`.
fn pairs_in_range(pairs: &[Pair], n: usize, shifts: usize) -> bool {
    pairs
        .iter()
        .all(|p| p.i < p.j && (p.j as usize) < n && (p.img as usize) < shifts)
}

/// Forces and torques of a run of pairs (sorted by i) into `acc` (see `Acc`). Body i's sums stay
/// in registers while its pairs last. With AVX2: four pairs at a time (`contact_simd`, the same
/// bits). `flags`: the states' `active` as bytes (`FastSim::flags`), read by the lanes and kept
/// equal.
///
/// # Safety
/// Every pair has `i < j < v.pos.len()` and `img < v.shifts.len()` (the lanes read the bodies and
/// shifts unchecked; `FastSim::rebuild_with` checks the list where it is made).
unsafe fn chunk_forces(v: &View, pairs: &[Pair], cs: &mut [Contact], flags: &mut [u8], acc: Acc) {
    #[cfg(target_arch = "x86_64")]
    if std::is_x86_feature_detected!("avx2") {
        v.check(pairs);
        // SAFETY: the CPU has AVX2 (checked just above), the body arrays have one length (checked
        // by `check`) and the pairs are in range (this function's contract)
        return unsafe { contact_simd::chunk(v, pairs, cs, flags, acc) };
    }
    chunk_loop(&Plain(v), pairs, cs, acc);
    for (f, c) in flags.iter_mut().zip(cs.iter()) {
        *f = c.active as u8;
    }
}

/// The integrator over a run of bodies; returns the largest squared displacement since `x_ref`.
/// With AVX2: four bodies at a time (`newton_simd`, the same bits).
fn integrate(cfg: &newton::Cfg, r: newton::Run) -> f64 {
    #[cfg(target_arch = "x86_64")]
    if std::is_x86_feature_detected!("avx2") {
        if std::is_x86_feature_detected!("avx512f") && std::is_x86_feature_detected!("avx512vl") {
            // SAFETY: the CPU has AVX2, AVX-512F and AVX-512VL (checked just above)
            return unsafe { newton_simd::integrate_evex(cfg, r) };
        }
        // SAFETY: the CPU has AVX2 (checked just above)
        return unsafe { newton_simd::integrate(cfg, r) };
    }
    integrate_impl(cfg, r)
}

#[inline(always)]
pub(crate) fn integrate_impl(cfg: &newton::Cfg, r: newton::Run) -> f64 {
    let newton::Run {
        inert,
        f,
        t,
        x,
        v,
        w,
        q,
        x_ref,
    } = r;
    let n = x.len();
    let (inert, f, t, v, w, q, x_ref) = (
        &inert[..n],
        &f[..n],
        &t[..n],
        &mut v[..n],
        &mut w[..n],
        &mut q[..n],
        &x_ref[..n],
    );
    let mut md: f64 = 0.0;
    // motion, then orientation, per block of bodies: two short loops whose iterations overlap
    // better than one long one
    const BLOCK: usize = 64;
    for b0 in (0..n).step_by(BLOCK) {
        let b1 = (b0 + BLOCK).min(n);
        for k in b0..b1 {
            let d = newton::motion(
                cfg, &inert[k], f[k], t[k], &mut x[k], &mut v[k], &mut w[k], &x_ref[k],
            );
            md = md.max(d);
        }
        for k in b0..b1 {
            newton::turn(cfg.dt, &w[k], &mut q[k]);
        }
    }
    md
}

/// One listed pair's work: the force on body i and the torques on i and j (None: no load).
trait Kernel {
    type C;
    /// What the kernel keeps of body i while its pairs last.
    type I: Copy;
    fn body(&self, i: usize) -> Self::I;
    fn pair(&self, bi: &Self::I, p: &Pair, c: &mut Self::C) -> Option<(V3, V3, V3)>;
    /// Whether `pair` would certainly return None and leave `c` as it is (a potential pair that
    /// does not touch), tested without gathering the bodies' kinematics.
    fn idle(&self, p: &Pair, c: &Self::C) -> bool;
    /// Ask the CPU to bring what `pair` will read of a state out of line (a hint: no effect on
    /// results), a few pairs ahead.
    #[inline(always)]
    fn prefetch(&self, _c: &Self::C) {}
}

/// The Cundall-Strack kernel (`contact::pair`).
struct Plain<'a, 'b>(&'a View<'b>);

impl Kernel for Plain<'_, '_> {
    type C = Contact;
    type I = (V3, V3, V3, f64);
    #[inline(always)]
    fn body(&self, i: usize) -> Self::I {
        let v = self.0;
        (v.pos[i], v.vel[i], v.w[i], v.rad[i])
    }
    #[inline(always)]
    fn pair(&self, bi: &Self::I, pr: &Pair, c: &mut Contact) -> Option<(V3, V3, V3)> {
        let v = self.0;
        let (i, j) = (pr.i as usize, pr.j as usize);
        let (xi, vi, wi, ri) = *bi;
        let two = Two {
            xi,
            xj: contact::add(v.pos[j], v.shifts[pr.img as usize]),
            vi,
            vj: v.vel[j],
            wi,
            wj: v.w[j],
            ri,
            rj: v.rad[j],
        };
        let created = |c: &mut Contact| {
            contact::create(
                c,
                &v.mats[v.mat[i] as usize],
                &v.mats[v.mat[j] as usize],
                ri,
                two.rj,
            )
        };
        contact::pair(c, &two, v.dt, created).map(|l| (l.f, l.ti, l.tj))
    }
    #[inline(always)]
    fn idle(&self, p: &Pair, c: &Contact) -> bool {
        // contact::pair's test, in its operations
        let v = self.0;
        let (i, j) = (p.i as usize, p.j as usize);
        let xj = contact::add(v.pos[j], v.shifts[p.img as usize]);
        let (_, d2, rs) = contact::separation(v.pos[i], xj, v.rad[i], v.rad[j]);
        !c.active && contact::apart(d2, rs)
    }
}

/// The rolling-resistance kernel (`six::pair`).
struct Six<'a, 'b> {
    cfg: &'a six::SixCfg,
    b: &'a six::Bodies6<'b>,
}

impl Kernel for Six<'_, '_> {
    type C = six::C6;
    type I = ();
    #[inline(always)]
    fn body(&self, _: usize) {}
    #[inline(always)]
    fn pair(&self, _: &(), p: &Pair, c: &mut six::C6) -> Option<(V3, V3, V3)> {
        six::pair(self.cfg, self.b, p, c)
    }
    #[inline(always)]
    fn idle(&self, p: &Pair, c: &six::C6) -> bool {
        six::idle(self.cfg, self.b, p, c)
    }
    #[inline(always)]
    fn prefetch(&self, c: &six::C6) {
        // a real contact's state lives in its own allocation
        if let Some(s) = c.0.as_deref() {
            crate::interaction::prefetch_value(s);
        }
    }
}

/// `chunk_forces` for rolling-resistance contacts. With AVX2: the contacts' rotations four at a
/// time (`six_simd`, the same bits).
///
/// # Safety
/// Every pair has `i < j < k.b.pos.len()` (the first pass reads positions and radii unchecked;
/// `FastSim::rebuild_with` checks the list where it is made).
unsafe fn chunk_forces6(k: &Six, pairs: &[Pair], cs: &mut [six::C6], acc: Acc) {
    #[cfg(target_arch = "x86_64")]
    if std::is_x86_feature_detected!("avx2") {
        assert_eq!(k.b.rad.len(), k.b.pos.len());
        debug_assert!(pairs_in_range(pairs, k.b.pos.len(), k.b.shifts.len()));
        // SAFETY: the CPU has AVX2 (checked just above), the radii are as many as the positions
        // (asserted just above) and the pairs are in range (this function's contract)
        return unsafe { six_simd::chunk(k, pairs, cs, acc) };
    }
    chunk_loop(k, pairs, cs, acc)
}

/// The pair loop of one chunk (see `chunk_forces`). Per block of pairs, a first pass keeps those
/// the kernel may load (`Kernel::idle`: no branch, no kinematics), the second runs the kernel on
/// them in the pairs' order.
#[inline(always)]
fn chunk_loop<K: Kernel>(k: &K, pairs: &[Pair], cs: &mut [K::C], mut acc: Acc) {
    const BLOCK: usize = 256;
    const AHEAD: usize = 6;
    let np = pairs.len();
    let cs = &mut cs[..np];
    let mut work = [0u32; BLOCK];
    let mut bi = None;
    for b0 in (0..np).step_by(BLOCK) {
        let nw = kept(k, pairs, cs, b0..(b0 + BLOCK).min(np), &mut work);
        for w in 0..nw {
            if w + AHEAD < nw {
                k.prefetch(&cs[work[w + AHEAD] as usize]);
            }
            let p = work[w] as usize;
            let pr = pairs[p];
            let i = pr.i as usize;
            if acc.open(i) {
                bi = Some(k.body(i));
            }
            let Some(b) = bi.as_ref() else { continue };
            if let Some((lf, lti, ltj)) = k.pair(b, &pr, &mut cs[p]) {
                acc.add(pr.j as usize, lf, lti, ltj);
            }
        }
    }
    acc.finish();
}

/// The first pass over a block of pairs: those the kernel may load (`Kernel::idle`: no branch, no
/// kinematics) into `work`, in order; returns how many.
#[inline(always)]
fn kept<K: Kernel>(
    k: &K,
    pairs: &[Pair],
    cs: &[K::C],
    block: std::ops::Range<usize>,
    work: &mut [u32],
) -> usize {
    let mut nw = 0;
    for p in block {
        work[nw] = p as u32;
        nw += !k.idle(&pairs[p], &cs[p]) as usize;
    }
    nw
}

/// The sums of a chunk's loads into its forces and torques (zeroed by `new`), which cover the
/// bodies from `lo`; loads on bodies past them go to `ghosts`. In the one order both pair loops
/// (`chunk_loop`, the lanes' `contact_simd::chunk`) keep: the open body i's in registers from
/// `open(i)` until another body opens (or `finish`), then added to its force; body j's into its
/// force at once (or into a ghost when another chunk owns it).
struct Acc<'a> {
    f: &'a mut [V3],
    t: &'a mut [V3],
    lo: usize,
    ghosts: &'a mut Vec<Ghost>,
    /// The open body (`usize::MAX`: none).
    i: usize,
    fi: V3,
    ti: V3,
}

impl<'a> Acc<'a> {
    /// Zeroes the chunk's forces and torques and its ghosts.
    #[inline(always)]
    fn new(f: &'a mut [V3], t: &'a mut [V3], lo: usize, ghosts: &'a mut Vec<Ghost>) -> Acc<'a> {
        ghosts.clear();
        for x in f.iter_mut() {
            *x = [0.0; 3];
        }
        for x in t.iter_mut() {
            *x = [0.0; 3];
        }
        Acc {
            f,
            t,
            lo,
            ghosts,
            i: usize::MAX,
            fi: [0.0; 3],
            ti: [0.0; 3],
        }
    }

    /// Opens body `i`'s sums, closing the open body's, unless they are open; true when it opened
    /// them.
    #[inline(always)]
    fn open(&mut self, i: usize) -> bool {
        if i == self.i {
            return false;
        }
        self.close();
        self.i = i;
        self.fi = [0.0; 3];
        self.ti = [0.0; 3];
        true
    }

    /// One contact's loads: `lf` and `lti` on body i, `-lf` and `ltj` on body `j`.
    #[inline(always)]
    fn add(&mut self, j: usize, lf: V3, lti: V3, ltj: V3) {
        self.fi = contact::add(self.fi, lf);
        self.ti = contact::add(self.ti, lti);
        // (j below the chunk's end: the length tests of `f` and `t` stand for it)
        let jj = j.wrapping_sub(self.lo);
        if let (Some(fj), Some(tj)) = (self.f.get_mut(jj), self.t.get_mut(jj)) {
            *fj = contact::sub(*fj, lf);
            *tj = contact::add(*tj, ltj);
        } else {
            self.ghosts.push(Ghost {
                j: j as u32,
                f: [-lf[0], -lf[1], -lf[2]],
                t: ltj,
            });
        }
    }

    /// The open body's sums into its force and torque.
    #[inline(always)]
    fn close(&mut self) {
        if self.i != usize::MAX {
            let ii = self.i - self.lo;
            self.f[ii] = contact::add(self.f[ii], self.fi);
            self.t[ii] = contact::add(self.t[ii], self.ti);
        }
    }

    /// Closes the open body: the chunk's sums are complete.
    #[inline(always)]
    fn finish(mut self) {
        self.close();
    }
}

/// The contact phase: the contact states, forces and torques cut at the chunks' bounds, one chunk
/// per task (`run(pairs range, states, forces, torques, first owned body, ghosts)`); not
/// `parallel`: the one chunk of one thread, here.
/// `fl`: a per-pair companion of the states (the plain contacts' flags; `()` for the rolling ones),
/// cut alike.
fn par_contacts<C: Send, F: Send>(
    parallel: bool,
    chunks: &mut [Chunk],
    (cs, fl): (&mut [C], &mut [F]),
    force: &mut [V3],
    torque: &mut [V3],
    run: impl Fn(
            std::ops::Range<usize>,
            (&mut [C], &mut [F]),
            &mut [V3],
            &mut [V3],
            usize,
            &mut Vec<Ghost>,
        ) + Sync,
) {
    if !parallel {
        let ch = &mut chunks[0];
        return run(ch.pairs.clone(), (cs, fl), force, torque, 0, &mut ch.ghosts);
    }
    type Part<'a, C, F> = (&'a mut [C], &'a mut [F], &'a mut [V3], &'a mut [V3]);
    let mut parts: Vec<Part<C, F>> = Vec::with_capacity(chunks.len());
    let (mut rest_c, mut rest_l, mut rest_f, mut rest_t) = (cs, fl, force, torque);
    for ch in chunks.iter() {
        let (c, rc) = rest_c.split_at_mut(ch.pairs.len());
        let (l, rl) = rest_l.split_at_mut(ch.pairs.len());
        let (f, rf) = rest_f.split_at_mut(ch.hi - ch.lo);
        let (t, rt) = rest_t.split_at_mut(ch.hi - ch.lo);
        parts.push((c, l, f, t));
        (rest_c, rest_l, rest_f, rest_t) = (rc, rl, rf, rt);
    }
    chunks
        .par_iter_mut()
        .zip(parts.into_par_iter())
        .for_each(|(ch, (cs, fl, f, t))| {
            run(ch.pairs.clone(), (cs, fl), f, t, ch.lo, &mut ch.ghosts)
        });
}

/// A contact seen from the other body.
fn flipped(c: &Contact) -> Contact {
    Contact {
        normal: [-c.normal[0], -c.normal[1], -c.normal[2]],
        fs: [-c.fs[0], -c.fs[1], -c.fs[2]],
        ..*c
    }
}

fn v3(v: &Vec3) -> V3 {
    [v[0], v[1], v[2]]
}

/// A body's constants for the integrator, or why it cannot be integrated.
fn inert_of(b: &crate::body::Bodies, id: usize) -> Result<newton::Inert, String> {
    let inv = |x: f64| if x != 0.0 { 1.0 / x } else { 0.0 };
    let blocked = b.blocked[id];
    if blocked != DOF_ALL && (b.mass[id] <= 0.0 || b.inertia[id].min() <= 0.0) {
        return Err(format!(
            "body #{} is dynamic but has no mass or inertia",
            id
        ));
    }
    Ok(newton::Inert {
        inv_mass: inv(b.mass[id]),
        inv_inertia: [
            inv(b.inertia[id][0]),
            inv(b.inertia[id][1]),
            inv(b.inertia[id][2]),
        ],
        blocked,
        damped: b.is_damped[id],
    })
}

/// Does an `Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow=True)` of the scene still act
/// (in this iteration, or at its first use)? Its flag switches itself off at its first call in a
/// later iteration (`CohFrictIp2::go`); the fast path runs only once it has expired
/// (`compat`'s runner takes one YADE-order step first).
pub fn cohesion_now_pending(scene: &Scene) -> bool {
    scene.engines.iter().any(|e| match e {
        Engine::InteractionLoop(il) => il.cohfrict_phys.as_ref().is_some_and(|p| {
            p.set_cohesion_now
                && (p.cohesion_definition_iteration == -1
                    || p.cohesion_definition_iteration == scene.iter)
        }),
        _ => false,
    })
}

/// The loop as the fast path runs it: an expired setCohesionNow switched off as its next call
/// would (with no effect on any contact); `settle_pending`: a pending one too (a check of what the
/// scene will be after the one YADE-order step).
fn settled(
    il: &crate::scene::InteractionLoop,
    iter: i64,
    settle_pending: bool,
) -> crate::scene::InteractionLoop {
    let mut il = il.clone();
    if let Some(p) = il.cohfrict_phys.as_mut() {
        let expired =
            p.cohesion_definition_iteration != -1 && p.cohesion_definition_iteration != iter;
        if p.set_cohesion_now && (expired || settle_pending) {
            p.set_cohesion_now = false;
            p.cohesion_definition_iteration = -1;
        }
    }
    il
}

impl FastSim {
    /// Build the fast stepper from a scene, or say why the scene is outside the fast path.
    pub fn from_scene(scene: &Scene, opt: FastOptions) -> Result<FastSim, String> {
        Self::from_scene_with(scene, opt, false)
    }

    /// `from_scene` as the scene will be after a pending setCohesionNow has acted (see
    /// `cohesion_now_pending`): whether the fast path can take over after one YADE-order step.
    pub fn check_after_cohesion_now(scene: &Scene, opt: FastOptions) -> Result<(), String> {
        Self::from_scene_with(scene, opt, true).map(|_| ())
    }

    fn from_scene_with(
        scene: &Scene,
        opt: FastOptions,
        settle_pending: bool,
    ) -> Result<FastSim, String> {
        let unsupported = |what: String| Err(format!("the fast path does not support {}", what));
        if scene.track_energy {
            return unsupported("energy tracking (O.trackEnergy)".into());
        }
        let mut newton = None;
        let mut il_seen: Option<crate::scene::InteractionLoop> = None;
        let mut collider = None;
        let mut six_cfg = None;
        let mut piston = None;
        for (k, e) in scene.engines.iter().enumerate() {
            if scene.is_dead(k) {
                return unsupported(format!("dead engines ({})", e.class_name()));
            }
            match e {
                Engine::ForceResetter => {}
                Engine::Collider(c) => collider = Some(&c.p),
                Engine::InteractionLoop(il) => {
                    let il = &settled(il, scene.iter, settle_pending);
                    let ss = il.sphere_sphere.as_ref();
                    let cs_ok = il
                        .cundall_strack
                        .is_some_and(|l| !l.never_erase && l.spherical_bodies);
                    let plain = ss.is_some_and(|p| {
                        p.interaction_detection_factor == 1.0 && p.avoid_granular_ratcheting
                    }) && il.sphere_sphere_6d.is_none()
                        && il.mindlin_phys.is_none()
                        && il.frict_phys
                        && cs_ok;
                    // rolling resistance (the study's aggregate): ScGeom6D, CohFrictPhys, CohesionMoment
                    let six_ok = ss.is_none()
                        && il
                            .sphere_sphere_6d
                            .is_some_and(|p| p.ss.interaction_detection_factor == 1.0)
                        && il
                            .cohfrict_phys
                            .as_ref()
                            .is_some_and(|p| !p.set_cohesion_now)
                        && il
                            .cohesion_moment
                            .is_some_and(|cm| !(cm.twist_creep && cm.use_incremental_form))
                        && il.mindlin_phys.is_none()
                        && (cs_ok || il.cundall_strack.is_none());
                    if !(plain || six_ok) || il_seen.is_some() || newton.is_some() {
                        return unsupported(
                            "this InteractionLoop (needs Ig2_Sphere_Sphere_ScGeom with default attributes, Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack with default attributes; or Ig2_Sphere_Sphere_ScGeom6D, Ip2_CohFrictMat_CohFrictMat_CohFrictPhys without setCohesionNow, Law2_ScGeom6D_CohFrictPhys_CohesionMoment; one loop before Newton)".into(),
                        );
                    }
                    if six_ok {
                        six_cfg = Some(six::SixCfg::new(
                            il.sphere_sphere_6d.unwrap(),
                            il.cohfrict_phys.clone().unwrap(),
                            il.cohesion_moment.unwrap(),
                        ));
                    }
                    il_seen = Some(il.clone());
                }
                Engine::Piston(pc) if newton.is_some() && piston.is_none() => {
                    piston = Some((k, pc.as_ref().clone()));
                }
                Engine::Newton(n) => {
                    if n.mask > 0 || newton.is_some() {
                        return unsupported("a NewtonIntegrator mask or two integrators".into());
                    }
                    newton = Some(n.as_ref());
                }
                other => return unsupported(format!("engine {}", other.class_name())),
            }
        }
        let Some(nw) = newton else {
            return unsupported("a scene without NewtonIntegrator".into());
        };
        let Some(il) = il_seen.as_ref() else {
            return unsupported("a scene without InteractionLoop".into());
        };
        let Some(collider) = collider else {
            return unsupported("a scene without InsertionSortCollider".into());
        };
        let period = match &scene.cell {
            None => None,
            Some(c) => {
                let h = c.hsize;
                let diag = (0..3).all(|i| (0..3).all(|j| i == j || h[(i, j)] == 0.0));
                if !diag
                    || c.vel_grad != crate::math::Mat3::zeros()
                    || c.next_vel_grad != crate::math::Mat3::zeros()
                    || nw.prev_vel_grad != crate::math::Mat3::zeros()
                {
                    return unsupported("a sheared or deforming periodic cell".into());
                }
                Some([h[(0, 0)], h[(1, 1)], h[(2, 2)]])
            }
        };
        let b = &scene.bodies;
        // spheres here, walls, boxes and facets in `boundary` (which refuses any other shape)
        let bnd = boundary::Boundaries::from_scene(scene, il, collider)?;
        if let Some((_, pc)) = &piston {
            if let Some(&id) = pc.ids.iter().find(|&&id| !bnd.has(id)) {
                return unsupported(format!(
                    "a RyadePistonController moving body #{}, which is not a fixed wall, box or facet",
                    id
                ));
            }
            // the spring-bed subgrade's plate (`subId`) is moved the same way
            if pc.sub_id >= 0 && !bnd.has(pc.sub_id as usize) {
                return unsupported(format!(
                    "a RyadePistonController subgrade plate #{}, which is not a fixed wall, box or facet",
                    pc.sub_id
                ));
            }
            if pc.sub_id >= 0 && pc.sub_m == 0.0 {
                return unsupported("a RyadePistonController subgrade plate of mass 0".into());
            }
        }
        let mut sphere_ids = Vec::new();
        let mut radius = Vec::new();
        for id in 0..b.len() {
            if let Shape::Sphere { radius: r } = b.shape[id] {
                if b.clump_id[id].is_some() {
                    return unsupported(format!("clumps (sphere #{} is a clump member)", id));
                }
                sphere_ids.push(id as u32);
                radius.push(r);
            }
        }
        let n = sphere_ids.len();
        // Collider::mayCollide's mask rule must let every two spheres meet (the Verlet list does
        // not look at masks)
        let mut masks: Vec<i32> = sphere_ids.iter().map(|&id| b.mask[id as usize]).collect();
        masks.sort_unstable();
        masks.dedup();
        let avoid = collider.avoid_self_interaction_mask;
        for &ma in &masks {
            for &mb in &masks {
                if !crate::collider::masks_may_collide(ma, mb, avoid) {
                    return unsupported(format!(
                        "sphere groupMasks that keep some spheres apart ({} and {})",
                        ma, mb
                    ));
                }
            }
        }
        let mut mats = Vec::with_capacity(scene.materials.len());
        let mut sphere_mat = vec![false; scene.materials.len()];
        for &id in &sphere_ids {
            sphere_mat[b.material[id as usize]] = true;
        }
        for (k, m) in scene.materials.iter().enumerate() {
            // the spheres' materials: FrictMat (Cundall-Strack) or, with the 6-D loop, CohFrictMat
            let wanted = if six_cfg.is_some() {
                crate::material::MatClass::CohFrictMat
            } else {
                crate::material::MatClass::FrictMat
            };
            if sphere_mat[k] && m.class() != wanted {
                return unsupported(format!(
                    "spheres of {} with this InteractionLoop",
                    m.class_name()
                ));
            }
            mats.push(Mat {
                young: m.young,
                poisson: m.poisson,
                friction_angle: m.friction_angle,
            });
        }
        let rmin = radius.iter().cloned().fold(f64::INFINITY, f64::min);
        if let (Some(l), true) = (period, n > 0) {
            let rmax = radius.iter().cloned().fold(0.0, f64::max);
            if l.iter().any(|&x| 2.0 * rmax + opt.skin * rmin >= 0.5 * x) {
                return unsupported("spheres larger than a quarter of the periodic cell".into());
            }
        }
        let inert = sphere_ids
            .iter()
            .map(|&id| inert_of(b, id as usize))
            .collect::<Result<Vec<_>, String>>()?;
        let grid = grid::GridPart::from_scene(scene, il, collider, &sphere_ids)?;
        let threads = opt.threads.max(1);
        let pool = if threads > 1 {
            Some(
                rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .map_err(|e| e.to_string())?,
            )
        } else {
            None
        };
        let mut sim = FastSim {
            iter: scene.iter,
            time: scene.time,
            cfg: newton::Cfg {
                dt: scene.dt,
                damping: nw.damping,
                gravity: v3(&nw.gravity),
                damp_gravity: nw.damp_gravity,
            },
            period,
            skin: opt.skin * if rmin.is_finite() { rmin } else { 0.0 },
            pos: sphere_ids
                .iter()
                .map(|&id| v3(&b.pos[id as usize]))
                .collect(),
            vel: sphere_ids
                .iter()
                .map(|&id| v3(&b.vel[id as usize]))
                .collect(),
            ang_vel: sphere_ids
                .iter()
                .map(|&id| v3(&b.ang_vel[id as usize]))
                .collect(),
            ori: sphere_ids.iter().map(|&id| b.ori[id as usize]).collect(),
            mat: sphere_ids
                .iter()
                .map(|&id| b.material[id as usize] as u32)
                .collect(),
            ids: sphere_ids,
            radius,
            inert,
            x_ref: vec![],
            force: vec![[0.0; 3]; n],
            torque: vec![[0.0; 3]; n],
            mats,
            pairs: vec![],
            contacts: vec![],
            flags: vec![],
            shifts: vec![[0.0; 3]],
            shift_cells: vec![[0; 3]],
            chunks: vec![],
            bnd,
            six: six_cfg,
            grid,
            error: None,
            piston,
            stop: false,
            contacts6: vec![],
            ori_prev: vec![],
            fmats: scene.materials.clone(),
            pool,
            threads,
            max_disp2: 0.0,
            rebuilds: 0,
            timing: Timing::default(),
        };
        // the scene's real sphere-sphere contacts carry over with their shear history
        let mut known = FxHashMap::default();
        for it in &scene.interactions.list {
            if let (Some(g), Some(ph), None, GeomFunctor::SphereSphere) =
                (&it.geom, &it.phys, &it.ext, it.functor)
            {
                let c = Contact {
                    active: true,
                    normal: v3(&g.normal),
                    fs: v3(&ph.shear_force),
                    pen: g.pen,
                    kn: ph.kn,
                    ks: ph.ks,
                    tan_phi: ph.tan_phi,
                };
                if it.id1 < it.id2 {
                    known.insert((it.id1, it.id2), c);
                } else {
                    known.insert((it.id2, it.id1), flipped(&c));
                }
            }
        }
        // (6-D contacts with their rotations and cohesive physics, as they are: body 1 the lower id)
        let mut known6 = FxHashMap::default();
        for it in &scene.interactions.list {
            if let (true, GeomFunctor::SphereSphere6D, true) =
                (it.is_real(), it.functor, sim.six.is_some())
            {
                if let Some(c) = six::C6::from_interaction(it) {
                    known6.insert((it.id1.min(it.id2), it.id1.max(it.id2)), c);
                }
            }
        }
        sim.rebuild_with(
            Known {
                plain: known,
                six: known6,
            },
            false,
        );
        Ok(sim)
    }

    pub fn len(&self) -> usize {
        self.pos.len()
    }

    pub fn is_empty(&self) -> bool {
        self.pos.is_empty()
    }

    /// Contacts (touching pairs) now.
    pub fn active_contacts(&self) -> usize {
        self.contacts.iter().filter(|c| c.active).count()
            + self.contacts6.iter().filter(|c| c.is_real()).count()
    }

    /// Real interactions of the geogrid (node bonds and sphere-connection contacts).
    pub fn grid_interactions(&self) -> usize {
        self.grid.as_ref().map_or(0, |g| g.real())
    }

    /// Pairs in the Verlet list.
    pub fn pairs(&self) -> usize {
        self.pairs.len()
    }

    /// Bytes held per particle, per contact (all contact storage over the touching pairs) and per
    /// listed pair.
    pub fn memory(&self) -> Memory {
        use std::mem::size_of;
        let body = size_of::<u32>() * 2
            + size_of::<V3>() * 7
            + size_of::<Quat>()
            + size_of::<f64>()
            + size_of::<newton::Inert>();
        let buffers: usize = self
            .chunks
            .iter()
            .map(|c| c.ghosts.capacity() * size_of::<Ghost>())
            .sum();
        let n = self.len().max(1) as f64;
        // (a rolling-resistance contact holds its state in its own allocation)
        let ext6 = self.contacts6.iter().filter(|c| c.is_real()).count() * size_of::<six::State6>();
        let pair_bytes = (self.pairs.capacity() * size_of::<Pair>()
            + self.contacts.capacity() * size_of::<Contact>()
            + self.flags.capacity()
            + self.contacts6.capacity() * size_of::<six::C6>()
            + ext6) as f64;
        Memory {
            per_particle: (body * self.len() + buffers) as f64 / n,
            per_contact: pair_bytes / self.active_contacts().max(1) as f64,
            per_pair: pair_bytes / self.pairs.len().max(1) as f64,
        }
    }

    /// The active contacts keyed by scene ids (lower id first, state seen from the lower id).
    fn known_contacts(&mut self) -> Known {
        // (each map sized for its contacts: no rehash while it fills)
        let n6 = self.contacts6.iter().filter(|c| c.is_real()).count();
        let mut six = FxHashMap::with_capacity_and_hasher(n6, Default::default());
        for (p, c) in self.pairs.iter().zip(self.contacts6.drain(..)) {
            if c.is_real() {
                let (a, b) = (self.ids[p.i as usize], self.ids[p.j as usize]);
                six.insert((a.min(b), a.max(b)), c);
            }
        }
        let n = self.flags.iter().filter(|&&f| f != 0).count();
        let mut known = FxHashMap::with_capacity_and_hasher(n, Default::default());
        for (p, c) in self.pairs.iter().zip(&self.contacts) {
            if c.active {
                let (a, b) = (self.ids[p.i as usize], self.ids[p.j as usize]);
                if a < b {
                    known.insert((a, b), *c);
                } else {
                    known.insert((b, a), flipped(c));
                }
            }
        }
        Known { plain: known, six }
    }

    /// Build the Verlet list again (bodies re-sorted), keeping every contact's state.
    fn rebuild_with(&mut self, known: Known, par: bool) {
        let Known {
            plain: known,
            six: mut known6,
        } = known;
        let built = neighbors::build(&self.pos, &self.radius, self.period, self.skin, par);
        let ord = &built.order;
        fn perm<T: Copy>(v: &mut Vec<T>, ord: &[u32]) {
            *v = ord.iter().map(|&o| v[o as usize]).collect();
        }
        perm(&mut self.ids, ord);
        perm(&mut self.pos, ord);
        perm(&mut self.vel, ord);
        perm(&mut self.ang_vel, ord);
        perm(&mut self.ori, ord);
        perm(&mut self.radius, ord);
        perm(&mut self.inert, ord);
        perm(&mut self.mat, ord);
        perm(&mut self.force, ord);
        perm(&mut self.torque, ord);
        self.pairs = built.pairs;
        self.shifts = built.shifts;
        // the pair loops' lanes read the bodies and shifts of the pairs unchecked
        assert!(
            pairs_in_range(&self.pairs, self.pos.len(), self.shifts.len()),
            "the Verlet list holds a pair outside the bodies or shifts"
        );
        self.shift_cells = built.shift_cells;
        let ids = &self.ids;
        let state = |p: &Pair| {
            let (a, b) = (ids[p.i as usize], ids[p.j as usize]);
            if a < b {
                known.get(&(a, b)).copied().unwrap_or_default()
            } else {
                known.get(&(b, a)).map(flipped).unwrap_or_default()
            }
        };
        if self.six.is_some() {
            self.contacts = vec![];
            self.flags = vec![];
            self.contacts6 = self
                .pairs
                .iter()
                .map(|p| {
                    let (a, b) = (ids[p.i as usize], ids[p.j as usize]);
                    known6.remove(&(a.min(b), a.max(b))).unwrap_or_default()
                })
                .collect();
        } else {
            self.contacts = if par {
                self.pairs.par_iter().map(state).collect()
            } else {
                self.pairs.iter().map(state).collect()
            };
            self.flags = self.contacts.iter().map(|c| c.active as u8).collect();
        }
        let listing = Listing::new(
            &self.ids,
            &self.pos,
            &built.wrapped,
            &self.radius,
            &built.cells,
        );
        self.bnd.rebuild(&listing, self.skin);
        if let Some(g) = &mut self.grid {
            g.rebuild(&listing, self.skin);
        }
        self.x_ref = self.pos.clone();
        self.max_disp2 = 0.0;
        self.rebuilds += 1;
        self.make_chunks();
    }

    /// Cut the pair list into one chunk per thread (equal estimated cost).
    fn make_chunks(&mut self) {
        let np = self.pairs.len();
        let t = self.threads;
        // cut at equal estimated cost: a touching pair (the full law) costs about 4 distance tests
        let active: Vec<bool> = if self.six.is_some() {
            self.contacts6.iter().map(|c| c.is_real()).collect()
        } else {
            self.contacts.iter().map(|c| c.active).collect()
        };
        let cost = |a: &bool| if *a { 4 } else { 1 };
        let total: usize = active.iter().map(cost).sum();
        let mut cuts = vec![0usize; t + 1];
        cuts[t] = np;
        if t > 1 {
            let (mut acc, mut k) = (0usize, 1usize);
            for (m, c) in active.iter().enumerate() {
                while k < t && acc >= total * k / t {
                    cuts[k] = m;
                    k += 1;
                }
                acc += cost(c);
            }
            while k < t {
                cuts[k] = np;
                k += 1;
            }
        }
        // move every cut to a body boundary: all pairs of a body i stay in one chunk
        for k in 1..t {
            let mut c = cuts[k].max(cuts[k - 1]);
            while c > 0 && c < np && self.pairs[c].i == self.pairs[c - 1].i {
                c += 1;
            }
            cuts[k] = c;
        }
        // owned bodies: from the chunk's first body i to the next chunk's (the ranges partition 0..n)
        let n = self.pos.len();
        let first = |c: usize| if c < np { self.pairs[c].i as usize } else { n };
        // (non-decreasing: the cuts are, and the pairs are sorted by i)
        let starts: Vec<usize> = (0..=t)
            .map(|k| {
                if k == 0 {
                    0
                } else if k == t {
                    n
                } else {
                    first(cuts[k])
                }
            })
            .collect();
        self.chunks = (0..t)
            .map(|k| Chunk {
                pairs: cuts[k]..cuts[k + 1],
                lo: starts[k],
                hi: starts[k + 1],
                ghosts: Vec::new(),
            })
            .collect();
    }

    /// One time step: (Verlet list rebuild if needed), contact forces, integration.
    pub fn step(&mut self) {
        let half = 0.5 * self.skin;
        if self.max_disp2 > half * half {
            let t0 = std::time::Instant::now();
            let known = self.known_contacts();
            if self.threads > 1 {
                let pool = self.pool.take().expect("thread pool");
                pool.install(|| self.rebuild_with(known, true));
                self.pool = Some(pool);
            } else {
                self.rebuild_with(known, false);
            }
            self.timing.rebuild += t0.elapsed().as_secs_f64();
        }
        if self.threads == 1 {
            self.step_serial();
        } else {
            self.step_parallel();
        }
        if let Some((_, pc)) = &mut self.piston {
            // the engine after NewtonIntegrator (`Scene::run_engine`, Engine::Piston)
            if pc.periodic.is_activated(self.iter) {
                // (its errors are bad ids and a plate of mass 0, refused by `from_scene`)
                self.stop |= pc.action(&mut self.bnd, self.iter).unwrap_or(true);
            }
        }
        self.iter += 1;
        self.time += self.cfg.dt;
    }

    /// Run `steps` steps, or fewer when an engine ends the run (then `take_stop` is true).
    pub fn run(&mut self, steps: u64) {
        for _ in 0..steps {
            self.step();
            if self.stop {
                break;
            }
        }
    }

    /// Did an engine end the run (cleared by this call)?
    pub fn take_stop(&mut self) -> bool {
        std::mem::take(&mut self.stop)
    }

    fn step_serial(&mut self) {
        let t0 = std::time::Instant::now();
        self.contact_phase(false);
        debug_assert!(self.chunks[0].ghosts.is_empty());
        self.boundary_phase();
        self.grid_phase();
        let t1 = std::time::Instant::now();
        self.timing.contacts += (t1 - t0).as_secs_f64();
        self.keep_orientations();
        let cfg = self.cfg;
        self.max_disp2 = integrate(
            &cfg,
            newton::Run {
                inert: &self.inert,
                f: &self.force,
                t: &self.torque,
                x: &mut self.pos,
                v: &mut self.vel,
                w: &mut self.ang_vel,
                q: &mut self.ori,
                x_ref: &self.x_ref,
            },
        );
        self.max_disp2 = self
            .max_disp2
            .max(self.bnd.advance(cfg.dt))
            .max(self.integrate_nodes());
        self.timing.newton += t1.elapsed().as_secs_f64();
    }

    /// With deferred rotations (`SixCfg::defer_rotations`): the orientations the contact phase just
    /// used, before the integration moves them, for `write_back`.
    fn keep_orientations(&mut self) {
        if self.six.as_ref().is_some_and(|c| c.defer_rotations) {
            self.ori_prev.clear();
            self.ori_prev.extend_from_slice(&self.ori);
        }
    }

    /// The grid's loads (serial, after the sphere and boundary contacts; see `grid`). Spheres owned
    /// by other chunks get their loads here too: the parallel integration reads `force` after this.
    fn grid_phase(&mut self) {
        let Some(g) = &mut self.grid else { return };
        let t0 = std::time::Instant::now();
        let r = g.forces(
            &self.pos,
            &self.vel,
            &self.ang_vel,
            &self.ori,
            self.iter,
            self.time,
            &mut self.force,
            &mut self.torque,
        );
        self.timing.grid += t0.elapsed().as_secs_f64();
        if let Err(e) = r {
            self.error.get_or_insert(e);
            self.stop = true;
        }
    }

    /// The grid nodes' step (the spheres' integrator); their largest squared displacement since
    /// the last rebuild.
    fn integrate_nodes(&mut self) -> f64 {
        let cfg = self.cfg;
        match &mut self.grid {
            None => 0.0,
            Some(g) => integrate(
                &cfg,
                newton::Run {
                    inert: &g.inert,
                    f: &g.force,
                    t: &g.torque,
                    x: &mut g.pos,
                    v: &mut g.vel,
                    w: &mut g.w,
                    q: &mut g.ori,
                    x_ref: &g.x_ref,
                },
            ),
        }
    }

    /// The error that ended the run, if any (cleared by this call).
    pub fn take_error(&mut self) -> Option<String> {
        self.error.take()
    }

    /// The sphere-sphere contacts of every chunk (in parallel, or the one chunk of one thread).
    fn contact_phase(&mut self, parallel: bool) {
        let dt = self.cfg.dt;
        let view = View {
            pos: &self.pos,
            vel: &self.vel,
            w: &self.ang_vel,
            rad: &self.radius,
            mats: &self.mats,
            mat: &self.mat,
            shifts: &self.shifts,
            dt,
        };
        let pairs = &self.pairs;
        match &self.six {
            None => par_contacts(
                parallel,
                &mut self.chunks,
                (&mut self.contacts, &mut self.flags),
                &mut self.force,
                &mut self.torque,
                // SAFETY: `self.pairs` was checked against the bodies and shifts where it was made
                // (`rebuild_with`); neither it nor they change between list builds
                |r, (cs, fl), f, t, lo, g| unsafe {
                    chunk_forces(&view, &pairs[r], cs, fl, Acc::new(f, t, lo, g))
                },
            ),
            Some(cfg) => {
                let b6 = six::Bodies6 {
                    pos: &self.pos,
                    vel: &self.vel,
                    w: &self.ang_vel,
                    ori: &self.ori,
                    rad: &self.radius,
                    mat: &self.mat,
                    ids: &self.ids,
                    shifts: &self.shifts,
                    mats: &self.fmats,
                    dt,
                    iter: self.iter,
                };
                let k = Six { cfg, b: &b6 };
                let n6 = self.contacts6.len();
                par_contacts(
                    parallel,
                    &mut self.chunks,
                    (&mut self.contacts6, &mut vec![(); n6]),
                    &mut self.force,
                    &mut self.torque,
                    // SAFETY: as for `chunk_forces` above
                    |r, (cs, _), f, t, lo, g| unsafe {
                        chunk_forces6(&k, &pairs[r], cs, Acc::new(f, t, lo, g))
                    },
                )
            }
        }
    }

    /// The boundary contacts (serial: a container's few), their loads added to the spheres'.
    fn boundary_phase(&mut self) {
        if self.bnd.is_empty() {
            return;
        }
        let s = boundary::Spheres {
            pos: &self.pos,
            vel: &self.vel,
            w: &self.ang_vel,
            ori: &self.ori,
            rad: &self.radius,
            mat: &self.mat,
        };
        self.bnd.forces(
            &s,
            self.cfg.dt,
            self.iter,
            &mut self.force,
            &mut self.torque,
        );
    }

    /// One rayon `install` per step: both parallel phases run inside it.
    fn step_parallel(&mut self) {
        let pool = self.pool.take().expect("thread pool");
        pool.install(|| self.step_parallel_phases());
        self.pool = Some(pool);
    }

    fn step_parallel_phases(&mut self) {
        let t0 = std::time::Instant::now();
        // contact phase: each chunk sums its owned bodies' forces in place and queues the others
        self.contact_phase(true);
        self.boundary_phase();
        self.grid_phase();
        let t1 = std::time::Instant::now();
        self.timing.contacts += (t1 - t0).as_secs_f64();
        self.keep_orientations();
        // integration over each chunk's own bodies (the thread that summed their forces, whose
        // cache holds them), after the queued forces on them, in chunk order (a few hundred: the
        // chunk borders and periodic wraps): the same sums in the same order as adding every
        // queue serially first
        let cfg = self.cfg;
        let (inert, x_ref, chunks) = (&self.inert, &self.x_ref, &self.chunks);
        let mut parts = Vec::with_capacity(chunks.len());
        {
            let mut x: &mut [V3] = &mut self.pos;
            let mut v: &mut [V3] = &mut self.vel;
            let mut w: &mut [V3] = &mut self.ang_vel;
            let mut q: &mut [Quat] = &mut self.ori;
            let mut f: &mut [V3] = &mut self.force;
            let mut t: &mut [V3] = &mut self.torque;
            for ch in chunks {
                let m = ch.hi - ch.lo;
                let (x0, x1) = std::mem::take(&mut x).split_at_mut(m);
                let (v0, v1) = std::mem::take(&mut v).split_at_mut(m);
                let (w0, w1) = std::mem::take(&mut w).split_at_mut(m);
                let (q0, q1) = std::mem::take(&mut q).split_at_mut(m);
                let (f0, f1) = std::mem::take(&mut f).split_at_mut(m);
                let (t0, t1) = std::mem::take(&mut t).split_at_mut(m);
                parts.push((ch.lo, x0, v0, w0, q0, f0, t0));
                (x, v, w, q, f, t) = (x1, v1, w1, q1, f1, t1);
            }
        }
        let md = parts
            .into_par_iter()
            .map(|(lo, x, v, w, q, f, t)| {
                let hi = lo + x.len();
                for ch in chunks {
                    for g in &ch.ghosts {
                        let j = g.j as usize;
                        if (lo..hi).contains(&j) {
                            f[j - lo] = contact::add(f[j - lo], g.f);
                            t[j - lo] = contact::add(t[j - lo], g.t);
                        }
                    }
                }
                integrate(
                    &cfg,
                    newton::Run {
                        inert: &inert[lo..hi],
                        f,
                        t,
                        x,
                        v,
                        w,
                        q,
                        x_ref: &x_ref[lo..hi],
                    },
                )
            })
            .reduce(|| 0.0, f64::max);
        self.max_disp2 = md.max(self.bnd.advance(cfg.dt)).max(self.integrate_nodes());
        self.timing.newton += t1.elapsed().as_secs_f64();
    }

    /// Copy the state back into the scene: bodies, forces of the last step, time, and the contacts
    /// as real interactions (the collider re-initialises on the next YADE-order step).
    pub fn write_back(&self, scene: &mut Scene) {
        let n = self.len();
        scene.forces.resize(scene.bodies.len());
        for k in 0..n {
            let id = self.ids[k] as usize;
            let b = &mut scene.bodies;
            b.pos[id] = Vec3::from(self.pos[k]);
            b.vel[id] = Vec3::from(self.vel[k]);
            b.ang_vel[id] = Vec3::from(self.ang_vel[k]);
            b.ori[id] = self.ori[k];
            *scene.forces.force_mut(id) = Vec3::from(self.force[k]);
            *scene.forces.torque_mut(id) = Vec3::from(self.torque[k]);
        }
        scene.iter = self.iter;
        scene.time = self.time;
        match &self.grid {
            Some(g) => g.write_back(scene),
            None => scene.interactions.clear(),
        }
        for (p, c) in self.pairs.iter().zip(&self.contacts) {
            if !c.active {
                continue;
            }
            let (i, j) = (p.i as usize, p.j as usize);
            let (a, b) = (self.ids[i], self.ids[j]);
            let cd = self.shift_cells[p.img as usize];
            // YADE's sphere-sphere interactions are (lower id, higher id)
            let (id1, id2, k1, k2, c, cd) = if a < b {
                (a, b, i, j, *c, cd)
            } else {
                (b, a, j, i, flipped(c), [-cd[0], -cd[1], -cd[2]])
            };
            let n = Vec3::from(c.normal);
            let (r1, r2) = (self.radius[k1], self.radius[k2]);
            let mut it = Interaction::new(id1, id2, cd, self.iter);
            it.functor = GeomFunctor::SphereSphere;
            it.iter_made_real = self.iter;
            it.geom = Some(ScGeom {
                contact_point: Vec3::from(self.pos[k1]) + n * (r1 - 0.5 * c.pen),
                pen: c.pen,
                normal: n,
                radius1: r1,
                radius2: r2,
                ..ScGeom::default()
            });
            it.phys = Some(FrictPhys {
                kn: c.kn,
                ks: c.ks,
                tan_phi: c.tan_phi,
                normal_force: n * (c.kn * c.pen.max(0.0)),
                shear_force: Vec3::from(c.fs),
            });
            scene.interactions.insert(it);
        }
        for (p, c) in self.pairs.iter().zip(&self.contacts6) {
            if !c.is_real() {
                continue;
            }
            let (a, b) = (self.ids[p.i as usize], self.ids[p.j as usize]);
            let cd = self.shift_cells[p.img as usize];
            // kept with the lower id as body 1 (six::pair), as YADE orders them
            let (i, j) = (p.i as usize, p.j as usize);
            let (id1, id2, k1, k2, cd) = if a < b {
                (a, b, i, j, cd)
            } else {
                (b, a, j, i, [-cd[0], -cd[1], -cd[2]])
            };
            let Some((g, ph, mut ext, made_real)) = c.to_interaction_parts() else {
                continue;
            };
            if let (Some(cfg), Some(s)) = (&self.six, c.0.as_deref()) {
                if cfg.defer_rotations && !self.ori_prev.is_empty() {
                    let ori = (&self.ori_prev[k1], &self.ori_prev[k2]);
                    let rot = six::settled_rotations(cfg, s, ori, self.iter - 1);
                    ext.geom = Some(crate::geom::GeomExt::Sc6D(rot));
                }
            }
            let mut it = Interaction::new(id1, id2, cd, made_real);
            it.functor = GeomFunctor::SphereSphere6D;
            it.iter_made_real = made_real;
            it.geom = Some(g);
            it.phys = Some(ph);
            it.ext = Some(ext);
            scene.interactions.insert(it);
        }
        self.bnd.write_back(scene, &self.ids);
        if let Some((k, pc)) = &self.piston {
            if let Some(Engine::Piston(p)) = scene.engines.get_mut(*k) {
                **p = pc.clone();
            }
        }
    }
}
