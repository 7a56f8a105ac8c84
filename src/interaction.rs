//! Interactions and their container (YADE `core/Interaction.{hpp,cpp}`,
//! `core/InteractionContainer.{hpp,cpp}`).
//!
//! The container is a flat vector visited in order by the interaction loop; YADE's order rules are
//! kept exactly because they set the force summation order: new pairs are appended, an erased pair
//! is replaced by the last one (`swap_remove`). A hash map finds a pair's slot.

use crate::geom::ScGeom;
use crate::phys::FrictPhys;
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
        self.functor = GeomFunctor::Unresolved;
        self.iter_made_real = -1;
    }

    /// `Interaction::swapOrder`: swap the ids and negate the period.
    pub fn swap_order(&mut self) {
        std::mem::swap(&mut self.id1, &mut self.id2);
        for c in self.cell_dist.iter_mut() {
            *c = -*c;
        }
    }
}

#[inline(always)]
fn key(a: u32, b: u32) -> u64 {
    let (lo, hi) = if a < b { (a, b) } else { (b, a) };
    ((lo as u64) << 32) | hi as u64
}

#[derive(Clone, Debug, Default)]
pub struct Interactions {
    pub list: Vec<Interaction>,
    index: FxHashMap<u64, u32>,
    /// Set when the container was cleared; forces the collider to re-initialise.
    pub dirty: bool,
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
        true
    }

    /// `InteractionContainer::erase`: the last interaction takes the erased one's slot.
    pub fn erase_at(&mut self, pos: usize) {
        let k = key(self.list[pos].id1, self.list[pos].id2);
        self.index.remove(&k);
        self.list.swap_remove(pos);
        if pos < self.list.len() {
            let moved = key(self.list[pos].id1, self.list[pos].id2);
            self.index.insert(moved, pos as u32);
        }
    }

    pub fn clear(&mut self) {
        self.list.clear();
        self.index.clear();
        self.dirty = true;
    }

    pub fn count_real(&self) -> usize {
        self.list.iter().filter(|i| i.is_real()).count()
    }
}
