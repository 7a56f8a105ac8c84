//! The files the user commands run (`study`, `gap`, `calibrate`, `bench` scenes), built into the
//! binary so that an installed `compat` works from any folder, with its checkout moved or deleted.
//! They are written once per build to a cache folder (`$RYADE_CACHE`, else `$XDG_CACHE_HOME/ryade`,
//! else `~/.cache/ryade`, else the temp dir), keeping their paths relative to the repository, since
//! the scripts find each other that way (`yade_ref/gap/run_case.py` runs `../study/study.py`).

use anyhow::{Context, Result};
use sha2::{Digest, Sha256};
use std::path::{Path, PathBuf};

macro_rules! embed {
    ($($p:literal),* $(,)?) => {
        &[$(($p, include_bytes!(concat!(env!("CARGO_MANIFEST_DIR"), "/", $p)) as &[u8])),*]
    };
}

/// (path relative to the repository, content)
pub const FILES: &[(&str, &[u8])] = embed!(
    "yade_ref/study/study.py",
    "yade_ref/gap/run_case.py",
    "yade_ref/calibration/calib_common.py",
    "yade_ref/calibration/tensile.py",
    "yade_ref/calibration/cantilever.py",
    "yade_ref/calibration/triaxial.py",
    "yade_ref/bench/run_scene.py",
    "yade_ref/bench/timed_run.py",
    "bench/scenes/dense8000.scene.json",
    "bench/scenes/r03_N_small.study.json",
    "bench/scenes/r03_N_small_s1.specimen.json",
    "bench/scenes/r05_G_medium.study.json",
    "bench/scenes/r05_G_medium_s1.specimen.json",
    "bench/scenes/r05_G_full_paper200.study.json",
    "bench/scenes/r05_G_full_paper200_s1.specimen.json",
    "bench/scenes/r05_N_medium_paper200.study.json",
    "bench/scenes/r05_N_medium_paper200_s1.specimen.json",
);

/// Marker written last: a folder without it is incomplete (an interrupted write) and is redone.
const COMPLETE: &str = ".complete";

fn cache_base() -> PathBuf {
    let env = |k: &str| {
        std::env::var_os(k)
            .filter(|v| !v.is_empty())
            .map(PathBuf::from)
    };
    env("RYADE_CACHE")
        .or_else(|| env("XDG_CACHE_HOME").map(|p| p.join("ryade")))
        .or_else(|| env("HOME").map(|p| p.join(".cache").join("ryade")))
        .unwrap_or_else(|| std::env::temp_dir().join("ryade-cache"))
}

/// A short digest of every embedded path and content (one folder per distinct set).
fn digest() -> String {
    let mut h = Sha256::new();
    for (p, c) in FILES {
        h.update(p.as_bytes());
        h.update((c.len() as u64).to_le_bytes());
        h.update(c);
    }
    h.finalize()[..8]
        .iter()
        .map(|b| format!("{:02x}", b))
        .collect()
}

/// The folder holding the embedded files (written on first use).
pub fn root() -> Result<PathBuf> {
    root_in(&cache_base())
}

fn root_in(base: &Path) -> Result<PathBuf> {
    let dir = base.join(format!("assets-{}", digest()));
    if dir.join(COMPLETE).is_file() {
        return Ok(dir);
    }
    std::fs::create_dir_all(base).with_context(|| format!("creating {}", base.display()))?;
    let tmp = base.join(format!(".assets-{}-{}", digest(), std::process::id()));
    let _ = std::fs::remove_dir_all(&tmp);
    write_all(&tmp)
        .with_context(|| format!("writing the built-in scripts to {}", tmp.display()))?;
    if std::fs::rename(&tmp, &dir).is_err() {
        // another compat finished first (or an incomplete folder is in the way)
        let _ = std::fs::remove_dir_all(&tmp);
        if !dir.join(COMPLETE).is_file() {
            let _ = std::fs::remove_dir_all(&dir);
            write_all(&dir)
                .with_context(|| format!("writing the built-in scripts to {}", dir.display()))?;
        }
    }
    Ok(dir)
}

fn write_all(dir: &Path) -> Result<()> {
    for (p, c) in FILES {
        let f = dir.join(p);
        std::fs::create_dir_all(f.parent().unwrap())?;
        std::fs::write(&f, c)?;
    }
    std::fs::write(dir.join(COMPLETE), b"")?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn written_files_equal_the_checkout_and_a_second_call_reuses_them() {
        let tmp = std::env::temp_dir().join(format!("ryade-assets-test-{}", std::process::id()));
        let d = root_in(&tmp).unwrap();
        assert!(d.starts_with(&tmp));
        let t0 = std::fs::metadata(d.join(FILES[0].0))
            .unwrap()
            .modified()
            .unwrap();
        assert_eq!(root_in(&tmp).unwrap(), d);
        let t1 = std::fs::metadata(d.join(FILES[0].0))
            .unwrap()
            .modified()
            .unwrap();
        assert_eq!(t0, t1, "the second call reuses the folder");
        for (p, _) in FILES {
            let want = std::fs::read(Path::new(env!("CARGO_MANIFEST_DIR")).join(p)).unwrap();
            assert_eq!(std::fs::read(d.join(p)).unwrap(), want, "{}", p);
        }
        std::fs::remove_dir_all(&tmp).ok();
    }
}
