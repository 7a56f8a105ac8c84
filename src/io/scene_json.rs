//! Import of a scene exported from YADE with 17 significant digits (`*.scene.json`, FORMAT.md).
//!
//! Everything is taken as YADE holds it (mass and inertia included, so no `pow(r,3)` rounding can
//! differ); any class or attribute we do not implement is an error naming it.

use crate::body::BodySpec;
use crate::cell::Cell;
use crate::collider::{Collider, ColliderParams};
use crate::geom;
use crate::integrator::Newton;
use crate::law;
use crate::material::FrictMat;
use crate::math::{Mat3, Quat, Vec3};
use crate::scene::{Engine, InteractionLoop, Scene};
use crate::shape::{Facet, Shape};
use anyhow::{anyhow, bail, Context, Result};
use serde_json::Value;
use std::path::Path;

/// A scene file: the scene plus the number of steps its golden run recorded.
pub struct SceneFile {
    pub scene: Scene,
    pub steps: u64,
    pub name: String,
}

fn f(v: &Value, key: &str) -> Result<f64> {
    v.get(key)
        .and_then(Value::as_f64)
        .ok_or_else(|| anyhow!("missing or non-numeric '{}' in {}", key, short(v)))
}

fn fo(v: &Value, key: &str, default: f64) -> Result<f64> {
    match v.get(key) {
        None => Ok(default),
        Some(x) => x
            .as_f64()
            .ok_or_else(|| anyhow!("'{}' is not a number in {}", key, short(v))),
    }
}

fn bo(v: &Value, key: &str, default: bool) -> Result<bool> {
    match v.get(key) {
        None => Ok(default),
        Some(x) => x
            .as_bool()
            .ok_or_else(|| anyhow!("'{}' is not a boolean in {}", key, short(v))),
    }
}

fn vec3(v: &Value, key: &str) -> Result<Vec3> {
    let a = v
        .get(key)
        .and_then(Value::as_array)
        .ok_or_else(|| anyhow!("missing vector '{}' in {}", key, short(v)))?;
    if a.len() != 3 {
        bail!("'{}' must have 3 components in {}", key, short(v));
    }
    let c = |i: usize| {
        a[i].as_f64()
            .ok_or_else(|| anyhow!("'{}'[{}] is not a number", key, i))
    };
    Ok(Vec3::new(c(0)?, c(1)?, c(2)?))
}

fn vec3_of(a: &Value) -> Result<Vec3> {
    let a = a
        .as_array()
        .ok_or_else(|| anyhow!("expected a 3-vector, got {}", short(a)))?;
    if a.len() != 3 {
        bail!("expected a 3-vector, got {} components", a.len());
    }
    let c = |i: usize| {
        a[i].as_f64()
            .ok_or_else(|| anyhow!("component {} is not a number", i))
    };
    Ok(Vec3::new(c(0)?, c(1)?, c(2)?))
}

fn short(v: &Value) -> String {
    let s = v.to_string();
    if s.len() > 120 {
        format!("{}...", &s[..120])
    } else {
        s
    }
}

fn class(v: &Value) -> Result<&str> {
    v.get("class")
        .and_then(Value::as_str)
        .ok_or_else(|| anyhow!("object without 'class': {}", short(v)))
}

pub fn load(path: &Path) -> Result<SceneFile> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
    let v: Value = serde_json::from_str(&text)
        .with_context(|| format!("{} is not valid JSON", path.display()))?;
    let name = path
        .file_name()
        .and_then(|n| n.to_str())
        .unwrap_or("scene")
        .trim_end_matches(".scene.json")
        .to_string();
    from_value(&v, name).with_context(|| format!("in scene file {}", path.display()))
}

pub fn from_value(v: &Value, name: String) -> Result<SceneFile> {
    if v.get("format").and_then(Value::as_str) != Some("ryade-scene-1") {
        bail!("not a ryade scene file (expected \"format\": \"ryade-scene-1\")");
    }
    let mut scene = Scene {
        dt: f(v, "dt")?,
        ..Scene::default()
    };
    if bo(v, "periodic", false)? {
        let rows = v
            .get("cell_hsize")
            .and_then(Value::as_array)
            .ok_or_else(|| anyhow!("periodic scene without 'cell_hsize'"))?;
        if rows.len() != 3 {
            bail!("cell_hsize must have 3 rows");
        }
        let r: Vec<Vec3> = rows.iter().map(vec3_of).collect::<Result<_>>()?;
        let h = Mat3::from_rows(&[r[0].transpose(), r[1].transpose(), r[2].transpose()]);
        scene.cell = Some(Cell::new(h).map_err(|e| anyhow!(e))?);
    }
    let bodies = v
        .get("bodies")
        .and_then(Value::as_array)
        .ok_or_else(|| anyhow!("missing 'bodies' array"))?;
    for (k, b) in bodies.iter().enumerate() {
        let id = b
            .get("id")
            .and_then(Value::as_u64)
            .ok_or_else(|| anyhow!("body {} without id", k))?;
        if id as usize != k {
            bail!(
                "body ids must be consecutive from 0 (found id {} at position {})",
                id,
                k
            );
        }
        let spec = body(b, &mut scene.materials).with_context(|| format!("body #{}", id))?;
        scene.bodies.push(spec);
    }
    let engines = v
        .get("engines")
        .and_then(Value::as_array)
        .ok_or_else(|| anyhow!("missing 'engines' array"))?;
    for e in engines {
        scene.engines.push(engine(e)?);
    }
    scene.forces.resize(scene.bodies.len());
    let steps = v.get("steps").and_then(Value::as_u64).unwrap_or(0);
    Ok(SceneFile { scene, steps, name })
}

pub fn material(m: &Value, mats: &mut Vec<FrictMat>) -> Result<usize> {
    let cls = class(m)?;
    if cls != "FrictMat" {
        bail!(
            "material class '{}' is not supported by ryade yet (supported: FrictMat)",
            cls
        );
    }
    let fm = FrictMat {
        id: m.get("id").and_then(Value::as_i64).unwrap_or(-1) as i32,
        label: m
            .get("label")
            .and_then(Value::as_str)
            .unwrap_or("")
            .to_string(),
        young: f(m, "young")?,
        poisson: f(m, "poisson")?,
        friction_angle: f(m, "frictionAngle")?,
        density: f(m, "density")?,
    };
    // share materials with a YADE id, as O.materials does
    if fm.id >= 0 {
        if let Some(i) = mats.iter().position(|x| x.id == fm.id) {
            if mats[i] != fm {
                bail!("two different materials share YADE id {}", fm.id);
            }
            return Ok(i);
        }
    }
    mats.push(fm);
    Ok(mats.len() - 1)
}

pub fn body(b: &Value, mats: &mut Vec<FrictMat>) -> Result<BodySpec> {
    let s = b.get("shape").ok_or_else(|| anyhow!("missing 'shape'"))?;
    let shape = match class(s)? {
        "Sphere" => Shape::Sphere {
            radius: f(s, "radius")?,
        },
        "Facet" => {
            let vs = s
                .get("vertices")
                .and_then(Value::as_array)
                .ok_or_else(|| anyhow!("facet without vertices"))?;
            if vs.len() != 3 {
                bail!("a facet needs exactly 3 vertices, got {}", vs.len());
            }
            let v = [vec3_of(&vs[0])?, vec3_of(&vs[1])?, vec3_of(&vs[2])?];
            Shape::Facet(Box::new(Facet::new(v).map_err(|e| anyhow!(e))?))
        }
        "Wall" => Shape::Wall {
            axis: s
                .get("axis")
                .and_then(Value::as_u64)
                .filter(|a| *a < 3)
                .ok_or_else(|| anyhow!("wall axis must be 0, 1 or 2"))? as usize,
            sense: s
                .get("sense")
                .and_then(Value::as_i64)
                .filter(|x| (-1..=1).contains(x))
                .ok_or_else(|| anyhow!("wall sense must be -1, 0 or 1"))? as i32,
        },
        "Box" => Shape::Box {
            extents: vec3(s, "extents")?,
        },
        other => bail!(
            "shape class '{}' is not supported by ryade yet (supported: Sphere, Facet, Wall, Box)",
            other
        ),
    };
    let material = material(
        b.get("material")
            .ok_or_else(|| anyhow!("missing 'material'"))?,
        mats,
    )?;
    let ori = b
        .get("ori")
        .and_then(Value::as_array)
        .filter(|a| a.len() == 4)
        .ok_or_else(|| anyhow!("'ori' must be [w, x, y, z]"))?;
    let q = |i: usize| {
        ori[i]
            .as_f64()
            .ok_or_else(|| anyhow!("ori[{}] is not a number", i))
    };
    let blocked = b.get("blockedDOFs").and_then(Value::as_u64).unwrap_or(0);
    if blocked > 63 {
        bail!("blockedDOFs bits must be < 64");
    }
    Ok(BodySpec {
        shape,
        material,
        mask: b.get("mask").and_then(Value::as_i64).unwrap_or(1) as i32,
        bounded: bo(b, "bounded", true)?,
        pos: vec3(b, "pos")?,
        vel: vec3(b, "vel")?,
        ang_vel: vec3(b, "angVel")?,
        ori: Quat::new(q(0)?, q(1)?, q(2)?, q(3)?),
        mass: f(b, "mass")?,
        inertia: vec3(b, "inertia")?,
        blocked: blocked as u8,
        is_damped: bo(b, "isDamped", true)?,
    })
}

pub fn engine(e: &Value) -> Result<Engine> {
    Ok(match class(e)? {
        "ForceResetter" => Engine::ForceResetter,
        "External" => Engine::External(
            e.get("id")
                .and_then(Value::as_u64)
                .ok_or_else(|| anyhow!("External engine without an integer 'id'"))? as u32,
        ),
        "InsertionSortCollider" => {
            let mut p = ColliderParams {
                verlet_dist: fo(e, "verletDist", -0.5)?,
                allow_bigger_than_period: bo(e, "allowBiggerThanPeriod", false)?,
                target_interv: fo(e, "targetInterv", 100.0)? as i32,
                min_sweep_dist_factor: fo(e, "minSweepDistFactor", 0.1)?,
                sort_axis: fo(e, "sortAxis", 0.0)? as usize,
                sort_then_collide: bo(e, "sortThenCollide", false)?,
                overlap_tolerance: fo(e, "overlapTolerance", 1e-7)?,
                avoid_self_interaction_mask: fo(e, "avoidSelfInteractionMask", 0.0)? as i32,
                ..Default::default()
            };
            p.bounds.sphere = None;
            p.bounds.facet = false;
            p.bounds.box_ = false;
            for b in e.get("bounds").and_then(Value::as_array).cloned().unwrap_or_default() {
                match class(&b)? {
                    "Bo1_Sphere_Aabb" => p.bounds.sphere = Some(fo(&b, "aabbEnlargeFactor", -1.0)?),
                    "Bo1_Facet_Aabb" => p.bounds.facet = true,
                    "Bo1_Wall_Aabb" => p.bounds.wall = true,
                    "Bo1_Box_Aabb" => p.bounds.box_ = true,
                    other => bail!("bound functor '{}' is not supported by ryade yet", other),
                }
            }
            Engine::Collider(Box::new(Collider::new(p)))
        }
        "InteractionLoop" => {
            let mut il = InteractionLoop {
                sphere_sphere: None,
                facet_sphere: None,
                wall_sphere: None,
                box_sphere: None,
                frict_phys: false,
                cundall_strack: None,
            };
            for g in e.get("geom").and_then(Value::as_array).cloned().unwrap_or_default() {
                match class(&g)? {
                    "Ig2_Sphere_Sphere_ScGeom" => {
                        il.sphere_sphere = Some(geom::sphere_sphere::Params {
                            interaction_detection_factor: fo(&g, "interactionDetectionFactor", 1.0)?,
                            avoid_granular_ratcheting: bo(&g, "avoidGranularRatcheting", true)?,
                        })
                    }
                    "Ig2_Facet_Sphere_ScGeom" => {
                        il.facet_sphere = Some(geom::facet_sphere::Params {
                            shrink_factor: fo(&g, "shrinkFactor", 0.0)?,
                        })
                    }
                    "Ig2_Wall_Sphere_ScGeom" => {
                        il.wall_sphere = Some(geom::wall_sphere::Params {
                            no_ratch: bo(&g, "noRatch", true)?,
                        })
                    }
                    "Ig2_Box_Sphere_ScGeom" => {
                        il.box_sphere = Some(geom::box_sphere::Params {
                            interaction_detection_factor: fo(&g, "interactionDetectionFactor", 1.0)?,
                        })
                    }
                    other => bail!("geometry functor '{}' is not supported by ryade yet", other),
                }
            }
            for p in e.get("phys").and_then(Value::as_array).cloned().unwrap_or_default() {
                match class(&p)? {
                    "Ip2_FrictMat_FrictMat_FrictPhys" => il.frict_phys = true,
                    other => bail!("physics functor '{}' is not supported by ryade yet", other),
                }
            }
            for l in e.get("law").and_then(Value::as_array).cloned().unwrap_or_default() {
                match class(&l)? {
                    "Law2_ScGeom_FrictPhys_CundallStrack" => {
                        il.cundall_strack = Some(law::Params {
                            never_erase: bo(&l, "neverErase", false)?,
                            spherical_bodies: bo(&l, "sphericalBodies", true)?,
                        })
                    }
                    other => bail!("law functor '{}' is not supported by ryade yet", other),
                }
            }
            Engine::InteractionLoop(Box::new(il))
        }
        "GlobalStiffnessTimeStepper" => {
            if bo(e, "densityScaling", false)? || bo(e, "viscEl", false)? {
                bail!("GlobalStiffnessTimeStepper with densityScaling or viscEl is not supported by ryade yet");
            }
            Engine::TimeStepper(Box::new(crate::timestepper::GlobalStiffnessTimeStepper {
                active: bo(e, "active", true)?,
                time_step_update_interval: fo(e, "timeStepUpdateInterval", 1.0)? as u32,
                default_dt: fo(e, "defaultDt", -1.0)?,
                max_dt: fo(e, "maxDt", f64::MAX)?,
                timestep_safety_coefficient: fo(e, "timestepSafetyCoefficient", 0.8)?,
                ..Default::default()
            }))
        }
        "NewtonIntegrator" => Engine::Newton(Box::new(Newton {
            damping: fo(e, "damping", 0.2)?,
            gravity: if e.get("gravity").is_some() { vec3(e, "gravity")? } else { Vec3::zeros() },
            damp_gravity: bo(e, "dampGravity", true)?,
            mask: fo(e, "mask", -1.0)? as i32,
            ..Default::default()
        })),
        other => bail!("engine '{}' is not supported by ryade yet (supported: ForceResetter, InsertionSortCollider, InteractionLoop, NewtonIntegrator)", other),
    })
}

/// Export a scene in the same format (17 significant digits are kept by serde_json's shortest
/// round-trip float formatting), so that YADE or ryade can load exactly the same state.
pub fn to_value(scene: &Scene, steps: u64) -> Value {
    use serde_json::json;
    let v3 = |v: &Vec3| json!([v[0], v[1], v[2]]);
    let b = &scene.bodies;
    let bodies: Vec<Value> = (0..b.len())
        .map(|id| {
            let shape = match &b.shape[id] {
                Shape::Sphere { radius } => json!({"class": "Sphere", "radius": radius}),
                Shape::Facet(f) => json!({"class": "Facet", "vertices": [v3(&f.vertices[0]), v3(&f.vertices[1]), v3(&f.vertices[2])]}),
                Shape::Wall { axis, sense } => json!({"class": "Wall", "axis": axis, "sense": sense}),
                Shape::Box { extents } => json!({"class": "Box", "extents": v3(extents)}),
            };
            let m = &scene.materials[b.material[id]];
            let q = b.ori[id];
            json!({
                "id": id, "shape": shape,
                "material": {"id": m.id, "class": "FrictMat", "young": m.young, "poisson": m.poisson,
                             "frictionAngle": m.friction_angle, "density": m.density, "label": m.label},
                "mask": b.mask[id], "bounded": b.bounded[id],
                "pos": v3(&b.pos[id]), "vel": v3(&b.vel[id]), "angVel": v3(&b.ang_vel[id]),
                "ori": [q.w, q.x, q.y, q.z], "mass": b.mass[id], "inertia": v3(&b.inertia[id]),
                "blockedDOFs": b.blocked[id], "isDamped": b.is_damped[id],
            })
        })
        .collect();
    let engines: Vec<Value> = scene
        .engines
        .iter()
        .map(|e| match e {
            Engine::ForceResetter => json!({"class": "ForceResetter"}),
            Engine::Collider(c) => {
                let p = &c.p;
                let mut bounds = Vec::new();
                if let Some(f) = p.bounds.sphere {
                    bounds.push(json!({"class": "Bo1_Sphere_Aabb", "aabbEnlargeFactor": f}));
                }
                if p.bounds.facet {
                    bounds.push(json!({"class": "Bo1_Facet_Aabb"}));
                }
                if p.bounds.wall {
                    bounds.push(json!({"class": "Bo1_Wall_Aabb"}));
                }
                if p.bounds.box_ {
                    bounds.push(json!({"class": "Bo1_Box_Aabb"}));
                }
                json!({"class": "InsertionSortCollider", "bounds": bounds, "verletDist": p.verlet_dist,
                       "allowBiggerThanPeriod": p.allow_bigger_than_period, "targetInterv": p.target_interv,
                       "minSweepDistFactor": p.min_sweep_dist_factor, "sortAxis": p.sort_axis,
                       "sortThenCollide": p.sort_then_collide})
            }
            Engine::InteractionLoop(il) => {
                let mut geom = Vec::new();
                if let Some(g) = &il.sphere_sphere {
                    geom.push(json!({"class": "Ig2_Sphere_Sphere_ScGeom", "interactionDetectionFactor": g.interaction_detection_factor, "avoidGranularRatcheting": g.avoid_granular_ratcheting}));
                }
                if let Some(g) = &il.facet_sphere {
                    geom.push(json!({"class": "Ig2_Facet_Sphere_ScGeom", "shrinkFactor": g.shrink_factor}));
                }
                if let Some(g) = &il.wall_sphere {
                    geom.push(json!({"class": "Ig2_Wall_Sphere_ScGeom", "noRatch": g.no_ratch}));
                }
                if let Some(g) = &il.box_sphere {
                    geom.push(json!({"class": "Ig2_Box_Sphere_ScGeom", "interactionDetectionFactor": g.interaction_detection_factor}));
                }
                let phys: Vec<Value> = if il.frict_phys { vec![json!({"class": "Ip2_FrictMat_FrictMat_FrictPhys"})] } else { vec![] };
                let law: Vec<Value> = il
                    .cundall_strack
                    .iter()
                    .map(|l| json!({"class": "Law2_ScGeom_FrictPhys_CundallStrack", "neverErase": l.never_erase, "sphericalBodies": l.spherical_bodies}))
                    .collect();
                json!({"class": "InteractionLoop", "geom": geom, "phys": phys, "law": law})
            }
            Engine::Newton(n) => json!({"class": "NewtonIntegrator", "damping": n.damping, "gravity": v3(&n.gravity), "dampGravity": n.damp_gravity, "mask": n.mask}),
            Engine::TimeStepper(t) => json!({"class": "GlobalStiffnessTimeStepper", "active": t.active,
                "timeStepUpdateInterval": t.time_step_update_interval, "defaultDt": t.default_dt,
                "maxDt": t.max_dt, "timestepSafetyCoefficient": t.timestep_safety_coefficient}),
            // a Python-side engine (PyRunner...): the file records its place; loading it needs the runner
            Engine::External(id) => json!({"class": "External", "id": id}),
        })
        .collect();
    let mut out = json!({
        "format": "ryade-scene-1", "source": "ryade", "steps": steps, "dt": scene.dt,
        "periodic": scene.cell.is_some(), "bodies": bodies, "engines": engines,
    });
    if let Some(c) = &scene.cell {
        let h = c.hsize;
        out["cell_hsize"] = json!([
            [h[(0, 0)], h[(0, 1)], h[(0, 2)]],
            [h[(1, 0)], h[(1, 1)], h[(1, 2)]],
            [h[(2, 0)], h[(2, 1)], h[(2, 2)]]
        ]);
    }
    out
}
