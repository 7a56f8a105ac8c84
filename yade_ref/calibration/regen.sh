#!/usr/bin/env bash
# Regenerate the calibration goldens with the installed YADE 2023.02a (one thread).
#   yade_ref/calibration/regen.sh [OUTDIR]   (default: golden/calibration)
# Writes OUTDIR/tensile.csv, OUTDIR/tensile.summary.json, OUTDIR/cantilever.json and OUTDIR/triaxial_quick/
# (triaxial.py --quick for plain, roll0.5, clump3: curves and summaries).
# About 50 s of CPU in all (tensile ~2 s, cantilever ~40 s, triaxial ~6 s).
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
OUT="${1:-$HERE/../../golden/calibration}"
mkdir -p "$OUT"; OUT="$(cd "$OUT" && pwd)"
command -v yade >/dev/null 2>&1 || { echo "error: 'yade' not found (apt-get install -y --no-install-recommends yade)" >&2; exit 3; }
export OMP_NUM_THREADS=1 OMP_WAIT_POLICY=PASSIVE
quiet() { grep -vE '^(Welcome to Yade|Using python version|TCP python prompt|XMLRPC info provider|Running script)' || true; }
yade -n -x "$HERE/tensile.py" "out=\"$OUT/tensile.csv\"" "summary=\"$OUT/tensile.summary.json\"" 2>&1 | quiet
yade -n -x "$HERE/cantilever.py" "out=\"$OUT/cantilever.json\"" 2>&1 | quiet
yade -n -x "$HERE/triaxial.py" -- --quick --variant plain,roll0.5,clump3 --out "$OUT/triaxial_quick" 2>&1 | quiet | grep -v '^\[triaxial .*\] \(compaction\|consolidation\|shear\):' || true
