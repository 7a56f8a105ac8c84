//! Where the harness finds its helpers: the repository, the Python with the `yade` compat package and
//! the running `compat` binary. One place, so that `compat study`, `diff rXX`, `gap`, `calibrate` and
//! `bench` resolve them alike.

use anyhow::{Context, Result};
use std::ffi::OsString;
use std::path::{Path, PathBuf};

/// Where the YADE scripts the commands run (yade_ref/study/study.py, ...) and the bench scenes come
/// from: `RYADE_ROOT` if set (`builtin`: the built-in copies), else the checkout this binary was built from while it still exists (so
/// an edit there takes effect without a rebuild), else the copies built into the binary (`assets`), so
/// an installed `compat` works from any folder with its checkout moved or deleted.
pub fn repo_root() -> Result<PathBuf> {
    match std::env::var_os("RYADE_ROOT") {
        // the built-in copies even where the build checkout exists
        Some(r) if r == "builtin" => return super::assets::root(),
        Some(r) => return Ok(PathBuf::from(r)),
        None => {}
    }
    let built = Path::new(env!("CARGO_MANIFEST_DIR"));
    if super::assets::FILES
        .iter()
        .all(|(p, _)| built.join(p).is_file())
    {
        return Ok(built.to_path_buf());
    }
    super::assets::root()
}

/// A ryade checkout with the goldens (golden/...): `RYADE_ROOT`, else the checkout this binary was
/// built from if it still exists. None when neither is there.
pub fn checkout_root() -> Option<PathBuf> {
    let r = std::env::var_os("RYADE_ROOT")
        .filter(|r| r != "builtin")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")));
    r.join("golden").is_dir().then_some(r)
}

/// The line that tells a user how to point a validation command at the goldens.
pub const GOLDEN_HINT: &str = "the goldens are in a ryade checkout: run from it, give --golden DIR, or set RYADE_ROOT=/path/to/ryade";

/// The Python that has the `yade` compat package installed (`RYADE_PYTHON`, default `python3`).
pub fn python() -> OsString {
    std::env::var_os("RYADE_PYTHON").unwrap_or_else(|| "python3".into())
}

/// The running `compat` binary, to start `compat run` children. `/proc/self/exe` keeps working when
/// the binary is rebuilt during a long sweep (current_exe() then names a deleted file).
pub fn compat_exe() -> Result<PathBuf> {
    if Path::new("/proc/self/exe").exists() {
        Ok(PathBuf::from("/proc/self/exe"))
    } else {
        std::env::current_exe().context("locating the compat executable")
    }
}
