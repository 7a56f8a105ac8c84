#!/usr/bin/env bash
# Install everything a fresh Debian machine needs for ryade: Debian's YADE (the reference engine),
# the `compat` command (into ~/.cargo/bin) and the `yade` Python package (into python3). Each build
# runs once and shows its progress. `compat` carries the scripts and bench scenes its commands run, so
# it works from any folder, also after this checkout is moved or deleted.
set -euo pipefail
cd "$(dirname "$0")"
SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
if ! command -v yade >/dev/null 2>&1; then
  echo "== installing Debian's yade (reference engine for the golden files)"
  $SUDO apt-get update
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends yade
fi
if ! command -v cargo >/dev/null 2>&1; then
  echo "cargo not found: install the Rust toolchain (https://rustup.rs) and re-run" >&2
  exit 1
fi
python3 -m pip --version >/dev/null 2>&1 || { echo "python3 with pip is required" >&2; exit 1; }
echo "== building and installing the compat command into ~/.cargo/bin (release build, a few minutes the first time)"
cargo install --path . --locked
echo "== building and installing the yade Python package (compat layer) into $(command -v python3)"
python3 -m maturin --version >/dev/null 2>&1 || python3 -m pip install maturin
# -v: pip shows maturin's cargo build as it goes
python3 -m pip install -v --no-build-isolation ./compat
command -v compat >/dev/null 2>&1 || echo "note: add ~/.cargo/bin to PATH to call 'compat' directly"
echo "== done: try 'compat study --size tiny' (any folder)"
