//! `InsertionSortCollider` (pkg/common/InsertionSortCollider.{hpp,cpp}), replayed step for step.
//!
//! Which contacts exist never depends on the collider (the Ig2 functors decide every step), but the
//! *order* in which pairs enter the interaction container does, and that order is the force summation
//! order. To match YADE to the last bit on multi-contact scenes we keep its algorithm exactly: the
//! first run `std::sort`s the bound lists (libstdc++'s introsort, see `stdsort`) and sweeps axis
//! `sort_axis`; later runs insertion-sort the three lists and create a pair at every min-over-max
//! inversion whose boxes overlap; striding (`verletDist`) decides when it runs at all.

use crate::body::Bodies;
use crate::bound::{update_bounds, BoundFunctors, Sweep};
use crate::cell::Cell;
use crate::interaction::{Interaction, Interactions};
use crate::stdsort::std_sort;

#[derive(Clone, Copy, Debug)]
struct BoundEntry {
    coord: f64,
    id: u32,
    period: i32,
    has_bb: bool,
    is_min: bool,
}

/// `Bounds::operator<`: zero-width bodies keep min before max.
#[inline(always)]
fn lt(a: &BoundEntry, b: &BoundEntry) -> bool {
    if a.id == b.id && a.coord == b.coord {
        a.is_min
    } else {
        a.coord < b.coord
    }
}

/// `Bounds::operator>`.
#[inline(always)]
fn gt(a: &BoundEntry, b: &BoundEntry) -> bool {
    if a.id == b.id && a.coord == b.coord {
        !a.is_min
    } else {
        a.coord > b.coord
    }
}

#[derive(Clone, Debug, Default)]
struct VecBounds {
    v: Vec<BoundEntry>,
    cell_dim: f64,
    lo_idx: usize,
}

/// `Collider::mayCollide`'s mask rule (pkg/common/Collider.cpp): the groupMasks share a bit, and two
/// equal masks do not carry a bit of `avoidSelfInteractionMask`.
#[inline(always)]
pub fn masks_may_collide(ma: i32, mb: i32, avoid: i32) -> bool {
    (ma & mb) != 0 && !(ma == mb && (ma & avoid) != 0)
}

impl VecBounds {
    /// `VecBounds::norm`: index modulo the list size, negative indices wrapped.
    #[inline(always)]
    fn norm(&self, i: i64) -> usize {
        let n = self.v.len() as i64;
        let i = if i < 0 { i + n } else { i };
        (i % n) as usize
    }
}

/// User parameters, YADE's defaults in `Default`.
#[derive(Clone, Debug, PartialEq)]
pub struct ColliderParams {
    pub bounds: BoundFunctors,
    /// Negative: |verletDist| × the smallest sphere radius, resolved on the first run.
    pub verlet_dist: f64,
    pub allow_bigger_than_period: bool,
    pub target_interv: i32,
    pub min_sweep_dist_factor: f64,
    pub sort_axis: usize,
    pub sort_then_collide: bool,
    pub overlap_tolerance: f64,
    pub avoid_self_interaction_mask: i32,
}

impl Default for ColliderParams {
    fn default() -> Self {
        ColliderParams {
            bounds: BoundFunctors::default(),
            verlet_dist: -0.5,
            allow_bigger_than_period: false,
            target_interv: 100,
            min_sweep_dist_factor: 0.1,
            sort_axis: 0,
            sort_then_collide: false,
            overlap_tolerance: 1e-7,
            avoid_self_interaction_mask: 0,
        }
    }
}

#[derive(Clone, Debug, Default)]
pub struct Collider {
    pub p: ColliderParams,
    bb: [VecBounds; 3],
    minima: Vec<f64>,
    maxima: Vec<f64>,
    periodic: bool,
    inv_sizes: [f64; 3],
    stride_active: bool,
    pub num_action: u64,
    pub num_reinit: u64,
    /// Forced re-sort on the next run (`InsertionSortCollider.doSort`).
    pub do_sort: bool,
}

/// Scene data the collider reads and writes.
pub struct ColliderCtx<'a> {
    pub bodies: &'a mut Bodies,
    pub interactions: &'a mut Interactions,
    pub cell: Option<&'a Cell>,
    pub iter: i64,
    /// Newton's displacement indicator (`NewtonIntegrator::maxVelocitySq`), if a Newton exists.
    pub newton_indicator: Option<f64>,
}

impl Collider {
    pub fn new(p: ColliderParams) -> Collider {
        Collider {
            p,
            ..Default::default()
        }
    }

    /// The resolved verlet distance (after the first run, when it was given as negative).
    pub fn verlet_dist(&self) -> f64 {
        self.p.verlet_dist
    }

    /// `InsertionSortCollider::isActivated`.
    pub fn is_activated(&self, n_bodies: usize, ctx_newton: Option<f64>, dirty: bool) -> bool {
        if !self.stride_active {
            return true;
        }
        let Some(fastest) = ctx_newton else {
            return true;
        };
        if fastest >= 1.0 || fastest == 0.0 {
            return true;
        }
        self.bb[0].v.len() != 2 * n_bodies || dirty || self.do_sort
    }

    /// Bytes held by the collider's bound lists and bound copies.
    pub fn memory_bytes(&self) -> usize {
        self.bb
            .iter()
            .map(|b| b.v.capacity() * std::mem::size_of::<BoundEntry>())
            .sum::<usize>()
            + (self.minima.capacity() + self.maxima.capacity()) * std::mem::size_of::<f64>()
    }

    /// `Collider::mayCollide` (pkg/common/Collider.cpp): not two members of one clump, no clump
    /// itself, masks sharing a bit and the avoidSelfInteractionMask rule (no "one must be dynamic"
    /// rule).
    #[inline(always)]
    fn may_collide(&self, bodies: &Bodies, a: u32, b: u32) -> bool {
        let (a, b) = (a as usize, b as usize);
        let (ca, cb) = (bodies.clump_id[a], bodies.clump_id[b]);
        if (ca.is_some() || cb.is_some()) && (ca == cb || bodies.is_clump(a) || bodies.is_clump(b))
        {
            return false;
        }
        masks_may_collide(
            bodies.mask[a],
            bodies.mask[b],
            self.p.avoid_self_interaction_mask,
        )
    }

    #[inline(always)]
    fn spatial_overlap(&self, a: u32, b: u32) -> bool {
        let (a, b) = (3 * a as usize, 3 * b as usize);
        let (mn, mx) = (&self.minima, &self.maxima);
        mn[a] <= mx[b]
            && mx[a] >= mn[b]
            && mn[a + 1] <= mx[b + 1]
            && mx[a + 1] >= mn[b + 1]
            && mn[a + 2] <= mx[b + 2]
            && mx[a + 2] >= mn[b + 2]
    }

    /// `spatialOverlapPeri`: overlap through the periods, with the period of body 2 relative to 1.
    fn spatial_overlap_peri(
        &self,
        a: u32,
        b: u32,
        cell: &Cell,
    ) -> Result<Option<[i32; 3]>, String> {
        let mut periods = [0i32; 3];
        let (a3, b3) = (3 * a as usize, 3 * b as usize);
        for (axis, period) in periods.iter_mut().enumerate() {
            let inv = self.inv_sizes[axis];
            let lmin = (self.minima[b3 + axis] - self.maxima[a3 + axis]) * inv;
            let lmax = (self.maxima[b3 + axis] - self.maxima[a3 + axis]) * inv;
            let shifted_min = (self.minima[a3 + axis] - self.maxima[a3 + axis]) * inv + 1.0;
            if (lmax - lmin) > 0.5 || shifted_min < 0.0 {
                if self.p.allow_bigger_than_period {
                    *period = 0;
                    continue;
                }
                return Err(format!(
                    "body #{} spans over half of the cell size {} (axis={}): set \
                     InsertionSortCollider(allowBiggerThanPeriod=True) for floors, or enlarge the cell",
                    if (lmax - lmin) > 0.5 { b } else { a },
                    cell.size()[axis],
                    axis
                ));
            }
            let period1 = lmax.floor() as i32;
            if (lmin - period1 as f64) <= self.p.overlap_tolerance {
                *period = -period1;
                continue;
            }
            if (lmax - period1 as f64 + self.p.overlap_tolerance) >= shifted_min {
                *period = -period1 - 1;
                continue;
            }
            return Ok(None);
        }
        Ok(Some(periods))
    }

    fn should_be_erased(&self, a: u32, b: u32, cell: Option<&Cell>) -> Result<bool, String> {
        match cell {
            None => Ok(!self.spatial_overlap(a, b)),
            Some(c) => Ok(self.spatial_overlap_peri(a, b, c)?.is_none()),
        }
    }

    /// `handleBoundInversion` (aperiodic): create the pair if the boxes overlap in 3-D.
    fn handle_inversion(
        &self,
        bodies: &Bodies,
        intrs: &mut Interactions,
        a: u32,
        b: u32,
        iter: i64,
    ) {
        if self.spatial_overlap(a, b) && self.may_collide(bodies, a, b) && !intrs.found(a, b) {
            intrs.insert(Interaction::new(a, b, [0; 3], iter));
        }
    }

    /// `handleBoundInversionPeri`.
    fn handle_inversion_peri(
        &self,
        bodies: &Bodies,
        intrs: &mut Interactions,
        cell: &Cell,
        a: u32,
        b: u32,
        iter: i64,
    ) -> Result<(), String> {
        if intrs.found(a, b) {
            return Ok(());
        }
        if let Some(periods) = self.spatial_overlap_peri(a, b, cell)? {
            if self.may_collide(bodies, a, b) {
                intrs.insert(Interaction::new(a, b, periods, iter));
            }
        }
        Ok(())
    }

    /// `insertionSort` (aperiodic).
    fn insertion_sort(
        &mut self,
        axis: usize,
        bodies: &Bodies,
        intrs: &mut Interactions,
        iter: i64,
        collide: bool,
    ) {
        let mut v = std::mem::take(&mut self.bb[axis].v);
        for i in 1..v.len() {
            let vi = v[i];
            let mut j = i as i64 - 1;
            while j >= 0 && gt(&v[j as usize], &vi) {
                let vj = v[j as usize];
                v[j as usize + 1] = vj;
                if vi.is_min && !vj.is_min && collide && vi.has_bb && vj.has_bb && vi.id != vj.id {
                    let (a, b) = if vi.id < vj.id {
                        (vi.id, vj.id)
                    } else {
                        (vj.id, vi.id)
                    };
                    self.handle_inversion(bodies, intrs, a, b, iter);
                }
                j -= 1;
            }
            v[(j + 1) as usize] = vi;
        }
        self.bb[axis].v = v;
    }

    /// `insertionSortPeri`: the list is circular, split at `lo_idx`; bounds crossing the split change
    /// period.
    fn insertion_sort_peri(
        &mut self,
        axis: usize,
        bodies: &Bodies,
        intrs: &mut Interactions,
        cell: &Cell,
        iter: i64,
        collide: bool,
    ) -> Result<(), String> {
        if self.bb[0].v.is_empty() {
            return Ok(());
        }
        let mut vb = std::mem::take(&mut self.bb[axis]);
        let size = vb.v.len();
        let cd = vb.cell_dim;
        let mut res = Ok(());
        let mut ui: usize = 0;
        while ui < size || vb.v[vb.norm(ui as i64)].coord < vb.v[vb.norm(ui as i64 - 1)].coord {
            let i = vb.norm(ui as i64);
            let i_1 = vb.norm(i as i64 - 1);
            if i == vb.lo_idx && vb.v[i].coord < 0.0 {
                vb.v[i].period -= 1;
                vb.v[i].coord += cd;
                vb.lo_idx = vb.norm(vb.lo_idx as i64 + 1);
            }
            let i_cmp = vb.v[i].coord + if i == vb.lo_idx { cd } else { 0.0 };
            if vb.v[i_1].coord <= i_cmp {
                ui += 1;
                continue;
            }
            let mut j = i_1;
            let mut vi = vb.v[i];
            let vi_has_bb = vi.has_bb;
            let is_min = vb.v[i].is_min;
            while j < ui
                && vb.v[j].coord
                    > (vi.coord
                        + if vb.norm(j as i64 + 1) == vb.lo_idx {
                            cd
                        } else {
                            0.0
                        })
            {
                let j1 = vb.norm(j as i64 + 1);
                vb.v[j1] = vb.v[j];
                if j == vb.lo_idx && vi.coord < 0.0 {
                    vi.period -= 1;
                    vi.coord += cd;
                    vb.lo_idx = vb.norm(vb.lo_idx as i64 + 1);
                } else if j1 == vb.lo_idx {
                    vb.v[j1].period += 1;
                    vb.v[j1].coord -= cd;
                    vb.lo_idx = vb.norm(vb.lo_idx as i64 - 1);
                }
                let vnew = vb.v[j1];
                if is_min
                    && !vb.v[j].is_min
                    && collide
                    && vi_has_bb
                    && vb.v[j].has_bb
                    && vi.id != vnew.id
                {
                    let (a, b) = if vi.id < vnew.id {
                        (vi.id, vnew.id)
                    } else {
                        (vnew.id, vi.id)
                    };
                    if let Err(e) = self.handle_inversion_peri(bodies, intrs, cell, a, b, iter) {
                        res = Err(e);
                    }
                }
                j = vb.norm(j as i64 - 1);
            }
            let k = vb.norm(j as i64 + 1);
            vb.v[k] = vi;
            ui += 1;
        }
        // keep coordinates within [0, cellDim] by moving the largest ones to the next period
        let mut i = vb.norm(vb.lo_idx as i64 - 1);
        while vb.v[i].coord > cd {
            vb.v[i].period += 1;
            vb.v[i].coord -= cd;
            vb.lo_idx = i;
            i = vb.norm(i as i64 - 1);
        }
        self.bb[axis] = vb;
        res
    }

    /// Insertion-sort the three axes (`insertionSort` or `insertionSortPeri`), creating pairs at
    /// inversions when `collide`.
    fn sort_all(&mut self, ctx: &mut ColliderCtx, collide: bool) -> Result<(), String> {
        for axis in 0..3 {
            match ctx.cell {
                None => self.insertion_sort(axis, ctx.bodies, ctx.interactions, ctx.iter, collide),
                Some(c) => self.insertion_sort_peri(
                    axis,
                    ctx.bodies,
                    ctx.interactions,
                    c,
                    ctx.iter,
                    collide,
                )?,
            }
        }
        Ok(())
    }

    /// `findOverlaps`: sweep the sorted list along one axis after a full sort.
    fn find_overlaps(
        &mut self,
        bodies: &Bodies,
        intrs: &mut Interactions,
        cell: Option<&Cell>,
        iter: i64,
    ) -> Result<(), String> {
        let axis = self.p.sort_axis;
        let v = std::mem::take(&mut self.bb[axis].v);
        let mut res = Ok(());
        match cell {
            None => {
                for i in 0..v.len() {
                    if !(v[i].is_min && v[i].has_bb) {
                        continue;
                    }
                    let iid = v[i].id;
                    let mut j = i + 1;
                    while j < v.len() && v[j].id != iid {
                        let jid = v[j].id;
                        if v[j].is_min
                            && v[j].has_bb
                            && self.spatial_overlap(iid, jid)
                            && self.may_collide(bodies, iid, jid)
                            && !intrs.found(iid, jid)
                        {
                            let (a, b) = if iid < jid { (iid, jid) } else { (jid, iid) };
                            intrs.insert(Interaction::new(a, b, [0; 3], iter));
                        }
                        j += 1;
                    }
                }
            }
            Some(c) => {
                let n = v.len() as i64;
                let norm = |i: i64| -> usize { (((i % n) + n) % n) as usize };
                for i in 0..v.len() {
                    if !(v[i].is_min && v[i].has_bb) {
                        continue;
                    }
                    let iid = v[i].id;
                    let mut j = norm(i as i64 + 1);
                    while v[j].id != iid {
                        let jid = v[j].id;
                        if v[j].is_min && v[j].has_bb {
                            let (a, b) = if iid < jid { (iid, jid) } else { (jid, iid) };
                            if let Err(e) = self.handle_inversion_peri(bodies, intrs, c, a, b, iter)
                            {
                                res = Err(e);
                            }
                        }
                        j = norm(j as i64 + 1);
                    }
                }
            }
        }
        self.bb[axis].v = v;
        res
    }

    /// `InsertionSortCollider::action`.
    pub fn action(&mut self, mut ctx: ColliderCtx) -> Result<(), String> {
        self.num_action += 1;
        let n = ctx.bodies.len();
        let periodic = ctx.cell.is_some();
        if periodic != self.periodic {
            for b in self.bb.iter_mut() {
                b.v.clear();
            }
            self.periodic = periodic;
        }
        let mut do_init_sort = false;
        if self.do_sort {
            do_init_sort = true;
            self.do_sort = false;
        }
        if self.bb[0].v.len() != 2 * n {
            let bbsize = self.bb[0].v.len();
            if 2 * n < bbsize {
                return Err(
                    "bodies were removed from the scene: ryade does not support erasing bodies yet"
                        .into(),
                );
            }
            if bbsize == 0 || ((2 * n - bbsize) as f64 / bbsize as f64) > 0.2 {
                do_init_sort = true;
            }
            for vb in self.bb.iter_mut() {
                for id in bbsize / 2..n {
                    for is_min in [true, false] {
                        vb.v.push(BoundEntry {
                            coord: 0.0,
                            id: id as u32,
                            period: 0,
                            has_bb: false,
                            is_min,
                        });
                    }
                }
            }
        }
        if self.minima.len() != 3 * n {
            self.minima.resize(3 * n, 0.0);
            self.maxima.resize(3 * n, 0.0);
        }
        if let Some(c) = ctx.cell {
            let s = c.size();
            for i in 0..3 {
                self.bb[i].cell_dim = s[i];
                self.inv_sizes[i] = 1.0 / s[i];
            }
        }
        if self.p.verlet_dist < 0.0 {
            let min_r = (0..n)
                .filter_map(|i| ctx.bodies.shape[i].sphere_radius())
                .fold(f64::INFINITY, |a, r| if r < a { r } else { a });
            self.p.verlet_dist = if min_r.is_infinite() {
                0.0
            } else {
                self.p.verlet_dist.abs() * min_r
            };
        }
        if ctx.interactions.dirty {
            do_init_sort = true;
            ctx.interactions.dirty = false;
        }
        update_bounds(
            &self.p.bounds,
            ctx.bodies,
            ctx.cell,
            ctx.iter,
            &Sweep {
                sweep_dist: self.p.verlet_dist,
                min_sweep_dist_factor: self.p.min_sweep_dist_factor,
                target_interv: self.p.target_interv,
            },
        )?;
        if self.p.verlet_dist > 0.0 {
            if ctx.newton_indicator.is_none() {
                return Err("InsertionSortCollider.verletDist>0, but there is no NewtonIntegrator in O.engines".into());
            }
            self.stride_active = true;
        }
        // copy bounds into the three lists (periodic: shifted into the period they were in)
        for j in 0..3 {
            let cd = self.bb[j].cell_dim;
            for k in 0..self.bb[j].v.len() {
                let e = &mut self.bb[j].v[k];
                let id = e.id as usize;
                let bound = ctx.bodies.bound[id].as_ref();
                e.has_bb = bound.is_some();
                let raw = match bound {
                    Some(b) => {
                        if e.is_min {
                            b.min[j]
                        } else {
                            b.max[j]
                        }
                    }
                    None => ctx.bodies.pos[id][j],
                };
                e.coord = raw - if periodic { cd * e.period as f64 } else { 0.0 };
                if do_init_sort && periodic {
                    let (c, p) = cell_wrap(e.coord, 0.0, cd);
                    e.coord = c;
                    e.period = p;
                }
                if let Some(b) = bound {
                    for a in 0..3 {
                        self.minima[3 * id + a] = b.min[a];
                        self.maxima[3 * id + a] = b.max[a];
                    }
                }
            }
        }
        // erase potential interactions whose boxes separated (container order, swap-with-last)
        let mut pos = 0;
        while pos < ctx.interactions.list.len() {
            let it = &ctx.interactions.list[pos];
            if !it.is_real() && self.should_be_erased(it.id1, it.id2, ctx.cell)? {
                ctx.interactions.erase_at(pos);
            } else {
                pos += 1;
            }
        }
        if !do_init_sort && !self.p.sort_then_collide {
            self.sort_all(&mut ctx, true)?;
        } else {
            if do_init_sort {
                for vb in self.bb.iter_mut() {
                    vb.lo_idx = 0;
                    std_sort(&mut vb.v, lt);
                }
                self.num_reinit += 1;
            } else {
                self.sort_all(&mut ctx, false)?;
            }
            self.find_overlaps(ctx.bodies, ctx.interactions, ctx.cell, ctx.iter)?;
        }
        Ok(())
    }
}

/// `InsertionSortCollider::cellWrap`: wrap into [x0, x1) and return the period number.
fn cell_wrap(x: f64, x0: f64, x1: f64) -> (f64, i32) {
    let xn = (x - x0) / (x1 - x0);
    let period = xn.floor() as i32;
    (x0 + (xn - period as f64) * (x1 - x0), period)
}
