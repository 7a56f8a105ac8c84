//! Import of a scene exported from YADE with 17 significant digits (`*.scene.json`, FORMAT.md; the
//! grid extension `ryade-scene-grid-1` of FORMAT_GRID.md adds grid shapes, CohFrictMat, the grid and
//! cohesive functors and the interactions that exist before the first step, with their full state).
//!
//! Everything is taken as YADE holds it (mass and inertia included, so no `pow(r,3)` rounding can
//! differ); any class or attribute we do not implement is an error naming it.

use crate::body::BodySpec;
use crate::bound::BoundFunctors;
use crate::cell::Cell;
use crate::collider::{Collider, ColliderParams};
use crate::geom;
use crate::geom::{Fict, GeomExt, GridCoGridCo, Rot6D, ScGeom, ScGridCo};
use crate::integrator::Newton;
use crate::interaction::{Interaction, IntrExt};
use crate::kinematic::KinematicPart;
use crate::law;
use crate::material::CohFrictParams;
use crate::material::FrictMat;
use crate::math::{Mat3, Quat, Vec3};
use crate::phys::{CohFrictPhys, FrictPhys};
use crate::scene::{Engine, InteractionLoop, Scene};
use crate::shape::{Facet, Shape};
use crate::shape::{GridConnection, GridNode};
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

fn vec3_or(v: &Value, key: &str, default: Vec3) -> Result<Vec3> {
    if v.get(key).is_some() {
        vec3(v, key)
    } else {
        Ok(default)
    }
}

/// A `PartialEngine.ids` list (non-negative body ids).
fn ids(v: &Value) -> Result<Vec<usize>> {
    match v.get("ids") {
        None => Ok(Vec::new()),
        Some(Value::Array(a)) => a
            .iter()
            .map(|x| {
                x.as_u64()
                    .map(|i| i as usize)
                    .ok_or_else(|| anyhow!("'ids' must hold body ids (integers >= 0), got {}", x))
            })
            .collect(),
        Some(x) => bail!("'ids' must be a list of body ids, got {}", short(x)),
    }
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

fn ivec3(v: &Value, key: &str) -> Result<Option<[i32; 3]>> {
    let Some(a) = v.get(key) else {
        return Ok(None);
    };
    let a = a
        .as_array()
        .filter(|a| a.len() == 3)
        .ok_or_else(|| anyhow!("'{}' must be 3 integers in {}", key, short(v)))?;
    let c = |i: usize| {
        a[i].as_i64()
            .map(|x| x as i32)
            .ok_or_else(|| anyhow!("'{}'[{}] is not an integer", key, i))
    };
    Ok(Some([c(0)?, c(1)?, c(2)?]))
}

fn quat(v: &Value, key: &str) -> Result<Quat> {
    let a = v
        .get(key)
        .and_then(Value::as_array)
        .filter(|a| a.len() == 4)
        .ok_or_else(|| anyhow!("'{}' must be [w, x, y, z] in {}", key, short(v)))?;
    let c = |i: usize| {
        a[i].as_f64()
            .ok_or_else(|| anyhow!("'{}'[{}] is not a number", key, i))
    };
    Ok(Quat::new(c(0)?, c(1)?, c(2)?, c(3)?))
}

fn int(v: &Value, key: &str, default: i64) -> Result<i64> {
    match v.get(key) {
        None => Ok(default),
        Some(x) => x
            .as_i64()
            .ok_or_else(|| anyhow!("'{}' is not an integer in {}", key, short(v))),
    }
}

/// One interaction of the `interactions` array (FORMAT_GRID.md) with its geometry and physics.
pub fn interaction(i: &Value, nbodies: usize) -> Result<Interaction> {
    let id = |k: &str| -> Result<u32> {
        let x = i
            .get(k)
            .and_then(Value::as_u64)
            .ok_or_else(|| anyhow!("interaction without an integer '{}'", k))?;
        if x as usize >= nbodies {
            bail!("interaction '{}' = {} is not a body id", k, x);
        }
        Ok(x as u32)
    };
    let mut it = Interaction::new(
        id("id1")?,
        id("id2")?,
        ivec3(i, "cellDist")?.unwrap_or([0; 3]),
        int(i, "iterBorn", 0)?,
    );
    it.iter_made_real = int(i, "iterMadeReal", -1)?;
    let mut ext = IntrExt::default();
    if let Some(g) = i.get("geom").filter(|g| !g.is_null()) {
        it.geom = Some(ScGeom {
            contact_point: vec3(g, "contactPoint")?,
            pen: f(g, "penetrationDepth")?,
            normal: vec3(g, "normal")?,
            shear_inc: vec3(g, "shearInc")?,
            orthonormal_axis: Vec3::zeros(),
            twist_axis: Vec3::zeros(),
            radius1: f(g, "refR1")?,
            radius2: f(g, "refR2")?,
        });
        let rot = || -> Result<Rot6D> {
            Ok(Rot6D {
                initial_orientation1: quat(g, "initialOrientation1")?,
                initial_orientation2: quat(g, "initialOrientation2")?,
                twist_creep: quat(g, "twistCreep")?,
                twist: f(g, "twist")?,
                bending: vec3(g, "bending")?,
            })
        };
        ext.geom = match class(g)? {
            "ScGeom" => None,
            "ScGeom6D" => Some(GeomExt::Sc6D(rot()?)),
            "GridNodeGeom6D" => {
                let cb = int(g, "connectionBody", -1)?;
                if cb >= nbodies as i64 {
                    bail!("connectionBody {} is not a body id", cb);
                }
                Some(GeomExt::GridNode {
                    rot: rot()?,
                    connection_body: (cb >= 0).then_some(cb as u32),
                })
            }
            "ScGridCoGeom" => Some(GeomExt::ScGridCo(ScGridCo {
                rot: rot()?,
                is_duplicate: int(g, "isDuplicate", 0)? as i32,
                true_int: int(g, "trueInt", -1)? as i32,
                id3: int(g, "id3", 0)? as i32,
                id4: int(g, "id4", 0)? as i32,
                id5: int(g, "id5", -1)? as i32,
                weight: if g.get("weight").is_some() {
                    vec3(g, "weight")?
                } else {
                    Vec3::zeros()
                },
                rel_pos: fo(g, "relPos", 0.0)?,
                fict: Fict::default(),
                share: 0,
            })),
            "GridCoGridCoGeom" => Some(GeomExt::GridCoGridCo(GridCoGridCo {
                rel_pos1: fo(g, "relPos1", 0.0)?,
                rel_pos2: fo(g, "relPos2", 0.0)?,
                ..Default::default()
            })),
            other => bail!(
                "interaction geometry class '{}' is not supported by ryade yet",
                other
            ),
        };
    }
    if let Some(p) = i.get("phys").filter(|p| !p.is_null()) {
        it.phys = Some(FrictPhys {
            kn: f(p, "kn")?,
            ks: f(p, "ks")?,
            tan_phi: f(p, "tangensOfFrictionAngle")?,
            normal_force: vec3(p, "normalForce")?,
            shear_force: vec3(p, "shearForce")?,
        });
        ext.coh = match class(p)? {
            "FrictPhys" => None,
            "CohFrictPhys" => {
                let d = CohFrictPhys::default();
                let v3o = |k: &str| -> Result<Vec3> {
                    if p.get(k).is_some() {
                        vec3(p, k)
                    } else {
                        Ok(Vec3::zeros())
                    }
                };
                Some(CohFrictPhys {
                    kr: fo(p, "kr", d.kr)?,
                    ktw: fo(p, "ktw", d.ktw)?,
                    cohesion_disables_friction: bo(
                        p,
                        "cohesionDisablesFriction",
                        d.cohesion_disables_friction,
                    )?,
                    cohesion_broken: bo(p, "cohesionBroken", d.cohesion_broken)?,
                    fragile: bo(p, "fragile", d.fragile)?,
                    init_cohesion: bo(p, "initCohesion", d.init_cohesion)?,
                    max_roll_pl: fo(p, "maxRollPl", d.max_roll_pl)?,
                    max_twist_pl: fo(p, "maxTwistPl", d.max_twist_pl)?,
                    normal_adhesion: fo(p, "normalAdhesion", d.normal_adhesion)?,
                    shear_adhesion: fo(p, "shearAdhesion", d.shear_adhesion)?,
                    unp: fo(p, "unp", d.unp)?,
                    unp_max: fo(p, "unpMax", d.unp_max)?,
                    moment_rotation_law: bo(p, "momentRotationLaw", d.moment_rotation_law)?,
                    creep_viscosity: fo(p, "creep_viscosity", d.creep_viscosity)?,
                    moment_twist: v3o("moment_twist")?,
                    moment_bending: v3o("moment_bending")?,
                })
            }
            "ViscElPhys" => None,
            other => bail!(
                "interaction physics class '{}' is not supported by ryade yet",
                other
            ),
        };
        if class(p)? == "ViscElPhys" {
            ext.viscel = Some(crate::phys::ViscElPhys {
                cn: f(p, "cn")?,
                cs: f(p, "cs")?,
                fn_el: fo(p, "Fn", 0.0)?,
                fv: fo(p, "Fv", 0.0)?,
                m_r: fo(p, "mR", 0.0)?,
                m_r_type: p.get("mRtype").and_then(Value::as_u64).unwrap_or(1) as u32,
            });
        }
    }
    if ext != IntrExt::default() {
        it.ext = Some(Box::new(ext));
    }
    if let Some(r) = i.get("isReal").and_then(Value::as_bool) {
        if r != it.is_real() {
            bail!(
                "interaction {}+{}: isReal is {} but geom/phys say {}",
                it.id1,
                it.id2,
                r,
                it.is_real()
            );
        }
    }
    Ok(it)
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

/// Format id of FORMAT.md scenes.
pub const FORMAT_ID: &str = "ryade-scene-1";
/// Format id of the grid extension (FORMAT_GRID.md).
pub const GRID_FORMAT_ID: &str = "ryade-scene-grid-1";

pub fn from_value(v: &Value, name: String) -> Result<SceneFile> {
    let fmt = v.get("format").and_then(Value::as_str);
    if fmt != Some(FORMAT_ID) && fmt != Some(GRID_FORMAT_ID) {
        bail!(
            "not a ryade scene file (expected \"format\": \"{}\" or \"{}\")",
            FORMAT_ID,
            GRID_FORMAT_ID
        );
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
        let id = scene.bodies.push(spec);
        body_extras(b, &mut scene.bodies, id).with_context(|| format!("body #{}", id))?;
    }
    check_clumps(&scene.bodies)?;
    let engines = v
        .get("engines")
        .and_then(Value::as_array)
        .ok_or_else(|| anyhow!("missing 'engines' array"))?;
    for e in engines {
        scene.engines.push(engine(e)?);
    }
    if let Some(intrs) = v.get("interactions") {
        let intrs = intrs
            .as_array()
            .ok_or_else(|| anyhow!("'interactions' must be an array"))?;
        for (k, i) in intrs.iter().enumerate() {
            let it = interaction(i, scene.bodies.len())
                .with_context(|| format!("interaction #{} of the scene file", k))?;
            let (a, b) = (it.id1, it.id2);
            if !scene.interactions.insert(it) {
                bail!("interaction {}+{} is listed twice", a, b);
            }
        }
    }
    scene.forces.resize(scene.bodies.len());
    let steps = v.get("steps").and_then(Value::as_u64).unwrap_or(0);
    Ok(SceneFile { scene, steps, name })
}

pub fn material(m: &Value, mats: &mut Vec<FrictMat>) -> Result<usize> {
    let cls = class(m)?;
    let coh = match cls {
        "FrictMat" => None,
        "CohFrictMat" => {
            let d = CohFrictParams::default();
            Some(Box::new(CohFrictParams {
                is_cohesive: bo(m, "isCohesive", d.is_cohesive)?,
                alpha_kr: fo(m, "alphaKr", d.alpha_kr)?,
                alpha_ktw: fo(m, "alphaKtw", d.alpha_ktw)?,
                eta_roll: fo(m, "etaRoll", d.eta_roll)?,
                eta_twist: fo(m, "etaTwist", d.eta_twist)?,
                normal_cohesion: fo(m, "normalCohesion", d.normal_cohesion)?,
                shear_cohesion: fo(m, "shearCohesion", d.shear_cohesion)?,
                fragile: bo(m, "fragile", d.fragile)?,
                moment_rotation_law: bo(m, "momentRotationLaw", d.moment_rotation_law)?,
            }))
        }
        "ViscElMat" | "LudingMat" | "BubbleMat" | "CpmMat" => None,
        _ => bail!(
            "material class '{}' is not supported by ryade yet (supported: FrictMat, CohFrictMat, ViscElMat, LudingMat, BubbleMat, CpmMat)",
            cls
        ),
    };
    let viscel = if cls == "ViscElMat" {
        // NaN (not given) travels as null
        let d = crate::material::ViscElParams::default();
        let nf = |k: &str| -> Result<f64> {
            match m.get(k) {
                None | Some(Value::Null) => Ok(f64::NAN),
                Some(_) => f(m, k),
            }
        };
        if bo(m, "lubrication", false)? {
            bail!("ViscElMat.lubrication=True is not supported by ryade yet");
        }
        Some(Box::new(crate::material::ViscElParams {
            tc: nf("tc")?,
            en: nf("en")?,
            et: nf("et")?,
            kn: nf("kn")?,
            cn: nf("cn")?,
            ks: nf("ks")?,
            cs: nf("cs")?,
            m_r: fo(m, "mR", d.m_r)?,
            m_r_type: m
                .get("mRtype")
                .and_then(Value::as_u64)
                .unwrap_or(d.m_r_type as u64) as u32,
        }))
    } else {
        None
    };
    let nan_or = |k: &str| -> Result<f64> {
        match m.get(k) {
            None | Some(Value::Null) => Ok(f64::NAN),
            Some(_) => f(m, k),
        }
    };
    let luding = if cls == "LudingMat" {
        Some(Box::new(crate::material::LudingParams {
            k1: nan_or("k1")?,
            kp: nan_or("kp")?,
            kc: nan_or("kc")?,
            ks: nan_or("ks")?,
            phi_f: nan_or("PhiF")?,
            g0: nan_or("G0")?,
        }))
    } else {
        None
    };
    let bubble = if cls == "BubbleMat" {
        Some(fo(m, "surfaceTension", 0.07197)?)
    } else {
        None
    };
    let cpm = if cls == "CpmMat" {
        let d = crate::material::CpmParams::default();
        Some(Box::new(crate::material::CpmParams {
            sigma_t: nan_or("sigmaT")?,
            never_damage: bo(m, "neverDamage", d.never_damage)?,
            eps_crack_onset: nan_or("epsCrackOnset")?,
            rel_ductility: nan_or("relDuctility")?,
            equiv_strain_shear_contrib: fo(
                m,
                "equivStrainShearContrib",
                d.equiv_strain_shear_contrib,
            )?,
            dam_law: fo(m, "damLaw", d.dam_law as f64)? as i32,
            dmg_tau: fo(m, "dmgTau", d.dmg_tau)?,
            dmg_rate_exp: fo(m, "dmgRateExp", d.dmg_rate_exp)?,
            pl_tau: fo(m, "plTau", d.pl_tau)?,
            pl_rate_exp: fo(m, "plRateExp", d.pl_rate_exp)?,
            iso_prestress: fo(m, "isoPrestress", d.iso_prestress)?,
        }))
    } else {
        None
    };
    let lud = luding.is_some() || bubble.is_some();
    let fm = FrictMat {
        id: m.get("id").and_then(Value::as_i64).unwrap_or(-1) as i32,
        label: m
            .get("label")
            .and_then(Value::as_str)
            .unwrap_or("")
            .to_string(),
        young: if lud { f64::NAN } else { f(m, "young")? },
        poisson: if lud { f64::NAN } else { f(m, "poisson")? },
        friction_angle: if lud {
            nan_or("frictionAngle")?
        } else {
            f(m, "frictionAngle")?
        },
        density: f(m, "density")?,
        coh,
        viscel,
        luding,
        bubble,
        cpm,
    };
    // share materials with a YADE id, as O.materials does
    if fm.id >= 0 {
        if let Some(i) = mats.iter().position(|x| x.id == fm.id) {
            // (compared as JSON: a NaN, a value not given, equals itself there)
            if mats[i] != fm
                && serde_json::to_value(&mats[i]).ok() != serde_json::to_value(&fm).ok()
            {
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
        "GridNode" => Shape::GridNode(Box::new(GridNode {
            radius: f(s, "radius")?,
            conn_list: s
                .get("connections")
                .and_then(Value::as_array)
                .map(|a| {
                    a.iter()
                        .map(|x| {
                            x.as_u64()
                                .map(|x| x as u32)
                                .ok_or_else(|| anyhow!("GridNode connections must be body ids"))
                        })
                        .collect::<Result<Vec<u32>>>()
                })
                .transpose()?
                .unwrap_or_default(),
        })),
        "GridConnection" => {
            let id = |k: &str| -> Result<u32> {
                s.get(k)
                    .and_then(Value::as_u64)
                    .map(|x| x as u32)
                    .ok_or_else(|| anyhow!("GridConnection without an integer '{}'", k))
            };
            Shape::GridConnection(Box::new(GridConnection {
                radius: f(s, "radius")?,
                node1: id("node1")?,
                node2: id("node2")?,
                periodic: bo(s, "periodic", false)?,
                cell_dist: ivec3(s, "cellDist")?.unwrap_or([0; 3]),
            }))
        }
        "Clump" => {
            let ms = s
                .get("members")
                .and_then(Value::as_array)
                .ok_or_else(|| anyhow!("clump without a 'members' array"))?;
            let mut members = Vec::with_capacity(ms.len());
            for m in ms {
                members.push(crate::clump::ClumpMember {
                    id: m
                        .get("id")
                        .and_then(Value::as_u64)
                        .ok_or_else(|| anyhow!("clump member without an integer 'id'"))?
                        as u32,
                    rel_pos: vec3(m, "relPos")?,
                    rel_ori: quat_of(
                        m.get("relOri")
                            .ok_or_else(|| anyhow!("clump member without 'relOri'"))?,
                    )?,
                });
            }
            if members.is_empty() || members.windows(2).any(|w| w[0].id >= w[1].id) {
                bail!("clump members must be listed once each, by increasing id");
            }
            Shape::Clump(Box::new(crate::clump::Clump { members }))
        }
        other => bail!(
            "shape class '{}' is not supported by ryade yet (supported: Sphere, Facet, Wall, Box, GridNode, GridConnection, Clump)",
            other
        ),
    };
    let material = match b.get("material") {
        // a clump has no material in YADE; `body_extras` gives it its first member's
        Some(Value::Null) | None if matches!(shape, Shape::Clump(_)) => 0,
        m => material(m.ok_or_else(|| anyhow!("missing 'material'"))?, mats)?,
    };
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

/// The body attributes `BodySpec` does not carry: `aspherical`, `angMom` and `clumpId` (all
/// optional; a clump body's material is taken from its first member, YADE leaves it empty).
pub fn body_extras(b: &Value, bodies: &mut crate::body::Bodies, id: usize) -> Result<()> {
    bodies.aspherical[id] = bo(b, "aspherical", false)?;
    bodies.ang_mom[id] = vec3_or(b, "angMom", Vec3::zeros())?;
    match b.get("clumpId") {
        None | Some(Value::Null) => {}
        Some(c) => {
            let c = c
                .as_i64()
                .ok_or_else(|| anyhow!("'clumpId' must be an integer"))?;
            bodies.clump_id[id] = if c < 0 { None } else { Some(c as u32) };
        }
    }
    if let Shape::Clump(c) = &bodies.shape[id] {
        if bodies.clump_id[id] != Some(id as u32) {
            bail!("a clump's 'clumpId' must be its own id");
        }
        let first = c.members.first().map(|m| m.id as usize);
        match first {
            Some(m) if m < id => bodies.material[id] = bodies.material[m],
            _ => bail!("a clump needs members with ids below its own"),
        }
    }
    Ok(())
}

/// Clump bookkeeping must agree both ways: every member names its clump and every clump lists
/// exactly the bodies that name it.
fn check_clumps(bodies: &crate::body::Bodies) -> Result<()> {
    let mut listed = vec![None; bodies.len()];
    for id in 0..bodies.len() {
        if let Shape::Clump(c) = &bodies.shape[id] {
            for m in &c.members {
                let mi = m.id as usize;
                if mi >= bodies.len() || bodies.is_clump(mi) {
                    bail!(
                        "clump #{}: member #{} is not a body that can be clumped",
                        id,
                        mi
                    );
                }
                if bodies.clump_id[mi] != Some(id as u32) {
                    bail!(
                        "clump #{} lists body #{} whose clumpId is not {}",
                        id,
                        mi,
                        id
                    );
                }
                listed[mi] = Some(id);
            }
        }
    }
    for (id, l) in listed.iter().enumerate() {
        if bodies.is_clump_member(id) && l.is_none() {
            bail!(
                "body #{} has clumpId {} but that clump does not list it",
                id,
                bodies.clump_id[id].unwrap()
            );
        }
    }
    Ok(())
}

fn quat_of(v: &Value) -> Result<Quat> {
    let a = v
        .as_array()
        .filter(|a| a.len() == 4)
        .ok_or_else(|| anyhow!("a quaternion must be [w, x, y, z]"))?;
    let c = |i: usize| {
        a[i].as_f64()
            .ok_or_else(|| anyhow!("quaternion component {} is not a number", i))
    };
    Ok(Quat::new(c(0)?, c(1)?, c(2)?, c(3)?))
}

/// The `bounds` list of a collider or a standalone BoundDispatcher (its Bo1 functors).
fn bound_functors(e: &Value) -> Result<BoundFunctors> {
    let mut f = BoundFunctors {
        sphere: None,
        facet: false,
        box_: false,
        ..Default::default()
    };
    for b in e
        .get("bounds")
        .and_then(Value::as_array)
        .cloned()
        .unwrap_or_default()
    {
        match class(&b)? {
            "Bo1_Sphere_Aabb" => f.sphere = Some(fo(&b, "aabbEnlargeFactor", -1.0)?),
            "Bo1_Facet_Aabb" => f.facet = true,
            "Bo1_Wall_Aabb" => f.wall = true,
            "Bo1_Box_Aabb" => f.box_ = true,
            "Bo1_GridConnection_Aabb" => f.grid_connection = true,
            other => bail!("bound functor '{}' is not supported by ryade yet", other),
        }
    }
    Ok(f)
}

fn bound_functors_json(f: &BoundFunctors) -> Vec<Value> {
    let mut bounds = Vec::new();
    if let Some(x) = f.sphere {
        bounds.push(serde_json::json!({"class": "Bo1_Sphere_Aabb", "aabbEnlargeFactor": x}));
    }
    if f.facet {
        bounds.push(serde_json::json!({"class": "Bo1_Facet_Aabb"}));
    }
    if f.wall {
        bounds.push(serde_json::json!({"class": "Bo1_Wall_Aabb"}));
    }
    if f.box_ {
        bounds.push(serde_json::json!({"class": "Bo1_Box_Aabb"}));
    }
    if f.grid_connection {
        bounds.push(
            serde_json::json!({"class": "Bo1_GridConnection_Aabb", "aabbEnlargeFactor": -1.0}),
        );
    }
    bounds
}

pub fn engine(e: &Value) -> Result<Engine> {
    let cls = class(e)?;
    Ok(match cls {
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
            p.bounds = bound_functors(e)?;
            Engine::Collider(Box::new(Collider::new(p)))
        }
        "BoundDispatcher" => Engine::Bounds(Box::new(bound_functors(e)?)),
        "InteractionLoop" => {
            let mut il = InteractionLoop::empty();
            for g in e.get("geom").and_then(Value::as_array).cloned().unwrap_or_default() {
                match class(&g)? {
                    "Ig2_Sphere_Sphere_ScGeom" => {
                        il.sphere_sphere_6d = None;
                        il.sphere_sphere = Some(geom::sphere_sphere::Params {
                            interaction_detection_factor: fo(&g, "interactionDetectionFactor", 1.0)?,
                            avoid_granular_ratcheting: bo(&g, "avoidGranularRatcheting", true)?,
                        })
                    }
                    "Ig2_Facet_Sphere_ScGeom" => {
                        il.facet_sphere = Some(geom::facet_sphere::Params {
                            shrink_factor: fo(&g, "shrinkFactor", 0.0)?,
                            hertzian: bo(&g, "hertzian", false)?,
                        })
                    }
                    "Ig2_Wall_Sphere_ScGeom" => {
                        il.wall_sphere = Some(geom::wall_sphere::Params {
                            no_ratch: bo(&g, "noRatch", true)?,
                            hertzian: bo(&g, "hertzian", false)?,
                        })
                    }
                    c @ ("Ig2_Box_Sphere_ScGeom" | "Ig2_Box_Sphere_ScGeom6D") => {
                        il.box_sphere = Some(geom::box_sphere::Params {
                            interaction_detection_factor: fo(&g, "interactionDetectionFactor", 1.0)?,
                            six_d: c == "Ig2_Box_Sphere_ScGeom6D",
                        })
                    }
                    c @ ("Ig2_Sphere_Sphere_ScGeom6D" | "Ig2_GridNode_GridNode_GridNodeGeom6D") => {
                        let p = geom::grid::SixDParams {
                            ss: geom::sphere_sphere::Params {
                                interaction_detection_factor: fo(&g, "interactionDetectionFactor", 1.0)?,
                                avoid_granular_ratcheting: bo(&g, "avoidGranularRatcheting", true)?,
                            },
                            update_rotations: bo(&g, "updateRotations", true)?,
                            creep: bo(&g, "creep", false)?,
                        };
                        if c == "Ig2_Sphere_Sphere_ScGeom6D" {
                            // one functor per shape pair: the later of the two sphere-sphere ones wins
                            il.sphere_sphere = None;
                            il.sphere_sphere_6d = Some(p);
                        } else {
                            il.gridnode_gridnode = Some(p);
                        }
                    }
                    "Ig2_Sphere_GridConnection_ScGridCoGeom" => {
                        il.sphere_gridco = Some(fo(&g, "interactionDetectionFactor", 1.0)?)
                    }
                    "Ig2_GridConnection_GridConnection_GridCoGridCoGeom" => il.gridco_gridco = true,
                    other => bail!("geometry functor '{}' is not supported by ryade yet", other),
                }
            }
            for p in e.get("phys").and_then(Value::as_array).cloned().unwrap_or_default() {
                match class(&p)? {
                    // this Ip2 and MindlinPhys's claim the same (FrictMat, FrictMat) cell: the
                    // later in the list replaces the other (`add2DEntry`)
                    "Ip2_FrictMat_FrictMat_FrictPhys" => {
                        il.frict_phys = true;
                        il.mindlin_phys = None;
                    }
                    "Ip2_CohFrictMat_CohFrictMat_CohFrictPhys" => {
                        for mm in ["normalCohesion", "shearCohesion", "frictAngle"] {
                            if p.get(mm).is_some_and(|x| !x.is_null()) {
                                bail!("Ip2_CohFrictMat_CohFrictMat_CohFrictPhys.{} (MatchMaker) is not supported by ryade yet", mm);
                            }
                        }
                        il.cohfrict_phys = Some(crate::phys::CohFrictIp2 {
                            set_cohesion_now: bo(&p, "setCohesionNow", false)?,
                            set_cohesion_on_new_contacts: bo(&p, "setCohesionOnNewContacts", false)?,
                            cohesion_definition_iteration: -1,
                        })
                    }
                    "Ip2_ViscElMat_ViscElMat_ViscElPhys" => {
                        il.viscel_ip2 = crate::phys::ViscElIp2 {
                            tc: match_maker(&p, "tc")?,
                            en: match_maker(&p, "en")?,
                            et: match_maker(&p, "et")?,
                            frict_angle: match_maker(&p, "frictAngle")?,
                        };
                        il.viscel_phys = true
                    }
                    "Ip2_LudingMat_LudingMat_LudingPhys" => il.luding_phys = true,
                    "Ip2_CpmMat_CpmMat_CpmPhys" => {
                        if p.get("E").is_some_and(|v| !v.is_null()) {
                            bail!("Ip2_CpmMat_CpmMat_CpmPhys.E (MatchMaker) is not supported by ryade yet");
                        }
                        il.cpm_phys = Some(fo(&p, "cohesiveThresholdIter", 10.0)? as i64)
                    }
                    "Ip2_FrictMat_CpmMat_FrictPhys" => {
                        if p.get("frictAngle").is_some_and(|v| !v.is_null()) {
                            bail!("Ip2_FrictMat_CpmMat_FrictPhys.frictAngle (MatchMaker) is not supported by ryade yet");
                        }
                        il.frict_cpm_phys = true
                    }
                    "Ip2_BubbleMat_BubbleMat_BubblePhys" => il.bubble_phys = true,
                    "Ip2_FrictMat_FrictMat_MindlinPhys" => {
                        // a number stands for a constant MatchMaker (algo 'val')
                        let opt = |k: &str| -> Result<Option<crate::phys::MatchMaker>> {
                            Ok(match p.get(k) {
                                None | Some(Value::Null) => None,
                                Some(v) if v.is_number() => Some(crate::phys::MatchMaker {
                                    matches: Vec::new(),
                                    algo: "val".into(),
                                    val: fo(&p, k, 0.0)?,
                                }),
                                Some(_) => match_maker(&p, k)?,
                            })
                        };
                        il.frict_phys = false;
                        il.mindlin_phys = Some(crate::phys::MindlinIp2 {
                            gamma: fo(&p, "gamma", 0.0)?,
                            eta: fo(&p, "eta", 0.0)?,
                            krot: fo(&p, "krot", 0.0)?,
                            ktwist: fo(&p, "ktwist", 0.0)?,
                            en: opt("en")?,
                            es: opt("es")?,
                            betan: opt("betan")?,
                            betas: opt("betas")?,
                            frict_angle: opt("frictAngle")?,
                        })
                    }
                    other => bail!("physics functor '{}' is not supported by ryade yet", other),
                }
            }
            for cb in e.get("callbacks").and_then(Value::as_array).cloned().unwrap_or_default() {
                match class(&cb)? {
                    "SumIntrForcesCb" => il.sum_intr_forces_cb.push(Default::default()),
                    other => bail!("InteractionLoop callback '{}' is not supported by ryade yet", other),
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
                    "Law2_ScGeom6D_CohFrictPhys_CohesionMoment" => {
                        il.cohesion_moment = Some(law::cohesion_moment::Params {
                            never_erase: bo(&l, "neverErase", false)?,
                            always_use_moment_law: bo(&l, "always_use_moment_law", false)?,
                            shear_creep: bo(&l, "shear_creep", false)?,
                            twist_creep: bo(&l, "twist_creep", false)?,
                            trace_energy: bo(&l, "traceEnergy", false)?,
                            use_incremental_form: bo(&l, "useIncrementalForm", false)?,
                            creep_viscosity: fo(&l, "creep_viscosity", 1.0)?,
                        })
                    }
                    "Law2_ScGridCoGeom_FrictPhys_CundallStrack" => {
                        il.scgridco_frict = Some(law::grid::ScGridCoParams {
                            never_erase: bo(&l, "neverErase", false)?,
                        })
                    }
                    "Law2_ScGridCoGeom_CohFrictPhys_CundallStrack" => {
                        il.scgridco_cohfrict = Some(law::grid::ScGridCoParams {
                            never_erase: bo(&l, "neverErase", false)?,
                        })
                    }
                    "Law2_GridCoGridCoGeom_FrictPhys_CundallStrack" => {
                        il.gridco_gridco_frict = Some(law::grid::GridCoGridCoParams {
                            never_erase: bo(&l, "neverErase", false)?,
                            spherical_bodies: bo(&l, "sphericalBodies", true)?,
                            trace_energy: bo(&l, "traceEnergy", false)?,
                        })
                    }
                    "Law2_ScGeom_ViscElPhys_Basic" => il.viscel_basic = true,
                    "Law2_ScGeom_LudingPhys_Basic" => il.luding_basic = true,
                    "Law2_ScGeom_CpmPhys_Cpm" => {
                        let d = law::cpm::Params::default();
                        il.cpm = Some(law::cpm::Params {
                            omega_threshold: fo(&l, "omegaThreshold", d.omega_threshold)?,
                            eps_soft: fo(&l, "epsSoft", d.eps_soft)?,
                            rel_kn_soft: fo(&l, "relKnSoft", d.rel_kn_soft)?,
                            yield_surf_type: fo(&l, "yieldSurfType", d.yield_surf_type as f64)? as i32,
                            yield_log_speed: fo(&l, "yieldLogSpeed", d.yield_log_speed)?,
                            yield_ellipse_shift: match l.get("yieldEllipseShift") {
                                None | Some(Value::Null) => f64::NAN,
                                Some(_) => f(&l, "yieldEllipseShift")?,
                            },
                        })
                    }
                    "Law2_ScGeom_BubblePhys_Bubble" => {
                        il.bubble = Some(law::bubble::Params {
                            pct_max_force: fo(&l, "pctMaxForce", 0.1)?,
                            surface_tension: fo(&l, "surfaceTension", 0.07197)?,
                            c1: 0.0,
                        })
                    }
                    "Law2_ScGeom_MindlinPhys_Mindlin" => {
                        if bo(&l, "calcEnergy", false)? {
                            bail!("Law2_ScGeom_MindlinPhys_Mindlin.calcEnergy is not supported by ryade yet");
                        }
                        il.mindlin = Some(law::mindlin::Params {
                            include_adhesion: bo(&l, "includeAdhesion", false)?,
                            include_moment: bo(&l, "includeMoment", false)?,
                            never_erase: bo(&l, "neverErase", false)?,
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
            exact_aspherical_rot: bo(e, "exactAsphericalRot", true)?,
            mask: fo(e, "mask", -1.0)? as i32,
            kin_split: bo(e, "kinSplit", false)?,
            ..Default::default()
        })),
        "TranslationEngine" | "RotationEngine" | "ServoPIDController" | "HelixEngine"
        | "InterpolatingHelixEngine" | "BicyclePedalEngine" => match kinematic_part(e, cls)? {
            KinematicPart::Translation(t) => Engine::Translation(Box::new(t)),
            KinematicPart::Rotation(r) => Engine::Rotation(Box::new(r)),
            KinematicPart::ServoPid(p) => Engine::ServoPid(Box::new(p)),
            KinematicPart::Helix(h) => Engine::Helix(Box::new(h)),
            k => Engine::Kinematic(Box::new(k)),
        },
        "InterpolatingDirectedForceEngine" => Engine::DirectedForce(Box::new(
            crate::force_engine::InterpolatingDirectedForceEngine {
                base: crate::force_engine::ForceEngine {
                    ids: ids(e)?,
                    force: vec3_or(e, "force", Vec3::zeros())?,
                },
                times: f64_list(e, "times")?,
                magnitudes: f64_list(e, "magnitudes")?,
                direction: vec3_or(e, "direction", Vec3::new(1.0, 0.0, 0.0))?,
                wrap: bo(e, "wrap", false)?,
                pos: fo(e, "_pos", 0.0)? as usize,
            },
        )),
        "ForceEngine" => Engine::Force(Box::new(crate::force_engine::ForceEngine {
            ids: ids(e)?,
            force: vec3_or(e, "force", Vec3::zeros())?,
        })),
        "HarmonicForceEngine" => Engine::HarmonicForce(Box::new(crate::force_engine::HarmonicForceEngine {
            ids: ids(e)?,
            a: vec3_or(e, "A", Vec3::zeros())?,
            f: vec3_or(e, "f", Vec3::zeros())?,
            fi: vec3_or(e, "fi", Vec3::zeros())?,
        })),
        "TriaxialStressController" | "TriaxialCompressionEngine" | "ThreeDTriaxialEngine" => {
            Engine::TriaxialStress(Box::new(
                crate::triax::TriaxialStressController::from_json(e).map_err(|m| anyhow!(m))?,
            ))
        }
        "HydroForceEngine" => Engine::Hydro(Box::new(
            crate::hydro::HydroForceEngine::from_json(e).map_err(|m| anyhow!(m))?,
        )),
        "CombinedKinematicEngine" => {
            let mut c = crate::kinematic::CombinedKinematicEngine {
                ids: ids(e)?,
                ..Default::default()
            };
            for p in e.get("comb").and_then(|v| v.as_array()).cloned().unwrap_or_default() {
                let pc = p.get("class").and_then(|v| v.as_str()).unwrap_or("");
                c.comb.push(kinematic_part(&p, pc)?);
                c.comb_dead.push(bo(&p, "dead", false)?);
            }
            Engine::CombinedKinematic(Box::new(c))
        }
        // a ryade extension (not a YADE class): the study's piston law, src/piston.rs
        "RyadePistonController" => Engine::Piston(Box::new(
            crate::piston::PistonController::from_json(e).map_err(|m| anyhow!(m))?,
        )),
        "PeriTriaxController" => Engine::PeriTriax(Box::new(peri_triax(e)?)),
        other => bail!("engine '{}' is not supported by ryade yet (supported: ForceResetter, InsertionSortCollider, InteractionLoop, NewtonIntegrator, GlobalStiffnessTimeStepper, TranslationEngine, RotationEngine, HelixEngine, CombinedKinematicEngine, ServoPIDController, ForceEngine, HarmonicForceEngine, PeriTriaxController, TriaxialStressController; ryade's own: RyadePistonController)", other),
    })
}

/// A kinematic engine of KinematicEngines.cpp (alone or a member of a `CombinedKinematicEngine`).
fn kinematic_part(e: &Value, cls: &str) -> Result<KinematicPart> {
    Ok(match cls {
        "TranslationEngine" => KinematicPart::Translation(crate::kinematic::TranslationEngine {
            ids: ids(e)?,
            velocity: fo(e, "velocity", 0.0)?,
            // taken as stored: YADE's postLoad normalisation already happened where the file was written
            translation_axis: vec3_or(e, "translationAxis", Vec3::zeros())?,
        }),
        "RotationEngine" => KinematicPart::Rotation(rotation(e)?),
        "ServoPIDController" => KinematicPart::ServoPid(crate::kinematic::ServoPid {
            ids: ids(e)?,
            axis: vec3_or(e, "axis", Vec3::zeros())?,
            target: fo(e, "target", 0.0)?,
            kp: fo(e, "kP", 0.0)?,
            ki: fo(e, "kI", 0.0)?,
            kd: fo(e, "kD", 0.0)?,
            i_term: fo(e, "iTerm", 0.0)?,
            cur_vel: fo(e, "curVel", 0.0)?,
            error_cur: fo(e, "errorCur", 0.0)?,
            error_prev: fo(e, "errorPrev", 0.0)?,
            max_velocity: fo(e, "maxVelocity", 0.0)?,
            iter_period: fo(e, "iterPeriod", 100.0)? as i64,
            iter_prev_start: fo(e, "iterPrevStart", -1.0)? as i64,
            ..Default::default()
        }),
        "HelixEngine" => KinematicPart::Helix(helix(e)?),
        "InterpolatingHelixEngine" => {
            KinematicPart::InterpolatingHelix(crate::kinematic::InterpolatingHelixEngine {
                helix: helix(e)?,
                times: f64_list(e, "times")?,
                angular_velocities: f64_list(e, "angularVelocities")?,
                wrap: bo(e, "wrap", false)?,
                slope: fo(e, "slope", 0.0)?,
                pos: fo(e, "_pos", 0.0)? as usize,
            })
        }
        "BicyclePedalEngine" => KinematicPart::BicyclePedal(crate::kinematic::BicyclePedalEngine {
            ids: ids(e)?,
            angular_velocity: fo(e, "angularVelocity", 0.0)?,
            rotation_axis: vec3_or(e, "rotationAxis", Vec3::new(1.0, 0.0, 0.0))?,
            radius: fo(e, "radius", -1.0)?,
            fi: fo(e, "fi", std::f64::consts::PI / 2.0)?,
        }),
        other => bail!("kinematic engine '{}' is not supported by ryade yet", other),
    })
}

/// A functor's MatchMaker attribute: `null`/missing, or `{"matches": [[id1, id2, value], ..], "algo": ..,
/// "val": ..}`.
fn match_maker(p: &Value, key: &str) -> Result<Option<crate::phys::MatchMaker>> {
    let Some(m) = p.get(key).filter(|x| !x.is_null()) else {
        return Ok(None);
    };
    let mut matches = Vec::new();
    for it in m
        .get("matches")
        .and_then(Value::as_array)
        .cloned()
        .unwrap_or_default()
    {
        let a = it.as_array().filter(|a| a.len() == 3).ok_or_else(|| {
            anyhow!(
                "{}.matches: each item must be [id1, id2, value], got {}",
                key,
                short(&it)
            )
        })?;
        let num = |x: &Value| {
            x.as_f64()
                .ok_or_else(|| anyhow!("{}.matches: not a number: {}", key, x))
        };
        matches.push((num(&a[0])? as i32, num(&a[1])? as i32, num(&a[2])?));
    }
    let algo = m
        .get("algo")
        .and_then(Value::as_str)
        .unwrap_or("avg")
        .to_string();
    if !["val", "zero", "avg", "min", "max", "harmAvg"].contains(&algo.as_str()) {
        bail!(
            "MatchMaker:: algo '{}' not recognized (possible values: val, avg, min, max, harmAvg).",
            algo
        );
    }
    let val = match m.get("val") {
        Some(Value::String(s)) if s == "nan" => f64::NAN,
        Some(v) if v.is_number() => v.as_f64().unwrap(),
        _ => f64::NAN,
    };
    Ok(Some(crate::phys::MatchMaker { matches, algo, val }))
}

/// A MatchMaker's JSON object (see `match_maker`).
pub fn match_maker_of(v: &Value) -> Result<crate::phys::MatchMaker> {
    let w = serde_json::json!({ "m": v });
    Ok(match_maker(&w, "m")?.expect("not null"))
}

fn match_maker_value(m: &Option<crate::phys::MatchMaker>) -> Value {
    use serde_json::json;
    match m {
        None => Value::Null,
        Some(m) => {
            json!({"matches": m.matches.iter().map(|x| json!([x.0, x.1, x.2])).collect::<Vec<_>>(),
            "algo": m.algo, "val": if m.val.is_nan() { json!("nan") } else { json!(m.val) }})
        }
    }
}

fn helix(e: &Value) -> Result<crate::kinematic::HelixEngine> {
    Ok(crate::kinematic::HelixEngine {
        rot: rotation(e)?,
        linear_velocity: fo(e, "linearVelocity", 0.0)?,
        angle_turned: fo(e, "angleTurned", 0.0)?,
    })
}

/// A list of numbers (missing: empty).
fn f64_list(e: &Value, key: &str) -> Result<Vec<f64>> {
    match e.get(key) {
        None | Some(Value::Null) => Ok(Vec::new()),
        Some(Value::Array(a)) => a
            .iter()
            .map(|x| {
                x.as_f64()
                    .ok_or_else(|| anyhow!("'{}' must hold numbers, got {}", key, x))
            })
            .collect(),
        Some(x) => bail!("'{}' must be a list of numbers, got {}", key, short(x)),
    }
}

fn rotation(e: &Value) -> Result<crate::kinematic::RotationEngine> {
    Ok(crate::kinematic::RotationEngine {
        ids: ids(e)?,
        angular_velocity: fo(e, "angularVelocity", 0.0)?,
        // taken as stored (normalised where the file was written, as for TranslationEngine)
        rotation_axis: vec3_or(e, "rotationAxis", Vec3::new(1.0, 0.0, 0.0))?,
        rotate_around_zero: bo(e, "rotateAroundZero", false)?,
        zero_point: vec3_or(e, "zeroPoint", Vec3::zeros())?,
    })
}

/// A kinematic engine's JSON (alone or as a member of a `CombinedKinematicEngine`).
fn kinematic_value(k: &KinematicPart) -> Value {
    use serde_json::json;
    let v3 = |v: &Vec3| json!([v[0], v[1], v[2]]);

    match k {
        KinematicPart::Rotation(r) => json!({"class": "RotationEngine", "ids": r.ids,
                "angularVelocity": r.angular_velocity, "rotationAxis": v3(&r.rotation_axis),
                "rotateAroundZero": r.rotate_around_zero, "zeroPoint": v3(&r.zero_point)}),
        KinematicPart::Translation(t) => {
            json!({"class": "TranslationEngine", "ids": t.ids, "velocity": t.velocity,
                "translationAxis": v3(&t.translation_axis)})
        }
        KinematicPart::ServoPid(p) => {
            json!({"class": "ServoPIDController", "ids": p.ids, "axis": v3(&p.axis), "target": p.target,
                "kP": p.kp, "kI": p.ki, "kD": p.kd, "iTerm": p.i_term, "curVel": p.cur_vel, "errorCur": p.error_cur,
                "errorPrev": p.error_prev, "maxVelocity": p.max_velocity, "iterPeriod": p.iter_period,
                "iterPrevStart": p.iter_prev_start})
        }
        KinematicPart::InterpolatingHelix(ih) => {
            let mut v = kinematic_value(&KinematicPart::Helix(ih.helix.clone()));
            v["class"] = json!("InterpolatingHelixEngine");
            v["times"] = json!(ih.times);
            v["angularVelocities"] = json!(ih.angular_velocities);
            v["wrap"] = json!(ih.wrap);
            v["slope"] = json!(ih.slope);
            v["_pos"] = json!(ih.pos);
            v
        }
        KinematicPart::BicyclePedal(b) => json!({"class": "BicyclePedalEngine", "ids": b.ids,
            "angularVelocity": b.angular_velocity, "rotationAxis": v3(&b.rotation_axis), "radius": b.radius,
            "fi": b.fi}),
        KinematicPart::Helix(h) => {
            let r = &h.rot;
            json!({"class": "HelixEngine", "ids": r.ids, "angularVelocity": r.angular_velocity,
                "rotationAxis": v3(&r.rotation_axis), "rotateAroundZero": r.rotate_around_zero,
                "zeroPoint": v3(&r.zero_point), "linearVelocity": h.linear_velocity, "angleTurned": h.angle_turned})
        }
    }
}

/// A number that may be NaN, written as `null` (JSON has no NaN); missing: `default`.
fn f_nan(v: &Value, key: &str, default: f64) -> Result<f64> {
    match v.get(key) {
        None => Ok(default),
        Some(Value::Null) => Ok(f64::NAN),
        Some(x) => x
            .as_f64()
            .ok_or_else(|| anyhow!("'{}' is neither a number nor null in {}", key, short(v))),
    }
}

/// NaN as `null`, any other double as a number.
fn nan_json(x: f64) -> Value {
    if x.is_nan() {
        Value::Null
    } else {
        serde_json::json!(x)
    }
}

/// A 3x3 matrix as three rows (FORMAT.md), or `default` when absent.
fn mat3_or(v: &Value, key: &str, default: Mat3) -> Result<Mat3> {
    let Some(rows) = v.get(key) else {
        return Ok(default);
    };
    let rows = rows
        .as_array()
        .filter(|r| r.len() == 3)
        .ok_or_else(|| anyhow!("'{}' must be 3 rows in {}", key, short(v)))?;
    let r: Vec<Vec3> = rows.iter().map(vec3_of).collect::<Result<_>>()?;
    Ok(Mat3::from_rows(&[
        r[0].transpose(),
        r[1].transpose(),
        r[2].transpose(),
    ]))
}

/// `{"class": "PeriTriaxController", ...}` (FORMAT.md): YADE's attributes with their 2023.02a
/// defaults, and the recorded doneHook firings (`doneHookEvents`) when the file carries them.
fn peri_triax(e: &Value) -> Result<crate::peri_triax::PeriTriax> {
    use crate::peri_triax::{HookEvent, HookSet, PeriTriax};
    let d = PeriTriax::default();
    let s = |key: &str| -> Result<String> {
        match e.get(key) {
            None => Ok(String::new()),
            Some(x) => x
                .as_str()
                .map(str::to_string)
                .ok_or_else(|| anyhow!("'{}' must be a string", key)),
        }
    };
    let mut p = PeriTriax {
        dyn_cell: bo(e, "dynCell", d.dyn_cell)?,
        goal: vec3_or(e, "goal", d.goal)?,
        stress_mask: int(e, "stressMask", d.stress_mask as i64)? as i32,
        max_strain_rate: vec3_or(e, "maxStrainRate", d.max_strain_rate)?,
        max_unbalanced: fo(e, "maxUnbalanced", d.max_unbalanced)?,
        abs_stress_tol: fo(e, "absStressTol", d.abs_stress_tol)?,
        rel_stress_tol: fo(e, "relStressTol", d.rel_stress_tol)?,
        grow_damping: fo(e, "growDamping", d.grow_damping)?,
        glob_update: int(e, "globUpdate", d.glob_update as i64)? as i32,
        done_hook: s("doneHook")?,
        max_body_span: vec3_or(e, "maxBodySpan", d.max_body_span)?,
        stress_tensor: mat3_or(e, "stressTensor", d.stress_tensor)?,
        stress: vec3_or(e, "stress", d.stress)?,
        strain: vec3_or(e, "strain", d.strain)?,
        strain_rate: vec3_or(e, "strainRate", d.strain_rate)?,
        stiff: vec3_or(e, "stiff", d.stiff)?,
        curr_unbalanced: f_nan(e, "currUnbalanced", d.curr_unbalanced)?,
        prev_grow: vec3_or(e, "prevGrow", d.prev_grow)?,
        mass: f_nan(e, "mass", d.mass)?,
        external_work: fo(e, "externalWork", d.external_work)?,
        ..d
    };
    if let Some(evs) = e.get("doneHookEvents") {
        let evs = evs
            .as_array()
            .ok_or_else(|| anyhow!("'doneHookEvents' must be an array"))?;
        p.replay_hooks = true;
        for ev in evs {
            let set = ev
                .get("set")
                .and_then(Value::as_object)
                .ok_or_else(|| anyhow!("doneHook event without 'set' object: {}", short(ev)))?;
            let mut sets = Vec::new();
            for (k, x) in set {
                let num = || {
                    x.as_f64()
                        .ok_or_else(|| anyhow!("doneHook event: '{}' is not a number", k))
                };
                let v3 = || vec3_of(x);
                sets.push(match k.as_str() {
                    "goal" => HookSet::Goal(v3()?),
                    "stressMask" => HookSet::StressMask(num()? as i32),
                    "maxStrainRate" => HookSet::MaxStrainRate(v3()?),
                    "maxUnbalanced" => HookSet::MaxUnbalanced(num()?),
                    "absStressTol" => HookSet::AbsStressTol(num()?),
                    "relStressTol" => HookSet::RelStressTol(num()?),
                    "growDamping" => HookSet::GrowDamping(num()?),
                    "globUpdate" => HookSet::GlobUpdate(num()? as i32),
                    "doneHook" => HookSet::DoneHook(
                        x.as_str()
                            .ok_or_else(|| anyhow!("doneHook event: 'doneHook' is not a string"))?
                            .to_string(),
                    ),
                    "dynCell" => HookSet::DynCell(
                        x.as_bool()
                            .ok_or_else(|| anyhow!("doneHook event: 'dynCell' is not a boolean"))?,
                    ),
                    "mass" => HookSet::Mass(if x.is_null() { f64::NAN } else { num()? }),
                    "dead" => HookSet::Dead(
                        x.as_bool()
                            .ok_or_else(|| anyhow!("doneHook event: 'dead' is not a boolean"))?,
                    ),
                    other => bail!("doneHook event sets '{}', which ryade cannot replay", other),
                });
            }
            p.hook_events.push_back(HookEvent {
                iter: int(ev, "iter", -1)?,
                hook: ev
                    .get("hook")
                    .and_then(Value::as_str)
                    .ok_or_else(|| anyhow!("doneHook event without 'hook' string"))?
                    .to_string(),
                set: sets,
            });
        }
    }
    Ok(p)
}

/// The scene-file object of a PeriTriaxController (NaN as null; remaining recorded firings kept).
fn peri_triax_value(p: &crate::peri_triax::PeriTriax) -> Value {
    use crate::peri_triax::HookSet;
    use serde_json::json;
    let v3 = |v: &Vec3| json!([v[0], v[1], v[2]]);
    let m = &p.stress_tensor;
    let mut out = json!({"class": "PeriTriaxController", "dynCell": p.dyn_cell, "goal": v3(&p.goal),
        "stressMask": p.stress_mask, "maxStrainRate": v3(&p.max_strain_rate), "maxUnbalanced": p.max_unbalanced,
        "absStressTol": p.abs_stress_tol, "relStressTol": p.rel_stress_tol, "growDamping": p.grow_damping,
        "globUpdate": p.glob_update, "doneHook": p.done_hook, "maxBodySpan": v3(&p.max_body_span),
        "stressTensor": [[m[(0, 0)], m[(0, 1)], m[(0, 2)]], [m[(1, 0)], m[(1, 1)], m[(1, 2)]], [m[(2, 0)], m[(2, 1)], m[(2, 2)]]],
        "stress": v3(&p.stress), "strain": v3(&p.strain), "strainRate": v3(&p.strain_rate), "stiff": v3(&p.stiff),
        "currUnbalanced": nan_json(p.curr_unbalanced), "prevGrow": v3(&p.prev_grow), "mass": nan_json(p.mass),
        "externalWork": p.external_work});
    if p.replay_hooks {
        let evs: Vec<Value> = p
            .hook_events
            .iter()
            .map(|ev| {
                let mut set = serde_json::Map::new();
                for s in &ev.set {
                    let (k, v) = match s {
                        HookSet::Goal(v) => ("goal", v3(v)),
                        HookSet::StressMask(m) => ("stressMask", json!(m)),
                        HookSet::MaxStrainRate(v) => ("maxStrainRate", v3(v)),
                        HookSet::MaxUnbalanced(x) => ("maxUnbalanced", json!(x)),
                        HookSet::AbsStressTol(x) => ("absStressTol", json!(x)),
                        HookSet::RelStressTol(x) => ("relStressTol", json!(x)),
                        HookSet::GrowDamping(x) => ("growDamping", json!(x)),
                        HookSet::GlobUpdate(n) => ("globUpdate", json!(n)),
                        HookSet::DoneHook(h) => ("doneHook", json!(h)),
                        HookSet::DynCell(b) => ("dynCell", json!(b)),
                        HookSet::Mass(m) => ("mass", nan_json(*m)),
                        HookSet::Dead(b) => ("dead", json!(b)),
                    };
                    set.insert(k.to_string(), v);
                }
                json!({"iter": ev.iter, "hook": ev.hook, "set": set})
            })
            .collect();
        out["doneHookEvents"] = Value::Array(evs);
    }
    out
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
                Shape::GridNode(n) => json!({"class": "GridNode", "radius": n.radius, "connections": n.conn_list}),
                Shape::GridConnection(c) => json!({"class": "GridConnection", "radius": c.radius,
                    "node1": c.node1, "node2": c.node2, "periodic": c.periodic, "cellDist": c.cell_dist}),
                Shape::Clump(c) => json!({"class": "Clump", "members": c.members.iter().map(|m| json!({
                    "id": m.id, "relPos": v3(&m.rel_pos),
                    "relOri": [m.rel_ori.w, m.rel_ori.x, m.rel_ori.y, m.rel_ori.z]})).collect::<Vec<_>>()}),
            };
            let m = &scene.materials[b.material[id]];
            let q = b.ori[id];
            let mut mat = json!({"id": m.id, "class": m.class_name(), "young": m.young, "poisson": m.poisson,
                             "frictionAngle": m.friction_angle, "density": m.density, "label": m.label});
            if let Some(c) = &m.coh {
                for (k, v) in [
                    ("isCohesive", json!(c.is_cohesive)),
                    ("alphaKr", json!(c.alpha_kr)),
                    ("alphaKtw", json!(c.alpha_ktw)),
                    ("etaRoll", json!(c.eta_roll)),
                    ("etaTwist", json!(c.eta_twist)),
                    ("normalCohesion", json!(c.normal_cohesion)),
                    ("shearCohesion", json!(c.shear_cohesion)),
                    ("fragile", json!(c.fragile)),
                    ("momentRotationLaw", json!(c.moment_rotation_law)),
                ] {
                    mat[k] = v;
                }
            }
            if let Some(st) = m.bubble {
                mat["surfaceTension"] = json!(st);
            }
            if let Some(c) = &m.cpm {
                let nn = |x: f64| if x.is_nan() { Value::Null } else { json!(x) };
                for (k, v) in [
                    ("sigmaT", nn(c.sigma_t)),
                    ("neverDamage", json!(c.never_damage)),
                    ("epsCrackOnset", nn(c.eps_crack_onset)),
                    ("relDuctility", nn(c.rel_ductility)),
                    ("equivStrainShearContrib", json!(c.equiv_strain_shear_contrib)),
                    ("damLaw", json!(c.dam_law)),
                    ("dmgTau", json!(c.dmg_tau)),
                    ("dmgRateExp", json!(c.dmg_rate_exp)),
                    ("plTau", json!(c.pl_tau)),
                    ("plRateExp", json!(c.pl_rate_exp)),
                    ("isoPrestress", json!(c.iso_prestress)),
                ] {
                    mat[k] = v;
                }
            }
            if let Some(l) = &m.luding {
                let nn = |x: f64| if x.is_nan() { Value::Null } else { json!(x) };
                for (k, x) in [
                    ("k1", l.k1),
                    ("kp", l.kp),
                    ("kc", l.kc),
                    ("ks", l.ks),
                    ("PhiF", l.phi_f),
                    ("G0", l.g0),
                    ("frictionAngle", m.friction_angle),
                ] {
                    mat[k] = nn(x);
                }
            }
            if let Some(v) = &m.viscel {
                let nn = |x: f64| if x.is_nan() { Value::Null } else { json!(x) };
                for (k, x) in [
                    ("tc", v.tc),
                    ("en", v.en),
                    ("et", v.et),
                    ("kn", v.kn),
                    ("cn", v.cn),
                    ("ks", v.ks),
                    ("cs", v.cs),
                ] {
                    mat[k] = nn(x);
                }
                mat["mR"] = json!(v.m_r);
                mat["mRtype"] = json!(v.m_r_type);
            }
            let mut body = json!({
                "id": id, "shape": shape,
                "material": mat,
                "mask": b.mask[id], "bounded": b.bounded[id],
                "pos": v3(&b.pos[id]), "vel": v3(&b.vel[id]), "angVel": v3(&b.ang_vel[id]),
                "ori": [q.w, q.x, q.y, q.z], "mass": b.mass[id], "inertia": v3(&b.inertia[id]),
                "blockedDOFs": b.blocked[id], "isDamped": b.is_damped[id],
            });
            // clump attributes only where they matter, so other scenes export as before
            if let Some(c) = b.clump_id[id] {
                body["clumpId"] = json!(c);
            }
            if b.is_clump(id) {
                body["material"] = Value::Null;
                body["aspherical"] = json!(b.aspherical[id]);
                body["angMom"] = v3(&b.ang_mom[id]);
            }
            body
        })
        .collect();
    let engines: Vec<Value> = scene
        .engines
        .iter()
        .map(|e| match e {
            Engine::ForceResetter => json!({"class": "ForceResetter"}),
            Engine::Bounds(f) => json!({"class": "BoundDispatcher", "bounds": bound_functors_json(f)}),
            Engine::Collider(c) => {
                let p = &c.p;
                let mut c = json!({"class": "InsertionSortCollider", "bounds": bound_functors_json(&p.bounds), "verletDist": p.verlet_dist,
                       "allowBiggerThanPeriod": p.allow_bigger_than_period, "targetInterv": p.target_interv,
                       "minSweepDistFactor": p.min_sweep_dist_factor, "sortAxis": p.sort_axis,
                       "sortThenCollide": p.sort_then_collide});
                if p.avoid_self_interaction_mask != 0 {
                    c["avoidSelfInteractionMask"] = json!(p.avoid_self_interaction_mask);
                }
                c
            }
            Engine::InteractionLoop(il) => {
                let mut geom = Vec::new();
                if let Some(g) = &il.sphere_sphere {
                    geom.push(json!({"class": "Ig2_Sphere_Sphere_ScGeom", "interactionDetectionFactor": g.interaction_detection_factor, "avoidGranularRatcheting": g.avoid_granular_ratcheting}));
                }
                if let Some(g) = &il.facet_sphere {
                    geom.push(json!({"class": "Ig2_Facet_Sphere_ScGeom", "shrinkFactor": g.shrink_factor, "hertzian": g.hertzian}));
                }
                if let Some(g) = &il.wall_sphere {
                    geom.push(json!({"class": "Ig2_Wall_Sphere_ScGeom", "noRatch": g.no_ratch, "hertzian": g.hertzian}));
                }
                if let Some(g) = &il.box_sphere {
                    let c = if g.six_d { "Ig2_Box_Sphere_ScGeom6D" } else { "Ig2_Box_Sphere_ScGeom" };
                    geom.push(json!({"class": c, "interactionDetectionFactor": g.interaction_detection_factor}));
                }
                let six_d = |c: &str, g: &geom::grid::SixDParams| json!({"class": c,
                    "interactionDetectionFactor": g.ss.interaction_detection_factor,
                    "avoidGranularRatcheting": g.ss.avoid_granular_ratcheting,
                    "updateRotations": g.update_rotations, "creep": g.creep});
                if let Some(g) = &il.sphere_sphere_6d {
                    geom.push(six_d("Ig2_Sphere_Sphere_ScGeom6D", g));
                }
                if let Some(g) = &il.gridnode_gridnode {
                    geom.push(six_d("Ig2_GridNode_GridNode_GridNodeGeom6D", g));
                }
                if let Some(f) = il.sphere_gridco {
                    geom.push(json!({"class": "Ig2_Sphere_GridConnection_ScGridCoGeom", "interactionDetectionFactor": f}));
                }
                if il.gridco_gridco {
                    geom.push(json!({"class": "Ig2_GridConnection_GridConnection_GridCoGridCoGeom"}));
                }
                let mut phys: Vec<Value> = Vec::new();
                if let Some(p) = &il.cohfrict_phys {
                    phys.push(json!({"class": "Ip2_CohFrictMat_CohFrictMat_CohFrictPhys",
                        "setCohesionNow": p.set_cohesion_now, "setCohesionOnNewContacts": p.set_cohesion_on_new_contacts}));
                }
                if il.frict_phys {
                    phys.push(json!({"class": "Ip2_FrictMat_FrictMat_FrictPhys"}));
                }
                if il.viscel_phys {
                    let mut f = json!({"class": "Ip2_ViscElMat_ViscElMat_ViscElPhys"});
                    let v = &il.viscel_ip2;
                    for (k, m) in [("tc", &v.tc), ("en", &v.en), ("et", &v.et), ("frictAngle", &v.frict_angle)] {
                        if m.is_some() {
                            f[k] = match_maker_value(m);
                        }
                    }
                    phys.push(f);
                }
                if il.luding_phys {
                    phys.push(json!({"class": "Ip2_LudingMat_LudingMat_LudingPhys"}));
                }
                if let Some(t) = il.cpm_phys {
                    phys.push(json!({"class": "Ip2_CpmMat_CpmMat_CpmPhys", "cohesiveThresholdIter": t}));
                }
                if il.frict_cpm_phys {
                    phys.push(json!({"class": "Ip2_FrictMat_CpmMat_FrictPhys"}));
                }
                if il.bubble_phys {
                    phys.push(json!({"class": "Ip2_BubbleMat_BubbleMat_BubblePhys"}));
                }
                if let Some(p) = &il.mindlin_phys {
                    phys.push(json!({"class": "Ip2_FrictMat_FrictMat_MindlinPhys", "gamma": p.gamma, "eta": p.eta,
                        "krot": p.krot, "ktwist": p.ktwist, "en": match_maker_value(&p.en), "es": match_maker_value(&p.es),
                        "betan": match_maker_value(&p.betan), "betas": match_maker_value(&p.betas),
                        "frictAngle": match_maker_value(&p.frict_angle)}));
                }
                let mut law: Vec<Value> = Vec::new();
                if let Some(l) = &il.cohesion_moment {
                    law.push(json!({"class": "Law2_ScGeom6D_CohFrictPhys_CohesionMoment", "neverErase": l.never_erase,
                        "always_use_moment_law": l.always_use_moment_law, "shear_creep": l.shear_creep,
                        "twist_creep": l.twist_creep, "traceEnergy": l.trace_energy,
                        "useIncrementalForm": l.use_incremental_form, "creep_viscosity": l.creep_viscosity}));
                }
                if let Some(l) = &il.cundall_strack {
                    law.push(json!({"class": "Law2_ScGeom_FrictPhys_CundallStrack", "neverErase": l.never_erase, "sphericalBodies": l.spherical_bodies}));
                }
                if let Some(l) = &il.scgridco_frict {
                    law.push(json!({"class": "Law2_ScGridCoGeom_FrictPhys_CundallStrack", "neverErase": l.never_erase}));
                }
                if let Some(l) = &il.scgridco_cohfrict {
                    law.push(json!({"class": "Law2_ScGridCoGeom_CohFrictPhys_CundallStrack", "neverErase": l.never_erase}));
                }
                if let Some(l) = &il.gridco_gridco_frict {
                    law.push(json!({"class": "Law2_GridCoGridCoGeom_FrictPhys_CundallStrack", "neverErase": l.never_erase,
                        "sphericalBodies": l.spherical_bodies, "traceEnergy": l.trace_energy}));
                }
                if il.viscel_basic {
                    law.push(json!({"class": "Law2_ScGeom_ViscElPhys_Basic"}));
                }
                if il.luding_basic {
                    law.push(json!({"class": "Law2_ScGeom_LudingPhys_Basic"}));
                }
                if let Some(c) = &il.cpm {
                    let nn = |x: f64| if x.is_nan() { Value::Null } else { json!(x) };
                    law.push(json!({"class": "Law2_ScGeom_CpmPhys_Cpm", "omegaThreshold": c.omega_threshold,
                        "epsSoft": c.eps_soft, "relKnSoft": c.rel_kn_soft, "yieldSurfType": c.yield_surf_type,
                        "yieldLogSpeed": c.yield_log_speed, "yieldEllipseShift": nn(c.yield_ellipse_shift)}));
                }
                if let Some(l) = &il.bubble {
                    law.push(json!({"class": "Law2_ScGeom_BubblePhys_Bubble", "pctMaxForce": l.pct_max_force,
                        "surfaceTension": l.surface_tension}));
                }
                if let Some(l) = &il.mindlin {
                    law.push(json!({"class": "Law2_ScGeom_MindlinPhys_Mindlin", "includeAdhesion": l.include_adhesion,
                        "includeMoment": l.include_moment, "neverErase": l.never_erase}));
                }
                let mut d = json!({"class": "InteractionLoop", "geom": geom, "phys": phys, "law": law});
                if !il.sum_intr_forces_cb.is_empty() {
                    d["callbacks"] = json!(il
                        .sum_intr_forces_cb
                        .iter()
                        .map(|_| json!({"class": "SumIntrForcesCb"}))
                        .collect::<Vec<_>>());
                }
                d
            }
            Engine::Newton(n) => {
                let mut e = json!({"class": "NewtonIntegrator", "damping": n.damping, "gravity": v3(&n.gravity), "dampGravity": n.damp_gravity, "mask": n.mask});
                if !n.exact_aspherical_rot {
                    e["exactAsphericalRot"] = json!(false);
                }
                if n.kin_split {
                    e["kinSplit"] = json!(true);
                }
                e
            }
            Engine::TimeStepper(t) => json!({"class": "GlobalStiffnessTimeStepper", "active": t.active,
                "timeStepUpdateInterval": t.time_step_update_interval, "defaultDt": t.default_dt,
                "maxDt": t.max_dt, "timestepSafetyCoefficient": t.timestep_safety_coefficient}),
            Engine::Rotation(r) => kinematic_value(&KinematicPart::Rotation((**r).clone())),
            Engine::Translation(t) => kinematic_value(&KinematicPart::Translation((**t).clone())),
            Engine::ServoPid(p) => kinematic_value(&KinematicPart::ServoPid((**p).clone())),
            Engine::Helix(h) => kinematic_value(&KinematicPart::Helix((**h).clone())),
            Engine::Force(f) => json!({"class": "ForceEngine", "ids": f.ids, "force": v3(&f.force)}),
            Engine::HarmonicForce(h) => json!({"class": "HarmonicForceEngine", "ids": h.ids, "A": v3(&h.a),
                "f": v3(&h.f), "fi": v3(&h.fi)}),
            Engine::TriaxialStress(t) => t.to_json(),
            Engine::Hydro(h) => h.to_json(),
            Engine::Kinematic(k) => kinematic_value(k),
            Engine::DirectedForce(f) => json!({"class": "InterpolatingDirectedForceEngine", "ids": f.base.ids,
                "force": v3(&f.base.force), "times": f.times, "magnitudes": f.magnitudes,
                "direction": v3(&f.direction), "wrap": f.wrap, "_pos": f.pos}),
            Engine::CombinedKinematic(c) => {
                let comb: Vec<Value> = c.comb.iter().zip(&c.comb_dead).map(|(p, &dead)| {
                    let mut v = kinematic_value(p);
                    v["dead"] = json!(dead);
                    v
                }).collect();
                json!({"class": "CombinedKinematicEngine", "ids": c.ids, "comb": comb})
            }
            Engine::Piston(p) => p.to_json(),
            Engine::PeriTriax(p) => peri_triax_value(p),
            // a Python-side engine (PyRunner...): the file records its place; loading it needs the runner
            Engine::External(id) => json!({"class": "External", "id": id}),
        })
        .collect();
    let grid = uses_grid_format(scene);
    let mut out = json!({
        "format": if grid { GRID_FORMAT_ID } else { FORMAT_ID }, "source": "ryade", "steps": steps, "dt": scene.dt,
        "periodic": scene.cell.is_some(), "bodies": bodies, "engines": engines,
    });
    if grid {
        out["interactions"] = Value::Array(
            scene
                .interactions
                .list
                .iter()
                .map(interaction_to_value)
                .collect(),
        );
    }
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

/// Whether a scene needs the grid extension of the format (FORMAT_GRID.md) to be written.
fn uses_grid_format(scene: &Scene) -> bool {
    let b = &scene.bodies;
    (0..b.len()).any(|id| matches!(b.shape[id], Shape::GridNode(_) | Shape::GridConnection(_)))
        || scene.materials.iter().any(|m| m.coh.is_some())
        || scene.interactions.list.iter().any(|i| i.ext.is_some())
        || scene.engines.iter().any(|e| match e {
            Engine::InteractionLoop(il) => {
                il.sphere_sphere_6d.is_some()
                    || il.gridnode_gridnode.is_some()
                    || il.sphere_gridco.is_some()
                    || il.gridco_gridco
                    || il.cohfrict_phys.is_some()
                    || il.cohesion_moment.is_some()
                    || il.scgridco_frict.is_some()
                    || il.scgridco_cohfrict.is_some()
                    || il.gridco_gridco_frict.is_some()
            }
            Engine::Collider(c) => c.p.bounds.grid_connection,
            _ => false,
        })
}

/// One interaction in the `interactions` array format (the inverse of `interaction`).
pub fn interaction_to_value(it: &Interaction) -> Value {
    use serde_json::json;
    let v3 = |v: &Vec3| json!([v[0], v[1], v[2]]);
    let q4 = |q: &Quat| json!([q.w, q.x, q.y, q.z]);
    let geom = match &it.geom {
        None => Value::Null,
        Some(g) => {
            let cls = it.geom_class().unwrap();
            let mut d = json!({"class": cls.name(), "normal": v3(&g.normal), "penetrationDepth": g.pen,
                "contactPoint": v3(&g.contact_point), "shearInc": v3(&g.shear_inc),
                "refR1": g.radius1, "refR2": g.radius2});
            if let Some(e) = it.geom_ext() {
                if let Some(r) = e.rot() {
                    d["initialOrientation1"] = q4(&r.initial_orientation1);
                    d["initialOrientation2"] = q4(&r.initial_orientation2);
                    d["twistCreep"] = q4(&r.twist_creep);
                    d["twist"] = json!(r.twist);
                    d["bending"] = v3(&r.bending);
                }
                match e {
                    GeomExt::GridNode {
                        connection_body, ..
                    } => {
                        d["connectionBody"] = json!(connection_body.map_or(-1, |x| x as i64));
                    }
                    GeomExt::ScGridCo(x) => {
                        d["isDuplicate"] = json!(x.is_duplicate);
                        d["trueInt"] = json!(x.true_int);
                        d["id3"] = json!(x.id3);
                        d["id4"] = json!(x.id4);
                        d["id5"] = json!(x.id5);
                        d["weight"] = v3(&x.weight);
                        d["relPos"] = json!(x.rel_pos);
                    }
                    GeomExt::GridCoGridCo(x) => {
                        d["relPos1"] = json!(x.rel_pos1);
                        d["relPos2"] = json!(x.rel_pos2);
                    }
                    GeomExt::Sc6D(_) => {}
                }
            }
            d
        }
    };
    let phys = match &it.phys {
        None => Value::Null,
        Some(p) => {
            let cls = if it.coh().is_some() {
                "CohFrictPhys"
            } else if it.viscel().is_some() {
                "ViscElPhys"
            } else {
                "FrictPhys"
            };
            let mut d = json!({"class": cls,
                "kn": p.kn, "ks": p.ks, "tangensOfFrictionAngle": p.tan_phi,
                "normalForce": v3(&p.normal_force), "shearForce": v3(&p.shear_force)});
            if let Some(c) = it.coh() {
                for (k, v) in [
                    ("kr", json!(c.kr)),
                    ("ktw", json!(c.ktw)),
                    ("cohesionBroken", json!(c.cohesion_broken)),
                    ("fragile", json!(c.fragile)),
                    ("initCohesion", json!(c.init_cohesion)),
                    ("normalAdhesion", json!(c.normal_adhesion)),
                    ("shearAdhesion", json!(c.shear_adhesion)),
                    ("unp", json!(c.unp)),
                    ("unpMax", json!(c.unp_max)),
                    ("momentRotationLaw", json!(c.moment_rotation_law)),
                    ("maxRollPl", json!(c.max_roll_pl)),
                    ("maxTwistPl", json!(c.max_twist_pl)),
                    ("moment_twist", v3(&c.moment_twist)),
                    ("moment_bending", v3(&c.moment_bending)),
                    (
                        "cohesionDisablesFriction",
                        json!(c.cohesion_disables_friction),
                    ),
                    ("creep_viscosity", json!(c.creep_viscosity)),
                ] {
                    d[k] = v;
                }
            }
            if let Some(v) = it.viscel() {
                for (k, x) in [
                    ("cn", json!(v.cn)),
                    ("cs", json!(v.cs)),
                    ("Fn", json!(v.fn_el)),
                    ("Fv", json!(v.fv)),
                    ("mR", json!(v.m_r)),
                    ("mRtype", json!(v.m_r_type)),
                ] {
                    d[k] = x;
                }
            }
            d
        }
    };
    json!({"id1": it.id1, "id2": it.id2, "isReal": it.is_real(), "cellDist": it.cell_dist,
        "iterMadeReal": it.iter_made_real, "iterBorn": it.iter_born, "geom": geom, "phys": phys})
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `Ip2_FrictMat_FrictMat_FrictPhys` and `Ip2_FrictMat_FrictMat_MindlinPhys` claim the same
    /// (FrictMat, FrictMat) cell: the later one in the list takes the FrictMat pairs, as YADE's
    /// dispatcher (`add2DEntry`) does, whichever comes first.
    #[test]
    fn the_later_of_two_ip2s_for_one_cell_wins() {
        use crate::material::MatClass::{CohFrictMat, FrictMat};
        use crate::scene::PhysFunctor;
        let (fr, mi) = (
            "Ip2_FrictMat_FrictMat_FrictPhys",
            "Ip2_FrictMat_FrictMat_MindlinPhys",
        );
        for (first, second, want) in [(fr, mi, PhysFunctor::Mindlin), (mi, fr, PhysFunctor::Frict)]
        {
            let e = serde_json::json!({
                "class": "InteractionLoop",
                "geom": [{"class": "Ig2_Sphere_Sphere_ScGeom"}],
                "phys": [{"class": first}, {"class": second}],
                "law": [{"class": "Law2_ScGeom_FrictPhys_CundallStrack"}],
            });
            let Engine::InteractionLoop(il) = engine(&e).unwrap() else {
                panic!("not an InteractionLoop")
            };
            for (a, b) in [(FrictMat, FrictMat), (FrictMat, CohFrictMat)] {
                let got = il.phys_functor(a, b).unwrap().map(|(f, _)| f);
                assert_eq!(got, Some(want), "{first} then {second}: {a:?} + {b:?}");
            }
        }
    }
}
