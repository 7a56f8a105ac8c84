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
python3 -m maturin --version >/dev/null 2>&1 || python3 -m pip install maturin
# Profile-guided build of the package (RYADE_PGO=0 skips it): an instrumented build runs a short
# training (the study's r05 G medium scene for one load cycle on the fast path and on the
# YADE-order path, 300 steps of the dense packing), and the package is then built with that
# profile. Same results to the bit (the profile changes code layout and inlining, not arithmetic);
# the study's and the dense scenes run about 5 % faster (bench/README.md, session 31). Any failure
# falls back to the plain build. The instrumented build and the profile stay in compat/target/pgo.
pgo_dir="$PWD/compat/target/pgo"
compat_bin="${CARGO_INSTALL_ROOT:-${CARGO_HOME:-$HOME/.cargo}}/bin/compat"
pgo_profile() {
  local host sysroot profdata rc
  host=$(rustc -vV | sed -n 's/^host: //p')
  sysroot=$(rustc --print sysroot)
  profdata="$sysroot/lib/rustlib/$host/bin/llvm-profdata"
  if [ ! -x "$profdata" ] && command -v rustup >/dev/null 2>&1; then
    echo "== adding rustup's llvm-tools component (llvm-profdata, for the profile-guided build; up to 5 min)"
    timeout 300 rustup component add llvm-tools-preview && rc=0 || rc=$?
    [ "$rc" = 124 ] && echo "rustup timed out after 300 s"
  fi
  [ -x "$profdata" ] || { echo "no llvm-profdata in $sysroot (rustup component add llvm-tools-preview)"; return 1; }
  [ -x "$compat_bin" ] || { echo "no $compat_bin"; return 1; }
  echo "== profile-guided build 1/3: instrumented build of the yade package (a few minutes)"
  rm -rf "$pgo_dir/raw" "$pgo_dir/pkg" "$pgo_dir/out" "$pgo_dir/ryade.profdata"
  (cd compat && RUSTFLAGS="${RUSTFLAGS:-} -Cprofile-generate=$pgo_dir/raw" \
    CARGO_TARGET_DIR="$pgo_dir/target" cargo build --release) || return 1
  rm -rf "$pgo_dir/raw"
  mkdir -p "$pgo_dir/pkg"
  cp -r compat/python/yade "$pgo_dir/pkg/" || return 1
  cp "$pgo_dir/target/release/lib_ryade.so" "$pgo_dir/pkg/yade/_ryade.abi3.so" || return 1
  echo "== profile-guided build 2/3: training runs (about a minute)"
  local study=(yade_ref/study/study.py --import-specimen bench/scenes/r05_G_medium_s1.specimen.json
    --cycles 1 --controller native)
  PYTHONPATH="$pgo_dir/pkg" RYADE_FAST=on "$compat_bin" run "${study[@]}" --out "$pgo_dir/out/fast" \
    >/dev/null || return 1
  env -u RYADE_FAST PYTHONPATH="$pgo_dir/pkg" "$compat_bin" run "${study[@]}" --out "$pgo_dir/out/yo" \
    >/dev/null || return 1
  PYTHONPATH="$pgo_dir/pkg" "$compat_bin" run --fast yade_ref/bench/run_scene.py \
    bench/scenes/dense8000.scene.json 300 20 >/dev/null || return 1
  "$profdata" merge -o "$pgo_dir/ryade.profdata" "$pgo_dir"/raw/*.profraw || return 1
}
install_package() {
  echo "== building and installing the yade Python package (compat layer) into $(command -v python3)"
  # -v: pip shows maturin's cargo build as it goes
  python3 -m pip install -v --no-build-isolation ./compat
}
if [ "${RYADE_PGO:-1}" != "0" ] && pgo_profile; then
  echo "== profile-guided build 3/3: the yade package built with the profile"
  if ! RUSTFLAGS="${RUSTFLAGS:-} -Cprofile-use=$pgo_dir/ryade.profdata" install_package; then
    echo "note: the profile-guided build failed; building the plain package"
    install_package
  fi
else
  [ "${RYADE_PGO:-1}" != "0" ] && echo "note: profile-guided build skipped (see above); building the plain package"
  install_package
fi
command -v compat >/dev/null 2>&1 || echo "note: add ~/.cargo/bin to PATH to call 'compat' directly"
echo "== done: try 'compat study --size tiny' (any folder)"
