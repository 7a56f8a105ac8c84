#!/usr/bin/env bash
# Run every reference script of yade_ref/{micro,meso,pack,export,energy} UNCHANGED under `compat run` (ryade's
# YADE-compatible Python layer) and require the files it writes to equal YADE's goldens
# (decompressed content, byte for byte).
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/.." && pwd)"
COMPAT="${COMPAT:-$ROOT/target/release/compat}"
TMP="$(mktemp -d "${TMPDIR:-/tmp}/ryade_check_compat.XXXXXX")"
trap 'rm -rf "$TMP"' EXIT
content() { case "$1" in *.gz) gzip -dc -- "$1" ;; *) cat -- "$1" ;; esac; }
bad=0; n=0
for kind in micro meso pack export energy examples; do
  mkdir -p "$TMP/$kind"
  for s in "$HERE/$kind"/*.py; do
    [[ $kind == examples ]] && break
    name="$(basename "$s" .py)"
    t0=$(date +%s.%N)
    if ! "$COMPAT" run "$s" "$TMP/$kind" >"$TMP/$kind.$name.log" 2>&1; then
      echo "FAILED   $kind/$name.py under compat run:"; tail -n 15 "$TMP/$kind.$name.log"; bad=1; continue
    fi
    printf '%-6s %-14s %6.2fs\n' "$kind" "$name" "$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN{print b-a}')"
  done
  if [[ $kind == examples ]]; then
    if [[ ! -d "${YADE_EXAMPLES:-/usr/share/doc/yade/examples}" && "${CI:-}" != "true" ]]; then
      echo "SKIPPED  examples/ (YADE's example scripts are not installed here; CI installs them)"; continue
    fi
    "$HERE/examples/run_all.sh" compat "$TMP/examples" || bad=1
  fi
  for g in "$ROOT/golden/$kind"/*; do
    f="$(basename "$g")"; t="$TMP/$kind/$f"; n=$((n + 1))
    if [[ ! -f "$t" ]]; then echo "MISSING  $kind/$f (not written under compat run)"; bad=1
    elif cmp -s <(content "$g") <(content "$t"); then :
    else echo "DIFFERS  $kind/$f"; bad=1; fi
  done
done
# the study (r05 tiny seed 1, cases N, F, G: generation + 5 load cycles) and the tensile calibration
for case in N F G; do
  d="$TMP/study_$case"; n=$((n + 2))
  if ! "$COMPAT" run "$HERE/study/study.py" -- --ratio 0.5 --case $case --size tiny --seed 1 --out "$d" >"$TMP/study_$case.log" 2>&1; then
    echo "FAILED   study r05 $case under compat run:"; tail -n 15 "$TMP/study_$case.log"; bad=1; continue
  fi
  for f in history.csv profile.csv; do
    cmp -s "$ROOT/golden/study/r05_${case}_tiny_s1/$f" "$d/$f" && echo "OK       study r05_${case} $f" || { echo "DIFFERS  study r05_${case} $f"; bad=1; }
  done
done
# YADE's ServoPIDController as the study's piston controller (2 cycles on the committed N specimen)
d="$TMP/study_servopid"; g="$ROOT/golden/study/servopid_r05_N_tiny_s1_c2"; n=$((n + 3))
if "$COMPAT" run "$HERE/study/study.py" -- --import-specimen "$ROOT/golden/study/r05_N_tiny_s1/specimen.json" --cycles 2 \
    --controller servopid --out "$d" >"$TMP/study_servopid.log" 2>&1; then
  for f in history.csv steps.csv profile.csv; do
    cmp -s "$g/$f" "$d/$f" && echo "OK       study servopid $f" || { echo "DIFFERS  study servopid $f"; bad=1; }
  done
else echo "FAILED   study --controller servopid under compat run:"; tail -n 15 "$TMP/study_servopid.log"; bad=1; fi
mkdir -p "$TMP/calib"; n=$((n + 2))
if "$COMPAT" run "$HERE/calibration/tensile.py" "out=\"$TMP/calib/tensile.csv\"" "summary=\"$TMP/calib/tensile.summary.json\"" >"$TMP/calib.log" 2>&1; then
  for f in tensile.csv tensile.summary.json; do
    cmp -s "$ROOT/golden/calibration/$f" "$TMP/calib/$f" && echo "OK       calibration $f" || { echo "DIFFERS  calibration $f"; bad=1; }
  done
else echo "FAILED   calibration/tensile.py under compat run"; tail -n 15 "$TMP/calib.log"; bad=1; fi
# the periodic triaxial element test (PeriTriaxController, rolling resistance, clumps), quick version
mkdir -p "$TMP/triax"; n=$((n + 6))
if "$COMPAT" run "$HERE/calibration/triaxial.py" -- --quick --variant plain,roll0.5,clump3 --out "$TMP/triax" >"$TMP/triax.log" 2>&1; then
  for f in {plain,roll0.5,clump3}.{curve.csv,summary.json}; do
    cmp -s "$ROOT/golden/calibration/triaxial_quick/$f" "$TMP/triax/$f" && echo "OK       calibration triaxial_quick/$f" || { echo "DIFFERS  calibration triaxial_quick/$f"; bad=1; }
  done
else echo "FAILED   calibration/triaxial.py --quick under compat run"; tail -n 15 "$TMP/triax.log"; bad=1; fi
if [[ $bad -ne 0 ]]; then echo "check_compat: FAILED ($n golden files)"; exit 1; fi
echo "check_compat: all $n golden files reproduced by compat run"
