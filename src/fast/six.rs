//! The fast path's rolling-resistance contacts: `Ig2_Sphere_Sphere_ScGeom6D`,
//! `Ip2_CohFrictMat_CohFrictMat_CohFrictPhys` and `Law2_ScGeom6D_CohFrictPhys_CohesionMoment`, the
//! aggregate model of the study (`--eta-roll`).
//!
//! Each contact keeps the Scene's own interaction state (`ScGeom`, `FrictPhys` and the boxed
//! `IntrExt` with the 6-D rotations and the cohesive physics), and the kernel calls the YADE-order
//! path's functions on it (`geom::grid::six_d`, `phys::CohFrictIp2::go`,
//! `law::cohesion_moment::load`): one formula, one place. What differs is the scheduling (Verlet
//! list, spatial order, threads owning bodies) and so the order of the force sums. A pair is always
//! evaluated with the lower scene id as body 1, as YADE orders sphere-sphere interactions, so the
//! state moves between the two paths unchanged.

use super::contact::{Pair, V3};
use crate::geom::{self, GeomCtx, Kin};
use crate::geom::{GeomExt, ScGeom};
use crate::interaction::IntrExt;
use crate::law::cohesion_moment;
use crate::material::FrictMat;
use crate::math::{Quat, Vec3};
use crate::phys::{CohAction, CohFrictIp2, FrictPhys};

/// The functors' parameters (from the scene's InteractionLoop).
#[derive(Clone, Debug)]
pub(super) struct SixCfg {
    pub p6: geom::grid::SixDParams,
    pub ip2: CohFrictIp2,
    pub cm: cohesion_moment::Params,
}

/// One listed pair's interaction state (None/None: potential).
#[derive(Clone, Debug, Default)]
pub(super) struct C6 {
    pub geom: Option<ScGeom>,
    pub phys: Option<FrictPhys>,
    pub ext: Option<Box<IntrExt>>,
    pub made_real: i64,
}

impl C6 {
    pub fn is_real(&self) -> bool {
        self.geom.is_some() && self.phys.is_some()
    }

    fn erase(&mut self) {
        *self = C6::default();
    }
}

/// What the kernel reads of the bodies (fast-path slots).
pub(super) struct Bodies6<'a> {
    pub pos: &'a [V3],
    pub vel: &'a [V3],
    pub w: &'a [V3],
    pub ori: &'a [Quat],
    pub rad: &'a [f64],
    pub mat: &'a [u32],
    pub ids: &'a [u32],
    pub shifts: &'a [V3],
    pub mats: &'a [FrictMat],
    pub dt: f64,
    pub iter: i64,
}

fn v(a: &V3) -> Vec3 {
    Vec3::new(a[0], a[1], a[2])
}

fn a3(v: &Vec3) -> V3 {
    [v[0], v[1], v[2]]
}

/// Geometry, physics (on creation) and law of one pair (slots `p.i < p.j`). Returns the force on
/// slot i and the torques on i and j, or None (apart, or erased).
#[inline(always)]
pub(super) fn pair(cfg: &SixCfg, b: &Bodies6, p: &Pair, c: &mut C6) -> Option<(V3, V3, V3)> {
    let (i, j) = (p.i as usize, p.j as usize);
    let sh = b.shifts[p.img as usize];
    // body 1 is the lower scene id; body 2's period shift is then +sh (j second) or -sh (i second)
    let swap = b.ids[i] > b.ids[j];
    let (k1, k2, shift2) = if swap {
        (j, i, Vec3::new(-sh[0], -sh[1], -sh[2]))
    } else {
        (i, j, v(&sh))
    };
    let kin = |k: usize| Kin {
        pos: v(&b.pos[k]),
        vel: v(&b.vel[k]),
        ang_vel: v(&b.w[k]),
        ori: b.ori[k],
    };
    let was_real = c.is_real();
    let pr = geom::Pair {
        s1: kin(k1),
        s2: kin(k2),
        shift2,
        is_real: was_real,
        ctx: GeomCtx {
            dt: b.dt,
            shift_vel: Vec3::zeros(),
        },
    };
    let (r1, r2) = (b.rad[k1], b.rad[k2]);
    let mut conn_sync = None;
    if !geom::grid::six_d(
        &cfg.p6,
        r1,
        r2,
        &pr,
        &mut c.geom,
        &mut c.ext,
        false,
        &mut conn_sync,
    ) {
        if was_real {
            c.erase();
        }
        return None;
    }
    if !was_real {
        // Ip2_CohFrictMat_CohFrictMat_CohFrictPhys on the new contact (setCohesionNow is refused
        // by `FastSim::from_scene`, so the functor's own state does not change here)
        let mut ip2 = cfg.ip2.clone();
        let g = c.geom.as_ref().unwrap();
        let (gr1, gr2) = (g.radius1, g.radius2);
        let e = c.ext.get_or_insert_with(Default::default);
        let m1 = &b.mats[b.mat[k1] as usize];
        let m2 = &b.mats[b.mat[k2] as usize];
        if ip2.go(b.iter, m1, m2, gr1, gr2, &mut c.phys, &mut e.coh) == CohAction::InitRotations {
            if let Some(rot) = e.geom.as_mut().and_then(|g| g.rot_mut()) {
                rot.init_rotations(&b.ori[k1], &b.ori[k2]);
            }
        }
        c.made_real = b.iter;
    }
    let fresh = c.made_real == b.iter;
    let g = *c.geom.as_ref().unwrap();
    let e = c.ext.as_mut().unwrap();
    let rot = match e.geom.as_mut() {
        Some(GeomExt::Sc6D(r)) => r,
        _ => unreachable!("six_d makes an ScGeom6D"),
    };
    let cp = e.coh.as_mut().expect("CohFrictPhys");
    let lb = cohesion_moment::Bodies2 {
        pos1: pr.s1.pos,
        pos2_shifted: pr.s2.pos + shift2,
        ang_vel1: pr.s1.ang_vel,
        ang_vel2: pr.s2.ang_vel,
    };
    let ph = c.phys.as_mut().unwrap();
    match cohesion_moment::load(&cfg.cm, b.dt, fresh, &g, rot, ph, cp, &lb, None) {
        Ok(Some(l)) => {
            // the net loads of `cohesion_moment::apply`: force on 1, torques 1 and 2 with the moment
            let m = l.moment.unwrap_or_else(Vec3::zeros);
            let (f1, t1, t2) = (l.force, l.torque1 - m, l.torque2 + m);
            Some(if swap {
                (a3(&(-f1)), a3(&t2), a3(&t1))
            } else {
                (a3(&f1), a3(&t1), a3(&t2))
            })
        }
        Ok(None) => {
            c.erase();
            None
        }
        // excluded by `FastSim::from_scene` (the law's only error is a parameter check)
        Err(e) => unreachable!("{}", e),
    }
}
