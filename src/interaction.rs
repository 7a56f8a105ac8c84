//! Interactions and their container (YADE `core/Interaction.{hpp,cpp}`,
//! `core/InteractionContainer.{hpp,cpp}`).
//!
//! The container is a flat vector visited in order by the interaction loop; YADE's order rules are
//! kept exactly because they set the force summation order: new pairs are appended, an erased pair
//! is replaced by the last one (`swap_remove`). A hash map finds a pair's slot.

use crate::geom::{GeomClass, GeomExt, ScGeom};
use crate::phys::{
    BubblePhys, CohFrictPhys, FrictPhys, LudingPhys, MindlinPhys, PhysClass, ViscElPhys,
};
use rustc_hash::FxHashMap;

/// Which geometry functor handles an interaction, resolved once per interaction lifetime as YADE's
/// `functorCache` does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GeomFunctor {
    Unresolved,
    /// No functor for this pair of shapes: YADE sets `geomExists = false` and skips it for good.
    Missing,
    SphereSphere,
    FacetSphere,
    WallSphere,
    BoxSphere,
    SphereSphere6D,
    GridNodeGridNode,
    SphereGridConnection,
    GridConnectionGridConnection,
}

/// The class-specific parts of an interaction's geometry and physics beyond `ScGeom`/`FrictPhys`
/// (6-D rotations, grid data, cohesive physics). Interactions of plain sphere/facet/wall/box contacts
/// never allocate one; the others get it when their geometry or physics is created.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct IntrExt {
    pub geom: Option<GeomExt>,
    /// `Some` when the physics is a `CohFrictPhys`.
    pub coh: Option<CohFrictPhys>,
    /// `Some` when the physics is a `ViscElPhys`.
    pub viscel: Option<ViscElPhys>,
    /// `Some` when the physics is a `MindlinPhys`.
    pub mindlin: Option<MindlinPhys>,
    /// `Some` when the physics is a `LudingPhys`.
    pub luding: Option<LudingPhys>,
    /// `Some` when the physics is a `BubblePhys`.
    pub bubble: Option<BubblePhys>,
    /// `Some` when the physics is a `CpmPhys` (boxed: it is large).
    pub cpm: Option<Box<crate::phys::CpmPhys>>,
}

#[derive(Clone, Debug)]
pub struct Interaction {
    /// After the functor swap, id1 is the facet/wall/box of a mixed pair.
    pub id1: u32,
    pub id2: u32,
    /// Period of body 2 relative to body 1; survives `reset()` (YADE's warning in Interaction.hpp).
    pub cell_dist: [i32; 3],
    pub geom: Option<ScGeom>,
    pub phys: Option<FrictPhys>,
    /// The non-ScGeom / non-FrictPhys parts (see `IntrExt`); None for plain contacts.
    pub ext: Option<Box<IntrExt>>,
    pub functor: GeomFunctor,
    pub iter_made_real: i64,
    pub iter_born: i64,
}

impl Interaction {
    pub fn new(id1: u32, id2: u32, cell_dist: [i32; 3], iter: i64) -> Interaction {
        Interaction {
            id1,
            id2,
            cell_dist,
            geom: None,
            phys: None,
            ext: None,
            functor: GeomFunctor::Unresolved,
            iter_made_real: -1,
            iter_born: iter,
        }
    }

    /// `Interaction::isReal`: both geometry and physics exist.
    #[inline(always)]
    pub fn is_real(&self) -> bool {
        self.geom.is_some() && self.phys.is_some()
    }

    /// `Interaction::reset` (what `requestErase` does): back to potential, functor cache cleared.
    pub fn reset(&mut self) {
        self.geom = None;
        self.phys = None;
        self.ext = None;
        self.functor = GeomFunctor::Unresolved;
        self.iter_made_real = -1;
    }

    /// The viscoelastic physics part, if the physics is a `ViscElPhys`.
    #[inline(always)]
    pub fn viscel(&self) -> Option<&ViscElPhys> {
        self.ext.as_ref().and_then(|e| e.viscel.as_ref())
    }

    /// The Hertz-Mindlin physics part, if the physics is a `MindlinPhys`.
    #[inline(always)]
    pub fn mindlin(&self) -> Option<&MindlinPhys> {
        self.ext.as_ref().and_then(|e| e.mindlin.as_ref())
    }

    /// The concrete-model physics part, if the physics is a `CpmPhys`.
    #[inline(always)]
    pub fn cpm(&self) -> Option<&crate::phys::CpmPhys> {
        self.ext.as_ref().and_then(|e| e.cpm.as_deref())
    }

    /// The Luding physics part, if the physics is a `LudingPhys`.
    #[inline(always)]
    pub fn luding(&self) -> Option<&LudingPhys> {
        self.ext.as_ref().and_then(|e| e.luding.as_ref())
    }

    /// The geometry extension, if any.
    #[inline(always)]
    pub fn geom_ext(&self) -> Option<&GeomExt> {
        self.ext.as_ref().and_then(|e| e.geom.as_ref())
    }

    /// The cohesive physics part, if the physics is a `CohFrictPhys`.
    #[inline(always)]
    pub fn coh(&self) -> Option<&CohFrictPhys> {
        self.ext.as_ref().and_then(|e| e.coh.as_ref())
    }

    /// The extension, allocated on first use.
    pub fn ext_mut(&mut self) -> &mut IntrExt {
        self.ext.get_or_insert_with(Default::default)
    }

    /// YADE's class of the geometry (None without geometry).
    pub fn geom_class(&self) -> Option<GeomClass> {
        self.geom.as_ref()?;
        Some(self.geom_ext().map_or(GeomClass::ScGeom, |g| g.class()))
    }

    /// The class of the physics (of a real interaction), from the physics part the extension
    /// holds: a plain FrictPhys without one.
    #[inline(always)]
    pub fn phys_class(&self) -> PhysClass {
        let Some(e) = self.ext.as_deref() else {
            return PhysClass::FrictPhys;
        };
        if e.coh.is_some() {
            PhysClass::CohFrictPhys
        } else if e.viscel.is_some() {
            PhysClass::ViscElPhys
        } else if e.mindlin.is_some() {
            PhysClass::MindlinPhys
        } else if e.luding.is_some() {
            PhysClass::LudingPhys
        } else if e.bubble.is_some() {
            PhysClass::BubblePhys
        } else if e.cpm.is_some() {
            PhysClass::CpmPhys
        } else {
            PhysClass::FrictPhys
        }
    }

    /// `Interaction::swapOrder`: swap the ids and negate the period.
    pub fn swap_order(&mut self) {
        std::mem::swap(&mut self.id1, &mut self.id2);
        for c in self.cell_dist.iter_mut() {
            *c = -*c;
        }
    }
}

/// Ask the CPU to bring `v` into cache (a hint only: no effect on results).
#[inline(always)]
pub(crate) fn prefetch_value<T>(v: &T) {
    #[cfg(target_arch = "x86_64")]
    {
        let p = v as *const T as *const i8;
        let size = std::mem::size_of::<T>();
        let mut off = 0;
        while off < size {
            // SAFETY: prefetch never faults; the address lies inside `v`
            unsafe { std::arch::x86_64::_mm_prefetch(p.add(off), std::arch::x86_64::_MM_HINT_T0) };
            off += 64;
        }
        // SAFETY: as above
        unsafe { std::arch::x86_64::_mm_prefetch(p.add(size - 1), std::arch::x86_64::_MM_HINT_T0) };
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = v;
}

/// Ask the CPU to bring an interaction into cache (a hint only: no effect on results).
#[inline(always)]
pub fn prefetch(it: &Interaction) {
    prefetch_value(it);
}

/// Ask the CPU to bring an interaction's extension (6-D rotations, cohesive physics; a separate
/// allocation) into cache: call it a few slots after `prefetch`, once the interaction has arrived.
#[inline(always)]
pub fn prefetch_ext(it: &Interaction) {
    if let Some(e) = it.ext.as_deref() {
        prefetch_value(e);
    }
}

#[inline(always)]
fn key(a: u32, b: u32) -> u64 {
    let (lo, hi) = if a < b { (a, b) } else { (b, a) };
    ((lo as u64) << 32) | hi as u64
}

/// A compact per-slot summary the interaction loop reads instead of the (large) interaction, so
/// that the many potential pairs cost one small sequential read per step. `idle` is set only by the
/// interaction loop, for a potential sphere-sphere pair whose functor is resolved; `id1`, `id2` and
/// `cell_dist` are copied from the interaction at that moment. Invariant: while `idle` is set the
/// interaction is potential (no geometry, no physics), its functor is `SphereSphere` and its ids and
/// period equal the copies here. Only the interaction loop turns such a pair real, and it clears
/// `idle` when it does; new slots start with `idle` cleared. `deadline` is read only while `idle`
/// is set: the pair is provably still apart while `IdleSkip::travel` stays below it.
/// `idle_gc` is the same for a potential sphere-`GridConnection` pair (functor
/// `SphereGridConnection`, `id1` the sphere); at most one of the two flags is set.
#[derive(Clone, Copy, Debug)]
pub struct ScanEntry {
    pub id1: u32,
    pub id2: u32,
    pub cell_dist: [i32; 3],
    pub idle: bool,
    pub idle_gc: bool,
    /// For `idle_gc`: the sphere's count of real connection interactions gained
    /// (`IdleSkip::grid_gen`) when the deadline was set, or `idle_skip::GEN_FREE` for a deadline
    /// that no gain ends.
    pub gen: u16,
    pub deadline: f64,
}

impl ScanEntry {
    /// Either kind of idle pair: the loop need not prefetch its interaction.
    #[inline(always)]
    pub fn is_idle(&self) -> bool {
        self.idle | self.idle_gc
    }
}

impl Default for ScanEntry {
    fn default() -> Self {
        ScanEntry {
            id1: 0,
            id2: 0,
            cell_dist: [0; 3],
            idle: false,
            idle_gc: false,
            gen: 0,
            deadline: f64::NEG_INFINITY,
        }
    }
}

#[derive(Clone, Debug, Default)]
pub struct Interactions {
    pub list: Vec<Interaction>,
    /// One `ScanEntry` per slot of `list`, kept in step by `insert`, `erase_at` and `clear`.
    pub scan: Vec<ScanEntry>,
    index: FxHashMap<u64, u32>,
    /// Set when the container was cleared; forces the collider to re-initialise.
    pub dirty: bool,
    /// Sphere-connection geometry/physics objects that YADE shares between interactions (a sliding
    /// sphere handed over to the next connection): share id -> the pairs holding a copy.
    shared: FxHashMap<u32, Vec<(u32, u32)>>,
    next_share: u32,
}

impl Interactions {
    pub fn len(&self) -> usize {
        self.list.len()
    }

    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// `InteractionContainer::found`: false for a body with itself.
    #[inline(always)]
    pub fn found(&self, a: u32, b: u32) -> bool {
        a != b && self.index.contains_key(&key(a, b))
    }

    pub fn find(&self, a: u32, b: u32) -> Option<usize> {
        self.index.get(&key(a, b)).map(|&i| i as usize)
    }

    /// `InteractionContainer::insert`: append unless the pair exists.
    pub fn insert(&mut self, i: Interaction) -> bool {
        let k = key(i.id1, i.id2);
        if self.index.contains_key(&k) {
            return false;
        }
        self.index.insert(k, self.list.len() as u32);
        self.list.push(i);
        self.scan.push(ScanEntry::default());
        true
    }

    /// `InteractionContainer::erase`: the last interaction takes the erased one's slot.
    pub fn erase_at(&mut self, pos: usize) {
        let k = key(self.list[pos].id1, self.list[pos].id2);
        self.index.remove(&k);
        self.list.swap_remove(pos);
        self.scan.swap_remove(pos);
        if pos < self.list.len() {
            let moved = key(self.list[pos].id1, self.list[pos].id2);
            self.index.insert(moved, pos as u32);
        }
    }

    pub fn clear(&mut self) {
        self.list.clear();
        self.scan.clear();
        self.index.clear();
        self.shared.clear();
        self.dirty = true;
    }

    /// A new identity for a shared sphere-connection geometry object.
    pub fn new_share_id(&mut self) -> u32 {
        self.next_share += 1;
        self.next_share
    }

    /// Record that the interaction of `pair` holds a copy of shared object `share`.
    pub fn register_share(&mut self, share: u32, pair: (u32, u32)) {
        let v = self.shared.entry(share).or_default();
        if !v.contains(&pair) {
            v.push(pair);
        }
    }

    /// The share id of the sphere-connection geometry of interaction `k` (0: not shared).
    pub fn share_of(&self, k: usize) -> u32 {
        match self.list[k].geom_ext() {
            Some(GeomExt::ScGridCo(x)) => x.share,
            _ => 0,
        }
    }

    /// Interaction `k` changed a shared object: copy its geometry and physics to every other
    /// interaction still holding that object (all copies then stand for YADE's single C++ object).
    /// Holders that were reset or erased since are dropped from the group.
    pub fn sync_shared(&mut self, k: usize) {
        let share = self.share_of(k);
        if share == 0 {
            return;
        }
        // (the group taken out of the map while it is walked, and put back without reallocating)
        let Some(mut members) = self.shared.get_mut(&share).map(std::mem::take) else {
            return;
        };
        let (geom, phys) = (self.list[k].geom, self.list[k].phys);
        let ext = self.list[k].ext.as_ref().map(|e| (e.geom, e.coh));
        members.retain(|pair| {
            let Some(j) = self.find(pair.0, pair.1) else {
                return false;
            };
            if self.share_of(j) != share {
                return false;
            }
            if j != k {
                let it = &mut self.list[j];
                it.geom = geom;
                it.phys = phys;
                if let Some((g, c)) = ext {
                    let e = it.ext_mut();
                    e.geom = g;
                    e.coh = c;
                }
            }
            true
        });
        if members.len() <= 1 {
            self.shared.remove(&share);
        } else if let Some(v) = self.shared.get_mut(&share) {
            *v = members;
        }
    }

    /// Ask the CPU to bring slot `k` into cache ahead of use (a hint only: no effect on results).
    /// The interaction loop skips the idle slots, so the remaining ones are too sparse for the
    /// hardware prefetcher.
    #[inline(always)]
    pub fn prefetch(&self, k: usize) {
        if let Some(it) = self.list.get(k) {
            prefetch(it);
        }
    }

    /// `prefetch_ext` of slot `k`, if any.
    #[inline(always)]
    pub fn prefetch_ext(&self, k: usize) {
        if let Some(it) = self.list.get(k) {
            prefetch_ext(it);
        }
    }

    pub fn count_real(&self) -> usize {
        self.list.iter().filter(|i| i.is_real()).count()
    }
}
