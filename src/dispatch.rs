//! YADE's functor dispatch (`lib/multimethods/DynLibDispatcher.hpp`): a functor declared for a pair
//! of classes also serves derived classes; the nearest match by summed class-hierarchy distance wins,
//! two different functors at the same distance are an error. Functors whose two argument classes
//! share a base (shapes, materials) are registered in both orders, the reversed one with `swap`.
//! Used for geometry (shapes), physics (materials) and law (geometry, physics) dispatch.

/// A class hierarchy: `parent(c)` is the direct base of class `c` (None at the root).
pub trait Hierarchy: Copy + PartialEq {
    fn parent(self) -> Option<Self>;

    /// The ancestor at `depth` (0: the class itself), None past the root.
    fn ancestor(self, depth: usize) -> Option<Self> {
        let mut c = self;
        for _ in 0..depth {
            c = c.parent()?;
        }
        Some(c)
    }
}

/// One registered functor: its declared argument classes and a value identifying it.
#[derive(Clone, Copy)]
pub struct Entry<A, B, F> {
    pub a: A,
    pub b: B,
    pub f: F,
}

/// `locateMultivirtualFunctor2D` on a table built from `entries` in registration order (a later
/// functor for the same class pair replaces an earlier one, as `add2DEntry` does). `symmetric` is
/// true when both arguments come from the same base (reverse entries are added with swap = true).
/// Returns the functor and whether the arguments must be swapped; Err on an ambiguous dispatch.
pub fn resolve<A: Hierarchy, B: Hierarchy, F: Copy + PartialEq>(
    entries: &[Entry<A, B, F>],
    symmetric: bool,
    c1: A,
    c2: B,
    cast: impl Fn(A) -> Option<B>,
    cast_back: impl Fn(B) -> Option<A>,
) -> Result<Option<(F, bool)>, String> {
    // the dispatch matrix cell for (x, y)
    let cell = |x: A, y: B| -> Option<(F, bool)> {
        let mut found = None;
        for e in entries {
            if e.a == x && e.b == y {
                found = Some((e.f, false));
            } else if symmetric {
                if let (Some(ea), Some(eb)) = (cast(e.a), cast_back(e.b)) {
                    // reverse registration: (b, a) with swap
                    if eb == x && ea == y && !(e.a == x && e.b == y) {
                        found = Some((e.f, true));
                    }
                }
            }
        }
        found
    };
    if let Some(hit) = cell(c1, c2) {
        return Ok(Some(hit));
    }
    let mut max_dp1: Option<usize> = None;
    let mut max_dp2: Option<usize> = None;
    for dist in 1usize.. {
        let mut too_big = true;
        let mut found: Option<(F, bool)> = None;
        for dp1 in 0..=dist {
            let dp2 = dist - dp1;
            if max_dp1.is_some_and(|m| dp1 > m) || max_dp2.is_some_and(|m| dp2 > m) {
                continue;
            }
            let x = c1.ancestor(dp1);
            let y = c2.ancestor(dp2);
            if x.is_none() {
                max_dp1 = Some(dp1);
            }
            if y.is_none() {
                max_dp2 = Some(dp2);
            }
            let (Some(x), Some(y)) = (x, y) else {
                continue;
            };
            too_big = false;
            if let Some(hit) = cell(x, y) {
                if let Some(prev) = found {
                    if prev.0 != hit.0 {
                        return Err("ambiguous functor dispatch".into());
                    }
                }
                found = Some(hit);
            }
        }
        if found.is_some() {
            return Ok(found);
        }
        if too_big {
            return Ok(None);
        }
    }
    unreachable!()
}
