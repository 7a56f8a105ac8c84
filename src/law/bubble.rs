//! `Law2_ScGeom_BubblePhys_Bubble` (pkg/dem/BubbleMat.cpp): the attraction between two bubbles in a
//! liquid (Chan et al. 2011), a normal force only; erased when they stop overlapping.

use super::Load;
use crate::geom::ScGeom;
use crate::math::{cross, Vec3};
use crate::phys::{BubblePhys, FrictPhys};

/// The law's attributes and its `c1` (2 pi surfaceTension, set when a contact is new).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Params {
    pub pct_max_force: f64,
    pub surface_tension: f64,
    pub c1: f64,
}

impl Default for Params {
    fn default() -> Self {
        Params {
            pct_max_force: 0.1,
            surface_tension: 0.07197,
            c1: 0.0,
        }
    }
}

/// `Law2_ScGeom_BubblePhys_Bubble::go` up to the forces it adds (Ok(None): apart, erase).
/// `pos1`/`pos2` the bodies' positions (unused on a periodic cell, as in YADE).
#[allow(clippy::too_many_arguments)]
pub fn load(
    p: &mut Params,
    fresh: bool,
    g: &ScGeom,
    ph: &mut FrictPhys,
    bp: &mut BubblePhys,
    pos1: &Vec3,
    pos2: &Vec3,
    periodic: bool,
) -> Result<Option<Load>, String> {
    if g.pen <= 0.0 {
        return Ok(None);
    }
    if fresh {
        p.c1 = 2.0 * std::f64::consts::PI * p.surface_tension;
        bp.r_avg = 0.5 * (g.radius1 + g.radius2);
        bp.compute_coeffs(p.pct_max_force, p.c1);
    }
    bp.fn_ = bp.compute_force(-g.pen, p.c1)?;
    ph.normal_force = g.normal * bp.fn_;
    let nf = ph.normal_force;
    Ok(Some(if !periodic {
        // applyForceAtContactPoint(-normalForce, contactPoint, ...)
        let force = -nf;
        Load {
            force,
            torque1: cross(&(g.contact_point - pos1), &force),
            torque2: -cross(&(g.contact_point - pos2), &force),
        }
    } else {
        let c = cross(&g.normal, &nf);
        Load {
            force: -nf,
            torque1: c * (g.radius1 - 0.5 * g.pen),
            torque2: c * (g.radius2 - 0.5 * g.pen),
        }
    }))
}
