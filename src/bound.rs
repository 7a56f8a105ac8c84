//! Bounding boxes: the Bo1 functors (pkg/common/Bo1_Aabb.cpp, Wall.cpp) and the sweep logic of
//! `BoundDispatcher::processBody` (core/Dispatching.cpp).

use crate::body::{Bodies, Bound};
use crate::cell::Cell;
use crate::math::{cxx_max, cxx_min, mat_vec, Vec3};
use crate::shape::Shape;

/// Which Bo1 functors the collider was given (YADE dispatches on the shape class; a shape without a
/// functor gets no bound and never collides).
#[derive(Clone, Debug, PartialEq)]
pub struct BoundFunctors {
    pub sphere: Option<f64>,
    pub facet: bool,
    pub wall: bool,
    pub box_: bool,
    /// `Bo1_GridConnection_Aabb` (its aabbEnlargeFactor is declared but unused by YADE).
    pub grid_connection: bool,
}

impl Default for BoundFunctors {
    /// `[Bo1_Sphere_Aabb(), Bo1_Facet_Aabb(), Bo1_Box_Aabb()]`, YADE's default collider list.
    fn default() -> Self {
        BoundFunctors {
            sphere: Some(-1.0),
            facet: true,
            wall: false,
            box_: true,
            grid_connection: false,
        }
    }
}

/// The raw box of one body, before the sweep enlargement, or None without a functor.
pub fn aabb(
    f: &BoundFunctors,
    shape: &Shape,
    bodies: &Bodies,
    id: usize,
    cell: Option<&Cell>,
) -> Result<Option<(Vec3, Vec3)>, String> {
    let pos = bodies.pos[id];
    Ok(match shape {
        // clumps are never bounded (Clump::add clears their `bounded` flag)
        Shape::Clump(_) => None,
        Shape::GridConnection(gc) if f.grid_connection => {
            // Bo1_GridConnection_Aabb::go (pkg/common/Grid.cpp)
            let mut o1 = bodies.pos[gc.node1 as usize];
            let mut o2 = bodies.pos[gc.node2 as usize];
            if let Some(c) = cell {
                if c.has_shear() {
                    return Err("sheared periodic cells are not supported yet".into());
                }
                o1 = c.unshear_pt(&o1);
                o2 = c.unshear_pt(&o2);
                o2 += crate::math::mat_vec_i(&c.hsize, &gc.cell_dist);
            }
            let r = gc.radius;
            let mut mn = Vec3::zeros();
            let mut mx = Vec3::zeros();
            for k in 0..3 {
                mn[k] = cxx_min(o1[k], o2[k]) - r;
                mx[k] = cxx_max(o1[k], o2[k]) + r;
            }
            Some((mn, mx))
        }
        // the grid shapes are Spheres for Bo1_Sphere_Aabb when no more specific functor exists
        Shape::Sphere { .. } | Shape::GridNode(_) | Shape::GridConnection(_) => {
            let radius = shape.sphere_radius().unwrap();
            let Some(enlarge) = f.sphere else {
                return Ok(None);
            };
            let k = if enlarge > 0.0 { enlarge } else { 1.0 };
            let h = Vec3::repeat(k * radius);
            match cell {
                None => Some((pos - h, pos + h)),
                Some(c) => {
                    if c.has_shear() {
                        return Err("sheared periodic cells are not supported yet".into());
                    }
                    let p = c.unshear_pt(&pos);
                    Some((p - h, p + h))
                }
            }
        }
        Shape::Facet(fc) => {
            if !f.facet {
                return Ok(None);
            }
            let r = bodies.ori[id].to_rotation_matrix();
            match cell {
                None => {
                    let v0 = pos + mat_vec(&r, &fc.vertices[0]);
                    let (mut mn, mut mx) = (v0, v0);
                    for v in &fc.vertices[1..] {
                        let p = pos + mat_vec(&r, v);
                        mn = mn.zip_map(&p, |a, b| if b < a { b } else { a });
                        mx = mx.zip_map(&p, |a, b| if a < b { b } else { a });
                    }
                    Some((mn, mx))
                }
                Some(c) => {
                    let mut mn = Vec3::repeat(f64::INFINITY);
                    let mut mx = Vec3::repeat(f64::NEG_INFINITY);
                    for v in &fc.vertices {
                        let p = c.unshear_pt(&(pos + mat_vec(&r, v)));
                        mn = mn.zip_map(&p, |a, b| if b < a { b } else { a });
                        mx = mx.zip_map(&p, |a, b| if a < b { b } else { a });
                    }
                    Some((mn, mx))
                }
            }
        }
        Shape::Wall { axis, .. } => {
            if !f.wall {
                return Ok(None);
            }
            let mut mn = Vec3::repeat(f64::NEG_INFINITY);
            let mut mx = Vec3::repeat(f64::INFINITY);
            mn[*axis] = pos[*axis];
            mx[*axis] = pos[*axis];
            Some((mn, mx))
        }
        Shape::Box { extents } => {
            if !f.box_ {
                return Ok(None);
            }
            let r = bodies.ori[id].to_rotation_matrix();
            let mut h = Vec3::zeros();
            for i in 0..3 {
                for j in 0..3 {
                    h[i] += (r[(i, j)] * extents[j]).abs();
                }
            }
            Some((pos - h, pos + h))
        }
    })
}

/// Sweep parameters passed from the collider (`BoundDispatcher::sweepDist`, ...).
#[derive(Clone, Copy, Debug)]
pub struct Sweep {
    pub sweep_dist: f64,
    pub min_sweep_dist_factor: f64,
    pub target_interv: i32,
}

/// `BoundDispatcher::action`: recompute every bounded body's box, adapt its sweep length from its
/// displacement since the last update, store the reference position and enlarge the box.
pub fn update_bounds(
    f: &BoundFunctors,
    bodies: &mut Bodies,
    cell: Option<&Cell>,
    iter: i64,
    sw: &Sweep,
) -> Result<(), String> {
    for id in 0..bodies.len() {
        if !bodies.bounded[id] {
            continue;
        }
        let Some((mn, mx)) = aabb(f, &bodies.shape[id], bodies, id, cell)? else {
            continue;
        };
        let pos = bodies.pos[id];
        let b = bodies.bound[id].get_or_insert_with(Bound::default);
        b.min = mn;
        b.max = mx;
        let mut sweep = b.sweep_length;
        if sw.target_interv > 0 && iter > b.last_update_iter {
            let d = pos - b.ref_pos;
            let dist = d[0].abs().max(d[1].abs().max(d[2].abs()));
            if dist != 0.0 {
                let mut l = dist * sw.target_interv as f64 / (iter - b.last_update_iter) as f64;
                l = cxx_max(0.9 * sweep, l);
                sweep = cxx_max(
                    sw.min_sweep_dist_factor * sw.sweep_dist,
                    cxx_min(l, sw.sweep_dist),
                );
            } else {
                sweep = 0.0;
            }
        } else {
            sweep = sw.sweep_dist;
        }
        b.sweep_length = sweep;
        b.ref_pos = pos;
        b.last_update_iter = iter;
        if sweep > 0.0 {
            b.min -= Vec3::repeat(sweep);
            b.max += Vec3::repeat(sweep);
        }
    }
    Ok(())
}
