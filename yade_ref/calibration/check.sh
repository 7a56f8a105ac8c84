#!/usr/bin/env bash
# Regenerate the calibration goldens into a temporary directory and compare them byte for byte with
# golden/calibration. Prints OK / DIFFERS / MISSING per file; exits non-zero on any difference.
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
GOLD="$(cd "$HERE/../../golden/calibration" && pwd)"
TMP="$(mktemp -d "${TMPDIR:-/tmp}/ryade_calib_check.XXXXXX")"
trap 'rm -rf "$TMP"' EXIT
"$HERE/regen.sh" "$TMP" >/dev/null
bad=0
for f in tensile.csv tensile.summary.json cantilever.json triaxial_quick/{plain,roll0.5,clump3}.{curve.csv,summary.json}; do
    if [[ ! -f "$TMP/$f" || ! -f "$GOLD/$f" ]]; then echo "MISSING  $f"; bad=1
    elif cmp -s "$GOLD/$f" "$TMP/$f"; then echo "OK       $f"
    else echo "DIFFERS  $f"; bad=1; fi
done
exit $bad
