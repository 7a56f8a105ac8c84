//! YADE's engine timing (`O.timingEnabled`; core/Scene.cpp `Scene::moveToNextTimeStep`,
//! core/Timing.hpp): per engine slot, wall time and runs, and NewtonIntegrator's named
//! checkpoints (`timingDeltas`, pkg/dem/NewtonIntegrator.cpp `action`).

use std::time::Instant;

/// YADE's `TimingInfo` of one engine (core/Scene.cpp `Scene::moveToNextTimeStep`): nanoseconds of
/// wall time and the number of runs, counted only for runs where the engine was activated (a
/// collider or time stepper that does nothing this step is not counted). YADE charges the time
/// between two activated engines to the second; here each engine's own run is timed, so the few
/// nanoseconds of a skipped engine's activation test go nowhere.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct EngineTiming {
    pub nsec: u64,
    pub count: u64,
    /// YADE's `timingDeltas` (named checkpoints inside the engine): (name, ns, count). Only
    /// NewtonIntegrator has them, as in Debian's YADE build.
    pub deltas: Vec<(&'static str, u64, u64)>,
}

/// `NewtonIntegrator`'s checkpoints in YADE (pkg/dem/NewtonIntegrator.cpp `action`). ryade keeps the
/// largest velocity inside the body loop, so "sync max vel" only marks the place.
pub const NEWTON_CHECKPOINTS: [&str; 4] = [
    "forces sync",
    "motion integration",
    "sync max vel",
    "terminate",
];

/// The instants NewtonIntegrator's run reached each checkpoint (None: not Newton, or not timing).
pub type Marks = [Option<Instant>; 4];

/// Add the run of engine slot `k` that started at `t0` (ending now) to `timing`, which grows to the
/// `n` engines on demand; `marks[0]` set means a NewtonIntegrator run with its checkpoints.
pub fn record(timing: &mut Vec<EngineTiming>, k: usize, n: usize, t0: Instant, marks: &Marks) {
    let end = Instant::now();
    if timing.len() <= k {
        timing.resize(n.max(k + 1), EngineTiming::default());
    }
    let t = &mut timing[k];
    t.nsec += (end - t0).as_nanos() as u64;
    t.count += 1;
    let Some(start) = marks[0] else {
        return;
    };
    if t.deltas.is_empty() {
        t.deltas = NEWTON_CHECKPOINTS.iter().map(|&n| (n, 0, 0)).collect();
    }
    // each checkpoint's time runs from the previous one; the last ends with the run
    let mut prev = start;
    for (d, mark) in t
        .deltas
        .iter_mut()
        .zip(marks[1..].iter().chain([&Some(end)]))
    {
        let m = mark.unwrap_or(end);
        d.1 += (m - prev).as_nanos() as u64;
        d.2 += 1;
        prev = m;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs add up per slot; a Newton run splits its time over the four checkpoints, which never
    /// exceed the run.
    #[test]
    fn runs_and_checkpoints_add_up() {
        let mut t = Vec::new();
        let t0 = Instant::now();
        record(&mut t, 2, 4, t0, &[None; 4]);
        record(&mut t, 2, 4, t0, &[None; 4]);
        assert_eq!(t.len(), 4);
        assert_eq!((t[2].count, t[0].count), (2, 0));
        assert!(t[2].deltas.is_empty());
        let s = Instant::now();
        let m = Instant::now();
        record(&mut t, 1, 4, s, &[Some(s), Some(m), Some(m), Some(m)]);
        let names: Vec<&str> = t[1].deltas.iter().map(|d| d.0).collect();
        assert_eq!(names, NEWTON_CHECKPOINTS);
        assert!(t[1].deltas.iter().all(|d| d.2 == 1));
        assert_eq!(
            t[1].deltas[1].1 + t[1].deltas[2].1,
            0,
            "no time between equal marks"
        );
        assert!(t[1].deltas.iter().map(|d| d.1).sum::<u64>() <= t[1].nsec);
    }
}
