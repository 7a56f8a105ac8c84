#!/usr/bin/env bash
# Install everything a fresh Debian machine needs for ryade, then build and install `compat`.
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
echo "== building ryade (release)"
cargo build --release --locked 2>/dev/null || cargo build --release
echo "== installing the yade Python package (compat layer) into $(command -v python3)"
python3 -m pip --version >/dev/null 2>&1 || { echo "python3 with pip is required" >&2; exit 1; }
python3 -m maturin --version >/dev/null 2>&1 || python3 -m pip install -q maturin
python3 -m pip install -q --no-build-isolation ./compat
echo "== installing the compat command into ~/.cargo/bin"
cargo install --path . --locked --quiet 2>/dev/null || cargo install --path . --quiet
command -v compat >/dev/null 2>&1 || echo "note: add ~/.cargo/bin to PATH to call 'compat' directly"
