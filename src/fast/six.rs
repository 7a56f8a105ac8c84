//! The fast path's rolling-resistance contacts: `Ig2_Sphere_Sphere_ScGeom6D`,
//! `Ip2_CohFrictMat_CohFrictMat_CohFrictPhys` and `Law2_ScGeom6D_CohFrictPhys_CohesionMoment`, the
//! aggregate model of the study (`--eta-roll`).
//!
//! Each contact keeps the Scene's own state types (`ScGeom`, `FrictPhys`, the 6-D rotations `Rot6D`
//! and `CohFrictPhys`) in one allocation made when the contact forms: a listed pair that does not
//! touch holds only a null pointer, so the pair loop streams 8 bytes per pair. The kernel calls the
//! YADE-order path's functions on that state (`geom::sphere_sphere::go` and
//! `Rot6D::precompute_rotations`, which `geom::grid::six_d` composes, `phys::CohFrictIp2::go`,
//! `law::cohesion_moment::load`): one formula, one place. What differs is the scheduling (Verlet
//! list, spatial order, threads owning bodies) and so the order of the force sums. A pair is always
//! evaluated with the lower scene id as body 1, as YADE orders sphere-sphere interactions, so the
//! state moves between the two paths unchanged.

use super::contact::{Pair, V3};
use crate::geom::{self, GeomCtx, Kin};
use crate::geom::{GeomExt, Rot6D, ScGeom};
use crate::interaction::IntrExt;
use crate::law::cohesion_moment;
use crate::material::FrictMat;
use crate::math::{Quat, Vec3};
use crate::phys::{CohAction, CohFrictIp2, CohFrictPhys, FrictPhys};

/// The functors' parameters (from the scene's InteractionLoop).
#[derive(Clone, Debug)]
pub(super) struct SixCfg {
    pub p6: geom::grid::SixDParams,
    pub ip2: CohFrictIp2,
    pub cm: cohesion_moment::Params,
    /// The law never reads a contact's twist and bending (`useIncrementalForm`, so no twist
    /// creep): they are left out of the steps and worked out when the state goes back to the
    /// scene (`settled_rotations`), from the same operands, so to the same bits.
    pub defer_rotations: bool,
}

impl SixCfg {
    pub fn new(
        p6: geom::grid::SixDParams,
        ip2: CohFrictIp2,
        cm: cohesion_moment::Params,
    ) -> SixCfg {
        // Law2_ScGeom6D_CohFrictPhys_CohesionMoment::go reads twist and bending only in the total
        // form (`cohesion_moment::load`)
        let defer_rotations = cm.use_incremental_form && !cm.twist_creep;
        SixCfg {
            p6,
            ip2,
            cm,
            defer_rotations,
        }
    }
}

/// A real contact's state: the Scene's `ScGeom6D` (ScGeom + rotations) and `CohFrictPhys`
/// (FrictPhys + the cohesive part).
#[derive(Clone, Debug)]
pub(super) struct State6 {
    pub geom: Option<ScGeom>,
    pub phys: Option<FrictPhys>,
    pub rot: Rot6D,
    pub coh: Option<CohFrictPhys>,
    pub made_real: i64,
}

/// One listed pair: its contact state while real, None while potential.
#[derive(Clone, Debug, Default)]
pub(super) struct C6(pub Option<Box<State6>>);

impl C6 {
    pub fn is_real(&self) -> bool {
        self.0.is_some()
    }

    /// A real interaction of the Scene (body 1 the lower id), or None when it is no ScGeom6D contact.
    pub fn from_interaction(it: &crate::interaction::Interaction) -> Option<C6> {
        let e = it.ext.as_deref()?;
        let rot = match e.geom.as_ref()? {
            GeomExt::Sc6D(r) => *r,
            _ => return None,
        };
        Some(C6(Some(Box::new(State6 {
            geom: it.geom,
            phys: it.phys,
            rot,
            coh: e.coh,
            made_real: it.iter_made_real,
        }))))
    }

    /// The state as the Scene's interaction holds it: geometry, physics, the boxed extension.
    pub fn to_interaction_parts(&self) -> Option<(ScGeom, FrictPhys, Box<IntrExt>, i64)> {
        let s = self.0.as_deref()?;
        Some((
            s.geom?,
            s.phys?,
            Box::new(IntrExt {
                geom: Some(GeomExt::Sc6D(s.rot)),
                coh: s.coh,
                ..Default::default()
            }),
            s.made_real,
        ))
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

/// Pair `p` as the Scene sees it: whether its slots swap, body 1 (the lower scene id), body 2 and
/// body 2's period shift (+sh with j second, -sh with i second).
#[inline(always)]
pub(super) fn oriented(b: &Bodies6, p: &Pair) -> (bool, usize, usize, Vec3) {
    let (i, j) = (p.i as usize, p.j as usize);
    let sh = b.shifts[p.img as usize];
    let swap = b.ids[i] > b.ids[j];
    if swap {
        (true, j, i, Vec3::new(-sh[0], -sh[1], -sh[2]))
    } else {
        (false, i, j, v(&sh))
    }
}

/// Whether `pair` certainly leaves pair `p` as it is and loads nothing: a potential pair that
/// `Ig2_Sphere_Sphere_ScGeom6D` would leave potential (`sphere_sphere::go`'s own test).
#[inline(always)]
pub(super) fn idle(cfg: &SixCfg, b: &Bodies6, p: &Pair, c: &C6) -> bool {
    let (_, k1, k2, shift2) = oriented(b, p);
    let (p1, p2) = (v(&b.pos[k1]), v(&b.pos[k2]));
    // both tests, no branch on the first: real and potential pairs alternate without pattern
    !c.is_real()
        & !geom::sphere_sphere::within_reach(&cfg.p6.ss, b.rad[k1], b.rad[k2], &p1, &p2, &shift2)
}

/// Geometry, physics (on creation) and law of one pair (slots `p.i < p.j`): `geometry`,
/// `rotations`, `law`. Returns the force on slot i and the torques on i and j, or None (apart, or
/// erased).
#[inline(always)]
pub(super) fn pair(cfg: &SixCfg, b: &Bodies6, p: &Pair, c: &mut C6) -> Option<(V3, V3, V3)> {
    let o = orient(b, p, c.is_real());
    let st = geometry(cfg, b, &o, c);
    if st == Stage::Kept && !cfg.defer_rotations {
        rotations(cfg, &o, c);
    }
    law(cfg, b, &o, c, st)
}

/// What `geometry` left for `rotations` and `law`: the pair is apart (a potential pair that stays
/// so, or a contact just erased), a contact that was real, or a new one.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) enum Stage {
    #[default]
    Apart,
    Kept,
    New,
}

/// A pair as the Scene sees it (`oriented`), its bodies' kinematics gathered once for the three
/// parts (`geometry`, `rotations`, `law`).
pub(super) struct Oriented {
    pub swap: bool,
    pub k1: usize,
    pub k2: usize,
    pub pr: geom::Pair,
}

/// Pair `p` oriented, `is_real`: whether it was a contact before this step.
#[inline(always)]
pub(super) fn orient(b: &Bodies6, p: &Pair, is_real: bool) -> Oriented {
    let (swap, k1, k2, shift2) = oriented(b, p);
    let kin = |k: usize| Kin {
        pos: v(&b.pos[k]),
        vel: v(&b.vel[k]),
        ang_vel: v(&b.w[k]),
        ori: b.ori[k],
    };
    let pr = geom::Pair {
        s1: kin(k1),
        s2: kin(k2),
        shift2,
        is_real,
        ctx: GeomCtx {
            dt: b.dt,
            shift_vel: Vec3::zeros(),
        },
    };
    Oriented { swap, k1, k2, pr }
}

/// The first part of `Ig2_Sphere_Sphere_ScGeom6D::go` (`geom::grid::six_d`) on one pair: the
/// sphere-sphere geometry, and on a new contact its rotations' reset. A contact that was real gets
/// its rotations from `rotations` (or, four at a time, `six_simd`).
#[inline(always)]
pub(super) fn geometry(cfg: &SixCfg, b: &Bodies6, o: &Oriented, c: &mut C6) -> Stage {
    let pr = &o.pr;
    let (r1, r2) = (b.rad[o.k1], b.rad[o.k2]);
    if pr.is_real {
        if !geom::sphere_sphere::go(&cfg.p6.ss, r1, r2, pr, &mut c.0.as_mut().unwrap().geom) {
            c.0 = None;
            return Stage::Apart;
        }
        return Stage::Kept;
    }
    let mut g = None;
    if !geom::sphere_sphere::go(&cfg.p6.ss, r1, r2, pr, &mut g) {
        return Stage::Apart;
    }
    let mut s = Box::new(State6 {
        geom: g,
        phys: None,
        rot: Rot6D::default(),
        coh: None,
        made_real: b.iter,
    });
    let n = s.geom.as_ref().unwrap().normal;
    geom::grid::six_d_rotations(&cfg.p6, pr, &n, &mut s.rot, true);
    c.0 = Some(s);
    Stage::New
}

/// The rest of `Ig2_Sphere_Sphere_ScGeom6D::go` on a contact that was real (`Stage::Kept`), after
/// its `geometry`: the rotations (`geom::grid::six_d_rotations`).
#[inline(always)]
pub(super) fn rotations(cfg: &SixCfg, o: &Oriented, c: &mut C6) {
    let s = c.0.as_deref_mut().unwrap();
    let n = s.geom.as_ref().unwrap().normal;
    geom::grid::six_d_rotations(&cfg.p6, &o.pr, &n, &mut s.rot, false);
}

/// A real contact's rotations as the last step would have left them had it worked them out
/// (`SixCfg::defer_rotations`): `ScGeom6D::precomputeRotations` on the orientations `ori1`, `ori2`
/// of bodies 1 and 2 at that step's contact phase and the normal it left; a contact made in that
/// step (`made_real == last_iter`) keeps the reset its creation gave it.
pub(super) fn settled_rotations(
    cfg: &SixCfg,
    s: &State6,
    (ori1, ori2): (&Quat, &Quat),
    last_iter: i64,
) -> Rot6D {
    let mut rot = s.rot;
    if cfg.p6.update_rotations && s.made_real != last_iter {
        let n = s.geom.as_ref().unwrap().normal;
        rot.precompute_rotations(ori1, ori2, &n, false, cfg.p6.creep);
    }
    rot
}

/// Physics (on a new contact) and law of a pair after `geometry` (and `rotations`): the force on
/// slot i and the torques on i and j, or None (apart, or erased).
#[inline(always)]
pub(super) fn law(
    cfg: &SixCfg,
    b: &Bodies6,
    o: &Oriented,
    c: &mut C6,
    st: Stage,
) -> Option<(V3, V3, V3)> {
    if st == Stage::Apart {
        return None;
    }
    let (swap, k1, k2, pr) = (o.swap, o.k1, o.k2, &o.pr);
    let s = c.0.as_deref_mut().unwrap();
    if st == Stage::New {
        // Ip2_CohFrictMat_CohFrictMat_CohFrictPhys on the new contact (setCohesionNow is refused
        // by `FastSim::from_scene`, so the functor's own state does not change here)
        let mut ip2 = cfg.ip2.clone();
        let g = s.geom.as_ref().unwrap();
        let (gr1, gr2) = (g.radius1, g.radius2);
        let m1 = &b.mats[b.mat[k1] as usize];
        let m2 = &b.mats[b.mat[k2] as usize];
        if ip2.go(b.iter, m1, m2, gr1, gr2, &mut s.phys, &mut s.coh) == CohAction::InitRotations {
            s.rot.init_rotations(&b.ori[k1], &b.ori[k2]);
        }
        s.made_real = b.iter;
    }
    let fresh = s.made_real == b.iter;
    let g = *s.geom.as_ref().unwrap();
    let cp = s.coh.as_mut().expect("CohFrictPhys");
    let lb = cohesion_moment::Bodies2 {
        pos1: pr.s1.pos,
        pos2_shifted: pr.s2.pos + pr.shift2,
        ang_vel1: pr.s1.ang_vel,
        ang_vel2: pr.s2.ang_vel,
    };
    let ph = s.phys.as_mut().unwrap();
    match cohesion_moment::load(&cfg.cm, b.dt, fresh, &g, &mut s.rot, ph, cp, &lb, None) {
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
            c.0 = None;
            None
        }
        // excluded by `FastSim::from_scene` (the law's only error is a parameter check)
        Err(e) => unreachable!("{}", e),
    }
}
