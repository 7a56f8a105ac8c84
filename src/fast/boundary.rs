//! The fast path's boundaries: fixed (or translating) walls, boxes and facets in contact with its
//! spheres through FrictMat and Cundall-Strack.
//!
//! The contacts are the Scene's own: `ScGeom` made by the YADE-order path's Ig2 functors
//! (`geom::{wall_sphere, box_sphere, facet_sphere}::go`), `FrictPhys` by `phys::ip2_frict`, forces
//! by `law::load`; one formula, one place. Only the scheduling is the fast path's: the candidate
//! spheres of each boundary are listed at each Verlet rebuild (those within `r + skin`), and the
//! loads are added after the sphere-sphere phase, in list order. There are few boundary contacts
//! (a container's walls), so they run serially.

use super::contact::V3;
use crate::geom::{self, GeomCtx, Kin, Pair, ScGeom};
use crate::interaction::{GeomFunctor, Interaction, IntrExt};
use crate::law;
use crate::material::FrictMat;
use crate::math::{mat_t_vec, Mat3, Quat, Vec3};
use crate::phys::FrictPhys;
use crate::scene::{InteractionLoop, PhysFunctor, Scene};
use crate::shape::{Facet, Shape};
use rustc_hash::FxHashMap;

/// The shape of a boundary, with the parameters of its Ig2 functor.
#[derive(Clone, Debug)]
enum BShape {
    Wall {
        axis: usize,
        sense: i32,
        p: geom::wall_sphere::Params,
    },
    Box {
        ext: Vec3,
        p: geom::box_sphere::Params,
    },
    Facet {
        f: Box<Facet>,
        /// Largest distance of a vertex from the facet's position.
        reach: f64,
    },
}

/// One boundary body: fixed in every DOF, not rotating, moved only by its velocity.
#[derive(Clone, Debug)]
struct Boundary {
    id: u32,
    shape: BShape,
    /// Its Ig2 and Bo1 functors are in the scene's engines (else YADE never makes its contacts).
    touch: bool,
    pos: Vec3,
    vel: Vec3,
    ori: Quat,
    /// `ori`'s rotation matrix (`ori` is fixed for the run).
    rot: Mat3,
    mat: usize,
    x_ref: Vec3,
    force: Vec3,
    torque: Vec3,
}

/// A boundary-sphere pair of the candidate list; `geom`/`phys` are the interaction's while it is real.
#[derive(Clone, Debug)]
struct BContact {
    b: u32,
    sphere: u32,
    /// The sphere's slot in the fast path's (spatially sorted) arrays.
    k: u32,
    /// The sphere's period (YADE's `cellDist` of the interaction; zeros without a periodic cell):
    /// the image nearest the boundary when the pair was listed, kept while it is in contact.
    cd: [i32; 3],
    geom: Option<ScGeom>,
    phys: Option<FrictPhys>,
    /// The CohFrictPhys part when the physics is Ip2_CohFrictMat_CohFrictMat_CohFrictPhys's.
    ext: Option<Box<IntrExt>>,
    made_real: i64,
    /// A potential facet pair's idle skip (`FacetIdle`).
    idle: FacetIdle,
}

/// The idle skip of a potential sphere-facet pair. After `facet_sphere::go` found no contact, the
/// sphere is at least `FacetIdle::gap_of`'s distance from touching the triangle, a bound that moves
/// by no more than the sphere and the facet do (it is a distance to a convex set, and facets do not
/// rotate here). While their displacements since then stay under it (`gap`, kept with a margin for
/// round-off), `go` would answer "no contact" again with no side effect (shrinkFactor 0), so it is
/// not called: the same contacts, the same bits, fewer calls (the study's piston: 72 facets over
/// the spheres under it, most of them near a facet's plane but beside its triangle).
#[derive(Clone, Debug, Default)]
struct FacetIdle {
    /// 0: check every step.
    gap: f64,
    sphere_at: V3,
    facet_at: Vec3,
}

impl FacetIdle {
    /// A lower bound on the distance from the sphere's surface to the triangle (negative when it
    /// may touch): the distance from its centre `cl` (facet frame, origin at the incircle's centre)
    /// to the convex set {n·x = 0, ne_m·x <= icr} of the edge it lies farthest beyond (which holds
    /// the triangle), minus r. `go`'s penetration is never more than r minus it.
    fn gap_of(f: &Facet, cl: &Vec3, r: f64) -> f64 {
        let l = f.normal.dot(cl).abs();
        let bm =
            f.ne.iter()
                .map(|n| n.dot(cl))
                .fold(f64::NEG_INFINITY, f64::max);
        let e = (bm - f.icr).max(0.0);
        (l * l + e * e).sqrt() - r
    }

    /// Skip this step: the displacements since the check cannot have closed the gap
    /// ((|ds| + |db|)² <= 2 (|ds|² + |db|²)).
    #[inline(always)]
    fn skip(&self, sphere: &V3, facet: &Vec3) -> bool {
        if self.gap <= 0.0 {
            return false;
        }
        let ds = super::contact::sub(*sphere, self.sphere_at);
        let db = facet - self.facet_at;
        2.0 * (super::contact::dot(ds, ds) + db.norm_squared()) < self.gap * self.gap
    }
}

/// What the boundary phase reads of the spheres (in the fast path's slots).
pub(super) struct Spheres<'a> {
    pub pos: &'a [V3],
    pub vel: &'a [V3],
    pub w: &'a [V3],
    pub ori: &'a [Quat],
    pub rad: &'a [f64],
    pub mat: &'a [u32],
}

#[derive(Clone, Debug, Default)]
pub(super) struct Boundaries {
    list: Vec<Boundary>,
    contacts: Vec<BContact>,
    /// The one `Ig2_Facet_Sphere_ScGeom` of the scene: its state (a shrinkFactor YADE resets when
    /// too large) is shared by all facets, as in YADE.
    facet_p: geom::facet_sphere::Params,
    mats: Vec<FrictMat>,
    /// The physics functor of each (boundary material, sphere material) pair met, by the scene's
    /// own dispatch (`InteractionLoop::phys_functor`).
    coh_ip2: Option<crate::phys::CohFrictIp2>,
    law: law::Params,
    /// Collider.avoidSelfInteractionMask
    avoid_self: i32,
    /// Every body's groupMask, by scene id.
    masks: Vec<i32>,
    /// The periodic cell (static and unsheared: `FastSim::from_scene`).
    cell: Option<crate::cell::Cell>,
    /// Scene id -> index in `list`.
    at: FxHashMap<u32, u32>,
    /// Each contact's load of this step, and the contacts worked out one by one (`forces`'
    /// scratch).
    loads: Vec<Option<law::Load>>,
    one_by_one: Vec<usize>,
    /// The real contacts of a box four at a time in lanes (`box_lanes`), to the same bits; off
    /// only to test that.
    lanes: bool,
    /// How many groups of four the lanes took.
    lane_groups: u64,
}

/// The shift of period `cd` (`Cell::shift_pos`; zeros without a cell).
fn shift_of(cell: &Option<crate::cell::Cell>, cd: &[i32; 3]) -> Vec3 {
    cell.as_ref().map_or_else(Vec3::zeros, |c| c.shift_pos(cd))
}

fn v(a: &V3) -> Vec3 {
    Vec3::new(a[0], a[1], a[2])
}

impl Boundaries {
    /// The scene's walls, boxes and facets, or why one is outside the fast path (`has(id)` tells
    /// which bodies are taken here).
    pub(super) fn from_scene(
        scene: &Scene,
        il: &InteractionLoop,
        collider: &crate::collider::ColliderParams,
    ) -> Result<Boundaries, String> {
        let bo1 = &collider.bounds;
        let b = &scene.bodies;
        let mut sphere_mats: Vec<usize> = (0..b.len())
            .filter(|&id| matches!(b.shape[id], Shape::Sphere { .. }))
            .map(|id| b.material[id])
            .collect();
        sphere_mats.sort_unstable();
        sphere_mats.dedup();
        let mut list = Vec::new();
        for id in 0..b.len() {
            let shape = match &b.shape[id] {
                // (the grid's bodies are `grid`'s)
                Shape::Sphere { .. } | Shape::GridNode(_) | Shape::GridConnection(_) => continue,
                Shape::Wall { axis, sense } => (
                    BShape::Wall {
                        axis: *axis,
                        sense: *sense,
                        p: il.wall_sphere.unwrap_or_default(),
                    },
                    il.wall_sphere.is_some() && bo1.wall,
                ),
                Shape::Box { extents } => (
                    BShape::Box {
                        ext: *extents,
                        p: il.box_sphere.unwrap_or_default(),
                    },
                    il.box_sphere.is_some() && bo1.box_,
                ),
                Shape::Facet(f) => (
                    BShape::Facet {
                        reach: f.vertices.iter().map(|x| x.norm()).fold(0.0, f64::max),
                        f: f.clone(),
                    },
                    il.facet_sphere.is_some() && bo1.facet,
                ),
                s => {
                    return Err(format!(
                        "the fast path does not support {} bodies (#{})",
                        s.class_name(),
                        id
                    ))
                }
            };
            let what = b.shape[id].class_name();
            if b.blocked[id] != crate::body::DOF_ALL {
                return Err(format!(
                    "the fast path does not support a {} that is not fixed (#{}: its blockedDOFs are not 'xyzXYZ')",
                    what, id
                ));
            }
            if b.ang_vel[id] != Vec3::zeros() {
                return Err(format!(
                    "the fast path does not support a rotating {} (#{} has an angular velocity)",
                    what, id
                ));
            }
            // every (boundary, sphere) material pair must get FrictPhys or CohFrictPhys
            let mb = &scene.materials[b.material[id]];
            for &sm in &sphere_mats {
                let ms = &scene.materials[sm];
                match il.phys_functor(mb.class(), ms.class()) {
                    Ok(Some((PhysFunctor::Frict, _))) | Ok(Some((PhysFunctor::CohFrict, _))) => {}
                    _ => {
                        return Err(format!(
                            "the fast path does not support a {} of material {} against spheres of {} (#{})",
                            what,
                            mb.class_name(),
                            ms.class_name(),
                            id
                        ))
                    }
                }
            }
            if il
                .cohfrict_phys
                .as_ref()
                .is_some_and(|p| p.set_cohesion_now)
            {
                return Err(format!(
                    "the fast path does not support Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow=True) (with {} #{})",
                    what, id
                ));
            }
            let (shape, touch) = shape;
            list.push(Boundary {
                id: id as u32,
                shape,
                touch,
                pos: b.pos[id],
                vel: b.vel[id],
                ori: b.ori[id],
                rot: b.ori[id].to_rotation_matrix(),
                mat: b.material[id],
                x_ref: b.pos[id],
                force: Vec3::zeros(),
                torque: Vec3::zeros(),
            });
        }
        let mut bs = Boundaries {
            list,
            contacts: vec![],
            facet_p: il.facet_sphere.unwrap_or_default(),
            coh_ip2: il.cohfrict_phys.clone(),
            mats: scene.materials.clone(),
            law: il.cundall_strack.unwrap_or_default(),
            avoid_self: collider.avoid_self_interaction_mask,
            masks: b.mask.clone(),
            cell: scene.cell.clone(),
            at: FxHashMap::default(),
            loads: vec![],
            one_by_one: vec![],
            lanes: true,
            lane_groups: 0,
        };
        // the scene's real boundary contacts carry over with their history
        bs.at = bs
            .list
            .iter()
            .enumerate()
            .map(|(k, x)| (x.id, k as u32))
            .collect();
        let at = &bs.at;
        for it in &scene.interactions.list {
            let mixed = matches!(
                it.functor,
                GeomFunctor::WallSphere | GeomFunctor::BoxSphere | GeomFunctor::FacetSphere
            );
            let plain_ext = it.ext.as_ref().is_none_or(|e| e.geom.is_none());
            if let (true, true, Some(g), Some(ph), Some(&bk)) =
                (mixed, plain_ext, &it.geom, &it.phys, at.get(&it.id1))
            {
                bs.contacts.push(BContact {
                    b: bk,
                    sphere: it.id2,
                    k: u32::MAX,
                    cd: it.cell_dist,
                    geom: Some(*g),
                    phys: Some(*ph),
                    ext: it.ext.clone(),
                    made_real: it.iter_made_real,
                    idle: FacetIdle::default(),
                });
            }
        }
        Ok(bs)
    }

    pub(super) fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// Is body `id` one of the boundaries?
    pub(super) fn has(&self, id: usize) -> bool {
        self.at.contains_key(&(id as u32))
    }

    fn get(&self, id: usize) -> &Boundary {
        &self.list[self.at[&(id as u32)] as usize]
    }

    /// The period of the sphere image at `x` nearest `at` (zeros without a periodic cell).
    fn nearest_image(&self, at: &Vec3, x: &V3) -> [i32; 3] {
        match self.cell.as_ref().map(|c| c.size()) {
            Some(l) => std::array::from_fn(|a| ((at[a] - x[a]) / l[a]).round() as i32),
            None => [0; 3],
        }
    }

    /// `Collider::mayCollide`'s mask rule (pkg/common/Collider.cpp).
    fn may_collide(&self, a: u32, b: u32) -> bool {
        crate::collider::masks_may_collide(
            self.masks[a as usize],
            self.masks[b as usize],
            self.avoid_self,
        )
    }

    /// Is a sphere at `x` of radius `r` within `reach` of the boundary (rotation matrix `rot`)? (A
    /// cheap test, never false for a sphere the Ig2 functor could touch before the next rebuild.)
    fn near(bd: &Boundary, rot: &crate::math::Mat3, x: &Vec3, r: f64, skin: f64) -> bool {
        let d = x - bd.pos;
        match &bd.shape {
            BShape::Wall { axis, .. } => d[*axis].abs() <= r + skin,
            BShape::Box { ext, p } => {
                // the outside branch makes contacts up to r (interactionDetectionFactor - 1) apart
                let r = r * p.interaction_detection_factor.max(1.0);
                let l = mat_t_vec(rot, &d);
                let mut q2 = 0.0;
                for k in 0..3 {
                    let o = (l[k].abs() - ext[k]).max(0.0);
                    q2 += o * o;
                }
                q2 <= (r + skin) * (r + skin)
            }
            BShape::Facet { f, reach, .. } => {
                // near its plane, and within r + skin of the triangle in it: the triangle is where
                // ne_i · p <= icr for its three edge normals (local origin at the incircle's
                // centre, as in `facet_sphere::go`), so a point that close has ne_i · p <= icr + r + skin
                let l = mat_t_vec(rot, &d);
                let h = l.dot(&f.normal);
                let cp = l - f.normal * h;
                h.abs() <= r + skin
                    && l.norm() <= reach + r + skin
                    && f.ne.iter().all(|n| n.dot(&cp) <= f.icr + r + skin)
            }
        }
    }

    /// A box around every point at which `near` can hold for a sphere of radius up to `rmax`
    /// (world frame, half-widths; infinite along a wall's plane): a cheap first test.
    fn reach_box(bd: &Boundary, rot: &crate::math::Mat3, rmax: f64, skin: f64) -> Vec3 {
        match &bd.shape {
            BShape::Wall { axis, .. } => {
                let mut h = Vec3::repeat(f64::INFINITY);
                h[*axis] = rmax + skin;
                h
            }
            BShape::Box { ext, p } => {
                let d = rmax * p.interaction_detection_factor.max(1.0) + skin;
                Vec3::from_fn(|a, _| (0..3).map(|j| rot[(a, j)].abs() * ext[j]).sum::<f64>() + d)
            }
            BShape::Facet { f, reach } => {
                // within reach + r + skin of the position and r + skin of the plane: a disc
                // thickened by r + skin
                let (big, d) = (reach + rmax + skin, rmax + skin);
                let n = rot * f.normal;
                Vec3::from_fn(|a, _| big * (1.0 - n[a] * n[a]).max(0.0).sqrt() + d * n[a].abs())
            }
        }
    }

    /// The candidate list again (after the spheres were re-sorted): every sphere near a boundary,
    /// real contacts kept with their state. Per boundary in slot order, as a walk over all
    /// spheres would list them; a box around the boundary keeps `near` off the far spheres.
    pub(super) fn rebuild(&mut self, l: &super::Listing, skin: f64) {
        let (ids, pos, rad, wrapped) = (l.ids, l.pos, l.rad, l.wrapped);
        // the real contacts of each boundary, by slot (a sphere no longer listed loses its own)
        let mut known: Vec<Vec<BContact>> = vec![Vec::new(); self.list.len()];
        for mut c in self.contacts.drain(..) {
            if let (true, Some(k)) = (c.geom.is_some(), l.slot_of(c.sphere)) {
                c.k = k;
                known[c.b as usize].push(c);
            }
        }
        for bd in self.list.iter_mut() {
            bd.x_ref = bd.pos;
        }
        let rmax = rad.iter().copied().fold(0.0, f64::max);
        // periodic: offsets of wrapped positions, brought into (-l/2, l/2] below
        let size = self.cell.as_ref().map(|c| c.size());
        let wrap = |x: f64, a: usize| size.map_or(x, |l| super::contact::wrap_into(x, l[a]));
        let mut cand: Vec<u32> = Vec::new();
        let mut out = Vec::new();
        for (bk, (bd, mut kept)) in self.list.iter().zip(known).enumerate() {
            if !bd.touch {
                continue;
            }
            let rot = bd.rot;
            // (a margin for the rounding of the wrapped offsets)
            let half =
                Self::reach_box(bd, &rot, rmax, skin) + size.map_or(Vec3::zeros(), |l| l * 1e-12);
            let at: V3 = std::array::from_fn(|a| wrap(bd.pos[a], a));
            let (zlo, zhi) = (at[2] - half[2], at[2] + half[2]);
            let all = (f64::NEG_INFINITY, f64::INFINITY);
            let mut ranges = [all; 3];
            let nr = match size.map(|l| l[2]) {
                _ if !half[2].is_finite() => 1,
                Some(l) if 2.0 * half[2] >= l => 1,
                Some(l) => {
                    ranges[0] = (zlo.max(0.0), zhi.min(l));
                    let mut m = 1;
                    if zlo < 0.0 {
                        ranges[m] = (zlo + l, l);
                        m += 1;
                    }
                    if zhi > l {
                        ranges[m] = (0.0, zhi - l);
                        m += 1;
                    }
                    m
                }
                None => {
                    ranges[0] = (zlo, zhi);
                    1
                }
            };
            let ranges = &ranges[..nr];
            // the candidates: the spheres of the list build's cells around the box, ascending,
            // whose wrapped height is in a range (two across the period; a NaN one in none): the
            // height filter of the sort this replaced, so that the candidates are the same
            cand.clear();
            l.cells.runs_near(&at, &[half[0], half[1], half[2]], |r| {
                cand.extend(r.filter_map(|k| {
                    let z = wrapped[k][2];
                    ranges
                        .iter()
                        .any(|&(lo, hi)| z >= lo && z <= hi)
                        .then_some(k as u32)
                }))
            });
            // in slot order: a real contact kept, else a candidate the box and `near` let through
            kept.sort_unstable_by_key(|c| c.k);
            let mut kept = kept.into_iter().peekable();
            let mut cands = cand.iter().copied().peekable();
            loop {
                let k = match (kept.peek(), cands.peek()) {
                    (None, None) => break,
                    (Some(c), Some(&k)) if c.k <= k => {
                        if c.k == k {
                            cands.next();
                        }
                        out.push(kept.next().unwrap());
                        continue;
                    }
                    (Some(_), None) => {
                        out.push(kept.next().unwrap());
                        continue;
                    }
                    (_, Some(&k)) => {
                        cands.next();
                        k as usize
                    }
                };
                let (id, x, xw) = (ids[k], &pos[k], &wrapped[k]);
                // the nearest image's offset from the boundary (the period itself, rounded as
                // YADE does, only for the spheres the box lets through)
                let far = (0..3).any(|a| {
                    let d = xw[a] - at[a];
                    let d = size.map_or(d, |l| super::contact::nearest_image(d, l[a]));
                    d.abs() > half[a]
                });
                if far {
                    continue;
                }
                let cd = self.nearest_image(&bd.pos, x);
                let xs = v(x) + shift_of(&self.cell, &cd);
                if self.may_collide(bd.id, id) && Self::near(bd, &rot, &xs, rad[k], skin) {
                    out.push(BContact {
                        b: bk as u32,
                        sphere: id,
                        k: k as u32,
                        cd,
                        geom: None,
                        phys: None,
                        ext: None,
                        made_real: -1,
                        idle: FacetIdle::default(),
                    });
                }
            }
        }
        self.contacts = out;
    }

    /// Geometry, physics and law of every candidate pair; the sphere's load is added to `f`, `t`
    /// (after the sphere-sphere phase), the boundary's kept for `write_back`.
    pub(super) fn forces(&mut self, s: &Spheres, dt: f64, iter: i64, f: &mut [V3], t: &mut [V3]) {
        for bd in self.list.iter_mut() {
            bd.force = Vec3::zeros();
            bd.torque = Vec3::zeros();
        }
        let ctx = GeomCtx {
            dt,
            shift_vel: Vec3::zeros(),
        };
        #[cfg(target_arch = "x86_64")]
        let lanes = self.lanes && !self.law.never_erase && super::lanes_available();
        #[cfg(not(target_arch = "x86_64"))]
        let lanes = false;
        // each contact's load: the real contacts of a box four at a time in lanes (`box_lanes`),
        // the others one by one (each contact's work reads and writes its own state, and the
        // facets', which share `facet_p`, keep their order); then the loads are added in the
        // contacts' order
        let n = self.contacts.len();
        let mut loads = std::mem::take(&mut self.loads);
        loads.clear();
        loads.resize(n, None);
        let mut one_by_one = std::mem::take(&mut self.one_by_one);
        one_by_one.clear();
        let (mut group, mut ng) = ([0usize; 4], 0);
        for i in 0..n {
            if !(lanes && self.in_lanes(i)) {
                one_by_one.push(i);
                continue;
            }
            if ng > 0 && self.contacts[group[0]].b != self.contacts[i].b {
                one_by_one.extend_from_slice(&group[..ng]);
                ng = 0;
            }
            group[ng] = i;
            ng += 1;
            if ng == 4 {
                #[cfg(target_arch = "x86_64")]
                // SAFETY: AVX2, checked above
                let done = unsafe { self.box_lanes(group, s, dt, &mut loads) };
                #[cfg(not(target_arch = "x86_64"))]
                let done = false;
                if !done {
                    one_by_one.extend_from_slice(&group);
                }
                ng = 0;
            }
        }
        one_by_one.extend_from_slice(&group[..ng]);
        for &i in &one_by_one {
            loads[i] = self.one(i, s, &ctx, iter);
        }
        for (c, l) in self.contacts.iter().zip(&loads) {
            let Some(l) = l else { continue };
            let bd = &mut self.list[c.b as usize];
            bd.force += l.force;
            bd.torque += l.torque1;
            let k = c.k as usize;
            let fk = &mut f[k];
            *fk = [fk[0] - l.force[0], fk[1] - l.force[1], fk[2] - l.force[2]];
            let tk = &mut t[k];
            *tk = [
                tk[0] + l.torque2[0],
                tk[1] + l.torque2[1],
                tk[2] + l.torque2[2],
            ];
        }
        self.loads = loads;
        self.one_by_one = one_by_one;
    }

    /// Contact `ci`'s geometry and law: its load (None: no contact, or one the law erased).
    #[inline(always)]
    fn one(&mut self, ci: usize, s: &Spheres, ctx: &GeomCtx, iter: i64) -> Option<law::Load> {
        let ctx = *ctx;
        let c = &mut self.contacts[ci];
        let bd = &mut self.list[c.b as usize];
        let k = c.k as usize;
        if c.geom.is_none() && c.idle.skip(&s.pos[k], &bd.pos) {
            return None;
        }
        let r = s.rad[k];
        let shift2 = shift_of(&self.cell, &c.cd);
        let pr = Pair {
            s1: Kin {
                pos: bd.pos,
                vel: bd.vel,
                ang_vel: Vec3::zeros(),
                ori: bd.ori,
            },
            s2: Kin {
                pos: v(&s.pos[k]),
                vel: v(&s.vel[k]),
                ang_vel: v(&s.w[k]),
                ori: s.ori[k],
            },
            shift2,
            is_real: c.geom.is_some(),
            ctx,
        };
        let g = &mut c.geom;
        let made = match &mut bd.shape {
            BShape::Wall { axis, sense, p } => geom::wall_sphere::go(p, *axis, *sense, r, &pr, g),
            BShape::Box { ext, p } => geom::box_sphere::go_rotated(p, ext, r, &pr, g, &bd.rot),
            BShape::Facet { f, .. } => {
                geom::facet_sphere::go_rotated(&mut self.facet_p, f, r, &pr, g, &bd.rot)
            }
        };
        if !made {
            if let (BShape::Facet { f, .. }, true) = (&bd.shape, self.facet_p.shrink_factor == 0.0)
            {
                let cl = mat_t_vec(&bd.rot, &(pr.s2.pos + shift2 - bd.pos));
                let g = FacetIdle::gap_of(f, &cl, r);
                // a margin for the round-off of the bound and of `go`'s own arithmetic, which
                // starts from the absolute positions (and the period's shift)
                let scale = r + cl.norm() + pr.s2.pos.norm() + shift2.norm() + bd.pos.norm();
                c.idle = FacetIdle {
                    gap: (g * (1.0 - 1e-6) - 1e-12 * scale).max(0.0),
                    sphere_at: s.pos[k],
                    facet_at: bd.pos,
                };
            }
            return None;
        }
        let gg = c.geom.as_ref().unwrap();
        if c.phys.is_none() {
            let (m1, m2) = (&self.mats[bd.mat], &self.mats[s.mat[k] as usize]);
            match (&self.coh_ip2, m1.coh.is_some() && m2.coh.is_some()) {
                // Ip2_CohFrictMat_CohFrictMat_CohFrictPhys (no setCohesionNow: refused above,
                // so its state does not change; on a plain ScGeom there are no rotations to set)
                (Some(ip2), true) => {
                    let mut ip2 = ip2.clone();
                    let e = c.ext.get_or_insert_with(Default::default);
                    ip2.go(
                        iter,
                        m1,
                        m2,
                        gg.radius1,
                        gg.radius2,
                        &mut c.phys,
                        &mut e.coh,
                    );
                }
                _ => c.phys = Some(crate::phys::ip2_frict(m1, m2, gg)),
            }
            c.made_real = iter;
        }
        let bodies = law::LawBodies {
            pos1: &bd.pos,
            pos2_shifted: pr.s2.pos + shift2,
        };
        let l = law::load(&self.law, gg, c.phys.as_mut().unwrap(), &bodies, None);
        if l.is_none() {
            c.geom = None;
            c.phys = None;
            c.ext = None;
            c.made_real = -1;
        }
        l
    }

    /// Whether contact `i` is a real contact of a box (with its physics): the case `box_lanes`
    /// takes.
    #[inline(always)]
    fn in_lanes(&self, i: usize) -> bool {
        let c = &self.contacts[i];
        c.geom.is_some()
            && c.phys.is_some()
            && matches!(self.list[c.b as usize].shape, BShape::Box { .. })
    }

    /// Contacts `group` (`in_lanes`, of one box) as `one` does them, one contact per lane: the
    /// box's geometry (`box_sphere::{clamp_to_box, outside_depth, outside_contact}`), `ScGeom`'s
    /// precompute (`geom::precompute`) and Cundall-Strack (`law::{normal_force, shear_trial,
    /// coulomb_cap, loads}`), the formulas `one` runs in f64, so the same bits; their loads into
    /// `loads`. False, with nothing written, where a lane leaves the case worked out here (the
    /// sphere's centre not outside the box, or pen <= 0 or NaN): the caller then runs `one` on
    /// each. With `never_erase` off.
    ///
    /// # Safety
    /// The CPU has AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn box_lanes(
        &mut self,
        group: [usize; 4],
        s: &Spheres,
        dt: f64,
        loads: &mut [Option<law::Load>],
    ) -> bool {
        use super::contact_simd::F4;
        use crate::geom::box_sphere::{clamp_to_box, outside_contact, outside_depth};
        use crate::geom::{precompute, At, KinOf};
        use crate::math::r3::{self, R3};
        use crate::math::Real;
        let cs: [&BContact; 4] = group.map(|q| &self.contacts[q]);
        let bd = &self.list[cs[0].b as usize];
        let BShape::Box { ext, .. } = &bd.shape else {
            unreachable!("box_lanes: a box's contacts")
        };
        let ks: [usize; 4] = std::array::from_fn(|q| cs[q].k as usize);
        let g0: [&ScGeom; 4] = std::array::from_fn(|q| cs[q].geom.as_ref().unwrap());
        let p0: [&FrictPhys; 4] = std::array::from_fn(|q| cs[q].phys.as_ref().unwrap());
        let lanes = |v: [f64; 4]| F4::from_lanes(v);
        let v3 = |v: [V3; 4]| -> R3<F4> { std::array::from_fn(|c| lanes(v.map(|x| x[c]))) };
        let n3 = |v: [&Vec3; 4]| -> R3<F4> { std::array::from_fn(|c| lanes(v.map(|x| x[c]))) };
        let zero: R3<F4> = [F4::splat(0.0); 3];
        let (bpos, bvel) = (r3::splat::<F4>(&bd.pos), r3::splat::<F4>(&bd.vel));
        let spos = v3(ks.map(|k| s.pos[k]));
        let r = lanes(ks.map(|k| s.rad[k]));
        let shift2 = v3(cs.map(|c| *shift_of(&self.cell, &c.cd).as_ref()));
        let sp = r3::add(&spos, &shift2);
        let rel = r3::sub(&sp, &bpos);
        let c0 = r3::mat_t_vec(&bd.rot, &rel);
        let c = clamp_to_box(&c0, ext);
        let (c0l, cl) = (c0.map(F4::to_lanes), c.map(F4::to_lanes));
        let outside = |q: usize| (0..3).any(|k| c0l[k][q].to_bits() != cl[k][q].to_bits());
        if !(0..4).all(outside) {
            return false;
        }
        let (c_box, c_sph, depth) = outside_depth(&bd.rot, &c, &rel, r);
        let pen = depth.to_lanes();
        // (pen < 0: the law erases the contact; a zero pen, whose sign `max` in lanes may not
        // keep as f64::max does, and NaN: left to `one`)
        if pen.iter().any(|p| *p <= 0.0 || p.is_nan()) {
            return false;
        }
        let (cp, normal) = outside_contact(&c_box, &c_sph, &bpos, &sp, r);
        let at0 = At {
            normal: n3(g0.map(|g| &g.normal)),
            contact_point: cp,
            pen: depth,
            radius1: r,
            radius2: r,
        };
        let s1 = KinOf {
            pos: bpos,
            vel: bvel,
            ang_vel: zero,
        };
        let s2 = KinOf {
            pos: spos,
            vel: v3(ks.map(|k| s.vel[k])),
            ang_vel: v3(ks.map(|k| s.w[k])),
        };
        let dt = F4::splat(dt);
        let [oa, ta, normal, si] =
            precompute(&at0, &s1, &s2, dt, &zero, &normal, false, &shift2, false);
        let (kn, ks_, tan_phi) = (
            lanes(p0.map(|p| p.kn)),
            lanes(p0.map(|p| p.ks)),
            lanes(p0.map(|p| p.tan_phi)),
        );
        let nf = law::normal_force(&normal, depth, kn);
        let trial = law::shear_trial((&oa, &ta, &si), &n3(p0.map(|p| &p.shear_force)), ks_);
        let fs = law::coulomb_cap(trial, r3::norm2(&nf) * (tan_phi * tan_phi));
        let l = law::loads(
            self.law.spherical_bodies,
            (&normal, depth, (r, r), &cp),
            &nf,
            &fs,
            &bpos,
            &sp,
        );
        let out = |v: &R3<F4>| v.map(F4::to_lanes);
        let (cp, normal) = (out(&cp), out(&normal));
        let (si, oa, ta) = (out(&si), out(&oa), out(&ta));
        let (nf, fs, rr) = (out(&nf), out(&fs), r.to_lanes());
        let (lf, lt1, lt2) = (out(&l[0]), out(&l[1]), out(&l[2]));
        let at = |v: &[[f64; 4]; 3], q: usize| Vec3::new(v[0][q], v[1][q], v[2][q]);
        for (q, &ci) in group.iter().enumerate() {
            let c = &mut self.contacts[ci];
            c.geom = Some(ScGeom {
                contact_point: at(&cp, q),
                pen: pen[q],
                normal: at(&normal, q),
                shear_inc: at(&si, q),
                orthonormal_axis: at(&oa, q),
                twist_axis: at(&ta, q),
                radius1: rr[q],
                radius2: rr[q],
            });
            let ph = c.phys.as_mut().unwrap();
            ph.normal_force = at(&nf, q);
            ph.shear_force = at(&fs, q);
            loads[ci] = Some(law::Load {
                force: at(&lf, q),
                torque1: at(&lt1, q),
                torque2: at(&lt2, q),
            });
        }
        self.lane_groups += 1;
        true
    }
}

impl Boundaries {
    /// `NewtonIntegrator` on a body fixed in every DOF: x += v dt (no rotation: refused above).
    /// Returns the largest squared displacement since the last rebuild.
    pub(super) fn advance(&mut self, dt: f64) -> f64 {
        let mut md: f64 = 0.0;
        for bd in self.list.iter_mut() {
            bd.pos += bd.vel * dt;
            md = md.max((bd.pos - bd.x_ref).norm_squared());
        }
        md
    }

    /// The boundaries' state, forces of the last step and real contacts back into the scene
    /// (`slot_of[k]`: the scene id of the sphere in slot k).
    pub(super) fn write_back(&self, scene: &mut Scene, ids: &[u32]) {
        for e in scene.engines.iter_mut() {
            if let crate::scene::Engine::InteractionLoop(il) = e {
                if let Some(p) = il.facet_sphere.as_mut() {
                    *p = self.facet_p;
                }
            }
        }
        for bd in &self.list {
            let id = bd.id as usize;
            scene.bodies.pos[id] = bd.pos;
            scene.bodies.vel[id] = bd.vel;
            *scene.forces.force_mut(id) = bd.force;
            *scene.forces.torque_mut(id) = bd.torque;
        }
        for c in &self.contacts {
            let (Some(g), Some(ph)) = (&c.geom, &c.phys) else {
                continue;
            };
            let bd = &self.list[c.b as usize];
            debug_assert_eq!(ids[c.k as usize], c.sphere);
            // after the functor swap YADE keeps the boundary as id1
            let mut it = Interaction::new(bd.id, c.sphere, c.cd, c.made_real);
            it.functor = match bd.shape {
                BShape::Wall { .. } => GeomFunctor::WallSphere,
                BShape::Box { .. } => GeomFunctor::BoxSphere,
                BShape::Facet { .. } => GeomFunctor::FacetSphere,
            };
            it.iter_made_real = c.made_real;
            it.geom = Some(*g);
            it.phys = Some(*ph);
            it.ext = c.ext.clone();
            scene.interactions.insert(it);
        }
    }
}

/// The study's piston (`RyadePistonController`) drives boundaries: it reads their z forces of this
/// step and sets their velocities (`FastSim::from_scene` checks that its ids and its subgrade plate
/// are boundaries).
impl crate::piston::PistonIo for Boundaries {
    fn bodies(&self) -> usize {
        self.masks.len()
    }
    fn pos_z(&self, id: usize) -> f64 {
        self.get(id).pos[2]
    }
    fn vel_z(&self, id: usize) -> f64 {
        self.get(id).vel[2]
    }
    fn set_vel(&mut self, id: usize, v: Vec3) {
        let k = self.at[&(id as u32)] as usize;
        self.list[k].vel = v;
    }
    fn force_z(&self, id: usize) -> f64 {
        self.get(id).force[2]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Mat3;

    /// The real contacts of a box four at a time in lanes (`box_lanes`) change no bit: the golden
    /// scenes `pile` (30 spheres in a container of five boxes) and `peri_pile` (32 spheres on a
    /// box floor in a periodic cell, the study's setup, with the spheres' periods), run with the
    /// lanes and without, every body's state and force and every boundary's force equal after
    /// every step, the lanes taking a hundred groups or more (none in the run without). Fails,
    /// checked, with two lanes' shear forces swapped.
    #[test]
    fn box_contacts_in_lanes_change_no_bit() {
        if !std::is_x86_feature_detected!("avx2") {
            return;
        }
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("golden/micro");
        for name in ["pile", "peri_pile"] {
            let sf = crate::io::scene_json::load(&dir.join(format!("{name}.scene.json"))).unwrap();
            let sim = |lanes: bool| {
                let mut s =
                    super::super::FastSim::from_scene(&sf.scene, Default::default()).unwrap();
                s.bnd.lanes = lanes;
                s
            };
            let (mut a, mut b) = (sim(true), sim(false));
            let bits = |s: &super::super::FastSim| -> Vec<u64> {
                let bodies = [&s.pos, &s.vel, &s.ang_vel, &s.force, &s.torque];
                let bnd = s
                    .bnd
                    .list
                    .iter()
                    .flat_map(|bd| bd.force.iter().chain(bd.torque.iter()));
                bodies
                    .iter()
                    .flat_map(|v| v.iter().flatten())
                    .chain(bnd)
                    .map(|x| x.to_bits())
                    .collect()
            };
            for step in 0..sf.steps {
                a.step();
                b.step();
                assert!(
                    bits(&a) == bits(&b),
                    "{name} step {step}: the lanes changed a bit"
                );
            }
            let (ga, gb) = (a.bnd.lane_groups, b.bnd.lane_groups);
            assert!(
                ga >= 100 && gb == 0,
                "{name}: {ga} and {gb} groups in lanes"
            );
        }
    }

    /// The facet idle skip is exact: wherever `FacetIdle::gap_of` is positive, `facet_sphere::go`
    /// finds no contact for a new pair, and none for the sphere moved anywhere within that gap (the
    /// study's piston wedge: a long thin triangle, spheres around it near and beside its plane).
    /// Fails, checked, when the bound adds the in-plane and normal distances instead of taking
    /// their Euclidean sum (it then overestimates beside a vertex).
    #[test]
    fn facet_idle_gap_never_skips_a_contact() {
        let mut mt = rand_mt::Mt64::new(5);
        let mut u = move || (mt.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        // a 5-degree wedge of a 75 mm disc, vertices relative to its incircle's centre
        let (a, b) = (0.0f64, 5f64.to_radians());
        let w = [
            Vec3::zeros(),
            Vec3::new(0.075 * a.cos(), 0.075 * a.sin(), 0.0),
            Vec3::new(0.075 * b.cos(), 0.075 * b.sin(), 0.0),
        ];
        let side = |i: usize| (w[(i + 1) % 3] - w[(i + 2) % 3]).norm();
        let per = side(0) + side(1) + side(2);
        let inc = (w[0] * side(0) + w[1] * side(1) + w[2] * side(2)) / per;
        let f = Facet::new([w[0] - inc, w[1] - inc, w[2] - inc]).unwrap();
        let kin = |pos: Vec3| Kin {
            pos,
            vel: Vec3::zeros(),
            ang_vel: Vec3::zeros(),
            ori: Quat::IDENTITY,
        };
        let touches = |x: Vec3, r: f64| {
            let pr = Pair {
                s1: kin(Vec3::zeros()),
                s2: kin(x),
                shift2: Vec3::zeros(),
                is_real: false,
                ctx: GeomCtx {
                    dt: 1e-5,
                    shift_vel: Vec3::zeros(),
                },
            };
            let mut p = geom::facet_sphere::Params::default();
            geom::facet_sphere::go(&mut p, &f, r, &pr, &mut None)
        };
        let (mut skipped, mut contacts) = (0, 0);
        for _ in 0..200_000 {
            let r = 0.01 + 0.01 * u();
            let x = Vec3::new(0.1 * u() - 0.05, 0.1 * u() - 0.05, 0.05 * u() - 0.025);
            let g = FacetIdle::gap_of(&f, &x, r);
            if touches(x, r) {
                contacts += 1;
                assert!(g <= 0.0, "a contact with a positive gap {g} at {x}");
                continue;
            }
            if g <= 0.0 {
                continue;
            }
            skipped += 1;
            // anywhere the sphere may have moved while the skip holds
            let d = Vec3::new(u() - 0.5, u() - 0.5, u() - 0.5).normalize() * (g * u());
            assert!(
                !touches(x + d, r),
                "moved {} within the gap {g}: contact",
                d.norm()
            );
        }
        assert!(
            skipped > 50_000 && contacts > 10_000,
            "{skipped} {contacts}"
        );
    }

    /// The walk over every sphere that `rebuild` replaced: (boundary, slot, slot, period) of
    /// each pair `near` accepts.
    fn brute(
        bs: &Boundaries,
        pos: &[V3],
        rad: &[f64],
        skin: f64,
    ) -> Vec<(u32, u32, u32, [i32; 3])> {
        let mut out = Vec::new();
        for (bk, bd) in bs.list.iter().enumerate() {
            let rot = bd.ori.to_rotation_matrix();
            for (k, x) in pos.iter().enumerate() {
                let cd = bs.nearest_image(&bd.pos, x);
                let xs = v(x) + shift_of(&bs.cell, &cd);
                if Boundaries::near(bd, &rot, &xs, rad[k], skin) {
                    out.push((bk as u32, k as u32, k as u32, cd));
                }
            }
        }
        out
    }

    /// The cell, box and height prefilter of `rebuild` drops no pair that `near` accepts (walls,
    /// rotated boxes, facets of every orientation, open and periodic), and adds none.
    #[test]
    fn rebuild_lists_what_the_walk_over_all_spheres_lists() {
        let mut mt = rand_mt::Mt64::new(99);
        let mut rnd = || (mt.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        for periodic in [false, true] {
            let l = Vec3::new(1.0, 0.8, 1.3);
            let mut list = Vec::new();
            let unit_quat = |r: &mut dyn FnMut() -> f64| {
                let q = Quat::new(r() - 0.5, r() - 0.5, r() - 0.5, r() - 0.5);
                let n = q.norm2().sqrt();
                Quat::new(q.w / n, q.x / n, q.y / n, q.z / n)
            };
            for j in 0..40 {
                let shape = match j % 4 {
                    0 => BShape::Wall {
                        axis: j % 3,
                        sense: 0,
                        p: Default::default(),
                    },
                    1 => BShape::Box {
                        ext: Vec3::new(0.05 + 0.2 * rnd(), 0.05 + 0.2 * rnd(), 0.02 + 0.1 * rnd()),
                        p: Default::default(),
                    },
                    _ => {
                        let vx: [Vec3; 3] = std::array::from_fn(|_| {
                            Vec3::new(0.3 * rnd() - 0.15, 0.3 * rnd() - 0.15, 0.02 * rnd())
                        });
                        let c = crate::utils::inscribed_circle_center(&vx[0], &vx[1], &vx[2]);
                        let f = Facet::new([vx[0] - c, vx[1] - c, vx[2] - c]).unwrap();
                        BShape::Facet {
                            reach: f.vertices.iter().map(|x| x.norm()).fold(0.0, f64::max),
                            f: Box::new(f),
                        }
                    }
                };
                // (walls and every other box unrotated: their boxes are then tight)
                let ori = if j % 4 == 0 || j % 8 == 1 {
                    Quat::new(1.0, 0.0, 0.0, 0.0)
                } else {
                    unit_quat(&mut rnd)
                };
                // positions spread past the cell, half of them at its faces: images matter
                let mut pos = Vec3::new(1.4 * rnd() - 0.2, 1.2 * rnd() - 0.2, 1.7 * rnd() - 0.2);
                if j % 2 == 1 {
                    for a in 0..3 {
                        pos[a] = [-0.01, 0.01, l[a] - 0.01, l[a] + 0.01][(4.0 * rnd()) as usize];
                    }
                }
                list.push(Boundary {
                    id: j as u32,
                    shape,
                    touch: true,
                    pos,
                    vel: Vec3::zeros(),
                    ori,
                    rot: ori.to_rotation_matrix(),
                    mat: 0,
                    x_ref: pos,
                    force: Vec3::zeros(),
                    torque: Vec3::zeros(),
                });
            }
            let n = 20000;
            let nb = list.len() as u32;
            let pos: Vec<V3> = (0..n)
                .map(|_| [1.6 * rnd() - 0.3, 1.4 * rnd() - 0.3, 1.9 * rnd() - 0.3])
                .collect();
            let rad: Vec<f64> = (0..n).map(|_| 0.01 + 0.02 * rnd()).collect();
            let ids: Vec<u32> = (0..n as u32).map(|k| nb + k).collect();
            let mut bs = Boundaries {
                list,
                masks: vec![1; nb as usize + n],
                cell: periodic.then(|| crate::cell::Cell::new(Mat3::from_diagonal(&l)).unwrap()),
                ..Boundaries::default()
            };
            let skin = 0.006;
            // the spheres in a list build's order, with its cells
            let built = super::super::neighbors::build(
                &pos,
                &rad,
                periodic.then_some([l[0], l[1], l[2]]),
                skin,
                false,
            );
            let pos: Vec<V3> = built.order.iter().map(|&o| pos[o as usize]).collect();
            let rad: Vec<f64> = built.order.iter().map(|&o| rad[o as usize]).collect();
            let ids: Vec<u32> = built.order.iter().map(|&o| ids[o as usize]).collect();
            let want = brute(&bs, &pos, &rad, skin);
            bs.rebuild(
                &super::super::Listing::new(&ids, &pos, &built.wrapped, &rad, &built.cells),
                skin,
            );
            let got: Vec<(u32, u32, u32, [i32; 3])> = bs
                .contacts
                .iter()
                .map(|c| {
                    assert_eq!(c.sphere, ids[c.k as usize]);
                    (c.b, c.k, c.k, c.cd)
                })
                .collect();
            assert!(want.len() > 2000, "a test that lists pairs: {}", want.len());
            assert_eq!(got, want, "periodic {}", periodic);
        }
    }
}
