//! Where the harness finds its helpers: the repository, the Python with the `yade` compat package and
//! the running `compat` binary. One place, so that `compat study`, `diff rXX`, `gap`, `calibrate` and
//! `bench` resolve them alike.

use anyhow::{Context, Result};
use std::ffi::OsString;
use std::path::{Path, PathBuf};

/// The repository (for yade_ref/ scripts): `RYADE_ROOT`, else the source tree this binary was built from.
pub fn repo_root() -> PathBuf {
    std::env::var_os("RYADE_ROOT")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")))
}

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
