//! The Cundall-Strack pair loop four pairs at a time (AVX2): `contact::law`, the one formula, in
//! four lanes (`F4`), and the chunk's sums in `Acc`'s order, so forces, torques and contact states
//! are the scalar loop's to the bit (`tests::lanes_are_the_scalar_pair_loop_to_the_bit`). The lanes
//! break the scalar loop's chain of square root, division and branches on the contact's state, one
//! pair after the other; they gather the bodies and states from the same arrays (no second copy).

use super::contact::{self, Contact, Pair, Real, Touch, Two, V3};
use super::{Acc, Kernel, Plain, View};
use std::arch::x86_64::*;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// Four doubles, one per lane.
#[derive(Clone, Copy)]
pub struct F4(pub(super) __m256d);

/// The arithmetic operator `$tr` of the lane type `$t` as the intrinsic `$op`.
macro_rules! lane_op {
    ($t:ident, $tr:ident, $f:ident, $op:ident) => {
        impl $tr for $t {
            type Output = $t;
            #[inline(always)]
            fn $f(self, o: $t) -> $t {
                // SAFETY: a lane type exists only in code that runs after the check of its
                // instructions (AVX2 for F4, AVX-512F for F8)
                $t(unsafe { $op(self.0, o.0) })
            }
        }
    };
}
pub(super) use lane_op;
lane_op!(F4, Add, add, _mm256_add_pd);
lane_op!(F4, Sub, sub, _mm256_sub_pd);
lane_op!(F4, Mul, mul, _mm256_mul_pd);
lane_op!(F4, Div, div, _mm256_div_pd);

impl Neg for F4 {
    type Output = F4;
    #[inline(always)]
    fn neg(self) -> F4 {
        // SAFETY: as in lane_op; a flip of the sign bit, as f64's negation
        F4(unsafe { _mm256_xor_pd(self.0, _mm256_set1_pd(-0.0)) })
    }
}

impl Real for F4 {
    type Mask = __m256d;
    #[inline(always)]
    fn splat(x: f64) -> F4 {
        // SAFETY: as in lane_op
        F4(unsafe { _mm256_set1_pd(x) })
    }
    #[inline(always)]
    fn sqrt(self) -> F4 {
        // SAFETY: as in lane_op
        F4(unsafe { _mm256_sqrt_pd(self.0) })
    }
    #[inline(always)]
    fn max(self, o: F4) -> F4 {
        // SAFETY: as in lane_op; maxpd returns its second operand where the first is NaN
        F4(unsafe { _mm256_max_pd(self.0, o.0) })
    }
    #[inline(always)]
    fn gt(self, o: F4) -> __m256d {
        // SAFETY: as in lane_op
        unsafe { _mm256_cmp_pd::<_CMP_GT_OQ>(self.0, o.0) }
    }
    #[inline(always)]
    fn lt(self, o: F4) -> __m256d {
        // SAFETY: as in lane_op
        unsafe { _mm256_cmp_pd::<_CMP_LT_OQ>(self.0, o.0) }
    }
    #[inline(always)]
    fn is_nan(self) -> __m256d {
        // SAFETY: as in lane_op
        unsafe { _mm256_cmp_pd::<_CMP_UNORD_Q>(self.0, self.0) }
    }
    #[inline(always)]
    fn abs(self) -> F4 {
        // SAFETY: as in lane_op; the sign bit cleared, as f64::abs
        F4(unsafe { _mm256_andnot_pd(_mm256_set1_pd(-0.0), self.0) })
    }
    #[inline(always)]
    fn atan2(self, x: F4) -> F4 {
        // libm's, lane by lane
        // SAFETY: as in lane_op
        let (y, x) = unsafe { (lanes(self), lanes(x)) };
        let r: [f64; 4] = std::array::from_fn(|l| y[l].atan2(x[l]));
        // SAFETY: as in lane_op
        F4(unsafe { _mm256_loadu_pd(r.as_ptr()) })
    }
    #[inline(always)]
    fn any(m: __m256d) -> bool {
        // SAFETY: as in lane_op
        unsafe { _mm256_movemask_pd(m) != 0 }
    }
    #[inline(always)]
    fn select(m: __m256d, a: F4, b: F4) -> F4 {
        // SAFETY: as in lane_op
        F4(unsafe { _mm256_blendv_pd(b.0, a.0, m) })
    }
}

impl F4 {
    /// `a[l]` in lane l.
    #[inline(always)]
    pub(super) fn from_lanes(a: [f64; 4]) -> F4 {
        // SAFETY: as in lane_op
        F4(unsafe { _mm256_loadu_pd(a.as_ptr()) })
    }

    /// The four lanes as an array.
    #[inline(always)]
    pub(super) fn to_lanes(self) -> [f64; 4] {
        // SAFETY: as in lane_op
        unsafe { lanes(self) }
    }
}

/// The four lanes as an array.
#[inline(always)]
unsafe fn lanes(x: F4) -> [f64; 4] {
    let mut a = [0.0; 4];
    _mm256_storeu_pd(a.as_mut_ptr(), x.0);
    a
}

/// Element `k[l]` of `a` in lane l, for each of the three components. Safety: AVX2, and every
/// `k[l] < a.len()` (not checked: the checks were 7 % of the pair loop).
#[inline(always)]
pub(super) unsafe fn gather3(a: &[V3], k: [usize; 4]) -> [F4; 3] {
    gather_refs(k.map(|q| a.get_unchecked(q)))
}

/// Vector `e[l]` in lane l, for each of the three components.
#[inline(always)]
unsafe fn gather_refs(e: [&V3; 4]) -> [F4; 3] {
    let [e0, e1, e2, e3] = e;
    let (p0, p1, p2, p3) = (
        _mm_loadu_pd(e0.as_ptr()),
        _mm_loadu_pd(e1.as_ptr()),
        _mm_loadu_pd(e2.as_ptr()),
        _mm_loadu_pd(e3.as_ptr()),
    );
    let x = _mm256_insertf128_pd::<1>(
        _mm256_castpd128_pd256(_mm_unpacklo_pd(p0, p1)),
        _mm_unpacklo_pd(p2, p3),
    );
    let y = _mm256_insertf128_pd::<1>(
        _mm256_castpd128_pd256(_mm_unpackhi_pd(p0, p1)),
        _mm_unpackhi_pd(p2, p3),
    );
    let z = _mm256_set_pd(e3[2], e2[2], e1[2], e0[2]);
    [F4(x), F4(y), F4(z)]
}

/// One scalar per lane.
#[inline(always)]
pub(super) unsafe fn gather1(a: [f64; 4]) -> F4 {
    F4(_mm256_set_pd(a[3], a[2], a[1], a[0]))
}

/// A lane mask's bits (bit l: lane l).
#[inline(always)]
pub(super) unsafe fn bits(m: __m256d) -> i32 {
    _mm256_movemask_pd(m)
}

/// `chunk_forces` four pairs at a time (see the module): same arguments, same results. A first
/// pass over a block of pairs keeps those that are contacts or touch (the scalar kernel's test,
/// in lanes, reading whether a pair is a contact from `flags`, the states' `active` as bytes,
/// which it keeps equal: the contacts' own cache lines are then touched only for the pairs kept);
/// the second runs the formula on them four at a time. The pairs left over at the end
/// go through the scalar kernel.
///
/// # Safety
/// The CPU has AVX2, and every pair's bodies and shift are in `v`: `i` and `j` below the length
/// of `v.pos`, `v.vel`, `v.w` and `v.rad`, `img` below that of `v.shifts` (the lanes read them
/// unchecked; `FastSim::rebuild_with` checks the list where it is made, `View::check` the
/// lengths).
#[target_feature(enable = "avx2")]
pub(super) unsafe fn chunk(
    v: &View,
    pairs: &[Pair],
    cs: &mut [Contact],
    flags: &mut [u8],
    acc: Acc,
) {
    const BLOCK: usize = 256;
    let np = pairs.len();
    let (cs, fl) = (&mut cs[..np], &mut flags[..np]);
    debug_assert!(fl.iter().zip(cs.iter()).all(|(f, c)| *f == c.active as u8));
    let mut g = Group {
        v,
        pairs,
        cs,
        fl,
        acc,
    };
    let k = Plain(v);
    let mut work = [0usize; BLOCK + 4];
    let mut nw = 0;
    let mut p = 0;
    while p < np {
        let end = (p + BLOCK).min(np);
        while p + 4 <= end {
            let q = [p, p + 1, p + 2, p + 3];
            let x = g.geometry(q);
            // kept unless apart and no contact (`Plain::idle`)
            let idle = _mm256_andnot_pd(g.active(q), contact::apart(x.d2, x.rs));
            let m = !bits(idle);
            for (l, &w) in q.iter().enumerate() {
                // SAFETY: nw < BLOCK + 4 (fewer than 4 carried over, at most BLOCK added)
                *work.get_unchecked_mut(nw) = w;
                nw += ((m >> l) & 1) as usize;
            }
            p += 4;
        }
        while p < end {
            work[nw] = p;
            nw += !k.idle(&pairs[p], &g.cs[p]) as usize;
            p += 1;
        }
        let mut q = 0;
        while q + 4 <= nw {
            g.four([work[q], work[q + 1], work[q + 2], work[q + 3]]);
            q += 4;
        }
        work.copy_within(q..nw, 0);
        nw -= q;
    }
    for &q in &work[..nw] {
        let pr = pairs[q];
        let i = pr.i as usize;
        g.acc.open(i);
        let loads = k.pair(&k.body(i), &pr, &mut g.cs[q]);
        g.fl[q] = g.cs[q].active as u8;
        if let Some((lf, lti, ltj)) = loads {
            g.acc.add(pr.j as usize, lf, lti, ltj);
        }
    }
    g.acc.finish();
}

/// The second pass's state: the chunk's pairs and contacts (with their flags), and its sums.
struct Group<'a, 'b> {
    v: &'a View<'b>,
    pairs: &'a [Pair],
    cs: &'a mut [Contact],
    /// `cs[q].active` as bytes (as long as `cs`).
    fl: &'a mut [u8],
    acc: Acc<'a>,
}

/// Four pairs' bodies and distances, one pair per lane.
struct Geometry {
    pr: [Pair; 4],
    xi: [F4; 3],
    /// Body j's positions plus their periodic shifts.
    xj: [F4; 3],
    ri: F4,
    rj: F4,
    /// `contact::separation`: xj - xi, its square and ri + rj.
    d: [F4; 3],
    d2: F4,
    rs: F4,
}

impl Group<'_, '_> {
    /// Which of pairs `k` are contacts, as a lane mask. Safety (this and the next two): AVX2,
    /// every `k[l] < self.pairs.len() == self.cs.len()`, and the pairs in range of `self.v`
    /// (`chunk`'s contract).
    #[inline(always)]
    unsafe fn active(&self, k: [usize; 4]) -> __m256d {
        let a = k.map(|q| -(*self.fl.get_unchecked(q) as i64));
        _mm256_castsi256_pd(_mm256_set_epi64x(a[3], a[2], a[1], a[0]))
    }

    /// Pairs `k`, their bodies' positions and radii, and their distances, in `contact::pair`'s
    /// operations.
    #[inline(always)]
    unsafe fn geometry(&self, k: [usize; 4]) -> Geometry {
        let v = self.v;
        let pr = k.map(|q| *self.pairs.get_unchecked(q));
        let (ki, kj) = (pr.map(|q| q.i as usize), pr.map(|q| q.j as usize));
        let xi = gather3(v.pos, ki);
        let xj = contact::add(
            gather3(v.pos, kj),
            gather3(v.shifts, pr.map(|q| q.img as usize)),
        );
        let (ri, rj) = (
            gather1(ki.map(|i| *v.rad.get_unchecked(i))),
            gather1(kj.map(|j| *v.rad.get_unchecked(j))),
        );
        let (d, d2, rs) = contact::separation(xi, xj, ri, rj);
        Geometry {
            pr,
            xi,
            xj,
            ri,
            rj,
            d,
            d2,
            rs,
        }
    }

    /// `contact::pair` on pairs `k` (increasing), one per lane, and their loads into the sums in
    /// the pairs' order.
    #[inline(always)]
    unsafe fn four(&mut self, k: [usize; 4]) {
        let v = self.v;
        let x = self.geometry(k);
        let ki = x.pr.map(|q| q.i as usize);
        let kj = x.pr.map(|q| q.j as usize);
        let active = self.active(k);
        // a fresh pair: no contact, not apart (NaN included), as the scalar test
        let fresh = !bits(_mm256_or_pd(active, contact::apart(x.d2, x.rs))) & 0b1111;
        for l in 0..4 {
            if fresh & (1 << l) != 0 {
                let (i, j) = (ki[l], kj[l]);
                contact::create(
                    &mut self.cs[k[l]],
                    &v.mats[v.mat[i] as usize],
                    &v.mats[v.mat[j] as usize],
                    v.rad[i],
                    v.rad[j],
                );
                self.fl[k[l]] = 1;
            }
        }
        let c = k.map(|q| self.cs.get_unchecked(q));
        let s = Touch {
            n0: gather_refs(c.map(|c| &c.normal)),
            fs: gather_refs(c.map(|c| &c.fs)),
            kn: gather1(c.map(|c| c.kn)),
            ks: gather1(c.map(|c| c.ks)),
            tan_phi: gather1(c.map(|c| c.tan_phi)),
        };
        let b = Two {
            xi: x.xi,
            xj: x.xj,
            vi: gather3(v.vel, ki),
            vj: gather3(v.vel, kj),
            wi: gather3(v.w, ki),
            wj: gather3(v.w, kj),
            ri: x.ri,
            rj: x.rj,
        };
        let dist = x.d2.sqrt();
        let pen = x.rs - dist;
        // an existing contact with pen < 0 is erased (NaN: kept, as the scalar test)
        let gone = bits(_mm256_and_pd(
            active,
            _mm256_cmp_pd::<_CMP_LT_OQ>(pen.0, _mm256_setzero_pd()),
        ));
        let load = (fresh | bits(active)) & !gone;
        let o = contact::law(&s, &b, x.d, dist, pen, F4::splat(v.dt));
        let (n, fsn, pl) = (o.n.map(|x| lanes(x)), o.fs.map(|x| lanes(x)), lanes(pen));
        let (lf, lti, ltj) = (
            o.load.f.map(|x| lanes(x)),
            o.load.ti.map(|x| lanes(x)),
            o.load.tj.map(|x| lanes(x)),
        );
        for l in 0..4 {
            let c = self.cs.get_unchecked_mut(k[l]);
            if gone & (1 << l) != 0 {
                c.active = false;
                *self.fl.get_unchecked_mut(k[l]) = 0;
            } else if load & (1 << l) != 0 {
                c.normal = [n[0][l], n[1][l], n[2][l]];
                c.fs = [fsn[0][l], fsn[1][l], fsn[2][l]];
                c.pen = pl[l];
            }
        }
        for l in 0..4 {
            self.acc.open(ki[l]);
            if load & (1 << l) != 0 {
                self.acc.add(
                    kj[l],
                    [lf[0][l], lf[1][l], lf[2][l]],
                    [lti[0][l], lti[1][l], lti[2][l]],
                    [ltj[0][l], ltj[1][l], ltj[2][l]],
                );
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::Ghost;
    use super::*;
    use crate::phys::FrictConsts;

    /// The lanes read bodies and shifts unchecked; the check after each list build must refuse a
    /// pair past the bodies or the shifts, or out of order.
    #[test]
    fn a_pair_outside_the_bodies_or_shifts_is_refused() {
        let ok = contact::chain_pairs(10);
        assert!(super::super::pairs_in_range(&ok, 10, 2));
        let bad = |f: fn(&mut Pair)| {
            let mut p = ok.clone();
            f(&mut p[3]);
            super::super::pairs_in_range(&p, 10, 2)
        };
        assert!(!bad(|p| p.j = 10), "j past the bodies");
        assert!(!bad(|p| p.img = 2), "img past the shifts");
        assert!(!bad(|p| p.i = p.j), "i not below j");
        assert!(!super::super::pairs_in_range(&ok, 9, 2), "one body fewer");
    }

    /// The lanes read the body arrays at the pairs' indices unchecked: a view whose arrays differ
    /// in length is refused at each call.
    #[test]
    #[should_panic(expected = "differ in length")]
    fn a_view_with_arrays_of_two_lengths_is_refused() {
        let (pos, vel, w) = (vec![[0.0; 3]; 4], vec![[0.0; 3]; 4], vec![[0.0; 3]; 3]);
        let view = View {
            pos: &pos,
            vel: &vel,
            w: &w,
            rad: &[1.0; 4],
            mats: &[],
            mat: &[0; 4],
            shifts: &[[0.0; 3]],
            dt: 1e-5,
        };
        view.check(&[]);
    }

    /// rapier's scalar/SIMD parity, to the bit: random pairs in every state the kernel meets
    /// (contacts that stay, that open and are erased, that slide on the Coulomb cap; pairs apart;
    /// pairs that touch for the first time; periodic images; bodies owned by the next chunk, whose
    /// loads go to ghosts; odd counts leaving a scalar tail) through the scalar pair loop and the
    /// lanes, three steps in a row: the same contact states, forces, torques and ghosts.
    #[test]
    fn lanes_are_the_scalar_pair_loop_to_the_bit() {
        if !std::is_x86_feature_detected!("avx2") {
            return;
        }
        let mut mt = rand_mt::Mt64::new(7);
        let mut u = move || (mt.next_u64() >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
        for n in [40usize, 7, 301, 1000] {
            let rad: Vec<f64> = (0..n).map(|_| 1e-3 * (1.0 + 0.3 * u())).collect();
            // a jittered chain: each body within reach of its next few neighbours
            let pos: Vec<V3> = (0..n)
                .map(|i| [0.7e-3 * i as f64 + 4e-4 * u(), 4e-4 * u(), 4e-4 * u()])
                .collect();
            let vel: Vec<V3> = (0..n).map(|_| [u(), u(), u()]).collect();
            let w: Vec<V3> = (0..n)
                .map(|_| [50.0 * u(), 50.0 * u(), 50.0 * u()])
                .collect();
            let mats = [
                FrictConsts {
                    young: 1e8,
                    poisson: 0.3,
                    friction_angle: 0.5,
                },
                FrictConsts {
                    young: 3e7,
                    poisson: 0.25,
                    friction_angle: 0.2,
                },
            ];
            let mat: Vec<u32> = (0..n).map(|i| (i % 3 == 0) as u32).collect();
            // shift 1 brings body j back next to body i (the chain's far end as a periodic image)
            let shifts = [[0.0; 3], [-0.7e-3 * n as f64 + 0.7e-3, 0.0, 0.0]];
            let pairs = contact::chain_pairs(n);
            // states: contacts with a random normal and shear force (some far over the cap), and
            // pairs that are not contacts
            let cs0: Vec<Contact> = pairs
                .iter()
                .enumerate()
                .map(|(k, _)| {
                    if k % 5 == 1 {
                        return Contact::default();
                    }
                    let mut c = Contact::default();
                    contact::create(&mut c, &mats[k % 2], &mats[(k / 2) % 2], 1e-3, 1.1e-3);
                    let s = if k % 4 == 0 { 1e3 } else { 1.0 };
                    c.normal = [1.0 + 0.1 * u(), 0.1 * u(), 0.1 * u()];
                    c.fs = [s * u(), s * u(), s * u()];
                    c
                })
                .collect();
            let view = View {
                pos: &pos,
                vel: &vel,
                w: &w,
                rad: &rad,
                mats: &mats,
                mat: &mat,
                shifts: &shifts,
                dt: 1e-5,
            };
            // this chunk owns bodies 0..hi; the pairs of bodies past it go to another chunk
            let hi = n - n / 10;
            let cut = pairs.partition_point(|p| (p.i as usize) < hi);
            let pairs = &pairs[..cut];
            let (mut cs_s, mut cs_v) = (cs0[..cut].to_vec(), cs0[..cut].to_vec());
            let mut fl_v: Vec<u8> = cs_v.iter().map(|c| c.active as u8).collect();
            let (mut f_s, mut t_s, mut g_s) = (vec![[0.0; 3]; hi], vec![[0.0; 3]; hi], Vec::new());
            let (mut f_v, mut t_v, mut g_v) = (vec![[1.0; 3]; hi], vec![[1.0; 3]; hi], Vec::new());
            let (mut loads, mut gone, mut fresh) = (0, 0, 0);
            for _ in 0..3 {
                let was: Vec<bool> = cs_s.iter().map(|c| c.active).collect();
                let scalar = Acc::new(&mut f_s, &mut t_s, 0, &mut g_s);
                super::super::chunk_loop(&Plain(&view), pairs, &mut cs_s, scalar);
                let lanes = Acc::new(&mut f_v, &mut t_v, 0, &mut g_v);
                // SAFETY: AVX2 checked above; the chain's pairs are in range of its n bodies and
                // two shifts
                unsafe { chunk(&view, pairs, &mut cs_v, &mut fl_v, lanes) };
                let fl_s: Vec<u8> = cs_s.iter().map(|c| c.active as u8).collect();
                assert_eq!(fl_v, fl_s, "the flags follow the states, n {n}");
                for (a, c) in was.iter().zip(&cs_s) {
                    gone += (*a && !c.active) as usize;
                    fresh += (!*a && c.active) as usize;
                    loads += c.active as usize;
                }
                let bits3 = |a: &[V3]| a.iter().flatten().map(|x| x.to_bits()).collect::<Vec<_>>();
                let bitsc = |a: &[Contact]| {
                    a.iter()
                        .map(|c| {
                            let mut b = vec![c.active as u64, c.pen.to_bits(), c.kn.to_bits()];
                            b.extend([c.ks, c.tan_phi].map(f64::to_bits));
                            b.extend(c.normal.iter().chain(&c.fs).map(|x| x.to_bits()));
                            b
                        })
                        .collect::<Vec<_>>()
                };
                let bitsg = |a: &[Ghost]| {
                    a.iter()
                        .map(|g| (g.j, bits3(&[g.f, g.t])))
                        .collect::<Vec<_>>()
                };
                assert_eq!(bitsc(&cs_s), bitsc(&cs_v), "contact states, n {n}");
                assert_eq!(bits3(&f_s), bits3(&f_v), "forces, n {n}");
                assert_eq!(bits3(&t_s), bits3(&t_v), "torques, n {n}");
                assert_eq!(bitsg(&g_s), bitsg(&g_v), "ghosts, n {n}");
            }
            if n >= 301 {
                // the states the test means to reach were reached
                assert!(
                    gone > 10 && fresh > 10 && loads > 100,
                    "{gone} {fresh} {loads}"
                );
                assert!(!g_s.is_empty());
            }
        }
    }
}
