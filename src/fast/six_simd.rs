//! The rolling-resistance pair loop with the contacts' rotations four at a time (AVX2). Per group
//! of four kept pairs: each pair's geometry (`six::geometry`), then the rotations of those that
//! were contacts in four lanes (`geom::six_d::relative_delta`, `angle_axis_of`, `twist_bending`:
//! the formulas the YADE-order path runs in `f64`, the same operations in the same order, libm's
//! `atan2` lane by lane), then each pair's law (`six::law`), its loads added in the scalar loop's
//! order (`Acc`). So every state and sum is the scalar loop's to the bit
//! (`tests::groups_are_the_scalar_pair_loop_to_the_bit`). The rotations are a long chain of
//! dependent products, square roots, divisions and an arc tangent per contact; the lanes run four
//! chains side by side.

use super::contact::{self, Pair};
use super::contact_simd::{bits, gather1, gather3, F4};
use super::six::{self, Stage, C6};
use super::{Acc, Kernel, Six};
use crate::geom::six_d::{angle_axis_of, relative_delta, twist_bending, vec_norm, Rot6D, Q};
use crate::geom::sphere_sphere;
use crate::math::{Quat, Real, Vec3};

/// The pair loop of one chunk (see `super::chunk_loop`, the scalar one).
///
/// # Safety
/// The CPU has AVX2, and every pair's `i` and `j` are below the lengths of `k.b.pos` and
/// `k.b.rad` (the first pass reads them unchecked).
#[target_feature(enable = "avx2")]
pub(super) unsafe fn chunk(k: &Six, pairs: &[Pair], cs: &mut [C6], mut acc: Acc) {
    const BLOCK: usize = 256;
    let np = pairs.len();
    let cs = &mut cs[..np];
    let mut work = [0u32; BLOCK];
    for b0 in (0..np).step_by(BLOCK) {
        let nw = kept4(k, pairs, cs, b0..(b0 + BLOCK).min(np), &mut work);
        for g in (0..nw).step_by(4) {
            let ws = &work[g..(g + 4).min(nw)];
            // the next group's states, out of line
            for &p in work[(g + 4).min(nw)..(g + 8).min(nw)].iter() {
                k.prefetch(&cs[p as usize]);
            }
            let mut st = [Stage::Apart; 4];
            for (q, &p) in ws.iter().enumerate() {
                let o = six::orient(k.b, &pairs[p as usize], cs[p as usize].is_real());
                st[q] = six::geometry(k.cfg, k.b, &o, &mut cs[p as usize]);
            }
            rotations4(k, pairs, cs, ws, &st);
            for (q, &p) in ws.iter().enumerate() {
                let pr = pairs[p as usize];
                acc.open(pr.i as usize);
                let o = six::orient(k.b, &pr, true);
                if let Some((lf, lti, ltj)) = six::law(k.cfg, k.b, &o, &mut cs[p as usize], st[q]) {
                    acc.add(pr.j as usize, lf, lti, ltj);
                }
            }
        }
    }
    acc.finish();
}

/// `super::kept` (the first pass: the pairs `Six::idle` does not rule out, in order) four pairs at
/// a time. A lane keeps its pair when it is a contact, when it has a periodic shift, or when
/// `sphere_sphere::apart` does not hold for xj - xi. Without a shift that is the scalar test's
/// decision to the bit: oriented by scene id, the vector is xi + (-0) - xj or xj + 0 - xi, the
/// same components up to sign (and the sign of a zero), so the same squares through the same
/// test (`sphere_sphere::apart_of`: another order of the sum could round the other way at the
/// reach and drop a pair that touches). A pair with a shift is kept for the exact test in
/// `six::geometry`, which leaves a potential pair that does not touch as it was: keeping more
/// pairs than `idle` would change no result.
///
/// # Safety
/// AVX2, and the pairs' bodies in range of `k.b.pos` and `k.b.rad` (`chunk`'s contract); the block
/// within `pairs` and `cs` and no longer than `work` is asserted.
#[inline(always)]
unsafe fn kept4(
    k: &Six,
    pairs: &[Pair],
    cs: &[C6],
    block: std::ops::Range<usize>,
    work: &mut [u32],
) -> usize {
    assert!(
        block.end <= pairs.len() && block.end <= cs.len() && block.len() <= work.len(),
        "kept4: a block past its pairs"
    );
    let b = k.b;
    let f = F4::splat(k.cfg.p6.ss.interaction_detection_factor);
    let mut nw = 0;
    let mut p = block.start;
    while p + 4 <= block.end {
        let q = [p, p + 1, p + 2, p + 3];
        // SAFETY (the unchecked reads): x < block.end <= pairs.len() = cs.len() (`chunk`), and the
        // pairs' bodies are in range (the caller's contract)
        let pr = q.map(|x| *pairs.get_unchecked(x));
        let (ki, kj) = (pr.map(|x| x.i as usize), pr.map(|x| x.j as usize));
        let d = contact::sub(gather3(b.pos, kj), gather3(b.pos, ki));
        let (ri, rj) = (
            gather1(ki.map(|i| *b.rad.get_unchecked(i))),
            gather1(kj.map(|j| *b.rad.get_unchecked(j))),
        );
        let apart = bits(sphere_sphere::apart_of(f, ri, rj, d));
        let mut keep = !apart;
        for (l, &x) in q.iter().enumerate() {
            keep |= ((cs.get_unchecked(x).is_real() | (pr[l].img != 0)) as i32) << l;
        }
        for (l, &x) in q.iter().enumerate() {
            // SAFETY: nw < block.len() <= work.len()
            *work.get_unchecked_mut(nw) = x as u32;
            nw += ((keep >> l) & 1) as usize;
        }
        p += 4;
    }
    while p < block.end {
        work[nw] = p as u32;
        nw += !k.idle(&pairs[p], &cs[p]) as usize;
        p += 1;
    }
    nw
}

/// `six::rotations` of the group's contacts that were real (`Stage::Kept`), in four lanes
/// (`rotations_lanes`); in `f64` one by one where the lanes give way.
#[inline(always)]
fn rotations4(k: &Six, pairs: &[Pair], cs: &mut [C6], ws: &[u32], st: &[Stage; 4]) {
    if !k.cfg.p6.update_rotations || k.cfg.defer_rotations {
        return;
    }
    let mut live = [0usize; 4];
    let mut n = 0;
    for (q, &p) in ws.iter().enumerate() {
        if st[q] == Stage::Kept {
            live[n] = p as usize;
            n += 1;
        }
    }
    if n == 0 {
        return;
    }
    let of = |p: usize| {
        let (_, k1, k2, _) = six::oriented(k.b, &pairs[p]);
        let s = cs[p].0.as_deref().unwrap();
        RotOf {
            ori1: &k.b.ori[k1],
            ori2: &k.b.ori[k2],
            rot: &s.rot,
            normal: &s.geom.as_ref().unwrap().normal,
        }
    };
    let of4: [RotOf; 4] = std::array::from_fn(|l| of(live[l.min(n - 1)]));
    // SAFETY: AVX2, the contract of this module's callers
    match unsafe { rotations_lanes(&of4, k.cfg.p6.creep) } {
        Some(tb) => {
            for (l, &p) in live[..n].iter().enumerate() {
                let r = &mut cs[p].0.as_deref_mut().unwrap().rot;
                (r.twist, r.bending) = tb[l];
            }
        }
        None => {
            for &p in &live[..n] {
                six::rotations(k.cfg, &six::orient(k.b, &pairs[p], true), &mut cs[p]);
            }
        }
    }
}

/// What `ScGeom6D::precomputeRotations` reads of a contact that was real: its bodies'
/// orientations, its rotational state and its normal, already updated.
pub(crate) struct RotOf<'a> {
    pub ori1: &'a Quat,
    pub ori2: &'a Quat,
    pub rot: &'a Rot6D,
    pub normal: &'a Vec3,
}

/// `Rot6D::precompute_rotations` (a contact that was real) of four contacts, one per lane
/// (`geom::six_d::relative_delta`, `angle_axis_of`, `twist_bending`: the formulas the f64 path
/// runs, in the same order, libm's `atan2` lane by lane): each one's twist and bending, to the
/// f64 path's bits. None when a relative rotation's vector part is shorter than machine epsilon,
/// where Eigen takes its stable norm: the caller then runs them in f64 (`angle_axis`).
///
/// # Safety
/// The CPU has AVX2.
#[target_feature(enable = "avx2")]
pub(crate) unsafe fn rotations_lanes(c: &[RotOf; 4], creep: bool) -> Option<[(f64, Vec3); 4]> {
    let q4 = |f: &dyn Fn(&RotOf) -> Quat| -> Q<F4> {
        let qs: [Quat; 4] = std::array::from_fn(|l| f(&c[l]));
        [
            F4::from_lanes(qs.map(|q| q.w)),
            F4::from_lanes(qs.map(|q| q.x)),
            F4::from_lanes(qs.map(|q| q.y)),
            F4::from_lanes(qs.map(|q| q.z)),
        ]
    };
    let (o1, o2) = (q4(&|c| *c.ori1), q4(&|c| *c.ori2));
    let i1 = q4(&|c| c.rot.initial_orientation1);
    let i2 = q4(&|c| c.rot.initial_orientation2);
    let creep = creep.then(|| q4(&|c| c.rot.twist_creep));
    let normal: [F4; 3] =
        std::array::from_fn(|k| F4::from_lanes(std::array::from_fn(|l| c[l].normal[k])));
    let d = relative_delta(&o1, &o2, &i1, &i2, creep.as_ref());
    let norm = vec_norm(&d);
    if F4::any(norm.lt(F4::splat(f64::EPSILON))) {
        return None;
    }
    let (angle, axis) = angle_axis_of(&d, norm);
    let (twist, bending) = twist_bending(angle, axis, &normal);
    let (tw, bx, by, bz) = (
        twist.to_lanes(),
        bending[0].to_lanes(),
        bending[1].to_lanes(),
        bending[2].to_lanes(),
    );
    Some(std::array::from_fn(|l| {
        (tw[l], Vec3::new(bx[l], by[l], bz[l]))
    }))
}

#[cfg(test)]
mod tests {
    use super::super::contact::V3;
    use super::super::six::Bodies6;
    use super::super::{chunk_loop, FastOptions, FastSim, Ghost};
    use super::*;

    fn turn(q: &Quat, u: &mut impl FnMut() -> f64, s: f64) -> Quat {
        let axis = Vec3::new(u(), u(), u());
        let r = Quat::from_angle_axis(s * (0.5 + u()), &(axis / axis.norm().max(1e-300)));
        let mut q = r.mul(q);
        q.normalize();
        q
    }

    /// The rolling golden's scene and its fast run, whose rolling-contact functors the tests use.
    fn rolling_golden() -> (crate::scene::Scene, FastSim) {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("golden/micro_grid/rolling_inc.scene.json");
        let scene = crate::io::scene_json::load(&path).unwrap().scene;
        let sim = FastSim::from_scene(&scene, FastOptions::default()).unwrap();
        (scene, sim)
    }

    /// rapier's scalar/SIMD parity, to the bit: random rolling-resistance pairs through the scalar
    /// pair loop and the groups of four, three steps in a row (the functors' parameters of the
    /// rolling golden): contacts that stay and turn, that open and are erased, that form; pairs
    /// apart; periodic images; body 1 the lower scene id whichever slot it is in; groups with one to
    /// four contacts and groups with a contact that did not turn (the stable norm, one by one).
    /// The same contact states, forces and torques.
    #[test]
    fn groups_are_the_scalar_pair_loop_to_the_bit() {
        if !std::is_x86_feature_detected!("avx2") {
            return;
        }
        let (scene, sim) = rolling_golden();
        let mut cfg = sim.six.clone().expect("rolling contacts");
        // the incremental form's law does not read the rotations (they are deferred to the
        // write-back): work them out every step here, as the total form does
        assert!(cfg.defer_rotations);
        cfg.defer_rotations = false;
        let mats = sim.fmats.clone();
        let mut mt = rand_mt::Mt64::new(5);
        let mut u = move || (mt.next_u64() >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
        let mut seen = [0usize; 3];
        for n in [9usize, 301] {
            let rad: Vec<f64> = (0..n).map(|_| 1e-3 * (1.0 + 0.3 * u())).collect();
            let mut pos: Vec<V3> = (0..n)
                .map(|i| [0.7e-3 * i as f64 + 4e-4 * u(), 4e-4 * u(), 4e-4 * u()])
                .collect();
            let vel: Vec<V3> = (0..n).map(|_| [u(), u(), u()]).collect();
            let w: Vec<V3> = (0..n).map(|_| [5.0 * u(), 5.0 * u(), 5.0 * u()]).collect();
            let mut ori: Vec<Quat> = (0..n).map(|_| turn(&Quat::IDENTITY, &mut u, 3.0)).collect();
            let ids: Vec<u32> = (0..n).map(|i| ((i * 37) % n) as u32).collect();
            // the material of the golden's spheres (a CohFrictMat)
            let m = (0..scene.bodies.len())
                .find(|&id| scene.bodies.shape[id].sphere_radius().is_some())
                .map(|id| scene.bodies.material[id] as u32)
                .unwrap();
            let mat = vec![m; n];
            let shifts = [[0.0; 3], [-0.7e-3 * n as f64 + 0.7e-3, 0.0, 0.0]];
            let pairs = super::super::contact::chain_pairs(n);
            let mut cs_a = vec![C6::default(); pairs.len()];
            let mut prev = 0;
            for step in 0..4 {
                let b = Bodies6 {
                    pos: &pos,
                    vel: &vel,
                    w: &w,
                    ori: &ori,
                    rad: &rad,
                    mat: &mat,
                    ids: &ids,
                    shifts: &shifts,
                    mats: &mats,
                    dt: 1e-6,
                    iter: 10 + step,
                };
                let k = Six { cfg: &cfg, b: &b };
                let mut cs_b = cs_a.clone();
                let (mut fa, mut ta, mut ga) =
                    (vec![[0.0; 3]; n], vec![[0.0; 3]; n], Vec::<Ghost>::new());
                let (mut fb, mut tb, mut gb) =
                    (vec![[0.0; 3]; n], vec![[0.0; 3]; n], Vec::<Ghost>::new());
                chunk_loop(
                    &k,
                    &pairs,
                    &mut cs_a,
                    Acc::new(&mut fa, &mut ta, 0, &mut ga),
                );
                // SAFETY: the CPU has AVX2 (checked above)
                unsafe {
                    chunk(
                        &k,
                        &pairs,
                        &mut cs_b,
                        Acc::new(&mut fb, &mut tb, 0, &mut gb),
                    )
                };
                assert_eq!(
                    format!("{cs_a:?}"),
                    format!("{cs_b:?}"),
                    "n {n} step {step}: states"
                );
                let bits = |v: &[V3]| v.iter().flatten().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&fa), bits(&fb), "n {n} step {step}: forces");
                assert_eq!(bits(&ta), bits(&tb), "n {n} step {step}: torques");
                let real = cs_a.iter().filter(|c| c.is_real()).count();
                seen[0] = seen[0].max(real);
                seen[1] += (real < prev) as usize;
                prev = real;
                // every other body turns, the rest keep their orientation (contacts between two
                // of them have not turned since they formed: the stable norm); all drift
                for (i, q) in ori.iter_mut().enumerate() {
                    if i % 3 != 0 {
                        *q = turn(q, &mut u, 0.02);
                    }
                }
                for (i, p) in pos.iter_mut().enumerate() {
                    for x in p.iter_mut() {
                        *x += 5e-5 * u();
                    }
                    // some bodies jump: contacts open (and are erased), others form
                    if i % 7 == 3 {
                        p[1] += 8e-4;
                    }
                }
                seen[2] += (step > 0 && real > 0) as usize;
            }
        }
        assert!(seen[0] > 100 && seen[1] > 0 && seen[2] > 0, "{seen:?}");
    }

    /// `kept4`'s decisions against the scalar first pass (`super::super::kept`, `Six::idle`) pair by
    /// pair: the same on every pair without a shift, a superset on shifted ones. The pairs sit at
    /// the detection distance (factor 1.25) where |d|² summed as x² + (y² + z²) and as
    /// (x² + y²) + z² fall on either side of the reach, the ids ordered either way, with periodic
    /// pairs apart and touching and a few contacts.
    #[test]
    fn kept4_keeps_what_the_scalar_pass_keeps() {
        if !std::is_x86_feature_detected!("avx2") {
            return;
        }
        let (scene, sim) = rolling_golden();
        let mut cfg = sim.six.clone().expect("rolling contacts");
        let f = 1.25;
        cfg.p6.ss.interaction_detection_factor = f;
        let mut mt = rand_mt::Mt64::new(9);
        let mut u = move || (mt.next_u64() >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
        let (mut pos, mut rad, mut pairs) = (Vec::new(), Vec::new(), Vec::new());
        let shift = [0.05, 0.0, 0.0];
        let (mut split, mut tries) = (0, 0);
        while pairs.len() < 240 {
            tries += 1;
            assert!(tries < 10_000_000, "no pair at the rounding edge");
            let (ri, rj) = (1e-3 * (1.0 + 0.3 * u()), 1e-3 * (1.0 + 0.3 * u()));
            let xi = [u(), u(), u()];
            let dir = [u(), u(), u()];
            let l = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt();
            let reach = f * (ri + rj);
            // every fourth pair periodic: body j's image lies at the reach, j itself a period away
            let img = (pairs.len() % 4 == 3) as u32;
            let e = 1.0 + 4e-16 * (2.0 * u()).round();
            let xj: V3 = std::array::from_fn(|c| {
                xi[c] + dir[c] / l * reach * e - if img == 1 { shift[c] } else { 0.0 }
            });
            let d: V3 = std::array::from_fn(|c| (xj[c] + [0.0, shift[c]][img as usize]) - xi[c]);
            let (eigen, left) = (
                d[0] * d[0] + (d[1] * d[1] + d[2] * d[2]),
                (d[0] * d[0] + d[1] * d[1]) + d[2] * d[2],
            );
            let edge = (eigen <= reach * reach) != (left <= reach * reach);
            // half the plain pairs where the two orders disagree, the rest anywhere near the reach
            if img == 0 && pairs.len() % 2 == 0 && !edge {
                continue;
            }
            split += (img == 0 && edge) as usize;
            let i = pos.len() as u32;
            pos.extend([xi, xj]);
            rad.extend([ri, rj]);
            pairs.push(Pair { i, j: i + 1, img });
        }
        let n = pos.len();
        // ids in either order within a pair
        let ids: Vec<u32> = (0..n as u32)
            .map(|k| if (k / 2) % 3 == 0 { k ^ 1 } else { k })
            .collect();
        let m = (0..scene.bodies.len())
            .find(|&id| scene.bodies.shape[id].sphere_radius().is_some())
            .map(|id| scene.bodies.material[id] as u32)
            .unwrap();
        let (zero, ori) = (vec![[0.0; 3]; n], vec![Quat::IDENTITY; n]);
        let mat = vec![m; n];
        let mats = sim.fmats.clone();
        let b = Bodies6 {
            pos: &pos,
            vel: &zero,
            w: &zero,
            ori: &ori,
            rad: &rad,
            mat: &mat,
            ids: &ids,
            shifts: &[[0.0; 3], shift],
            mats: &mats,
            dt: 1e-6,
            iter: 1,
        };
        let k = Six { cfg: &cfg, b: &b };
        // a few contacts: kept whatever their distance
        let cs: Vec<C6> = (0..pairs.len())
            .map(|p| {
                C6((p % 11 == 5).then(|| {
                    Box::new(six::State6 {
                        geom: None,
                        phys: None,
                        rot: Default::default(),
                        coh: None,
                        made_real: 0,
                    })
                }))
            })
            .collect();
        let (mut w1, mut w4) = ([0u32; 256], [0u32; 256]);
        let n1 = super::super::kept(&k, &pairs, &cs, 0..pairs.len(), &mut w1);
        // SAFETY: AVX2 checked above; the test's pairs are in range of its bodies
        let n4 = unsafe { kept4(&k, &pairs, &cs, 0..pairs.len(), &mut w4) };
        let (scalar, lanes) = (&w1[..n1], &w4[..n4]);
        for (p, pr) in pairs.iter().enumerate() {
            let (a, b) = (scalar.contains(&(p as u32)), lanes.contains(&(p as u32)));
            if pr.img == 0 {
                assert_eq!(a, b, "pair {p}: scalar {a}, lanes {b}");
            } else {
                assert!(b || !a, "pair {p}: shifted pair dropped");
            }
        }
        // what the test means to reach was reached: pairs at the rounding edge, plain pairs kept
        // and dropped, shifted pairs apart
        let apart = |p: &u32| !scalar.contains(p);
        let plain = |p: &u32| pairs[*p as usize].img == 0;
        let all: Vec<u32> = (0..pairs.len() as u32).collect();
        assert!(split >= 60, "{split}");
        assert!(all.iter().filter(|p| plain(p) && apart(p)).count() > 20);
        assert!(all.iter().filter(|p| plain(p) && !apart(p)).count() > 20);
        assert!(all.iter().filter(|p| !plain(p) && apart(p)).count() > 5);
    }
}
