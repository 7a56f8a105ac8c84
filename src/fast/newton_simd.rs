//! The fast path's integrator four bodies at a time (AVX2): `newton::motion` and `newton::turn`
//! with the same operations in the same order in each lane, so the results are the scalar ones to
//! the bit (`tests::lanes_are_the_scalar_integrator_to_the_bit`). A block of four falls back to the
//! scalar functions where a lane needs a branch they take rarely: a blocked DOF (motion and turn),
//! a rotation too large for the Taylor series (turn).

use super::contact::V3;
use super::newton::{self, Cfg, Inert, Run};
use crate::math::Quat;
use std::arch::x86_64::*;

/// Three components of four bodies' vectors, one register each.
#[derive(Clone, Copy)]
struct V4 {
    x: __m256d,
    y: __m256d,
    z: __m256d,
}

/// Four consecutive vectors (12 doubles, x0 y0 z0 x1 | y1 z1 x2 y2 | z2 x3 y3 z3) into lanes.
#[inline(always)]
unsafe fn load(a: &[V3]) -> V4 {
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
    V4 {
        x: _mm256_blend_pd::<0b1010>(ab, bc),
        y: _mm256_shuffle_pd::<0b0101>(ab, cd),
        z: _mm256_shuffle_pd::<0b1010>(bc, cd),
    }
}

/// `load` backwards.
#[inline(always)]
unsafe fn store(v: &V4, a: &mut [V3]) {
    let a = &mut a[..4];
    let p = a.as_mut_ptr() as *mut f64;
    let ab = _mm256_shuffle_pd::<0b0000>(v.x, v.y);
    let cd = _mm256_shuffle_pd::<0b1111>(v.y, v.z);
    let bc = _mm256_shuffle_pd::<0b1010>(v.z, v.x);
    _mm256_storeu_pd(p, _mm256_permute2f128_pd::<0x20>(ab, bc));
    _mm256_storeu_pd(p.add(4), _mm256_blend_pd::<0b1100>(cd, ab));
    _mm256_storeu_pd(p.add(8), _mm256_permute2f128_pd::<0x31>(bc, cd));
}

#[inline(always)]
unsafe fn splat(x: f64) -> __m256d {
    _mm256_set1_pd(x)
}

/// YADE's `math::sign` per lane: 1, -1, or 0 (0 and NaN), as `newton::sign`.
#[inline(always)]
unsafe fn sign(x: __m256d) -> __m256d {
    let z = _mm256_setzero_pd();
    let one = splat(1.0);
    let pos = _mm256_and_pd(_mm256_cmp_pd::<_CMP_LT_OQ>(z, x), one);
    let neg = _mm256_and_pd(_mm256_cmp_pd::<_CMP_LT_OQ>(x, z), one);
    _mm256_sub_pd(pos, neg)
}

/// `newton::damp` on one component, in the lanes of `damped`.
#[inline(always)]
unsafe fn damp(c: &Cfg, v: __m256d, a: __m256d, damped: __m256d) -> __m256d {
    // a *= 1 - damping * sign(a * (v + 0.5 dt a))
    let arg = _mm256_mul_pd(a, _mm256_add_pd(v, _mm256_mul_pd(splat(0.5 * c.dt), a)));
    let f = _mm256_sub_pd(splat(1.0), _mm256_mul_pd(splat(c.damping), sign(arg)));
    _mm256_blendv_pd(a, _mm256_mul_pd(a, f), damped)
}

/// `newton::motion` for four bodies none of which has a blocked DOF; returns each one's squared
/// displacement since `x_ref`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
unsafe fn motion4(
    c: &Cfg,
    b: &[Inert],
    f: &[V3],
    t: &[V3],
    x: &mut [V3],
    v: &mut [V3],
    w: &mut [V3],
    x_ref: &[V3],
) -> __m256d {
    let im = _mm256_set_pd(b[3].inv_mass, b[2].inv_mass, b[1].inv_mass, b[0].inv_mass);
    let ii = |k: usize| {
        _mm256_set_pd(
            b[3].inv_inertia[k],
            b[2].inv_inertia[k],
            b[1].inv_inertia[k],
            b[0].inv_inertia[k],
        )
    };
    let on = |d: bool| if d { -1i64 } else { 0 };
    let damped = _mm256_castsi256_pd(_mm256_set_epi64x(
        on(b[3].damped),
        on(b[2].damped),
        on(b[1].damped),
        on(b[0].damped),
    ));
    let (fv, tv, mut vv, mut wv, mut xv, xr) =
        (load(f), load(t), load(v), load(w), load(x), load(x_ref));
    let dt = splat(c.dt);
    let g = [
        splat(c.gravity[0]),
        splat(c.gravity[1]),
        splat(c.gravity[2]),
    ];
    // linear: a = f / m (+ g when damped with it), damped, (+ g), v += dt a
    let mut a = [
        _mm256_mul_pd(fv.x, im),
        _mm256_mul_pd(fv.y, im),
        _mm256_mul_pd(fv.z, im),
    ];
    if c.damp_gravity {
        for k in 0..3 {
            a[k] = _mm256_add_pd(a[k], g[k]);
        }
    }
    let vs = [vv.x, vv.y, vv.z];
    for k in 0..3 {
        a[k] = damp(c, vs[k], a[k], damped);
    }
    if !c.damp_gravity {
        for k in 0..3 {
            a[k] = _mm256_add_pd(a[k], g[k]);
        }
    }
    vv.x = _mm256_add_pd(vv.x, _mm256_mul_pd(dt, a[0]));
    vv.y = _mm256_add_pd(vv.y, _mm256_mul_pd(dt, a[1]));
    vv.z = _mm256_add_pd(vv.z, _mm256_mul_pd(dt, a[2]));
    // angular: aa = t / I, damped, w += dt aa
    let mut aa = [
        _mm256_mul_pd(tv.x, ii(0)),
        _mm256_mul_pd(tv.y, ii(1)),
        _mm256_mul_pd(tv.z, ii(2)),
    ];
    let ws = [wv.x, wv.y, wv.z];
    for k in 0..3 {
        aa[k] = damp(c, ws[k], aa[k], damped);
    }
    wv.x = _mm256_add_pd(wv.x, _mm256_mul_pd(dt, aa[0]));
    wv.y = _mm256_add_pd(wv.y, _mm256_mul_pd(dt, aa[1]));
    wv.z = _mm256_add_pd(wv.z, _mm256_mul_pd(dt, aa[2]));
    // x += v dt; |x - x_ref|² summed left to right
    xv.x = _mm256_add_pd(xv.x, _mm256_mul_pd(vv.x, dt));
    xv.y = _mm256_add_pd(xv.y, _mm256_mul_pd(vv.y, dt));
    xv.z = _mm256_add_pd(xv.z, _mm256_mul_pd(vv.z, dt));
    let (dx, dy, dz) = (
        _mm256_sub_pd(xv.x, xr.x),
        _mm256_sub_pd(xv.y, xr.y),
        _mm256_sub_pd(xv.z, xr.z),
    );
    let d2 = _mm256_add_pd(
        _mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)),
        _mm256_mul_pd(dz, dz),
    );
    store(&vv, v);
    store(&wv, w);
    store(&xv, x);
    d2
}

/// `newton::turn` for four bodies; false (nothing written) when a lane's rotation is beyond the
/// Taylor series of `newton::rotation`.
#[inline(always)]
unsafe fn turn4(dt: f64, w: &[V3], q: &mut [Quat]) -> bool {
    const _: () = assert!(std::mem::size_of::<Quat>() == 32);
    let wv = load(w);
    let w2 = _mm256_add_pd(
        _mm256_add_pd(_mm256_mul_pd(wv.x, wv.x), _mm256_mul_pd(wv.y, wv.y)),
        _mm256_mul_pd(wv.z, wv.z),
    );
    let h = 0.5 * dt;
    let x2 = _mm256_mul_pd(w2, splat(h * h));
    if _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_LT_OQ>(x2, splat(1e-4))) != 0b1111 {
        return false;
    }
    // c = 1 + x2 (-1/2 + x2 (1/24 + x2 (-1/720 + x2 (1/40320)))),
    // s = h (1 + x2 (-1/6 + x2 (1/120 + x2 (-1/5040)))), as `newton::rotation`
    let p = |k: f64, r: __m256d| _mm256_add_pd(splat(k), _mm256_mul_pd(x2, r));
    let cc = p(
        1.0,
        p(-0.5, p(1.0 / 24.0, p(-1.0 / 720.0, splat(1.0 / 40320.0)))),
    );
    let s = _mm256_mul_pd(
        splat(h),
        p(1.0, p(-1.0 / 6.0, p(1.0 / 120.0, splat(-1.0 / 5040.0)))),
    );
    let (rw, rx, ry, rz) = (
        cc,
        _mm256_mul_pd(s, wv.x),
        _mm256_mul_pd(s, wv.y),
        _mm256_mul_pd(s, wv.z),
    );
    // the four quaternions (w, x, y, z each, `repr(C)`) into lanes: a 4x4 transpose
    let q = &mut q[..4];
    let p = q.as_mut_ptr() as *mut f64;
    let r: [__m256d; 4] = std::array::from_fn(|k| _mm256_loadu_pd(p.add(4 * k)));
    let (t0, t1) = (
        _mm256_unpacklo_pd(r[0], r[1]),
        _mm256_unpackhi_pd(r[0], r[1]),
    );
    let (t2, t3) = (
        _mm256_unpacklo_pd(r[2], r[3]),
        _mm256_unpackhi_pd(r[2], r[3]),
    );
    let (bw, bx, by, bz) = (
        _mm256_permute2f128_pd::<0x20>(t0, t2),
        _mm256_permute2f128_pd::<0x20>(t1, t3),
        _mm256_permute2f128_pd::<0x31>(t0, t2),
        _mm256_permute2f128_pd::<0x31>(t1, t3),
    );
    let (m, a, sb) = (_mm256_mul_pd, _mm256_add_pd, _mm256_sub_pd);
    // Quat::mul (rotation first)
    let nw = sb(sb(sb(m(rw, bw), m(rx, bx)), m(ry, by)), m(rz, bz));
    let nx = sb(a(a(m(rw, bx), m(rx, bw)), m(ry, bz)), m(rz, by));
    let ny = sb(a(a(m(rw, by), m(ry, bw)), m(rz, bx)), m(rx, bz));
    let nz = sb(a(a(m(rw, bz), m(rz, bw)), m(rx, by)), m(ry, bx));
    // no rotation where ω = 0
    let moving = _mm256_cmp_pd::<_CMP_NEQ_UQ>(w2, _mm256_setzero_pd());
    let (qw, qx, qy, qz) = (
        _mm256_blendv_pd(bw, nw, moving),
        _mm256_blendv_pd(bx, nx, moving),
        _mm256_blendv_pd(by, ny, moving),
        _mm256_blendv_pd(bz, nz, moving),
    );
    // renormalise as `turn`: (x²+y²) + (z²+w²); 1 - e/2 near 1, else 1/sqrt(n2) (n2 > 0), else 1
    let n2 = a(a(m(qx, qx), m(qy, qy)), a(m(qz, qz), m(qw, qw)));
    let e = sb(n2, splat(1.0));
    let near = _mm256_cmp_pd::<_CMP_LT_OQ>(_mm256_andnot_pd(splat(-0.0), e), splat(1e-8));
    let pos = _mm256_cmp_pd::<_CMP_GT_OQ>(n2, _mm256_setzero_pd());
    let newton = sb(splat(1.0), m(splat(0.5), e));
    // (the square root and division only when a lane needs them)
    let inv = if _mm256_movemask_pd(near) == 0b1111 {
        newton
    } else {
        let far = _mm256_blendv_pd(
            splat(1.0),
            _mm256_div_pd(splat(1.0), _mm256_sqrt_pd(n2)),
            pos,
        );
        _mm256_blendv_pd(far, newton, near)
    };
    let (ow, ox, oy, oz) = (m(qw, inv), m(qx, inv), m(qy, inv), m(qz, inv));
    let (t0, t1) = (_mm256_unpacklo_pd(ow, ox), _mm256_unpackhi_pd(ow, ox));
    let (t2, t3) = (_mm256_unpacklo_pd(oy, oz), _mm256_unpackhi_pd(oy, oz));
    _mm256_storeu_pd(p, _mm256_permute2f128_pd::<0x20>(t0, t2));
    _mm256_storeu_pd(p.add(4), _mm256_permute2f128_pd::<0x20>(t1, t3));
    _mm256_storeu_pd(p.add(8), _mm256_permute2f128_pd::<0x31>(t0, t2));
    _mm256_storeu_pd(p.add(12), _mm256_permute2f128_pd::<0x31>(t1, t3));
    true
}

/// The integrator over a run of bodies, four at a time (see the module); returns the largest
/// squared displacement since `x_ref`, as `integrate_impl`.
///
/// # Safety
/// The CPU must have AVX2.
#[target_feature(enable = "avx2")]
pub unsafe fn integrate(cfg: &Cfg, r: Run) -> f64 {
    integrate_lanes(cfg, r)
}

/// `integrate` compiled for AVX-512 (the same four-lane code and bits; its 32 registers spare
/// the spills of the 16 of AVX2: 11 % off the dense script's integration).
///
/// # Safety
/// The CPU must have AVX2, AVX-512F and AVX-512VL.
#[target_feature(enable = "avx2,avx512f,avx512vl")]
pub unsafe fn integrate_evex(cfg: &Cfg, r: Run) -> f64 {
    integrate_lanes(cfg, r)
}

/// The body of `integrate` and `integrate_evex`. Safety: the CPU has AVX2; only called from
/// those two, into which it is inlined.
#[inline(always)]
unsafe fn integrate_lanes(cfg: &Cfg, r: Run) -> f64 {
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
    let mut mdv = _mm256_setzero_pd();
    let mut k = 0;
    while k < n {
        let e = (k + 4).min(n);
        let r = k..e;
        if e - k == 4 && inert[r.clone()].iter().all(|b| b.blocked == 0) {
            let d = motion4(
                cfg,
                &inert[r.clone()],
                &f[r.clone()],
                &t[r.clone()],
                &mut x[r.clone()],
                &mut v[r.clone()],
                &mut w[r.clone()],
                &x_ref[r.clone()],
            );
            mdv = _mm256_max_pd(d, mdv);
            if !turn4(cfg.dt, &w[r.clone()], &mut q[r.clone()]) {
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
    let mut l = [0.0; 4];
    _mm256_storeu_pd(l.as_mut_ptr(), mdv);
    l.into_iter().fold(md, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// rapier's scalar/SIMD parity, to the bit: random bodies (some blocked, some undamped, some
    /// spinning beyond the Taylor series, odd counts) through the scalar integrator and through the
    /// four-lane one give identical states and the same largest displacement. Bodies 8-11 of every
    /// 16 make a block the lanes take (unblocked, inside the series) with two bodies at rest (the
    /// ω = 0 lanes), one quaternion off the unit sphere (the 1/sqrt renormalisation) and, in the
    /// first block, a zero quaternion (no renormalisation).
    #[test]
    fn lanes_are_the_scalar_integrator_to_the_bit() {
        if !std::is_x86_feature_detected!("avx2") {
            return;
        }
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
