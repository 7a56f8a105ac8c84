//! YADE's `utils` helpers that belong to the engine: time step, unbalanced force, porosity, and the
//! body builders `sphere`, `facet`, `box_`, `wall` (py/utils.py, preprocessing/dem/Shop_01.cpp).

use crate::body::{BodySpec, DOF_ALL};
use crate::math::{norm, norm2, Quat, Vec3};
use crate::scene::Scene;
use crate::shape::{Facet, Shape};

/// `Shop::PWaveTimeStep`: min over spheres of `r / sqrt(E/rho)`, rho recovered from the mass as YADE
/// does (`mass / ((4/3)·π·r³)`). None when there is no sphere (YADE returns 1.0 with a warning).
pub fn pwave_time_step(scene: &Scene) -> Option<f64> {
    let b = &scene.bodies;
    let mut dt = f64::INFINITY;
    let mut found = false;
    for id in 0..b.len() {
        if let Shape::Sphere { radius } = b.shape[id] {
            let density = b.mass[id] / ((4.0 / 3.0) * std::f64::consts::PI * radius.powf(3.0));
            let young = scene.materials[b.material[id]].young;
            let d = radius / (young / density).sqrt();
            found = true;
            if d < dt {
                dt = d;
            }
        }
    }
    found.then_some(dt)
}

/// `Shop::unbalancedForce`: mean (or max) |F + m g| over dynamic bodies divided by the mean
/// |Fn + Fs| over real contacts. NaN without contacts, as in YADE.
pub fn unbalanced_force(scene: &Scene, use_max_force: bool) -> f64 {
    let g = scene
        .newton()
        .map(|n| n.gravity)
        .unwrap_or_else(Vec3::zeros);
    let b = &scene.bodies;
    let mut sum = 0.0;
    let mut maxf: f64 = 0.0;
    let mut nb = 0usize;
    for id in 0..b.len() {
        if !b.is_dynamic(id) {
            continue;
        }
        let f = norm(&(scene.forces.force[id] + g * b.mass[id]));
        if use_max_force {
            maxf = maxf.max(f);
        } else {
            sum += f;
        }
        nb += 1;
    }
    let mut fsum = 0.0;
    let mut nc = 0usize;
    for it in &scene.interactions.list {
        if let (Some(_), Some(ph)) = (&it.geom, &it.phys) {
            fsum += norm(&(ph.normal_force + ph.shear_force));
            nc += 1;
        }
    }
    let num = if use_max_force { maxf } else { sum / nb as f64 };
    num / (fsum / nc as f64)
}

/// `utils.porosity()` for a periodic scene or a given volume: `(V - Vs) / V`, Vs over all spheres.
pub fn porosity(scene: &Scene, volume: Option<f64>) -> Result<f64, String> {
    let b = &scene.bodies;
    let vs: f64 = (0..b.len())
        .filter_map(|id| b.shape[id].sphere_radius())
        .map(|r| (4.0 / 3.0) * std::f64::consts::PI * r.powf(3.0))
        .sum();
    let v = match (volume, &scene.cell) {
        (Some(v), _) if v > 0.0 => v,
        (_, Some(c)) => c.volume(),
        _ => {
            let (mn, mx) = aabb_extrema(scene).ok_or("porosity(): the scene has no spheres")?;
            let d = mx - mn;
            d[0] * d[1] * d[2]
        }
    };
    Ok((v - vs) / v)
}

/// `utils.aabbExtrema()` over spheres (centre ± radius).
pub fn aabb_extrema(scene: &Scene) -> Option<(Vec3, Vec3)> {
    let b = &scene.bodies;
    let mut out: Option<(Vec3, Vec3)> = None;
    for id in 0..b.len() {
        if let Some(r) = b.shape[id].sphere_radius() {
            let (lo, hi) = (b.pos[id] - Vec3::repeat(r), b.pos[id] + Vec3::repeat(r));
            out = Some(match out {
                None => (lo, hi),
                Some((a, c)) => (a.inf(&lo), c.sup(&hi)),
            });
        }
    }
    out
}

/// `utils.sphere(center, radius, fixed=False, material)` (py/utils.py): mass `(4/3·π·r**3)·ρ`,
/// inertia `(2/5·V·r**2)·ρ`, with Python's `**` as libm `pow`.
pub fn sphere(center: Vec3, radius: f64, material: usize, density: f64, fixed: bool) -> BodySpec {
    let v = (4.0 / 3.0) * std::f64::consts::PI * radius.powf(3.0);
    let mass = v * density;
    let inertia = (2.0 / 5.0) * v * radius.powf(2.0) * density;
    let blocked = if fixed { DOF_ALL } else { 0 };
    at_rest(
        Shape::Sphere { radius },
        material,
        center,
        mass,
        Vec3::repeat(inertia),
        blocked,
    )
}

/// `Shop::inscribedCircleCenter`: `v0 + ((v2-v0)|v1-v0| + (v1-v0)|v2-v0|) / (|v1-v0|+|v2-v1|+|v0-v2|)`.
pub fn inscribed_circle_center(v0: &Vec3, v1: &Vec3, v2: &Vec3) -> Vec3 {
    let a = norm(&(v1 - v0));
    let b = norm(&(v2 - v0));
    let p = a + norm(&(v2 - v1)) + norm(&(v0 - v2));
    let s = (v2 - v0) * a + (v1 - v0) * b;
    v0 + Vec3::new(s[0] / p, s[1] / p, s[2] / p)
}

/// `utils.facet(vertices, fixed=True)`: body at the inscribed circle centre, local vertices.
pub fn facet(vertices: [Vec3; 3], material: usize) -> Result<BodySpec, String> {
    let c = inscribed_circle_center(&vertices[0], &vertices[1], &vertices[2]);
    let local = [vertices[0] - c, vertices[1] - c, vertices[2] - c];
    let shape = Shape::Facet(Box::new(Facet::new(local)?));
    Ok(at_rest(shape, material, c, 0.0, Vec3::zeros(), DOF_ALL))
}

/// `utils.box(center, extents, fixed)`: extents are half sizes; mass from the material density.
pub fn box_(center: Vec3, extents: Vec3, material: usize, density: f64, fixed: bool) -> BodySpec {
    let v = 8.0 * extents[0] * extents[1] * extents[2];
    let mass = v * density;
    // geomInert = (V/3)·(e1²+e2², e0²+e2², e0²+e1²), then times density
    let e2 = Vec3::new(
        extents[0].powf(2.0),
        extents[1].powf(2.0),
        extents[2].powf(2.0),
    );
    let inertia = Vec3::new(
        v / 3.0 * (e2[1] + e2[2]) * density,
        v / 3.0 * (e2[0] + e2[2]) * density,
        v / 3.0 * (e2[0] + e2[1]) * density,
    );
    let blocked = if fixed { DOF_ALL } else { 0 };
    at_rest(
        Shape::Box { extents },
        material,
        center,
        mass,
        inertia,
        blocked,
    )
}

/// `utils.wall(position, axis, sense)`: fixed infinite plane.
pub fn wall(position: f64, axis: usize, sense: i32, material: usize) -> BodySpec {
    let mut pos = Vec3::zeros();
    pos[axis] = position;
    at_rest(
        Shape::Wall { axis, sense },
        material,
        pos,
        0.0,
        Vec3::zeros(),
        DOF_ALL,
    )
}

/// A body at rest with identity orientation, mask 1, bounded, damped.
fn at_rest(
    shape: Shape,
    material: usize,
    pos: Vec3,
    mass: f64,
    inertia: Vec3,
    blocked: u8,
) -> BodySpec {
    BodySpec {
        shape,
        material,
        mask: 1,
        bounded: true,
        pos,
        vel: Vec3::zeros(),
        ang_vel: Vec3::zeros(),
        ori: Quat::IDENTITY,
        mass,
        inertia,
        blocked,
        is_damped: true,
    }
}

/// Kinetic energy of all bodies (`utils.kineticEnergy`): translational plus rotational.
pub fn kinetic_energy(scene: &Scene) -> f64 {
    let b = &scene.bodies;
    let mut e = 0.0;
    for id in 0..b.len() {
        if !b.is_dynamic(id) {
            continue;
        }
        e += 0.5 * b.mass[id] * norm2(&b.vel[id]);
        let w = b.ang_vel[id];
        e += 0.5 * crate::math::dot(&w, &b.inertia[id].component_mul(&w));
    }
    e
}

/// The critical time step of the stiffest sphere-sphere contact a scene can form: two equal spheres
/// of mass m on a spring kn = E·r have `dt_crit = 2/ω = 2·sqrt(m/(2·kn))` (central difference). A
/// larger dt diverges whatever the damping. None without spheres.
pub fn critical_time_step(scene: &Scene) -> Option<f64> {
    let b = &scene.bodies;
    (0..b.len())
        .filter(|&id| b.is_dynamic(id))
        .filter_map(|id| {
            let r = b.shape[id].sphere_radius()?;
            let kn = scene.materials[b.material[id]].young * r;
            Some(2.0 * (b.mass[id] / (2.0 * kn)).sqrt())
        })
        .fold(None, |acc: Option<f64>, x| {
            Some(acc.map_or(x, |a| a.min(x)))
        })
}

/// Refuse a time step above the critical one, with the numbers a user needs to fix it.
pub fn check_time_step(scene: &Scene) -> Result<(), String> {
    if !(scene.dt > 0.0 && scene.dt.is_finite()) {
        return Err(format!(
            "O.dt = {} is not a positive finite time step",
            scene.dt
        ));
    }
    if let Some(crit) = critical_time_step(scene) {
        if scene.dt > crit {
            return Err(format!(
                "O.dt = {:e} s is above the critical time step {:e} s of a sphere-sphere contact \
                 (PWaveTimeStep = {:e} s): the run would explode; use e.g. O.dt = 0.5*PWaveTimeStep()",
                scene.dt,
                crit,
                pwave_time_step(scene).unwrap_or(f64::NAN)
            ));
        }
    }
    Ok(())
}
