//! The fast path's integrator several bodies at a time: `newton::motion` and `newton::turn` with
//! the same operations in the same order in each lane, so the results are the scalar ones to the
//! bit (`tests::lanes_are_the_scalar_integrator_to_the_bit`). One generic body (`integrate_lanes`)
//! over the lanes (`Lanes`, on top of `Real`): four with AVX2 (`F4`, the pair loop's type), eight
//! with AVX-512 (`F8`). A block falls back to the scalar functions where a lane needs a branch
//! they take rarely: a blocked DOF (motion and turn), a rotation too large for the Taylor series
//! (turn).

use super::contact::V3;
use super::contact_simd::{lane_op, F4};
use super::newton::{self, Cfg, Inert, Run};
use crate::math::{Quat, Real};
use std::arch::x86_64::*;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// What the integrator needs of `N` bodies' doubles side by side beyond `Real` (whose operations
/// run f64's in each lane, so each lane gives the scalar bits): the transposes from and to the
/// bodies' arrays and a few mask operations. Safety of every method: the CPU has the lanes'
/// instructions (AVX2 for `F4`, AVX-512F for `F8`); the slices hold at least `N` items.
trait Lanes: Real {
    const N: usize;
    /// Unordered `!=` (true for NaN).
    unsafe fn neq(self, o: Self) -> Self::Mask;
    /// 1.0 where `m`, else +0.0.
    unsafe fn one_where(m: Self::Mask) -> Self;
    unsafe fn all(m: Self::Mask) -> bool;
    /// `N` consecutive vectors, one register per component.
    unsafe fn load3(a: &[V3]) -> [Self; 3];
    /// `load3` backwards.
    unsafe fn store3(v: [Self; 3], a: &mut [V3]);
    /// `N` consecutive quaternions as w, x, y, z.
    unsafe fn load_q(q: &[Quat]) -> [Self; 4];
    /// `load_q` backwards.
    unsafe fn store_q(v: [Self; 4], q: &mut [Quat]);
    /// `f(l)` in lane l.
    unsafe fn per_lane(f: impl Fn(usize) -> f64) -> Self;
    /// Lane l set where `f(l)`.
    unsafe fn mask_of(f: impl Fn(usize) -> bool) -> Self::Mask;
    /// The largest lane and `m`, folded with `f64::max` in lane order.
    unsafe fn fold_max(self, m: f64) -> f64;
}

impl Lanes for F4 {
    const N: usize = 4;
    #[inline(always)]
    unsafe fn neq(self, o: F4) -> __m256d {
        _mm256_cmp_pd::<_CMP_NEQ_UQ>(self.0, o.0)
    }
    #[inline(always)]
    unsafe fn one_where(m: __m256d) -> F4 {
        F4(_mm256_and_pd(m, _mm256_set1_pd(1.0)))
    }
    #[inline(always)]
    unsafe fn all(m: __m256d) -> bool {
        _mm256_movemask_pd(m) == 0b1111
    }
    /// 12 doubles, x0 y0 z0 x1 | y1 z1 x2 y2 | z2 x3 y3 z3, into lanes.
    #[inline(always)]
    unsafe fn load3(a: &[V3]) -> [F4; 3] {
        let a = &a[..4];
        let p = a.as_ptr() as *const f64;
        let (m0, m1, m2) = (
            _mm256_loadu_pd(p),
            _mm256_loadu_pd(p.add(4)),
            _mm256_loadu_pd(p.add(8)),
        );
        // (x0 y0 | x2 y2), (z0 x1 | z2 x3), (y1 z1 | y3 z3)
        let ab = _mm256_blend_pd::<0b1100>(m0, m1);
        let bc = _mm256_permute2f128_pd::<0x21>(m0, m2);
        let cd = _mm256_blend_pd::<0b1100>(m1, m2);
        [
            F4(_mm256_blend_pd::<0b1010>(ab, bc)),
            F4(_mm256_shuffle_pd::<0b0101>(ab, cd)),
            F4(_mm256_shuffle_pd::<0b1010>(bc, cd)),
        ]
    }
    #[inline(always)]
    unsafe fn store3(v: [F4; 3], a: &mut [V3]) {
        let a = &mut a[..4];
        let p = a.as_mut_ptr() as *mut f64;
        let [x, y, z] = v.map(|c| c.0);
        let ab = _mm256_shuffle_pd::<0b0000>(x, y);
        let cd = _mm256_shuffle_pd::<0b1111>(y, z);
        let bc = _mm256_shuffle_pd::<0b1010>(z, x);
        _mm256_storeu_pd(p, _mm256_permute2f128_pd::<0x20>(ab, bc));
        _mm256_storeu_pd(p.add(4), _mm256_blend_pd::<0b1100>(cd, ab));
        _mm256_storeu_pd(p.add(8), _mm256_permute2f128_pd::<0x31>(bc, cd));
    }
    /// The four quaternions (w, x, y, z each, `repr(C)`) into lanes: a 4x4 transpose.
    #[inline(always)]
    unsafe fn load_q(q: &[Quat]) -> [F4; 4] {
        let q = &q[..4];
        let p = q.as_ptr() as *const f64;
        let r: [__m256d; 4] = std::array::from_fn(|k| _mm256_loadu_pd(p.add(4 * k)));
        let (t0, t1) = (
            _mm256_unpacklo_pd(r[0], r[1]),
            _mm256_unpackhi_pd(r[0], r[1]),
        );
        let (t2, t3) = (
            _mm256_unpacklo_pd(r[2], r[3]),
            _mm256_unpackhi_pd(r[2], r[3]),
        );
        [
            F4(_mm256_permute2f128_pd::<0x20>(t0, t2)),
            F4(_mm256_permute2f128_pd::<0x20>(t1, t3)),
            F4(_mm256_permute2f128_pd::<0x31>(t0, t2)),
            F4(_mm256_permute2f128_pd::<0x31>(t1, t3)),
        ]
    }
    #[inline(always)]
    unsafe fn store_q(v: [F4; 4], q: &mut [Quat]) {
        let q = &mut q[..4];
        let p = q.as_mut_ptr() as *mut f64;
        let [ow, ox, oy, oz] = v.map(|c| c.0);
        let (t0, t1) = (_mm256_unpacklo_pd(ow, ox), _mm256_unpackhi_pd(ow, ox));
        let (t2, t3) = (_mm256_unpacklo_pd(oy, oz), _mm256_unpackhi_pd(oy, oz));
        _mm256_storeu_pd(p, _mm256_permute2f128_pd::<0x20>(t0, t2));
        _mm256_storeu_pd(p.add(4), _mm256_permute2f128_pd::<0x20>(t1, t3));
        _mm256_storeu_pd(p.add(8), _mm256_permute2f128_pd::<0x31>(t0, t2));
        _mm256_storeu_pd(p.add(12), _mm256_permute2f128_pd::<0x31>(t1, t3));
    }
    #[inline(always)]
    unsafe fn per_lane(f: impl Fn(usize) -> f64) -> F4 {
        F4(_mm256_set_pd(f(3), f(2), f(1), f(0)))
    }
    #[inline(always)]
    unsafe fn mask_of(f: impl Fn(usize) -> bool) -> __m256d {
        let on = |l: usize| if f(l) { -1i64 } else { 0 };
        _mm256_castsi256_pd(_mm256_set_epi64x(on(3), on(2), on(1), on(0)))
    }
    #[inline(always)]
    unsafe fn fold_max(self, m: f64) -> f64 {
        let mut l = [0.0; 4];
        _mm256_storeu_pd(l.as_mut_ptr(), self.0);
        l.into_iter().fold(m, f64::max)
    }
}

/// Eight doubles, one per lane (AVX-512F).
#[derive(Clone, Copy)]
struct F8(__m512d);

lane_op!(F8, Add, add, _mm512_add_pd);
lane_op!(F8, Sub, sub, _mm512_sub_pd);
lane_op!(F8, Mul, mul, _mm512_mul_pd);
lane_op!(F8, Div, div, _mm512_div_pd);

impl Neg for F8 {
    type Output = F8;
    #[inline(always)]
    fn neg(self) -> F8 {
        // SAFETY: as in lane_op; a flip of the sign bit, as f64's negation
        F8(unsafe {
            _mm512_castsi512_pd(_mm512_xor_si512(
                _mm512_castpd_si512(self.0),
                _mm512_set1_epi64(i64::MIN),
            ))
        })
    }
}

impl Real for F8 {
    type Mask = __mmask8;
    #[inline(always)]
    fn splat(x: f64) -> F8 {
        // SAFETY: as in lane_op
        F8(unsafe { _mm512_set1_pd(x) })
    }
    #[inline(always)]
    fn sqrt(self) -> F8 {
        // SAFETY: as in lane_op
        F8(unsafe { _mm512_sqrt_pd(self.0) })
    }
    #[inline(always)]
    fn max(self, o: F8) -> F8 {
        // SAFETY: as in lane_op; vmaxpd returns its second operand where the first is NaN
        F8(unsafe { _mm512_max_pd(self.0, o.0) })
    }
    #[inline(always)]
    fn gt(self, o: F8) -> __mmask8 {
        // SAFETY: as in lane_op
        unsafe { _mm512_cmp_pd_mask::<_CMP_GT_OQ>(self.0, o.0) }
    }
    #[inline(always)]
    fn lt(self, o: F8) -> __mmask8 {
        // SAFETY: as in lane_op
        unsafe { _mm512_cmp_pd_mask::<_CMP_LT_OQ>(self.0, o.0) }
    }
    #[inline(always)]
    fn is_nan(self) -> __mmask8 {
        // SAFETY: as in lane_op
        unsafe { _mm512_cmp_pd_mask::<_CMP_UNORD_Q>(self.0, self.0) }
    }
    #[inline(always)]
    fn abs(self) -> F8 {
        // SAFETY: as in lane_op; the sign bit cleared, as f64::abs
        F8(unsafe { _mm512_abs_pd(self.0) })
    }
    #[inline(always)]
    fn atan2(self, x: F8) -> F8 {
        // libm's, lane by lane
        // SAFETY: as in lane_op
        unsafe {
            let (mut y8, mut x8) = ([0.0; 8], [0.0; 8]);
            _mm512_storeu_pd(y8.as_mut_ptr(), self.0);
            _mm512_storeu_pd(x8.as_mut_ptr(), x.0);
            let r: [f64; 8] = std::array::from_fn(|l| y8[l].atan2(x8[l]));
            F8(_mm512_loadu_pd(r.as_ptr()))
        }
    }
    #[inline(always)]
    fn any(m: __mmask8) -> bool {
        m != 0
    }
    #[inline(always)]
    fn select(m: __mmask8, a: F8, b: F8) -> F8 {
        // SAFETY: as in lane_op; the blend takes its second operand where the mask holds
        F8(unsafe { _mm512_mask_blend_pd(m, b.0, a.0) })
    }
}

/// `_mm512_permutex2var_pd(a, idx, b)`: lane l takes `a[idx[l]]` (idx < 8) or `b[idx[l] - 8]`.
#[inline]
#[target_feature(enable = "avx512f")]
unsafe fn perm2(a: __m512d, idx: [i64; 8], b: __m512d) -> __m512d {
    let i = _mm512_set_epi64(
        idx[7], idx[6], idx[5], idx[4], idx[3], idx[2], idx[1], idx[0],
    );
    _mm512_permutex2var_pd(a, i, b)
}

impl Lanes for F8 {
    const N: usize = 8;
    #[inline]
    #[target_feature(enable = "avx512f")]
    unsafe fn neq(self, o: F8) -> __mmask8 {
        _mm512_cmp_pd_mask::<_CMP_NEQ_UQ>(self.0, o.0)
    }
    #[inline]
    #[target_feature(enable = "avx512f")]
    unsafe fn one_where(m: __mmask8) -> F8 {
        F8(_mm512_maskz_mov_pd(m, _mm512_set1_pd(1.0)))
    }
    #[inline]
    #[target_feature(enable = "avx512f")]
    unsafe fn all(m: __mmask8) -> bool {
        m == 0xff
    }
    /// 24 doubles: m0 = x0 y0 z0 x1 y1 z1 x2 y2, m1 = z2 x3 y3 z3 x4 y4 z4 x5,
    /// m2 = y5 z5 x6 y6 z6 x7 y7 z7.
    #[inline]
    #[target_feature(enable = "avx512f")]
    unsafe fn load3(a: &[V3]) -> [F8; 3] {
        let a = &a[..8];
        let p = a.as_ptr() as *const f64;
        let (m0, m1, m2) = (
            _mm512_loadu_pd(p),
            _mm512_loadu_pd(p.add(8)),
            _mm512_loadu_pd(p.add(16)),
        );
        let x = perm2(
            perm2(m0, [0, 3, 6, 9, 12, 15, 0, 0], m1),
            [0, 1, 2, 3, 4, 5, 10, 13],
            m2,
        );
        let y = perm2(
            perm2(m0, [1, 4, 7, 10, 13, 0, 0, 0], m1),
            [0, 1, 2, 3, 4, 8, 11, 14],
            m2,
        );
        let z = perm2(
            perm2(m0, [2, 5, 8, 11, 14, 0, 0, 0], m1),
            [0, 1, 2, 3, 4, 9, 12, 15],
            m2,
        );
        [F8(x), F8(y), F8(z)]
    }
    #[inline]
    #[target_feature(enable = "avx512f")]
    unsafe fn store3(v: [F8; 3], a: &mut [V3]) {
        let a = &mut a[..8];
        let p = a.as_mut_ptr() as *mut f64;
        let [x, y, z] = v.map(|c| c.0);
        let m0 = perm2(
            perm2(x, [0, 8, 0, 1, 9, 0, 2, 10], y),
            [0, 1, 8, 3, 4, 9, 6, 7],
            z,
        );
        let m1 = perm2(
            perm2(x, [0, 3, 11, 0, 4, 12, 0, 5], y),
            [10, 1, 2, 11, 4, 5, 12, 7],
            z,
        );
        let m2 = perm2(
            perm2(x, [13, 0, 6, 14, 0, 7, 15, 0], y),
            [0, 13, 2, 3, 14, 5, 6, 15],
            z,
        );
        _mm512_storeu_pd(p, m0);
        _mm512_storeu_pd(p.add(8), m1);
        _mm512_storeu_pd(p.add(16), m2);
    }
    /// 32 doubles, two quaternions per register, into w, x, y, z.
    #[inline]
    #[target_feature(enable = "avx512f")]
    unsafe fn load_q(q: &[Quat]) -> [F8; 4] {
        let q = &q[..8];
        let p = q.as_ptr() as *const f64;
        let r: [__m512d; 4] = std::array::from_fn(|k| _mm512_loadu_pd(p.add(8 * k)));
        std::array::from_fn(|c| {
            let c = c as i64;
            let lo = perm2(r[0], [c, c + 4, c + 8, c + 12, 0, 0, 0, 0], r[1]);
            let hi = perm2(r[2], [c, c + 4, c + 8, c + 12, 0, 0, 0, 0], r[3]);
            F8(perm2(lo, [0, 1, 2, 3, 8, 9, 10, 11], hi))
        })
    }
    #[inline]
    #[target_feature(enable = "avx512f")]
    unsafe fn store_q(v: [F8; 4], q: &mut [Quat]) {
        let q = &mut q[..8];
        let p = q.as_mut_ptr() as *mut f64;
        let [w, x, y, z] = v.map(|c| c.0);
        // (w x) and (y z) interleaved per lane, then the quaternions' halves joined
        let wx_lo = perm2(w, [0, 8, 1, 9, 2, 10, 3, 11], x);
        let wx_hi = perm2(w, [4, 12, 5, 13, 6, 14, 7, 15], x);
        let yz_lo = perm2(y, [0, 8, 1, 9, 2, 10, 3, 11], z);
        let yz_hi = perm2(y, [4, 12, 5, 13, 6, 14, 7, 15], z);
        // quaternion l: wx[2l], wx[2l+1], yz[2l], yz[2l+1]
        let out = [
            perm2(wx_lo, [0, 1, 8, 9, 2, 3, 10, 11], yz_lo),
            perm2(wx_lo, [4, 5, 12, 13, 6, 7, 14, 15], yz_lo),
            perm2(wx_hi, [0, 1, 8, 9, 2, 3, 10, 11], yz_hi),
            perm2(wx_hi, [4, 5, 12, 13, 6, 7, 14, 15], yz_hi),
        ];
        for (k, o) in out.into_iter().enumerate() {
            _mm512_storeu_pd(p.add(8 * k), o);
        }
    }
    #[inline]
    #[target_feature(enable = "avx512f")]
    unsafe fn per_lane(f: impl Fn(usize) -> f64) -> F8 {
        F8(_mm512_set_pd(
            f(7),
            f(6),
            f(5),
            f(4),
            f(3),
            f(2),
            f(1),
            f(0),
        ))
    }
    #[inline]
    #[target_feature(enable = "avx512f")]
    unsafe fn mask_of(f: impl Fn(usize) -> bool) -> __mmask8 {
        (0..8).fold(0, |m, l| m | ((f(l) as u8) << l))
    }
    #[inline]
    #[target_feature(enable = "avx512f")]
    unsafe fn fold_max(self, m: f64) -> f64 {
        let mut l = [0.0; 8];
        _mm512_storeu_pd(l.as_mut_ptr(), self.0);
        l.into_iter().fold(m, f64::max)
    }
}

/// YADE's `math::sign` per lane: 1, -1, or 0 (0 and NaN), as `newton::sign`.
#[inline(always)]
unsafe fn sign<L: Lanes>(x: L) -> L {
    let z = L::splat(0.0);
    L::one_where(z.lt(x)) - L::one_where(x.lt(z))
}

/// `newton::damp` on one component, in the lanes of `damped`.
#[inline(always)]
unsafe fn damp<L: Lanes>(c: &Cfg, v: L, a: L, damped: L::Mask) -> L {
    // a *= 1 - damping * sign(a * (v + 0.5 dt a))
    let arg = a * (v + L::splat(0.5 * c.dt) * a);
    let f = L::splat(1.0) - L::splat(c.damping) * sign(arg);
    L::select(damped, a * f, a)
}

/// `newton::motion` for `L::N` bodies none of which has a blocked DOF; returns each one's squared
/// displacement since `x_ref`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
unsafe fn motion_lanes<L: Lanes>(
    c: &Cfg,
    b: &[Inert],
    f: &[V3],
    t: &[V3],
    x: &mut [V3],
    v: &mut [V3],
    w: &mut [V3],
    x_ref: &[V3],
) -> L {
    let im = L::per_lane(|l| b[l].inv_mass);
    let ii = |k: usize| L::per_lane(|l| b[l].inv_inertia[k]);
    let damped = L::mask_of(|l| b[l].damped);
    let (fv, tv, mut vv, mut wv, mut xv, xr) = (
        L::load3(f),
        L::load3(t),
        L::load3(v),
        L::load3(w),
        L::load3(x),
        L::load3(x_ref),
    );
    let dt = L::splat(c.dt);
    let g = c.gravity.map(|x| L::splat(x));
    // linear: a = f / m (+ g when damped with it), damped, (+ g), v += dt a
    let mut a = fv.map(|fk| fk * im);
    if c.damp_gravity {
        for k in 0..3 {
            a[k] = a[k] + g[k];
        }
    }
    for k in 0..3 {
        a[k] = damp(c, vv[k], a[k], damped);
    }
    if !c.damp_gravity {
        for k in 0..3 {
            a[k] = a[k] + g[k];
        }
    }
    for k in 0..3 {
        vv[k] = vv[k] + dt * a[k];
    }
    // angular: aa = t / I, damped, w += dt aa
    for k in 0..3 {
        let aa = damp(c, wv[k], tv[k] * ii(k), damped);
        wv[k] = wv[k] + dt * aa;
    }
    // x += v dt; |x - x_ref|² summed left to right
    for k in 0..3 {
        xv[k] = xv[k] + vv[k] * dt;
    }
    let d: [L; 3] = std::array::from_fn(|k| xv[k] - xr[k]);
    let d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    L::store3(vv, v);
    L::store3(wv, w);
    L::store3(xv, x);
    d2
}

/// `newton::turn` for `L::N` bodies; false (nothing written) when a lane's rotation is beyond the
/// Taylor series of `newton::rotation`.
#[inline(always)]
unsafe fn turn_lanes<L: Lanes>(dt: f64, w: &[V3], q: &mut [Quat]) -> bool {
    const _: () = assert!(std::mem::size_of::<Quat>() == 32);
    let wv = L::load3(w);
    let w2 = wv[0] * wv[0] + wv[1] * wv[1] + wv[2] * wv[2];
    let h = 0.5 * dt;
    let x2 = w2 * L::splat(h * h);
    if !L::all(x2.lt(L::splat(1e-4))) {
        return false;
    }
    // c = 1 + x2 (-1/2 + x2 (1/24 + x2 (-1/720 + x2 (1/40320)))),
    // s = h (1 + x2 (-1/6 + x2 (1/120 + x2 (-1/5040)))), as `newton::rotation`
    let p = |k: f64, r: L| L::splat(k) + x2 * r;
    let cc = p(
        1.0,
        p(
            -0.5,
            p(1.0 / 24.0, p(-1.0 / 720.0, L::splat(1.0 / 40320.0))),
        ),
    );
    let s = L::splat(h) * p(1.0, p(-1.0 / 6.0, p(1.0 / 120.0, L::splat(-1.0 / 5040.0))));
    let (rw, rx, ry, rz) = (cc, s * wv[0], s * wv[1], s * wv[2]);
    let [bw, bx, by, bz] = L::load_q(q);
    // Quat::mul (rotation first)
    let nw = rw * bw - rx * bx - ry * by - rz * bz;
    let nx = rw * bx + rx * bw + ry * bz - rz * by;
    let ny = rw * by + ry * bw + rz * bx - rx * bz;
    let nz = rw * bz + rz * bw + rx * by - ry * bx;
    // no rotation where ω = 0
    let moving = w2.neq(L::splat(0.0));
    let (qw, qx, qy, qz) = (
        L::select(moving, nw, bw),
        L::select(moving, nx, bx),
        L::select(moving, ny, by),
        L::select(moving, nz, bz),
    );
    // renormalise as `turn`: (x²+y²) + (z²+w²); 1 - e/2 near 1, else 1/sqrt(n2) (n2 > 0), else 1
    let n2 = (qx * qx + qy * qy) + (qz * qz + qw * qw);
    let e = n2 - L::splat(1.0);
    let near = e.abs().lt(L::splat(1e-8));
    let newton = L::splat(1.0) - L::splat(0.5) * e;
    // (the square root and division only when a lane needs them)
    let inv = if L::all(near) {
        newton
    } else {
        let pos = n2.gt(L::splat(0.0));
        let far = L::select(pos, L::splat(1.0) / n2.sqrt(), L::splat(1.0));
        L::select(near, newton, far)
    };
    L::store_q([qw * inv, qx * inv, qy * inv, qz * inv], q);
    true
}

/// The integrator over a run of bodies, four at a time (see the module); returns the largest
/// squared displacement since `x_ref`, as `integrate_impl`.
///
/// # Safety
/// The CPU must have AVX2.
#[target_feature(enable = "avx2")]
pub unsafe fn integrate(cfg: &Cfg, r: Run) -> f64 {
    integrate_lanes::<F4>(cfg, r)
}

/// The integrator eight bodies at a time (AVX-512; the same generic body and bits).
///
/// # Safety
/// The CPU must have AVX2, AVX-512F and AVX-512VL.
#[target_feature(enable = "avx2,avx512f,avx512vl")]
pub unsafe fn integrate_evex(cfg: &Cfg, r: Run) -> f64 {
    integrate_lanes::<F8>(cfg, r)
}

/// The body of `integrate` and `integrate_evex`. Safety: the CPU has the lanes' instructions;
/// only called from those two, into which it is inlined.
#[inline(always)]
unsafe fn integrate_lanes<L: Lanes>(cfg: &Cfg, r: Run) -> f64 {
    let Run {
        inert,
        f,
        t,
        x,
        v,
        w,
        q,
        x_ref,
    } = r;
    let n = x.len();
    let mut md: f64 = 0.0;
    // the lanes' largest squared displacements (maxpd returns its second operand where the
    // first is NaN: a NaN is passed over, as f64::max does; the squares are never -0)
    let mut mdv = L::splat(0.0);
    let mut k = 0;
    while k < n {
        let e = (k + L::N).min(n);
        let r = k..e;
        if e - k == L::N && inert[r.clone()].iter().all(|b| b.blocked == 0) {
            let d = motion_lanes::<L>(
                cfg,
                &inert[r.clone()],
                &f[r.clone()],
                &t[r.clone()],
                &mut x[r.clone()],
                &mut v[r.clone()],
                &mut w[r.clone()],
                &x_ref[r.clone()],
            );
            mdv = d.max(mdv);
            if !turn_lanes::<L>(cfg.dt, &w[r.clone()], &mut q[r.clone()]) {
                for j in r {
                    newton::turn(cfg.dt, &w[j], &mut q[j]);
                }
            }
        } else {
            for j in r {
                let d = newton::motion(
                    cfg, &inert[j], f[j], t[j], &mut x[j], &mut v[j], &mut w[j], &x_ref[j],
                );
                md = md.max(d);
                newton::turn(cfg.dt, &w[j], &mut q[j]);
            }
        }
        k = e;
    }
    mdv.fold_max(md)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// rapier's scalar/SIMD parity, to the bit: random bodies (some blocked, some undamped, some
    /// spinning beyond the Taylor series, odd counts) through the scalar integrator and through the
    /// four-lane one (and the eight-lane one where the CPU has AVX-512) give identical states and
    /// the same largest displacement. Bodies 8-15 make a block both lane widths take (unblocked,
    /// inside the series; asserted below) with two bodies at rest (the ω = 0 lanes), one
    /// quaternion off the unit sphere (the 1/sqrt renormalisation) and a zero quaternion (no
    /// renormalisation).
    #[test]
    fn lanes_are_the_scalar_integrator_to_the_bit() {
        if !std::is_x86_feature_detected!("avx2") {
            return;
        }
        // the fixture's patterns below leave bodies 8-15 unblocked and inside the series
        assert!((8..16).all(|i: usize| !matches!(i % 17, 3 | 5) && i % 13 != 6));
        let mut mt = rand_mt::Mt64::new(11);
        let mut u = move || (mt.next_u64() >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
        for (n, damp_gravity) in [(37usize, true), (64, false), (3, true), (401, true)] {
            let cfg = Cfg {
                dt: 1e-4 * (1.0 + u()),
                damping: 0.2,
                gravity: [0.0, 0.0, -9.81],
                damp_gravity,
            };
            let v3 = |u: &mut dyn FnMut() -> f64, s: f64| [s * u(), s * u(), s * u()];
            let inert: Vec<Inert> = (0..n)
                .map(|i| Inert {
                    inv_mass: 10.0 + u(),
                    inv_inertia: [1e3 * (1.0 + u()); 3],
                    blocked: match i % 17 {
                        3 => 4,
                        5 => crate::body::DOF_ALL,
                        _ => 0,
                    },
                    damped: i % 7 != 2,
                })
                .collect();
            let f: Vec<V3> = (0..n).map(|_| v3(&mut u, 5.0)).collect();
            // bodies 8 and 9 of every 16: no torque and no spin (the ω = 0 lanes of an unblocked
            // block)
            let t: Vec<V3> = (0..n)
                .map(|i| {
                    if i % 16 == 8 || i % 16 == 9 {
                        [0.0; 3]
                    } else {
                        v3(&mut u, 0.01)
                    }
                })
                .collect();
            let x: Vec<V3> = (0..n).map(|_| v3(&mut u, 1.0)).collect();
            let v: Vec<V3> = (0..n)
                .map(|i| {
                    if i % 11 == 4 {
                        [0.0; 3]
                    } else {
                        v3(&mut u, 0.1)
                    }
                })
                .collect();
            let w: Vec<V3> = (0..n)
                .map(|i| match (i % 16, i % 13) {
                    (8 | 9, _) => [0.0; 3],
                    (_, 1) => [0.0; 3],
                    (_, 6) => v3(&mut u, 2e3),
                    _ => v3(&mut u, 3.0),
                })
                .collect();
            // unit quaternions, some off the unit sphere (1/sqrt renormalisation) and one zero
            let q: Vec<Quat> = (0..n)
                .map(|i| {
                    let mut q = Quat::new(1.0 + u(), u(), u(), u());
                    q.normalize();
                    match i % 16 {
                        10 => Quat::new(1.01 * q.w, 1.01 * q.x, 1.01 * q.y, 1.01 * q.z),
                        11 if i < 16 => Quat::new(0.0, 0.0, 0.0, 0.0),
                        _ => q,
                    }
                })
                .collect();
            let x_ref: Vec<V3> = x.iter().map(|a| [a[0] + 1e-3, a[1], a[2]]).collect();
            let (mut xs, mut vs, mut ws, mut qs) = (x.clone(), v.clone(), w.clone(), q.clone());
            let (mut xe, mut ve, mut we, mut qe) = (x.clone(), v.clone(), w.clone(), q.clone());
            let (mut xv, mut vv, mut wv, mut qv) = (x, v, w, q);
            let evex = std::is_x86_feature_detected!("avx512f")
                && std::is_x86_feature_detected!("avx512vl");
            for _ in 0..3 {
                let run = |x, v, w, q| Run {
                    inert: &inert,
                    f: &f,
                    t: &t,
                    x,
                    v,
                    w,
                    q,
                    x_ref: &x_ref,
                };
                let ms =
                    super::super::integrate_impl(&cfg, run(&mut xs, &mut vs, &mut ws, &mut qs));
                // SAFETY: AVX2 checked above
                let mv = unsafe { integrate(&cfg, run(&mut xv, &mut vv, &mut wv, &mut qv)) };
                assert_eq!(ms.to_bits(), mv.to_bits(), "largest displacement, n {n}");
                if evex {
                    // SAFETY: AVX-512F and VL checked above
                    let me =
                        unsafe { integrate_evex(&cfg, run(&mut xe, &mut ve, &mut we, &mut qe)) };
                    assert_eq!(
                        ms.to_bits(),
                        me.to_bits(),
                        "largest displacement, n {n}, AVX-512"
                    );
                }
            }
            let bits3 = |a: &[V3]| a.iter().flatten().map(|x| x.to_bits()).collect::<Vec<_>>();
            let bitsq = |a: &[Quat]| {
                a.iter()
                    .flat_map(|q| [q.w, q.x, q.y, q.z])
                    .map(|x| x.to_bits())
                    .collect::<Vec<_>>()
            };
            if evex {
                assert_eq!(
                    (bits3(&xe), bits3(&ve), bits3(&we), bitsq(&qe)),
                    (bits3(&xs), bits3(&vs), bits3(&ws), bitsq(&qs)),
                    "AVX-512 build, n {n}"
                );
            }
            assert_eq!(bits3(&xs), bits3(&xv), "positions, n {n}");
            assert_eq!(bits3(&vs), bits3(&vv), "velocities, n {n}");
            assert_eq!(bits3(&ws), bits3(&wv), "angular velocities, n {n}");
            assert_eq!(bitsq(&qs), bitsq(&qv), "orientations, n {n}");
        }
    }
}
