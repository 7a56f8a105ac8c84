//! `O.energy`: YADE's `EnergyTracker` (core/EnergyTracker.hpp) over its `OpenMPArrayAccumulator`
//! (lib/base/openmp-accu.hpp), with one thread's arithmetic.
//!
//! Each engine or law functor caches the index of every energy it adds (`-1` until its first add,
//! which looks the name up or creates it). `clear()` forgets the names and shrinks the visible size
//! but keeps the storage, and the engines keep their cached indices: after a clear, YADE's engines go
//! on adding to slots no name shows (the energies look empty), and a name created later takes slot 0
//! (zeroed), where the engine that cached slot 0 keeps adding. ryade mirrors that, so a script reads
//! what YADE prints.

use std::collections::BTreeMap;

/// Slots per cache line: YADE grows the accumulator by cache lines (64 bytes of doubles) and zeroes
/// only the lines it adds.
const PER_LINE: usize = 8;

#[derive(Clone, Debug, Default)]
pub struct EnergyTracker {
    /// The accumulator's storage: never shrinks (`clear` only moves `size`).
    slots: Vec<f64>,
    /// `energies.size()`: the slots `total()` sums and names may point to.
    size: usize,
    /// name -> slot (`std::map`, so `keys()`/`items()` list names in byte order)
    names: BTreeMap<String, usize>,
    /// `resetStep`: slots zeroed by `ForceResetter` every step.
    reset: Vec<bool>,
}

/// An engine's cached energy indices, one per energy name it adds (`-1`: not looked up yet).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct IdCache(Vec<(&'static str, i32)>);

impl IdCache {
    fn slot(&mut self, name: &'static str) -> &mut i32 {
        let k = match self.0.iter().position(|(n, _)| *n == name) {
            Some(k) => k,
            None => {
                self.0.push((name, -1));
                self.0.len() - 1
            }
        };
        &mut self.0[k].1
    }
}

impl EnergyTracker {
    /// `OpenMPArrayAccumulator::resize`: grows the storage by cache lines, never shrinks it, and
    /// zeroes the slots it adds to the visible size.
    fn resize(&mut self, n: usize) {
        let lines = n.div_ceil(PER_LINE);
        if lines * PER_LINE > self.slots.len() {
            self.slots.resize(lines * PER_LINE, 0.0);
        }
        for k in self.size..n {
            self.slots[k] = 0.0;
        }
        self.size = n;
    }

    /// `EnergyTracker::findId`: the slot of `name`, created (with its reset flag) if new and
    /// `create`; `None` if absent and not created.
    fn find_id(&mut self, name: &str, reset: bool, create: bool) -> Option<usize> {
        if let Some(&id) = self.names.get(name) {
            return Some(id);
        }
        if !create {
            return None;
        }
        let id = self.size;
        self.resize(id + 1);
        self.reset.resize(id + 1, false);
        self.reset[id] = reset;
        self.names.insert(name.to_string(), id);
        Some(id)
    }

    /// `EnergyTracker::add(val, name, id, reset)`: `reset` marks a value recomputed every step
    /// (kinetic, elastic potential) rather than accumulated (dissipation, work).
    pub fn add(&mut self, val: f64, name: &'static str, cache: &mut IdCache, reset: bool) {
        let id = cache.slot(name);
        if *id < 0 {
            *id = self.find_id(name, reset, true).unwrap() as i32;
        }
        let k = *id as usize;
        if k >= self.slots.len() {
            // only reachable after `clear()`; YADE writes past its size there too
            self.slots
                .resize(k.div_ceil(PER_LINE).max(1) * PER_LINE, 0.0);
        }
        self.slots[k] += val;
    }

    /// `OpenMPArrayAccumulator::get` with one thread: `0 + slot`.
    fn get(&self, id: usize) -> f64 {
        0.0 + self.slots[id]
    }

    /// `O.energy[name]`; `None` for a name the tracker does not have (YADE: KeyError).
    pub fn get_item(&self, name: &str) -> Option<f64> {
        self.names.get(name).map(|&id| self.get(id))
    }

    /// `O.energy[name] = val`: creates a non-resettable entry if new.
    pub fn set_item(&mut self, name: &str, val: f64) {
        let id = self.find_id(name, false, true).unwrap();
        self.slots[id] = val;
    }

    /// `O.energy.clear()`: names and reset flags dropped, size 0, slots kept (see the module doc).
    pub fn clear(&mut self) {
        self.resize(0);
        self.names.clear();
        self.reset.clear();
    }

    /// `EnergyTracker::resetResettables` (ForceResetter, every step while `O.trackEnergy`).
    pub fn reset_resettables(&mut self) {
        for id in 0..self.size {
            if self.reset[id] {
                self.slots[id] = 0.0;
            }
        }
    }

    /// `O.energy.total()`: the slots summed in index (creation) order.
    pub fn total(&self) -> f64 {
        let mut t = 0.0;
        for id in 0..self.size {
            t += self.get(id);
        }
        t
    }

    /// `O.energy.items()`: (name, value) in name order.
    pub fn items(&self) -> Vec<(String, f64)> {
        self.names
            .iter()
            .map(|(n, &id)| (n.clone(), self.get(id)))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_sorted_total_in_creation_order_resettables_zeroed() {
        let mut e = EnergyTracker::default();
        let mut c = IdCache::default();
        e.add(1.0, "nonviscDamp", &mut c, false);
        e.add(2.0, "kinetic", &mut c, true);
        e.add(1e-17, "gravWork", &mut c, false);
        e.add(0.5, "nonviscDamp", &mut c, false);
        assert_eq!(
            e.items(),
            vec![
                ("gravWork".to_string(), 1e-17),
                ("kinetic".to_string(), 2.0),
                ("nonviscDamp".to_string(), 1.5)
            ]
        );
        e.reset_resettables();
        assert_eq!(e.get_item("kinetic"), Some(0.0));
        assert_eq!(e.get_item("nonviscDamp"), Some(1.5));
        assert_eq!(e.get_item("nope"), None);
    }

    #[test]
    fn total_sums_in_creation_order_not_name_order() {
        let mut e = EnergyTracker::default();
        let mut c = IdCache::default();
        e.add(1e16, "z", &mut c, false);
        e.add(-1e16, "a", &mut c, false);
        e.add(1.0, "m", &mut c, false);
        // creation order: (1e16 - 1e16) + 1 = 1; name order would give (-1e16 + 1) + 1e16 = 0
        assert_eq!(e.total(), 1.0);
    }

    #[test]
    fn clear_keeps_slots_and_engine_caches_as_yade() {
        // YADE 2023.02a: after O.energy.clear(), running shows no energy; a name set later takes
        // slot 0 and the engine that cached slot 0 keeps adding to it
        let mut e = EnergyTracker::default();
        let mut newton = IdCache::default();
        e.add(3.0, "nonviscDamp", &mut newton, false);
        e.add(4.0, "kinetic", &mut newton, true);
        e.clear();
        assert!(e.items().is_empty());
        assert_eq!(e.total(), 0.0);
        e.add(1.0, "nonviscDamp", &mut newton, false);
        e.reset_resettables();
        assert!(e.items().is_empty());
        e.set_item("foo", 1.5);
        e.add(0.25, "nonviscDamp", &mut newton, false);
        assert_eq!(e.items(), vec![("foo".to_string(), 1.75)]);
        // a new engine (fresh cache) finds no name and creates slot 1, zeroed (it held 4.0)
        let mut fresh = IdCache::default();
        e.add(0.5, "kinetic", &mut fresh, true);
        assert_eq!(e.get_item("kinetic"), Some(0.5));
    }
}
