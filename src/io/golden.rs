//! Golden per-step records (`*.bodies.csv.gz`, `*.intrs.csv.gz`, FORMAT.md): reading, and writing
//! the same format from ryade so both engines' outputs can be compared with one tool.

use crate::math::Vec3;
use crate::scene::Scene;
use anyhow::{anyhow, bail, Context, Result};
use flate2::read::GzDecoder;
use std::io::{BufRead, BufReader, Read, Write};
use std::path::Path;

pub const BODY_COLS: [&str; 19] = [
    "pos_x", "pos_y", "pos_z", "vel_x", "vel_y", "vel_z", "angVel_x", "angVel_y", "angVel_z",
    "ori_w", "ori_x", "ori_y", "ori_z", "f_x", "f_y", "f_z", "t_x", "t_y", "t_z",
];
pub const INTR_COLS: [&str; 18] = [
    "normal_x",
    "normal_y",
    "normal_z",
    "pen",
    "cp_x",
    "cp_y",
    "cp_z",
    "shearInc_x",
    "shearInc_y",
    "shearInc_z",
    "fn_x",
    "fn_y",
    "fn_z",
    "fs_x",
    "fs_y",
    "fs_z",
    "kn",
    "ks",
];

/// Columns of `*.intrs6d.csv.gz` after `step,ord,id1,id2` (golden/FORMAT_GRID.md): the ScGeom6D
/// rotations, the CohFrictPhys moments/state and the ScGridCoGeom duplicate state; `nan` where the
/// interaction's class has no such field.
pub const INTR6D_COLS: [&str; 15] = [
    "twist",
    "bending_x",
    "bending_y",
    "bending_z",
    "mtw_x",
    "mtw_y",
    "mtw_z",
    "mb_x",
    "mb_y",
    "mb_z",
    "unp",
    "cohesionBroken",
    "relPos",
    "isDuplicate",
    "trueInt",
];

#[derive(Clone, Debug, PartialEq)]
pub struct Intr6dRow {
    pub step: u64,
    pub ord: u32,
    pub id1: u32,
    pub id2: u32,
    pub v: [f64; 15],
}

#[derive(Clone, Debug, PartialEq)]
pub struct BodyRow {
    pub step: u64,
    pub id: u32,
    pub v: [f64; 19],
}

#[derive(Clone, Debug, PartialEq)]
pub struct IntrRow {
    pub step: u64,
    pub ord: u32,
    pub id1: u32,
    pub id2: u32,
    pub v: [f64; 18],
}

fn open_text(path: &Path) -> Result<Box<dyn BufRead>> {
    let file = std::fs::File::open(path).with_context(|| format!("opening {}", path.display()))?;
    let r: Box<dyn Read> = if path.extension().is_some_and(|e| e == "gz") {
        Box::new(GzDecoder::new(file))
    } else {
        Box::new(file)
    };
    Ok(Box::new(BufReader::new(r)))
}

fn parse_rows<const N: usize>(
    path: &Path,
    key_cols: &[&str],
    cols: &[&str; N],
) -> Result<Vec<(Vec<u64>, [f64; N])>> {
    let mut rdr = csv::ReaderBuilder::new()
        .has_headers(true)
        .from_reader(open_text(path)?);
    let header = rdr
        .headers()
        .with_context(|| format!("reading header of {}", path.display()))?
        .clone();
    let expect: Vec<&str> = key_cols.iter().chain(cols.iter()).copied().collect();
    let got: Vec<&str> = header.iter().collect();
    if got != expect {
        bail!(
            "{}: unexpected columns {:?}; expected {:?} (see golden/FORMAT.md)",
            path.display(),
            got,
            expect
        );
    }
    let mut out = Vec::new();
    for (line, rec) in rdr.records().enumerate() {
        let rec = rec.with_context(|| {
            format!(
                "{}: malformed CSV at data line {}",
                path.display(),
                line + 1
            )
        })?;
        if rec.len() != expect.len() {
            bail!(
                "{}: line {} has {} fields, expected {}",
                path.display(),
                line + 2,
                rec.len(),
                expect.len()
            );
        }
        let mut keys = Vec::with_capacity(key_cols.len());
        for (k, name) in key_cols.iter().enumerate() {
            keys.push(rec[k].parse::<u64>().map_err(|_| {
                anyhow!(
                    "{}: line {}: '{}' is not an integer in column {}",
                    path.display(),
                    line + 2,
                    &rec[k],
                    name
                )
            })?);
        }
        let mut v = [0.0; N];
        for (i, x) in v.iter_mut().enumerate() {
            let s = &rec[key_cols.len() + i];
            *x = s.parse::<f64>().map_err(|_| {
                anyhow!(
                    "{}: line {}: '{}' is not a number in column {}",
                    path.display(),
                    line + 2,
                    s,
                    cols[i]
                )
            })?;
        }
        out.push((keys, v));
    }
    Ok(out)
}

/// Columns of `<scene>.peri.csv.gz` (digest scenes with a PeriTriaxController, FORMAT.md).
pub const PERI_COLS: [&str; 17] = [
    "hSize_xx",
    "hSize_yy",
    "hSize_zz",
    "velGrad_xx",
    "velGrad_yy",
    "velGrad_zz",
    "stress_x",
    "stress_y",
    "stress_z",
    "strain_x",
    "strain_y",
    "strain_z",
    "stiff_x",
    "stiff_y",
    "stiff_z",
    "currUnbalanced",
    "externalWork",
];

/// `<scene>.peri.csv.gz`: (step, values in PERI_COLS order).
pub fn read_peri(path: &Path) -> Result<Vec<(u64, [f64; 17])>> {
    Ok(parse_rows(path, &["step"], &PERI_COLS)?
        .into_iter()
        .map(|(k, v)| (k[0], v))
        .collect())
}

/// The PERI_COLS values of the scene (cell diagonal and its first PeriTriaxController), or None
/// without a cell or controller.
pub fn peri_values(scene: &Scene) -> Option<[f64; 17]> {
    let c = scene.cell.as_ref()?;
    let p = scene.engines.iter().find_map(|e| match e {
        crate::scene::Engine::PeriTriax(p) => Some(p),
        _ => None,
    })?;
    let mut v = Vec::with_capacity(17);
    v.extend_from_slice(&[c.hsize[(0, 0)], c.hsize[(1, 1)], c.hsize[(2, 2)]]);
    v.extend_from_slice(&[c.vel_grad[(0, 0)], c.vel_grad[(1, 1)], c.vel_grad[(2, 2)]]);
    push3(&mut v, &p.stress);
    push3(&mut v, &p.strain);
    push3(&mut v, &p.stiff);
    v.push(p.curr_unbalanced);
    v.push(p.external_work);
    v.try_into().ok()
}

/// `<scene>.digest.csv.gz` (digest scenes): step -> [bodies, intrs, cell] digests.
pub fn read_step_digests(path: &Path) -> Result<std::collections::BTreeMap<u64, [String; 3]>> {
    use std::io::Read;
    let f = std::fs::File::open(path).with_context(|| format!("opening {}", path.display()))?;
    let mut text = String::new();
    flate2::read::GzDecoder::new(f)
        .read_to_string(&mut text)
        .with_context(|| format!("decompressing {}", path.display()))?;
    let mut out = std::collections::BTreeMap::new();
    for (i, line) in text.lines().enumerate() {
        if i == 0 {
            if line != "step,bodies,intrs,cell" {
                bail!(
                    "{}: expected header 'step,bodies,intrs,cell'",
                    path.display()
                );
            }
            continue;
        }
        let f: Vec<&str> = line.split(',').collect();
        if f.len() != 4 {
            bail!(
                "{}: line {} has {} fields, expected 4",
                path.display(),
                i + 1,
                f.len()
            );
        }
        let step = f[0]
            .parse::<u64>()
            .map_err(|_| anyhow!("{}: line {}: bad step '{}'", path.display(), i + 1, f[0]))?;
        out.insert(step, [f[1].to_string(), f[2].to_string(), f[3].to_string()]);
    }
    Ok(out)
}

/// Little-endian bytes of doubles with every NaN written as the quiet NaN 0x7ff8000000000000 (the
/// sign and payload of a NaN depend on how it was made; the recorder does the same).
fn put_doubles(out: &mut Vec<u8>, vals: &[f64]) {
    for &x in vals {
        let x = if x.is_nan() {
            f64::from_bits(0x7ff8_0000_0000_0000)
        } else {
            x
        };
        out.extend_from_slice(&x.to_le_bytes());
    }
}

/// First 16 hex digits of the SHA-256 of `data`.
fn digest16(data: &[u8]) -> String {
    use sha2::{Digest, Sha256};
    Sha256::digest(data)
        .iter()
        .take(8)
        .map(|b| format!("{:02x}", b))
        .collect()
}

/// The three step digests of a digest scene (FORMAT.md): bodies (19 doubles each, id order), real
/// interactions (id1, id2 as int64 and the 18 INTR_COLS doubles, container order), cell (hSize,
/// trsf, velGrad, prevVelGrad row by row, then each PeriTriaxController's state in engine order).
/// Also returns how many doubles went into them.
pub fn step_digests(scene: &Scene) -> ([String; 3], u64) {
    let mut n = 0u64;
    let mut b = Vec::new();
    for id in 0..scene.bodies.len() {
        put_doubles(&mut b, &body_values(scene, id));
        n += 19;
    }
    let mut i = Vec::new();
    for (a, c, v) in intr_values(scene) {
        i.extend_from_slice(&(a as i64).to_le_bytes());
        i.extend_from_slice(&(c as i64).to_le_bytes());
        put_doubles(&mut i, &v);
        n += 20;
    }
    let mut c = Vec::new();
    if let Some(cell) = &scene.cell {
        for m in [&cell.hsize, &cell.trsf, &cell.vel_grad, &cell.prev_vel_grad] {
            for r in 0..3 {
                put_doubles(&mut c, &[m[(r, 0)], m[(r, 1)], m[(r, 2)]]);
            }
        }
        n += 36;
        for e in &scene.engines {
            if let crate::scene::Engine::PeriTriax(p) = e {
                let v = p.digest_values();
                n += v.len() as u64;
                put_doubles(&mut c, &v);
            }
        }
    }
    ([digest16(&b), digest16(&i), digest16(&c)], n)
}

pub fn read_bodies(path: &Path) -> Result<Vec<BodyRow>> {
    Ok(parse_rows(path, &["step", "id"], &BODY_COLS)?
        .into_iter()
        .map(|(k, v)| BodyRow {
            step: k[0],
            id: k[1] as u32,
            v,
        })
        .collect())
}

pub fn read_intrs(path: &Path) -> Result<Vec<IntrRow>> {
    Ok(
        parse_rows(path, &["step", "ord", "id1", "id2"], &INTR_COLS)?
            .into_iter()
            .map(|(k, v)| IntrRow {
                step: k[0],
                ord: k[1] as u32,
                id1: k[2] as u32,
                id2: k[3] as u32,
                v,
            })
            .collect(),
    )
}

pub fn read_intrs6d(path: &Path) -> Result<Vec<Intr6dRow>> {
    Ok(
        parse_rows(path, &["step", "ord", "id1", "id2"], &INTR6D_COLS)?
            .into_iter()
            .map(|(k, v)| Intr6dRow {
                step: k[0],
                ord: k[1] as u32,
                id1: k[2] as u32,
                id2: k[3] as u32,
                v,
            })
            .collect(),
    )
}

/// The `intrs6d` values of the real interactions in container order (INTR6D_COLS order).
pub fn intr6d_values(scene: &Scene) -> Vec<(u32, u32, [f64; 15])> {
    use crate::geom::GeomExt;
    let mut out = Vec::new();
    for it in &scene.interactions.list {
        if !it.is_real() {
            continue;
        }
        let mut v = [f64::NAN; 15];
        if let Some(r) = it.geom_ext().and_then(|g| g.rot()) {
            v[0] = r.twist;
            v[1..4].copy_from_slice(&[r.bending[0], r.bending[1], r.bending[2]]);
        }
        if let Some(c) = it.coh() {
            v[4..7].copy_from_slice(&[c.moment_twist[0], c.moment_twist[1], c.moment_twist[2]]);
            v[7..10].copy_from_slice(&[
                c.moment_bending[0],
                c.moment_bending[1],
                c.moment_bending[2],
            ]);
            v[10] = c.unp;
            v[11] = if c.cohesion_broken { 1.0 } else { 0.0 };
        }
        if let Some(GeomExt::ScGridCo(x)) = it.geom_ext() {
            v[12] = x.rel_pos;
            v[13] = x.is_duplicate as f64;
            v[14] = x.true_int as f64;
        }
        out.push((it.id1, it.id2, v));
    }
    out
}

/// Format an `intrs6d` cell as YADE's recorder does: integers for the flag/id columns, `nan` for
/// missing values, `%.17g` otherwise.
fn cell6d(col: usize, x: f64) -> String {
    if x.is_nan() {
        "nan".into()
    } else if col == 11 || col == 13 || col == 14 {
        format!("{}", x as i64)
    } else {
        g17(x)
    }
}

fn push3(out: &mut Vec<f64>, v: &Vec3) {
    out.extend_from_slice(&[v[0], v[1], v[2]]);
}

/// The 19 recorded values of one body, in BODY_COLS order.
pub fn body_values(scene: &Scene, id: usize) -> [f64; 19] {
    let b = &scene.bodies;
    let mut v = Vec::with_capacity(19);
    push3(&mut v, &b.pos[id]);
    push3(&mut v, &b.vel[id]);
    push3(&mut v, &b.ang_vel[id]);
    let q = b.ori[id];
    v.extend_from_slice(&[q.w, q.x, q.y, q.z]);
    let w = scene.forces.ft.get(id).copied().unwrap_or_default();
    push3(&mut v, &w.f);
    push3(&mut v, &w.t);
    v.try_into().unwrap()
}

/// Real interactions in container order: (id1, id2, values in INTR_COLS order).
pub fn intr_values(scene: &Scene) -> Vec<(u32, u32, [f64; 18])> {
    let mut out = Vec::new();
    for it in &scene.interactions.list {
        if let (Some(g), Some(p)) = (&it.geom, &it.phys) {
            let mut v = Vec::with_capacity(18);
            push3(&mut v, &g.normal);
            v.push(g.pen);
            push3(&mut v, &g.contact_point);
            push3(&mut v, &g.shear_inc);
            push3(&mut v, &p.normal_force);
            push3(&mut v, &p.shear_force);
            v.push(p.kn);
            v.push(p.ks);
            out.push((it.id1, it.id2, v.try_into().unwrap()));
        }
    }
    out
}

/// Format a double as C's `%.17g` (what the YADE recorder writes).
pub fn g17(x: f64) -> String {
    if x == 0.0 {
        return if x.is_sign_negative() {
            "-0".into()
        } else {
            "0".into()
        };
    }
    if !x.is_finite() {
        return if x.is_nan() {
            "nan".into()
        } else if x > 0.0 {
            "inf".into()
        } else {
            "-inf".into()
        };
    }
    let e = format!("{:.16e}", x);
    let (mant, exp) = e.split_once('e').unwrap();
    let exp: i32 = exp.parse().unwrap();
    if (-4..17).contains(&exp) {
        let decimals = (16 - exp).max(0) as usize;
        let s = format!("{:.*}", decimals, x);
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    } else {
        let m = if mant.contains('.') {
            mant.trim_end_matches('0').trim_end_matches('.')
        } else {
            mant
        };
        format!("{}e{}{:02}", m, if exp < 0 { '-' } else { '+' }, exp.abs())
    }
}

/// Writes the per-step records of a ryade run in the golden format, flushing every step so that a
/// run stopped by an error keeps everything recorded before it.
pub struct Recorder {
    bodies: Box<dyn Write>,
    intrs: Box<dyn Write>,
    /// `*.intrs6d.csv`, written for scenes that use the grid extension.
    intrs6d: Option<Box<dyn Write>>,
}

impl Recorder {
    pub fn create(dir: &Path, name: &str) -> Result<Recorder> {
        Recorder::create_with(dir, name, false)
    }

    /// As `create`, plus `<name>.intrs6d.csv` when `grid`.
    pub fn create_with(dir: &Path, name: &str, grid: bool) -> Result<Recorder> {
        std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
        let open = |suffix: &str| -> Result<Box<dyn Write>> {
            let p = dir.join(format!("{}.{}", name, suffix));
            Ok(Box::new(std::io::BufWriter::new(
                std::fs::File::create(&p).with_context(|| format!("creating {}", p.display()))?,
            )))
        };
        let mut r = Recorder {
            bodies: open("bodies.csv")?,
            intrs: open("intrs.csv")?,
            intrs6d: if grid {
                Some(open("intrs6d.csv")?)
            } else {
                None
            },
        };
        writeln!(r.bodies, "step,id,{}", BODY_COLS.join(","))?;
        writeln!(r.intrs, "step,ord,id1,id2,{}", INTR_COLS.join(","))?;
        if let Some(w) = r.intrs6d.as_mut() {
            writeln!(w, "step,ord,id1,id2,{}", INTR6D_COLS.join(","))?;
        }
        Ok(r)
    }

    pub fn record(&mut self, scene: &Scene) -> Result<()> {
        let step = scene.iter;
        for id in 0..scene.bodies.len() {
            let v = body_values(scene, id);
            let cells: Vec<String> = v.iter().map(|x| g17(*x)).collect();
            writeln!(self.bodies, "{},{},{}", step, id, cells.join(","))?;
        }
        for (ord, (a, b, v)) in intr_values(scene).into_iter().enumerate() {
            let cells: Vec<String> = v.iter().map(|x| g17(*x)).collect();
            writeln!(
                self.intrs,
                "{},{},{},{},{}",
                step,
                ord,
                a,
                b,
                cells.join(",")
            )?;
        }
        if let Some(w) = self.intrs6d.as_mut() {
            for (ord, (a, b, v)) in intr6d_values(scene).into_iter().enumerate() {
                let cells: Vec<String> = v.iter().enumerate().map(|(c, x)| cell6d(c, *x)).collect();
                writeln!(w, "{},{},{},{},{}", step, ord, a, b, cells.join(","))?;
            }
            w.flush()?;
        }
        self.bodies.flush()?;
        self.intrs.flush()?;
        Ok(())
    }
}

#[cfg(test)]
#[allow(clippy::excessive_precision)]
mod tests {
    use super::g17;
    #[test]
    fn g17_matches_c_printf() {
        // values and their C printf("%.17g") renderings
        for (x, s) in [
            (1e-5, "1.0000000000000001e-05"),
            (0.1, "0.10000000000000001"),
            (100000.0, "100000"),
            (-9.9999999999999396, "-9.9999999999999396"),
            (133333.33333333334, "133333.33333333334"),
            (1e17, "1e+17"),
            (123456789012345678.0, "1.2345678901234568e+17"),
            (0.0001, "0.0001"),
            (2.5, "2.5"),
        ] {
            assert_eq!(g17(x), s, "for {:e}", x);
            assert_eq!(g17(x).parse::<f64>().unwrap().to_bits(), x.to_bits());
        }
    }
}
