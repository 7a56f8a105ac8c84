//! YADE's `utils` helpers that belong to the engine: time step, unbalanced force, porosity, and the
//! body builders `sphere`, `facet`, `box_`, `wall` (py/utils.py, preprocessing/dem/Shop_01.cpp) and
//! `grid_node`, `grid_connection` (py/gridpfacet.py).

use crate::body::{BodySpec, DOF_ALL};
use crate::math::{norm, norm2, Quat, Vec3};
use crate::scene::Scene;
use crate::shape::{Facet, Shape};

/// A double as a default C++ `std::ostream` prints it (`%g`, 6 significant digits): fixed notation
/// for exponents -5..5, else scientific with a sign and at least two exponent digits; trailing
/// zeros dropped.
pub fn cxx_stream_double(x: f64) -> String {
    if x.is_nan() {
        return if x.is_sign_negative() { "-nan" } else { "nan" }.into();
    }
    if x.is_infinite() {
        return if x < 0.0 { "-inf" } else { "inf" }.into();
    }
    if x == 0.0 {
        return if x.is_sign_negative() { "-0" } else { "0" }.into();
    }
    let sci = format!("{:.5e}", x);
    let (mant, exp) = sci.split_once('e').unwrap();
    let exp: i32 = exp.parse().unwrap();
    let trim = |s: &str| -> String {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s.to_string()
        }
    };
    if (-4..6).contains(&exp) {
        trim(&format!("{:.*}", (5 - exp) as usize, x))
    } else {
        let sign = if exp < 0 { '-' } else { '+' };
        format!("{}e{}{:02}", trim(mant), sign, exp.abs())
    }
}

/// `Law2_ScGeom6D_CohFrictPhys_CohesionMoment::normElastEnergy` / `shearElastEnergy`
/// (pkg/dem/CohesiveFrictionalContactLaw.cpp): Σ ½|Fn|²/kn (or ½|Fs|²/ks) over the real interactions
/// in container order. YADE reads every physics through a static cast to CohFrictPhys, so plain
/// FrictPhys contacts count too (the fields it reads are theirs).
pub fn cohesion_moment_elastic_energy(scene: &Scene, shear: bool) -> f64 {
    let mut e = 0.0;
    for it in scene.interactions.list.iter().filter(|it| it.is_real()) {
        if let Some(ph) = it.phys.as_ref() {
            e += if shear {
                0.5 * (norm2(&ph.shear_force) / ph.ks)
            } else {
                0.5 * (norm2(&ph.normal_force) / ph.kn)
            };
        }
    }
    e
}

/// `Law2_ScGeom_CpmPhys_Cpm::elasticEnergy` (pkg/dem/ConcretePM.cpp, the public model): over the real
/// CpmPhys contacts in container order, ½|Fn|²/((1-ω)kn) (ω only in tension) plus ½|Fs|²/ks.
pub fn cpm_elastic_energy(scene: &Scene) -> f64 {
    let mut e = 0.0;
    for it in scene.interactions.list.iter().filter(|it| it.is_real()) {
        if let (Some(ph), Some(cp)) = (it.phys.as_ref(), it.cpm()) {
            let w = if cp.eps_n > 0.0 { cp.omega } else { 0.0 };
            e += 0.5 * norm2(&ph.normal_force) / ((1.0 - w) * ph.kn);
            e += 0.5 * norm2(&ph.shear_force) / ph.ks;
        }
    }
    e
}

/// `Shop::PWaveTimeStep`: min over spheres of `r / sqrt(E/rho)`, rho recovered from the mass as YADE
/// does (`mass / ((4/3)·π·r³)`). None when there is no sphere (YADE returns 1.0 with a warning).
pub fn pwave_time_step(scene: &Scene) -> Option<f64> {
    let b = &scene.bodies;
    let mut dt = f64::INFINITY;
    let mut found = false;
    for id in 0..b.len() {
        // every Sphere-derived shape counts, grid nodes and connections included (YADE's dynamic_cast)
        if let Some(radius) = b.shape[id].sphere_radius() {
            let mat = &scene.materials[b.material[id]];
            if mat.luding.is_some() || mat.bubble.is_some() {
                continue; // not an ElastMat: YADE skips it
            }
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
        if b.is_clump_member(id) || !b.is_dynamic(id) {
            continue;
        }
        let mut f = norm(&(scene.forces.force(id) + g * b.mass[id]));
        if let (Shape::Clump(c), true) = (&b.shape[id], f == 0.0) {
            // a clump read before Newton summed its members (Shop::unbalancedForce does the same)
            let mut cf = *scene.forces.force(id);
            for m in &c.members {
                cf += scene.forces.force(m.id as usize);
            }
            f = norm(&(cf + g * b.mass[id]));
        }
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

/// `gridpfacet.gridNode(center, radius, fixed, material)` (py/gridpfacet.py): volume 0, so mass and
/// inertia start at 0 (the connections add theirs); unbounded and mask 0, so the node never
/// collides (node-node bonds are created explicitly by `grid_connection`).
pub fn grid_node(center: Vec3, radius: f64, material: usize, fixed: bool) -> BodySpec {
    let mut b = at_rest(
        Shape::GridNode(Box::new(crate::shape::GridNode {
            radius,
            conn_list: Vec::new(),
        })),
        material,
        center,
        0.0,
        Vec3::zeros(),
        if fixed { DOF_ALL } else { 0 },
    );
    // V = 0: mass 0*density and inertia (2/5*0*r**2)*density, both +0
    b.bounded = false;
    b.mask = 0;
    b
}

/// `gridpfacet.gridConnection(id1, id2, radius, material, mask, cellDist)` (py/gridpfacet.py), in
/// its order of operations and Python's evaluation order: `createInteraction(id1, id2)`, the
/// connection body (fixed, at node 1, mass `V·ρ` of its own material with `V = ½·L·π·r²`), each
/// node's mass `+= V·ρ` and inertia `+= (2/5)·V·r²·ρ` with ρ, E and ν of node 1's material, then
/// the bond overrides `unp = -L + r1 + r2`, `kn = E·π·r²/L`, `kr = E·I/L`, `ks = 12·E·I/L³`,
/// `ktw = 2·I·G/L` (`I = π(2r)⁴/64`, `G = E/(2(1+ν))`), `connectionBody` and the mask. Python's `**`
/// is libm `pow`. Returns the connection's body id.
pub fn grid_connection(
    scene: &mut Scene,
    id1: usize,
    id2: usize,
    radius: f64,
    material: usize,
    mask: i32,
    cell_dist: Option<[i32; 3]>,
) -> Result<usize, String> {
    use crate::geom::GeomExt;
    let pi = std::f64::consts::PI;
    for id in [id1, id2] {
        if !matches!(scene.bodies.shape.get(id), Some(Shape::GridNode(_))) {
            return Err(format!("gridConnection: body #{} is not a GridNode", id));
        }
    }
    let k = scene.create_interaction(id1, id2)?;
    let node_mat = scene.materials[scene.bodies.material[id1]].clone();
    let conn_id = scene.bodies.len();
    for id in [id1, id2] {
        if let Shape::GridNode(n) = &mut scene.bodies.shape[id] {
            n.conn_list.push(conn_id as u32);
        }
    }
    let b = &scene.bodies;
    let (p1, p2) = (b.pos[id1], b.pos[id2]);
    let periodic = scene.cell.is_some();
    if periodic {
        if let Some(cd) = cell_dist {
            scene.interactions.list[k].cell_dist = cd;
        }
    }
    let cd = scene.interactions.list[k].cell_dist;
    let rel = match &scene.cell {
        Some(c) => (p2 + crate::math::mat_vec_i(&c.hsize, &cd)) - p1,
        None => p2 - p1,
    };
    let l = norm(&rel);
    let v = 0.5 * l * pi * radius.powf(2.0);
    let geom_inert = (2.0 / 5.0) * v * radius.powf(2.0);
    let conn_density = scene.materials[material].density;
    let mut spec = at_rest(
        Shape::GridConnection(Box::new(crate::shape::GridConnection {
            radius,
            node1: id1 as u32,
            node2: id2 as u32,
            periodic,
            cell_dist: if periodic { cd } else { [0; 3] },
        })),
        material,
        p1,
        v * conn_density,
        Vec3::repeat(geom_inert * conn_density),
        DOF_ALL,
    );
    spec.mask = mask;
    let b = &mut scene.bodies;
    for id in [id1, id2] {
        b.mass[id] += v * node_mat.density;
    }
    for kk in 0..3 {
        for id in [id1, id2] {
            b.inertia[id][kk] += geom_inert * node_mat.density;
        }
    }
    let r1 = b.shape[id1].sphere_radius().unwrap();
    let r2 = b.shape[id2].sphere_radius().unwrap();
    let cid = b.push(spec);
    scene.forces.resize(scene.bodies.len());
    let unp = -l + r1 + r2;
    let i_ = pi * (2.0 * radius).powf(4.0) / 64.0;
    let e = node_mat.young;
    let it = &mut scene.interactions.list[k];
    let ph = it
        .phys
        .as_mut()
        .ok_or("gridConnection: the interaction has no physics")?;
    ph.kn = e * pi * radius.powf(2.0) / l;
    ph.ks = 12.0 * e * i_ / l.powf(3.0);
    let g = e / (2.0 * (1.0 + node_mat.poisson));
    let ext = it.ext_mut();
    let coh = ext
        .coh
        .as_mut()
        .ok_or("gridConnection: the bond physics is not a CohFrictPhys (add Ip2_CohFrictMat_CohFrictMat_CohFrictPhys and use a CohFrictMat for the nodes)")?;
    coh.unp = unp;
    coh.kr = e * i_ / l;
    coh.ktw = 2.0 * i_ * g / l;
    match ext.geom.as_mut() {
        Some(GeomExt::GridNode {
            connection_body, ..
        }) => *connection_body = Some(cid as u32),
        _ => {
            return Err(
                "gridConnection: the bond geometry is not a GridNodeGeom6D (add Ig2_GridNode_GridNode_GridNodeGeom6D)"
                    .into(),
            )
        }
    }
    Ok(cid)
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

/// Kinetic energy of all dynamic bodies but clump members (`Shop::kineticEnergy`,
/// preprocessing/dem/Shop_01.cpp):
/// per body `E = .5*(m*|v|²)` (periodic: `.5*m*|v - velGrad*(x - v*dt)|²`) plus `0.5*ω·(I∘ω)`,
/// summed body by body in id order, in YADE's evaluation order; aspherical bodies (clumps) take
/// `0.5*ω·((T I Tᵀ) ω)` with T = ori (NewtonIntegrator's energy term has `Tᵀ I T` in 2023.02a).
pub fn kinetic_energy(scene: &Scene) -> f64 {
    let b = &scene.bodies;
    let mut ret = 0.0;
    for id in 0..b.len() {
        // a clump member's motion is its clump's (YADE counts the clump only)
        if !b.is_dynamic(id) || b.is_clump_member(id) {
            continue;
        }
        let v = b.vel[id];
        let mut e = match &scene.cell {
            Some(c) => {
                let x = b.pos[id] - v * scene.dt;
                let f = v - crate::math::mat_vec(&c.vel_grad, &x);
                0.5 * b.mass[id] * norm2(&f)
            }
            None => 0.5 * (b.mass[id] * norm2(&v)),
        };
        let w = b.ang_vel[id];
        e += if b.aspherical[id] {
            let t = b.ori[id].to_rotation_matrix();
            let m = crate::math::mat_mul(
                &crate::math::mat_mul(&t, &crate::math::Mat3::from_diagonal(&b.inertia[id])),
                &t.transpose(),
            );
            0.5 * crate::math::dot(&w, &crate::math::mat_vec(&m, &w))
        } else {
            0.5 * crate::math::dot(&w, &b.inertia[id].component_mul(&w))
        };
        ret += e;
    }
    ret
}

/// The critical time step of the stiffest sphere-sphere contact a scene can form: two equal spheres
/// of mass m on a spring kn = E·r have `dt_crit = 2/ω = 2·sqrt(m/(2·kn))` (central difference). A
/// larger dt diverges whatever the damping. None without spheres.
pub fn critical_time_step(scene: &Scene) -> Option<f64> {
    let b = &scene.bodies;
    (0..b.len())
        .filter(|&id| b.is_dynamic(id))
        .filter_map(|id| {
            let r = b.shape[id].plain_sphere_radius()?;
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

/// An engine attribute set from Python (JSON) as a number; `what` names it in the error (Err(Some)).
pub fn attr_f64(what: &str, v: &serde_json::Value) -> Result<f64, Option<String>> {
    v.as_f64()
        .ok_or_else(|| Some(format!("{} must be a number", what)))
}

/// The same for a bool (a number is read as != 0, as Python's bool()).
pub fn attr_bool(what: &str, v: &serde_json::Value) -> Result<bool, Option<String>> {
    v.as_bool()
        .or_else(|| v.as_f64().map(|x| x != 0.0))
        .ok_or_else(|| Some(format!("{} must be a bool", what)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn doubles_print_as_cxx_streams() {
        for (x, s) in [
            (0.0, "0"),
            (1.0, "1"),
            (123456.0, "123456"),
            (1234567.0, "1.23457e+06"),
            (0.0001, "0.0001"),
            (0.00001234, "1.234e-05"),
            (-2.5, "-2.5"),
            (999999.7, "1e+06"),
            (1.0 / 3.0, "0.333333"),
            (2.0e-300, "2e-300"),
        ] {
            assert_eq!(cxx_stream_double(x), s);
        }
    }
}
