#!/usr/bin/env bash
# Regenerate the study goldens with the installed YADE 2023.02a (one thread per run):
#   yade_ref/study/golden.sh [-j JOBS] [OUTROOT] [CASE_SPEC ...]
# CASE_SPEC is r<RR>_<C>_tiny_s<S> (e.g. r05_G_tiny_s2); default: every ratio (03 05 07) x case (N F G)
# x seed (1 2 3) at tiny size, i.e. the 27 runs that `compat diff rXX` and CI's band check use.
# Each writes OUTROOT/<spec>/{history.csv,profile.csv,steps.csv,specimen.json,summary.json,yade.log}.
# Everything except summary.json (wall/cpu times) and yade.log is deterministic: YADE with one thread
# and the same seed is bit-identical run to run. CPU cost per run: r07 ~15 s, r05 ~25 s, r03 ~3.5 min.
# STUDY_EXTRA adds study.py options to every run, e.g. the preset goldens (golden/study_paper200):
#   STUDY_EXTRA="--preset paper200" yade_ref/study/golden.sh -j 2 golden/study_paper200 r05_N_medium_s1 ...
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
JOBS=1
if [ "${1:-}" = "-j" ]; then JOBS="$2"; shift 2; fi
OUT="${1:-$ROOT/golden/study}"
shift || true
export OMP_NUM_THREADS=1 OMP_WAIT_POLICY=PASSIVE
command -v yade >/dev/null || { echo "error: yade not found (apt-get install -y --no-install-recommends yade)" >&2; exit 3; }
SPECS=("$@")
if [ ${#SPECS[@]} -eq 0 ]; then
    for r in 05 07 03; do for s in 1 2 3; do for c in N F G; do SPECS+=("r${r}_${c}_tiny_s${s}"); done; done; done
fi
one() {
    local spec="$1" out="$2" here="$3"
    [[ "$spec" =~ ^r([0-9]{2})_([NFG])_(tiny|small|medium|full)_s([0-9]+)$ ]] || { echo "bad case spec '$spec' (want r05_G_tiny_s1)" >&2; return 2; }
    local ratio="0.${BASH_REMATCH[1]#0}" case="${BASH_REMATCH[2]}" size="${BASH_REMATCH[3]}" seed="${BASH_REMATCH[4]}"
    [ "${BASH_REMATCH[1]}" = "10" ] && ratio=1.0
    local d="$out/$spec"
    mkdir -p "$d"
    yade -n -x "$here/study.py" -- --ratio "$ratio" --case "$case" --size "$size" --seed "$seed" --out "$d" \
        --export-specimen "$d/specimen.json" ${STUDY_EXTRA:-} </dev/null 2>&1 | grep -a -v -e '^TCP python prompt' -e '^XMLRPC info' > "$d/yade.log"
    echo "== $spec: $(grep -a '^\[study\] cycle' "$d/yade.log" | tail -1)"
}
export -f one
printf '%s\n' "${SPECS[@]}" | xargs -P "$JOBS" -I{} bash -c 'one "$@"' _ {} "$OUT" "$HERE"
