//! `RyadePistonController`: the study's piston law as an engine. **A ryade extension**: YADE has no
//! such class; a script that uses it runs under ryade only (`compat run`), and YADE stops it with a
//! `NameError` naming the class.
//!
//! It does, every step, what `Study.tick` of `yade_ref/study/study.py` does in the loading phases
//! (`approach`, `seat`, `cycle`) from its `PyRunner` after `NewtonIntegrator`: the piston pressure from
//! the z-forces of the piston bodies, the first-order filter, the target (seating pressure, or the
//! haversine / triangle wave), the PI law with its clamp, the piston velocity, the per-cycle statistics,
//! the stops (the approach's contact, the rut limit) and the `steps.csv` samples, buffered here and
//! taken by the script once per run. Every operation is the script's, in the script's order, with the
//! libm functions CPython calls (`math.sin`, `float.__pow__` = `pow`, `float.__mod__` = `fmod` plus
//! CPython's sign fix-up, builtin `min`/`max`/`sum`), so the study gives the same bits with either
//! controller (`--controller pi` / `--controller native`; compat/tests/test_piston_native.py).

use crate::body::Bodies;
use crate::forces::Forces;
use crate::math::Vec3;

/// What the controller reads and sets of the piston bodies, so that both schedulers (the Scene's
/// bodies and forces; the fast path's boundaries) run the one law.
pub trait PistonIo {
    /// Bodies in the scene (ids at or past it are refused).
    fn bodies(&self) -> usize;
    fn pos_z(&self, id: usize) -> f64;
    fn vel_z(&self, id: usize) -> f64;
    fn set_vel(&mut self, id: usize, v: Vec3);
    /// The z force of this step (0 for a body with no force entry, as `O.forces.f`).
    fn force_z(&self, id: usize) -> f64;
}

/// The Scene's bodies and forces as the controller sees them.
pub struct SceneIo<'a> {
    pub bodies: &'a mut Bodies,
    pub forces: &'a Forces,
}

impl PistonIo for SceneIo<'_> {
    fn bodies(&self) -> usize {
        self.bodies.len()
    }
    fn pos_z(&self, id: usize) -> f64 {
        self.bodies.pos[id][2]
    }
    fn vel_z(&self, id: usize) -> f64 {
        self.bodies.vel[id][2]
    }
    fn set_vel(&mut self, id: usize, v: Vec3) {
        self.bodies.vel[id] = v;
    }
    fn force_z(&self, id: usize) -> f64 {
        self.forces.ft.get(id).map_or(0.0, |w| w.f[2])
    }
}

/// The controller's phase (`Study.phase` in study.py, loading phases only; `idle` leaves the piston
/// alone, while a subgrade plate is still stepped).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Phase {
    #[default]
    Idle,
    Approach,
    Seat,
    Cycle,
}

impl Phase {
    pub fn name(self) -> &'static str {
        match self {
            Phase::Idle => "idle",
            Phase::Approach => "approach",
            Phase::Seat => "seat",
            Phase::Cycle => "cycle",
        }
    }
    pub fn parse(s: &str) -> Option<Phase> {
        Some(match s {
            "idle" => Phase::Idle,
            "approach" => Phase::Approach,
            "seat" => Phase::Seat,
            "cycle" => Phase::Cycle,
            _ => return None,
        })
    }
}

/// The load wave of the cycles (study.py `--wave`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Wave {
    #[default]
    Haversine,
    Triangle,
}

impl Wave {
    pub fn name(self) -> &'static str {
        match self {
            Wave::Haversine => "haversine",
            Wave::Triangle => "triangle",
        }
    }
    pub fn parse(s: &str) -> Option<Wave> {
        Some(match s {
            "haversine" => Wave::Haversine,
            "triangle" => Wave::Triangle,
            _ => return None,
        })
    }
}

/// One `steps.csv` sample: study.py `tick()`'s
/// `[O.iter, phase, p / 1e3, pf / 1e3, target / 1e3, piston_bottom() - Z0, vNow]`.
#[derive(Clone, Debug, PartialEq)]
pub struct StepRow {
    pub iter: i64,
    pub phase: Phase,
    pub p_kpa: f64,
    pub pf_kpa: f64,
    pub target_kpa: f64,
    pub z: f64,
    pub v: f64,
}

/// Per-cycle statistics (study.py `load()`'s `self.cyc`, accumulated by `tick()`).
#[derive(Clone, Debug, PartialEq)]
pub struct CycleStats {
    pub n: i64,
    pub peak: f64,
    pub peak_raw: f64,
    pub se: f64,
    pub se_raw: f64,
    pub max_rut: f64,
}

impl Default for CycleStats {
    /// study.py `load()`: `{'n': 0, 'peak': -1e300, 'peakRaw': -1e300, 'se': 0.0, 'seRaw': 0.0, 'maxRut': -1e300}`.
    fn default() -> Self {
        CycleStats {
            n: 0,
            peak: -1e300,
            peak_raw: -1e300,
            se: 0.0,
            se_raw: 0.0,
            max_rut: -1e300,
        }
    }
}

/// The iteration part of YADE's `PeriodicEngine::isActivated` (pkg/common/PeriodicEngines.hpp), the
/// rule the study's `PyRunner(iterPeriod=1)` runs by: a fresh one skips its first step (`initRun`
/// false), which the controller that replaces it must do too. `virtPeriod` and `realPeriod` are not
/// modelled (0).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct IterPeriodic {
    pub iter_period: i64,
    pub n_do: i64,
    pub init_run: bool,
    pub first_iter_run: i64,
    pub n_done: i64,
    pub iter_last: i64,
}

impl Default for IterPeriodic {
    /// The controller's defaults: every step (`iterPeriod` 1), YADE's for the rest.
    fn default() -> Self {
        IterPeriodic {
            iter_period: 1,
            n_do: -1,
            init_run: false,
            first_iter_run: 0,
            n_done: 0,
            iter_last: 0,
        }
    }
}

impl IterPeriodic {
    /// `PeriodicEngine::isActivated` with `virtPeriod = realPeriod = 0`.
    pub fn is_activated(&mut self, iter: i64) -> bool {
        if self.first_iter_run > 0 && self.n_done == 0 {
            if self.first_iter_run == iter {
                self.iter_last = iter;
                self.n_done += 1;
                return true;
            }
            return false;
        }
        if iter < self.iter_last {
            self.n_done = 0;
        }
        if (self.n_do < 0 || self.n_done < self.n_do)
            && self.iter_period > 0
            && iter - self.iter_last >= self.iter_period
        {
            self.iter_last = iter;
            self.n_done += 1;
            return true;
        }
        if self.n_done == 0 {
            self.iter_last = iter;
            self.n_done += 1;
            return self.init_run;
        }
        false
    }
}

/// The study's piston controller (Python class `RyadePistonController`; attribute names there in
/// brackets). Pressures in Pa, lengths in m, velocities in m/s.
#[derive(Clone, Debug)]
pub struct PistonController {
    /// When it runs (`iterPeriod`, `nDo`, `initRun`, `firstIterRun`, `nDone`, `iterLast`): the
    /// study's PyRunner's rule; the study hands over the PyRunner's `nDone` and `iterLast`.
    pub periodic: IterPeriodic,
    /// The piston bodies (`ids`), in `Study.piston` order: forces are summed in this order, the first
    /// one's position and velocity stand for the piston.
    pub ids: Vec<usize>,
    /// Loaded area `P.A` (`area`).
    pub area: f64,
    /// Filter coefficient `P.alpha` (`alpha`).
    pub alpha: f64,
    /// PI gains `P.Kp`, `P.Ki` (`Kp`, `Ki`).
    pub kp: f64,
    pub ki: f64,
    /// Speed limit `--vmax` (`vmax`).
    pub vmax: f64,
    /// The law's time step `P.dt` (`dt`): t = (iter - iterSeatEnd) dt and I += e dt.
    pub dt: f64,
    /// Seating and peak pressures `--seat-kpa * 1e3`, `--peak-kpa * 1e3` (`pSeat`, `pPeak`).
    pub p_seat: f64,
    pub p_peak: f64,
    /// Load frequency `--freq` (`freq`) and wave (`wave`).
    pub freq: f64,
    pub wave: Wave,
    /// Piston velocity of the approach (`vApproach`; study.py: -0.1).
    pub v_approach: f64,
    /// First cycle step (`iterSeatEnd`; study.py sets 10**12 before seating).
    pub iter_seat_end: i64,
    pub phase: Phase,
    /// The run stops once the rut exceeds this (`stopRut`, `--stop-rut`).
    pub stop_rut: f64,
    /// Piston bottom at the end of seating (`zRef`).
    pub z_ref: f64,
    /// Piston bottom minus the first piston body's z (`pistonOff`).
    pub piston_off: f64,
    /// Plate top `P.Z0` (`Z0`), the datum of the sampled piston height.
    pub z0: f64,
    /// `steps.csv` sampling period (`stepsEvery`; 0 or less: no samples).
    pub steps_every: i64,
    /// Sum the piston forces as CPython >= 3.12's builtin `sum` does (Neumaier compensation) instead
    /// of 3.11's plain left-to-right sum (`neumaierSum`; the Python class sets it from the running
    /// interpreter, so the law matches the script's `sum()` in either).
    pub neumaier_sum: bool,
    /// Filtered pressure (`pf`) and the integral of the error (`I`).
    pub pf: f64,
    pub i_term: f64,
    /// This cycle's statistics (`n`, `peak`, `peakRaw`, `se`, `seRaw`, `maxRut`).
    pub stats: CycleStats,
    /// Set when the rut passed `stop_rut` (`stopped`).
    pub stopped: bool,
    /// Samples not yet taken by the script (`takeSteps()`).
    pub rows: Vec<StepRow>,
    /// The last active step's raw pressure, target and imposed velocity (`p`, `target`, `v`).
    pub p: f64,
    pub target: f64,
    pub v: f64,
    /// The study's spring-bed subgrade under the bottom plate (knob `--subgrade-k`; study.py
    /// `start_subgrade`/`tick_subgrade`): the plate body (`subId`, -1: none), its mass, spring K A,
    /// dashpot c and the layer's weight P0 (`subM`, `subKA`, `subC`, `subP0`), its state u, v
    /// (`subU`, `subV`). Stepped every time the engine runs, in every phase, before the piston law.
    pub sub_id: i64,
    pub sub_m: f64,
    pub sub_ka: f64,
    pub sub_c: f64,
    pub sub_p0: f64,
    pub sub_u: f64,
    pub sub_v: f64,
}

impl Default for PistonController {
    fn default() -> Self {
        PistonController {
            periodic: IterPeriodic::default(),
            ids: Vec::new(),
            area: 1.0,
            alpha: 1.0,
            kp: 0.0,
            ki: 0.0,
            vmax: 1.0,
            dt: 0.0,
            p_seat: 0.0,
            p_peak: 0.0,
            freq: 0.0,
            wave: Wave::Haversine,
            v_approach: -0.1,
            iter_seat_end: 1_000_000_000_000,
            phase: Phase::Idle,
            stop_rut: f64::INFINITY,
            z_ref: 0.0,
            piston_off: 0.0,
            z0: 0.0,
            steps_every: 0,
            neumaier_sum: false,
            pf: 0.0,
            i_term: 0.0,
            stats: CycleStats::default(),
            stopped: false,
            rows: Vec::new(),
            p: 0.0,
            target: 0.0,
            v: 0.0,
            sub_id: -1,
            sub_m: 1.0,
            sub_ka: 0.0,
            sub_c: 0.0,
            sub_p0: 0.0,
            sub_u: 0.0,
            sub_v: 0.0,
        }
    }
}

/// Python's `max(a, b)` on floats: `b` only if `b > a` (so NaN and ties keep `a`).
pub fn py_max(a: f64, b: f64) -> f64 {
    if b > a {
        b
    } else {
        a
    }
}

/// Python's `min(a, b)` on floats: `b` only if `b < a`.
pub fn py_min(a: f64, b: f64) -> f64 {
    if b < a {
        b
    } else {
        a
    }
}

/// study.py `tick()`'s clamp `max(-vmax, min(vmax, v))`.
pub fn clamp_velocity(v: f64, vmax: f64) -> f64 {
    py_max(-vmax, py_min(vmax, v))
}

/// Python's `x % w` on floats (CPython `float_rem`): `fmod`, then the sign of the divisor.
pub fn py_mod(x: f64, w: f64) -> f64 {
    let m = x % w;
    if m != 0.0 {
        if (w < 0.0) != (m < 0.0) {
            m + w
        } else {
            m
        }
    } else {
        0.0f64.copysign(w)
    }
}

/// Python's `x ** 2` on a float (CPython `float_pow`): its special cases, then libm `pow(|x|, 2.0)`.
/// The exponent goes through `black_box` so that LLVM does not rewrite `pow(x, 2.0)` into `x * x`.
pub fn py_square(x: f64) -> f64 {
    if x.is_nan() {
        return x;
    }
    if x.is_infinite() {
        return f64::INFINITY;
    }
    if x == 0.0 {
        return 0.0;
    }
    let a = x.abs();
    if a == 1.0 {
        return 1.0;
    }
    a.powf(std::hint::black_box(2.0))
}

/// CPython's builtin `sum(values)` of floats (the start is the int 0, so the first addition is
/// `0.0 + x0`): plain left-to-right in 3.11, Neumaier-compensated from 3.12 on (`neumaier`).
pub fn py_sum(values: impl Iterator<Item = f64>, neumaier: bool) -> f64 {
    let mut it = values;
    let Some(x0) = it.next() else {
        return 0.0;
    };
    let mut s = 0.0 + x0;
    if !neumaier {
        for x in it {
            s += x;
        }
        return s;
    }
    let mut c = 0.0;
    for x in it {
        let t = s + x;
        if s.abs() >= x.abs() {
            c += (s - t) + x;
        } else {
            c += (x - t) + s;
        }
        s = t;
    }
    if c != 0.0 && c.is_finite() {
        s += c;
    }
    s
}

impl PistonController {
    /// study.py `p_target(t)`: the seating pressure before t = 0, then the haversine
    /// `lo + (hi - lo) sin(pi ph)**2` or the triangle `lo + (hi - lo) (1 - |2 ph - 1|)`, ph = (t f) % 1.
    pub fn p_target(&self, t: f64) -> f64 {
        let (lo, hi) = (self.p_seat, self.p_peak);
        if t < 0.0 {
            return lo;
        }
        let ph = py_mod(t * self.freq, 1.0);
        match self.wave {
            Wave::Haversine => lo + (hi - lo) * py_square((std::f64::consts::PI * ph).sin()),
            Wave::Triangle => lo + (hi - lo) * (1.0 - (2.0 * ph - 1.0).abs()),
        }
    }

    /// study.py `pressure()`: `sum(O.forces.f(i)[2] for i in piston) / A`.
    fn pressure(&self, io: &impl PistonIo) -> f64 {
        py_sum(self.ids.iter().map(|&id| io.force_z(id)), self.neumaier_sum) / self.area
    }

    /// study.py `set_piston_vel(v)`: every piston body's `state.vel = Vector3(0, 0, v)`.
    fn set_velocity(&self, io: &mut impl PistonIo, v: f64) {
        for &id in &self.ids {
            io.set_vel(id, Vec3::new(0.0, 0.0, v));
        }
    }

    /// study.py `piston_bottom()`: the first piston body's z plus the offset.
    fn piston_bottom(&self, io: &impl PistonIo) -> f64 {
        io.pos_z(self.ids[0]) + self.piston_off
    }

    /// study.py `tick_subgrade()`: the bottom plate's equation of motion
    /// m dv/dt = F_c + P0 - K A u - c v, explicit, its velocity used by the next step's integration.
    fn tick_subgrade(&mut self, io: &mut impl PistonIo) -> Result<(), String> {
        let id = self.sub_id as usize;
        if id >= io.bodies() {
            return Err(format!("RyadePistonController: no subgrade plate #{}", id));
        }
        if self.sub_m == 0.0 {
            // Python: ZeroDivisionError
            return Err("RyadePistonController: subM is 0 (the subgrade plate's mass)".into());
        }
        // f = O.forces.f(id)[2] + P0 - KA * u - c * v, Python's left-to-right order
        let f = io.force_z(id) + self.sub_p0 - self.sub_ka * self.sub_u - self.sub_c * self.sub_v;
        self.sub_u += self.dt * self.sub_v; // s['u'] += dt * s['v']
        self.sub_v += self.dt * f / self.sub_m; // s['v'] += dt * f / s['m']
        io.set_vel(id, Vec3::new(0.0, 0.0, self.sub_v));
        Ok(())
    }

    /// One step of study.py `tick()`: the subgrade plate first (in every phase), then the piston in the
    /// phases `approach`, `seat`, `cycle` (nothing more when idle),
    /// with the step's synced forces (the engine follows `NewtonIntegrator`). Returns true when the
    /// run must end after this step (study.py `stop_after_this_step()`). The caller checks
    /// `periodic.is_activated` first (`Scene::run_engine`).
    pub fn action(&mut self, io: &mut impl PistonIo, iter: i64) -> Result<bool, String> {
        if self.sub_id >= 0 {
            self.tick_subgrade(io)?; // tick(): the subgrade first, in every phase
        }
        if self.phase == Phase::Idle {
            return Ok(false);
        }
        if self.ids.is_empty() {
            return Err("RyadePistonController: ids is empty".into());
        }
        if let Some(&bad) = self.ids.iter().find(|&&id| id >= io.bodies()) {
            return Err(format!("RyadePistonController: no body #{}", bad));
        }
        let v_now = io.vel_z(self.ids[0]); // tick(): vNow, this step's piston velocity
        let p = self.pressure(io); // tick(): p = self.pressure()
        self.pf += self.alpha * (p - self.pf); // tick(): self.pf += P.alpha * (p - self.pf)
        let t = (iter - self.iter_seat_end) as f64 * self.dt; // tick(): t = m * P.dt
        let phase = self.phase;
        let mut stop = false;
        let target;
        if phase == Phase::Approach {
            target = self.p_seat; // tick(): approach target a.seat_kpa * 1e3
            if p >= target {
                self.phase = Phase::Idle;
                stop = true;
            }
            self.v = self.v_approach;
            self.set_velocity(io, self.v_approach); // tick(): set_piston_vel(-0.1)
        } else {
            target = if phase == Phase::Seat {
                self.p_seat
            } else {
                self.p_target(t)
            };
            let e = target - self.pf; // tick(): e = target - self.pf
            self.i_term += e * self.dt; // tick(): self.I += e * P.dt
            let v = -(self.kp * e + self.ki * self.i_term); // tick(): v = -(P.Kp * e + P.Ki * self.I)
            let v = clamp_velocity(v, self.vmax); // tick(): max(-a.vmax, min(a.vmax, v))
            self.v = v;
            self.set_velocity(io, v); // tick(): set_piston_vel(v)
            if phase == Phase::Cycle {
                let zb = self.piston_bottom(io); // tick(): zb = self.piston_bottom()
                let c = &mut self.stats;
                c.n += 1; // tick(): c['n'] += 1
                c.peak = py_max(c.peak, self.pf); // tick(): c['peak'] = max(c['peak'], self.pf)
                c.peak_raw = py_max(c.peak_raw, p); // tick(): c['peakRaw'] = max(c['peakRaw'], p)
                c.se += py_square(self.pf - target); // tick(): c['se'] += (self.pf - target)**2
                c.se_raw += py_square(p - target); // tick(): c['seRaw'] += (p - target)**2
                c.max_rut = py_max(c.max_rut, self.z_ref - zb); // tick(): c['maxRut'] = max(c['maxRut'], self.zRef - zb)
                if self.z_ref - zb > self.stop_rut {
                    // tick(): the rut stop
                    self.stopped = true;
                    self.phase = Phase::Idle;
                    stop = true;
                }
            }
        }
        self.p = p;
        self.target = target;
        if self.steps_every > 0 && iter.rem_euclid(self.steps_every) == 0 {
            // tick(): self.steps.append([O.iter, phase, p / 1e3, self.pf / 1e3, target / 1e3,
            //                            self.piston_bottom() - P.Z0, vNow])
            self.rows.push(StepRow {
                iter,
                phase,
                p_kpa: p / 1e3,
                pf_kpa: self.pf / 1e3,
                target_kpa: target / 1e3,
                z: self.piston_bottom(io) - self.z0,
                v: v_now,
            });
        }
        Ok(stop)
    }
}

/// Attribute names of the Python class, in the order `to_json` writes them.
pub const ATTRS: [&str; 43] = [
    "iterPeriod",
    "nDo",
    "initRun",
    "firstIterRun",
    "nDone",
    "iterLast",
    "ids",
    "area",
    "alpha",
    "Kp",
    "Ki",
    "vmax",
    "dt",
    "pSeat",
    "pPeak",
    "freq",
    "wave",
    "vApproach",
    "iterSeatEnd",
    "phase",
    "stopRut",
    "zRef",
    "pistonOff",
    "Z0",
    "stepsEvery",
    "neumaierSum",
    "pf",
    "I",
    "n",
    "peak",
    "peakRaw",
    "se",
    "seRaw",
    "maxRut",
    "stopped",
    "p",
    "subId",
    "subM",
    "subKA",
    "subC",
    "subP0",
    "subU",
    "subV",
];

/// A float as JSON: a number, or the string "inf", "-inf" or "nan" (JSON has no such numbers).
fn float_json(x: f64) -> serde_json::Value {
    if x.is_finite() {
        serde_json::json!(x)
    } else if x.is_nan() {
        serde_json::json!("nan")
    } else if x > 0.0 {
        serde_json::json!("inf")
    } else {
        serde_json::json!("-inf")
    }
}

/// Inverse of `float_json`.
fn json_float(v: &serde_json::Value) -> Option<f64> {
    match v.as_str() {
        Some("inf") => Some(f64::INFINITY),
        Some("-inf") => Some(f64::NEG_INFINITY),
        Some("nan") => Some(f64::NAN),
        _ => v.as_f64(),
    }
}

/// `GET` and `GET_MUT` for the attributes of type `T`: Python name => field path.
macro_rules! attr_table {
    ($get:ident, $get_mut:ident, $t:ty; $($name:literal => $($field:ident).+),* $(,)?) => {
        impl PistonController {
            fn $get(&self, key: &str) -> Option<$t> {
                Some(match key {
                    $($name => self.$($field).+,)*
                    _ => return None,
                })
            }
            fn $get_mut(&mut self, key: &str) -> Option<&mut $t> {
                Some(match key {
                    $($name => &mut self.$($field).+,)*
                    _ => return None,
                })
            }
        }
    };
}

attr_table!(float_attr, float_attr_mut, f64;
    "area" => area, "alpha" => alpha, "Kp" => kp, "Ki" => ki, "vmax" => vmax, "dt" => dt, "pSeat" => p_seat,
    "pPeak" => p_peak, "freq" => freq, "vApproach" => v_approach, "stopRut" => stop_rut, "zRef" => z_ref,
    "pistonOff" => piston_off, "Z0" => z0, "pf" => pf, "I" => i_term, "peak" => stats.peak,
    "peakRaw" => stats.peak_raw, "se" => stats.se, "seRaw" => stats.se_raw, "maxRut" => stats.max_rut, "p" => p,
    "target" => target, "v" => v, "subM" => sub_m, "subKA" => sub_ka, "subC" => sub_c, "subP0" => sub_p0,
    "subU" => sub_u, "subV" => sub_v);
attr_table!(int_attr, int_attr_mut, i64;
    "iterPeriod" => periodic.iter_period, "nDo" => periodic.n_do, "firstIterRun" => periodic.first_iter_run,
    "nDone" => periodic.n_done, "iterLast" => periodic.iter_last, "iterSeatEnd" => iter_seat_end,
    "stepsEvery" => steps_every, "n" => stats.n, "subId" => sub_id);
attr_table!(bool_attr, bool_attr_mut, bool;
    "initRun" => periodic.init_run, "neumaierSum" => neumaier_sum, "stopped" => stopped);

impl PistonController {
    /// Set the attribute `key` (the Python name, `ATTRS`, `target`, `v`) from JSON.
    pub fn set(&mut self, key: &str, v: &serde_json::Value) -> Result<(), String> {
        let bad = |what: &str| format!("RyadePistonController.{} must be {}, got {}", key, what, v);
        if let Some(x) = self.float_attr_mut(key) {
            *x = json_float(v).ok_or_else(|| bad("a number"))?;
        } else if let Some(x) = self.int_attr_mut(key) {
            *x = v.as_i64().ok_or_else(|| bad("an integer"))?;
        } else if let Some(x) = self.bool_attr_mut(key) {
            *x = v.as_bool().ok_or_else(|| bad("a bool"))?;
        } else {
            match key {
                "ids" => {
                    self.ids = v
                        .as_array()
                        .and_then(|a| a.iter().map(|x| x.as_u64().map(|i| i as usize)).collect())
                        .ok_or_else(|| bad("a list of body ids"))?
                }
                "wave" => {
                    self.wave = v
                        .as_str()
                        .and_then(Wave::parse)
                        .ok_or_else(|| bad("'haversine' or 'triangle'"))?
                }
                "phase" => {
                    self.phase = v
                        .as_str()
                        .and_then(Phase::parse)
                        .ok_or_else(|| bad("'idle', 'approach', 'seat' or 'cycle'"))?
                }
                _ => return Err(format!("RyadePistonController has no attribute '{}'", key)),
            }
        }
        Ok(())
    }

    /// The attribute `key` as JSON (non-finite floats as the strings of `float_json`).
    pub fn get(&self, key: &str) -> Result<serde_json::Value, String> {
        use serde_json::json;
        if let Some(x) = self.float_attr(key) {
            return Ok(float_json(x));
        }
        if let Some(x) = self.int_attr(key) {
            return Ok(json!(x));
        }
        if let Some(x) = self.bool_attr(key) {
            return Ok(json!(x));
        }
        Ok(match key {
            "ids" => json!(self.ids),
            "wave" => json!(self.wave.name()),
            "phase" => json!(self.phase.name()),
            _ => return Err(format!("RyadePistonController has no attribute '{}'", key)),
        })
    }

    /// From a scene-file / compat engine object: `{"class": "RyadePistonController", attr: value...}`
    /// (any attribute of `ATTRS`, `target`, `v`; the others keep their defaults).
    pub fn from_json(v: &serde_json::Value) -> Result<PistonController, String> {
        let mut c = PistonController::default();
        let obj = v
            .as_object()
            .ok_or_else(|| "RyadePistonController: not a JSON object".to_string())?;
        for (k, x) in obj {
            if k != "class" {
                c.set(k, x)?;
            }
        }
        Ok(c)
    }

    /// The engine object of `from_json` (the buffered samples are not written).
    pub fn to_json(&self) -> serde_json::Value {
        let mut m = serde_json::Map::new();
        m.insert("class".into(), "RyadePistonController".into());
        for k in ATTRS.iter().chain(&["target", "v"]) {
            m.insert(
                k.to_string(),
                self.get(k).expect("every ATTRS name is readable"),
            );
        }
        serde_json::Value::Object(m)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn controller() -> PistonController {
        PistonController {
            p_seat: 27.6e3,
            p_peak: 275.8e3,
            freq: 50.0,
            ..Default::default()
        }
    }

    /// The haversine target by hand: 27.6 kPa before and at t = 0, the peak 275.8 kPa at a half
    /// period, lo + (hi - lo)/2 at a quarter period, and again lo after a whole period.
    #[test]
    fn haversine_target() {
        let c = controller();
        assert_eq!(c.p_target(-1.0), 27.6e3);
        assert_eq!(c.p_target(0.0), 27.6e3);
        // t f = 0.5: sin(pi/2) = 1 exactly
        assert_eq!(c.p_target(0.01), 275.8e3);
        // t f = 0.25: Python gives sin(pi/4)**2 = 0.4999999999999999, p_target = 151699.99999999997
        let q = c.p_target(0.005);
        assert_eq!(q, 151699.99999999997);
        // a whole period: ph = (0.02 * 50) % 1 = 0: back to the seating pressure (sin(0) = 0)
        assert_eq!(c.p_target(0.02), 27.6e3);
        // 1.25 periods: the same phase as 0.25
        assert_eq!(c.p_target(0.025), q);
    }

    /// The triangle wave: lo at ph = 0, hi at ph = 0.5, the midpoint at ph = 0.25 and 0.75.
    #[test]
    fn triangle_target() {
        let c = PistonController {
            wave: Wave::Triangle,
            ..controller()
        };
        assert_eq!(c.p_target(0.0), 27.6e3);
        assert_eq!(c.p_target(0.01), 275.8e3);
        assert_eq!(c.p_target(0.005), 27.6e3 + 248.2e3 * 0.5);
        assert_eq!(c.p_target(0.015), 27.6e3 + 248.2e3 * 0.5);
    }

    /// Bodies as the controller sees them, for the tests.
    struct MockIo {
        vel: Vec<Vec3>,
        fz: Vec<f64>,
    }
    impl PistonIo for MockIo {
        fn bodies(&self) -> usize {
            self.fz.len()
        }
        fn pos_z(&self, _: usize) -> f64 {
            0.0
        }
        fn vel_z(&self, id: usize) -> f64 {
            self.vel[id][2]
        }
        fn set_vel(&mut self, id: usize, v: Vec3) {
            self.vel[id] = v;
        }
        fn force_z(&self, id: usize) -> f64 {
            self.fz[id]
        }
    }

    /// study.py `tick_subgrade` by hand: f = F + P0 - K A u - c v with F = -7.5, P0 = 5,
    /// K A u = 1000 x 0.001 and c v = 10 x (-0.01), so f = -3.4 N; u += dt v gives 0.00099 m and
    /// v += dt f / m gives -0.0117 m/s, set on the plate.
    /// It steps in the idle phase too (study.py `tick()` steps it before its idle check), leaving the
    /// piston alone there; a plate of mass 0 is an error, as Python's ZeroDivisionError.
    #[test]
    fn subgrade_plate_steps_in_every_phase() {
        let mut c = PistonController {
            ids: vec![0],
            dt: 1e-3,
            sub_id: 1,
            sub_m: 2.0,
            sub_ka: 1000.0,
            sub_c: 10.0,
            sub_p0: 5.0,
            sub_u: 0.001,
            sub_v: -0.01,
            ..controller()
        };
        let piston_v = Vec3::new(0.0, 0.0, 0.5);
        let mut io = MockIo {
            vel: vec![piston_v, Vec3::zeros()],
            fz: vec![0.0, -7.5],
        };
        assert_eq!(c.phase, Phase::Idle);
        assert_eq!(c.action(&mut io, 0), Ok(false));
        assert!((c.sub_u - 0.00099).abs() < 1e-15, "{}", c.sub_u);
        assert!((c.sub_v + 0.0117).abs() < 1e-15, "{}", c.sub_v);
        assert_eq!(io.vel[1], Vec3::new(0.0, 0.0, c.sub_v));
        assert_eq!(io.vel[0], piston_v);
        // a second step from the new state: f = -7.5 + 5 - 0.99 + 0.117
        c.action(&mut io, 1).unwrap();
        assert!((c.sub_u - (0.00099 - 0.0117e-3)).abs() < 1e-15);
        assert!((c.sub_v - (-0.0117 + 1e-3 * (-7.5 + 5.0 - 0.99 + 0.117) / 2.0)).abs() < 1e-15);
        c.sub_m = 0.0;
        assert!(c.action(&mut io, 2).unwrap_err().contains("subM is 0"));
        c.sub_id = 2;
        assert!(c
            .action(&mut io, 3)
            .unwrap_err()
            .contains("no subgrade plate #2"));
    }

    /// Python's float `%`, `min`/`max` and `**2` by hand.
    #[test]
    fn python_float_semantics() {
        assert_eq!(py_mod(2.75, 1.0), 0.75);
        assert_eq!(py_mod(-0.25, 1.0), 0.75); // the sign of the divisor
        assert!(py_mod(-1.0, 1.0).is_sign_positive()); // -1.0 % 1.0 == 0.0 (not -0.0)
        assert!(py_mod(0.0, -1.0).is_sign_negative());
        assert_eq!(py_max(1.0, f64::NAN), 1.0); // max(1.0, nan) == 1.0
        assert!(py_max(f64::NAN, 1.0).is_nan()); // max(nan, 1.0) is nan
        assert_eq!(py_min(1.0, f64::NAN), 1.0);
        assert_eq!(py_square(-3.0), 9.0);
        assert_eq!(py_square(-0.0), 0.0);
        assert!(py_square(-0.0).is_sign_positive());
        assert_eq!(py_square(f64::NEG_INFINITY), f64::INFINITY);
        assert_eq!(py_square(0.1), 0.010000000000000002); // Python: 0.1**2
    }

    /// The clamp `max(-vmax, min(vmax, v))`: inside, both limits, and NaN (min(vmax, nan) = vmax).
    #[test]
    fn velocity_clamp() {
        assert_eq!(clamp_velocity(0.25, 1.0), 0.25);
        assert_eq!(clamp_velocity(-0.25, 1.0), -0.25);
        assert_eq!(clamp_velocity(3.0, 1.0), 1.0);
        assert_eq!(clamp_velocity(-3.0, 1.0), -1.0);
        assert_eq!(clamp_velocity(f64::NAN, 1.0), 1.0);
        assert_eq!(clamp_velocity(-1.0, 1.0), -1.0);
    }

    /// Python 3.11's `sum` is plain left to right; 3.12's compensates (1e16 + 1 - 1e16 = 1 there).
    #[test]
    fn python_sum_orders() {
        let v = [1e16, 1.0, -1e16];
        assert_eq!(py_sum(v.iter().copied(), false), 0.0);
        assert_eq!(py_sum(v.iter().copied(), true), 1.0);
        assert_eq!(py_sum([-0.0].iter().copied(), false), 0.0); // 0 + -0.0 == 0.0
        assert!(py_sum([-0.0].iter().copied(), false).is_sign_positive());
        assert_eq!(py_sum(std::iter::empty(), true), 0.0);
    }

    fn piston_scene(n: usize) -> (Bodies, Forces) {
        let mut b = Bodies::default();
        for _ in 0..n {
            b.push(crate::utils::sphere(Vec3::zeros(), 0.1, 0, 1000.0, true));
        }
        let mut f = Forces::default();
        f.resize(n);
        (b, f)
    }

    /// One PI step by hand: p = (0 + 30 + 20)/A, the filter, e, I, v and the clamp, the velocity on
    /// every piston body, the cycle statistics, a sample on a multiple of stepsEvery.
    #[test]
    fn pi_step_by_hand() {
        let (mut bodies, mut forces) = piston_scene(3);
        *forces.force_mut(1) = Vec3::new(1.0, 0.0, 30.0);
        *forces.force_mut(2) = Vec3::new(0.0, 0.0, 20.0);
        bodies.pos[1] = Vec3::new(0.0, 0.0, 0.5);
        bodies.vel[1] = Vec3::new(0.0, 0.0, -0.25);
        let mut c = PistonController {
            ids: vec![1, 2],
            area: 0.5,
            alpha: 0.5,
            kp: 1e-3,
            ki: 2e-3,
            vmax: 1.0,
            dt: 0.01,
            phase: Phase::Cycle,
            iter_seat_end: 100,
            z_ref: 0.6,
            piston_off: -0.025,
            z0: 0.05,
            steps_every: 10,
            pf: 60.0,
            i_term: 0.0,
            ..controller()
        };
        let stop = c
            .action(
                &mut SceneIo {
                    bodies: &mut bodies,
                    forces: &forces,
                },
                100,
            )
            .unwrap();
        assert!(!stop);
        // p = 50 / 0.5 = 100; pf = 60 + 0.5 * 40 = 80; t = 0: target 27600
        assert_eq!(c.p, 100.0);
        assert_eq!(c.pf, 80.0);
        assert_eq!(c.target, 27.6e3);
        let e = 27.6e3 - 80.0;
        assert_eq!(c.i_term, e * 0.01);
        // v = -(1e-3 e + 2e-3 I) = -(27.52 + 0.5504) -> clamped to -1
        assert_eq!(c.v, -1.0);
        for id in [1, 2] {
            assert_eq!(bodies.vel[id], Vec3::new(0.0, 0.0, -1.0));
        }
        assert_eq!(bodies.vel[0], Vec3::zeros());
        assert_eq!(c.stats.n, 1);
        assert_eq!(c.stats.peak, 80.0);
        assert_eq!(c.stats.peak_raw, 100.0);
        assert_eq!(c.stats.se, (80.0 - 27.6e3) * (80.0 - 27.6e3));
        assert_eq!(c.stats.max_rut, 0.6 - (0.5 - 0.025));
        assert_eq!(c.rows.len(), 1);
        let r = &c.rows[0];
        assert_eq!((r.iter, r.phase), (100, Phase::Cycle));
        assert_eq!((r.p_kpa, r.pf_kpa, r.target_kpa), (0.1, 0.08, 27.6));
        assert_eq!(r.z, 0.5 + -0.025 - 0.05);
        assert_eq!(r.v, -0.25); // the velocity of the step, before this step's update
                                // a small error stays inside the clamp: v = -(Kp e + Ki I)
        c.p_seat = 81.0;
        c.phase = Phase::Seat;
        c.i_term = 0.0;
        c.pf = 80.0;
        *forces.force_mut(1) = Vec3::new(0.0, 0.0, 20.0);
        *forces.force_mut(2) = Vec3::new(0.0, 0.0, 20.0);
        c.action(
            &mut SceneIo {
                bodies: &mut bodies,
                forces: &forces,
            },
            101,
        )
        .unwrap();
        assert_eq!(c.pf, 80.0);
        assert_eq!(c.v, -(1e-3 * 1.0 + 2e-3 * 0.01));
        assert_eq!(c.stats.n, 1); // seating: no statistics
        assert_eq!(c.rows.len(), 1); // 101 is not a multiple of 10
    }

    /// The approach moves at vApproach and stops at the seating pressure; the rut stop ends a cycle.
    #[test]
    fn stops() {
        let (mut bodies, mut forces) = piston_scene(1);
        let mut c = PistonController {
            ids: vec![0],
            area: 1.0,
            phase: Phase::Approach,
            ..controller()
        };
        assert!(!c
            .action(
                &mut SceneIo {
                    bodies: &mut bodies,
                    forces: &forces
                },
                0
            )
            .unwrap());
        assert_eq!(bodies.vel[0], Vec3::new(0.0, 0.0, -0.1));
        *forces.force_mut(0) = Vec3::new(0.0, 0.0, 27.6e3);
        assert!(c
            .action(
                &mut SceneIo {
                    bodies: &mut bodies,
                    forces: &forces
                },
                1
            )
            .unwrap());
        assert_eq!(c.phase, Phase::Idle);
        assert!(!c.stopped);
        assert!(!c
            .action(
                &mut SceneIo {
                    bodies: &mut bodies,
                    forces: &forces
                },
                2
            )
            .unwrap()); // idle: nothing
        c.phase = Phase::Cycle;
        c.iter_seat_end = 3;
        c.z_ref = 0.1;
        c.stop_rut = 0.075;
        bodies.pos[0] = Vec3::new(0.0, 0.0, 0.03);
        assert!(!c
            .action(
                &mut SceneIo {
                    bodies: &mut bodies,
                    forces: &forces
                },
                3
            )
            .unwrap()); // rut 0.07
        bodies.pos[0] = Vec3::new(0.0, 0.0, 0.02);
        assert!(c
            .action(
                &mut SceneIo {
                    bodies: &mut bodies,
                    forces: &forces
                },
                4
            )
            .unwrap()); // rut 0.08
        assert!(c.stopped);
        assert_eq!(c.phase, Phase::Idle);
        assert_eq!(c.stats.n, 2);
        assert_eq!(c.stats.max_rut, 0.1 - 0.02);
    }

    /// PeriodicEngine's rule with iterPeriod 1: a fresh engine skips its first step, then runs every
    /// step; one taken over from a PyRunner that already ran (nDone > 0) runs at once; going back in
    /// time (O.reset) starts over; firstIterRun waits for its iteration.
    #[test]
    fn periodic_rule() {
        let mut p = IterPeriodic::default();
        assert!(!p.is_activated(0));
        assert!(p.is_activated(1));
        assert!(p.is_activated(2));
        let mut q = IterPeriodic {
            n_done: 57000,
            iter_last: 56999,
            ..Default::default()
        };
        assert!(q.is_activated(57000));
        assert!(!q.is_activated(5)); // back in time: nDone = 0, a fresh start
        assert!(q.is_activated(6));
        let mut r = IterPeriodic {
            first_iter_run: 3,
            ..Default::default()
        };
        assert!(!r.is_activated(1));
        assert!(r.is_activated(3));
        let mut s = IterPeriodic {
            init_run: true,
            n_do: 2,
            ..Default::default()
        };
        assert!(s.is_activated(0));
        assert!(s.is_activated(1));
        assert!(!s.is_activated(2)); // nDo reached
    }

    /// Every attribute survives to_json / from_json, non-finite floats included.
    #[test]
    fn json_round_trip() {
        let mut c = PistonController {
            ids: vec![4, 5],
            wave: Wave::Triangle,
            phase: Phase::Seat,
            stop_rut: f64::INFINITY,
            pf: f64::NAN,
            steps_every: 10,
            ..controller()
        };
        c.stats.peak = f64::NEG_INFINITY;
        let d = PistonController::from_json(&c.to_json()).unwrap();
        assert_eq!(d.to_json().to_string(), c.to_json().to_string());
        assert!(d.pf.is_nan());
        assert_eq!(d.stop_rut, f64::INFINITY);
        assert!(PistonController::from_json(
            &serde_json::json!({"class": "RyadePistonController", "kp": 1.0})
        )
        .unwrap_err()
        .contains("no attribute 'kp'"));
    }
}
