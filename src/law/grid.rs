//! Grid contact laws (pkg/common/Grid.cpp): the sphere-connection laws put the contact force on
//! the sphere and split it between the two nodes of the connection, `(1-relPos, relPos)`; the
//! connection-connection law splits it over the four nodes. Nothing acts on the connection body.

use super::{cundall_shear, cxx_max, LawEnergy};
use crate::forces::Forces;
use crate::geom::{GridCoGridCo, ScGeom, ScGridCo};
use crate::math::{cross, dot, norm, Vec3};
use crate::phys::{CohFrictPhys, FrictPhys};

/// `neverErase` of `Law2_ScGridCoGeom_FrictPhys_CundallStrack` (and of its CohFrictPhys sibling).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct ScGridCoParams {
    pub never_erase: bool,
}

/// `Law2_ScGridCoGeom_FrictPhys_CundallStrack::go` (Grid.cpp). Body 1 is the sphere; `x.id3`/`x.id4`
/// the nodes. A duplicate contact (handled by another connection) gets no force.
#[allow(clippy::too_many_arguments)]
pub fn scgridco_frict(
    p: &ScGridCoParams,
    g: &ScGeom,
    x: &ScGridCo,
    ph: &mut FrictPhys,
    id1: usize,
    id2: usize,
    forces: &mut Forces,
    energy: Option<&mut LawEnergy<'_>>,
) -> bool {
    if g.pen < 0.0 {
        if p.never_erase {
            ph.shear_force = Vec3::zeros();
            ph.normal_force = Vec3::zeros();
        } else {
            return false;
        }
    }
    if x.is_duplicate != 0 && id2 as i32 != x.true_int {
        return x.is_duplicate != 2;
    }
    ph.normal_force = g.normal * (ph.kn * cxx_max(g.pen, 0.0));
    cundall_shear(g, ph, energy);
    let force = -ph.normal_force - ph.shear_force;
    apply_to_nodes(g, x, &force, id1, forces);
    true
}

/// The sphere gets `force` and its torque; the nodes get `(relPos-1)·force`, `-relPos·force` and
/// the twist split `(1-relPos, relPos)` (or barycentric forces for a PFacet contact).
fn apply_to_nodes(g: &ScGeom, x: &ScGridCo, force: &Vec3, id1: usize, forces: &mut Forces) {
    forces.add_force(id1, force);
    let nf = cross(&g.normal, force);
    forces.add_torque(id1, &(nf * (g.radius1 - 0.5 * g.pen)));
    let twist = nf * (g.radius2 - 0.5 * g.pen);
    if x.id5 == -1 {
        let (n3, n4) = (x.id3 as usize, x.id4 as usize);
        forces.add_force(n3, &(force * (x.rel_pos - 1.0)));
        forces.add_torque(n3, &(twist * (1.0 - x.rel_pos)));
        forces.add_force(n4, &(force * (-x.rel_pos)));
        forces.add_torque(n4, &(twist * x.rel_pos));
    } else {
        let f = -force;
        forces.add_force(x.id3 as usize, &(f * x.weight[0]));
        forces.add_force(x.id4 as usize, &(f * x.weight[1]));
        forces.add_force(x.id5 as usize, &(f * x.weight[2]));
    }
}

/// `Law2_ScGridCoGeom_CohFrictPhys_CundallStrack::go` (Grid.cpp): cohesive normal and shear forces on
/// the nodes, no moments, no check of a negative penetration. YADE's unpMax test here differs from
/// the one of Law2_ScGeom6D_CohFrictPhys_CohesionMoment (`unpMax != 0 && unp < unpMax`); kept.
#[allow(clippy::too_many_arguments)]
pub fn scgridco_cohfrict(
    fresh: bool,
    g: &ScGeom,
    x: &ScGridCo,
    ph: &mut FrictPhys,
    cp: &mut CohFrictPhys,
    id1: usize,
    id2: usize,
    forces: &mut Forces,
    energy: Option<&mut LawEnergy<'_>>,
) -> bool {
    if x.is_duplicate != 0 && id2 as i32 != x.true_int {
        return x.is_duplicate != 2;
    }
    if fresh && x.is_duplicate != 2 {
        ph.shear_force = Vec3::zeros();
    }
    let un = g.pen;
    let mut fn_ = ph.kn * (un - cp.unp);
    if cp.fragile && (-fn_) > cp.normal_adhesion {
        return false;
    }
    if (-fn_) > cp.normal_adhesion {
        fn_ = -cp.normal_adhesion;
        cp.unp = un + cp.normal_adhesion / ph.kn;
        if cp.unp_max != 0.0 && cp.unp < cp.unp_max {
            return false;
        }
    }
    ph.normal_force = g.normal * fn_;
    g.rotate(&mut ph.shear_force);
    ph.shear_force -= g.shear_inc * ph.ks;
    let fs = norm(&ph.shear_force);
    let mut max_fs = cp.shear_adhesion;
    if !cp.cohesion_disables_friction || max_fs == 0.0 {
        max_fs += fn_ * ph.tan_phi;
    }
    max_fs = cxx_max(0.0, max_fs);
    if fs > max_fs {
        if cp.fragile && !cp.cohesion_broken {
            cp.set_breaking_state();
            max_fs = cxx_max(0.0, fn_ * ph.tan_phi);
        }
        max_fs /= fs;
        let trial = ph.shear_force;
        ph.shear_force *= max_fs;
        if let Some(e) = energy {
            let d = dot(&((trial - ph.shear_force) * (1.0 / ph.ks)), &ph.shear_force);
            if d > 0.0 {
                e.add(d, "plastDissip", false);
            }
        }
        if fn_ < 0.0 {
            ph.normal_force = Vec3::zeros();
        }
    }
    let force = -ph.normal_force - ph.shear_force;
    let xx = ScGridCo { id5: -1, ..*x };
    apply_to_nodes(g, &xx, &force, id1, forces);
    true
}

/// Parameters of `Law2_GridCoGridCoGeom_FrictPhys_CundallStrack` (inherited from
/// `Law2_ScGeom_FrictPhys_CundallStrack`; `sphericalBodies` is not used by this law).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct GridCoGridCoParams {
    pub never_erase: bool,
    pub spherical_bodies: bool,
    pub trace_energy: bool,
}

/// `Law2_GridCoGridCoGeom_FrictPhys_CundallStrack::go` (Grid.cpp): nodes `n1 = (id11, id12)` of
/// connection 1 get `(1-k, k)·force`, nodes `n2` of connection 2 `-(1-m, m)·force`; both torque
/// splits are added with a + sign, as in YADE.
#[allow(clippy::too_many_arguments)]
pub fn gridco_gridco_frict(
    p: &GridCoGridCoParams,
    g: &ScGeom,
    x: &GridCoGridCo,
    ph: &mut FrictPhys,
    n1: (usize, usize),
    n2: (usize, usize),
    forces: &mut Forces,
    energy: Option<&mut LawEnergy<'_>>,
) -> bool {
    if g.pen < 0.0 {
        if p.never_erase {
            ph.shear_force = Vec3::zeros();
            ph.normal_force = Vec3::zeros();
        } else {
            return false;
        }
    }
    ph.normal_force = g.normal * (ph.kn * cxx_max(g.pen, 0.0));
    // with traceEnergy the dispatch passes the energy too: the slip dissipation then goes to the
    // functor's own plasticDissipation (not in O.energy), elastPotential still to O.energy
    cundall_shear(g, ph, energy);
    let force = -ph.normal_force - ph.shear_force;
    let nf = cross(&g.normal, &force);
    let torque1 = nf * (g.radius1 - 0.5 * g.pen);
    let torque2 = nf * (g.radius2 - 0.5 * g.pen);
    let (k, m) = (x.rel_pos1, x.rel_pos2);
    forces.add_force(n1.0, &(force * (1.0 - k)));
    forces.add_force(n1.1, &(force * k));
    forces.add_force(n2.0, &(force * (-(1.0 - m))));
    forces.add_force(n2.1, &(force * (-m)));
    forces.add_torque(n1.0, &(torque1 * (1.0 - k)));
    forces.add_torque(n1.1, &(torque1 * k));
    forces.add_torque(n2.0, &(torque2 * (1.0 - m)));
    forces.add_torque(n2.1, &(torque2 * m));
    true
}
