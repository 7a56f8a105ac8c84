#!/usr/bin/env bash
# Regenerate the study goldens with the installed YADE 2023.02a (one thread):
#   yade_ref/study/golden.sh [OUTROOT]      (default OUTROOT: golden/study)
# writes OUTROOT/r05_{N,F,G}_tiny_s1/{history.csv,profile.csv,steps.csv,specimen.json,summary.json,yade.log}.
# Everything except summary.json (wall/cpu times) and yade.log is deterministic: YADE with one thread
# and the same seed is bit-identical run to run. The three runs take ~2 min on a quiet 2-core machine.
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
OUT="${1:-$ROOT/golden/study}"
export OMP_NUM_THREADS=1 OMP_WAIT_POLICY=PASSIVE
command -v yade >/dev/null || { echo "error: yade not found (apt-get install -y --no-install-recommends yade)" >&2; exit 3; }
for c in N F G; do
    d="$OUT/r05_${c}_tiny_s1"
    mkdir -p "$d"
    echo "== r05 $c tiny seed 1 -> $d"
    yade -n -x "$HERE/study.py" -- --ratio 0.5 --case "$c" --size tiny --seed 1 --out "$d" \
        --export-specimen "$d/specimen.json" </dev/null 2>&1 | grep -a -v -e '^TCP python prompt' -e '^XMLRPC info' > "$d/yade.log"
    grep -a '^\[study\]' "$d/yade.log"
done
