#!/usr/bin/env bash
# Regenerate the grid goldens (golden/FORMAT_GRID.md) with the installed YADE 2023.02a.
#   yade_ref/micro_grid/regen.sh OUTDIR            -> OUTDIR/<scene>.{scene.json,bodies,intrs,intrs6d.csv.gz}
#   yade_ref/micro_grid/regen.sh golden/micro_grid -> refresh the committed grid goldens in place
# Every script runs as `yade -n -x <script> <outdir>` with one thread (OMP_NUM_THREADS=1); the scripts run
# in parallel (RYADE_REGEN_JOBS, default: number of CPUs). Exit status non-zero if any script failed.
set -euo pipefail
shopt -s nullglob

usage() { echo "usage: $0 OUTDIR" >&2; exit 2; }
[[ $# -eq 1 && -n "$1" ]] || usage

if ! command -v yade >/dev/null 2>&1; then
    echo "error: 'yade' not found. Install Debian YADE 2023.02a with:" >&2
    echo "    apt-get install -y --no-install-recommends yade" >&2
    exit 3
fi

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
OUT="$1"
mkdir -p "$OUT"
OUT="$(cd "$OUT" && pwd)"

export OMP_NUM_THREADS=1
export OMP_WAIT_POLICY=PASSIVE
JOBS="${RYADE_REGEN_JOBS:-$(nproc 2>/dev/null || echo 1)}"
[[ "$JOBS" =~ ^[1-9][0-9]*$ ]] || JOBS=1

LOGDIR="$(mktemp -d "${TMPDIR:-/tmp}/ryade_regen_grid_logs.XXXXXX")"
cleanup() { rm -rf "$LOGDIR"; }
trap cleanup EXIT

scripts=("$HERE"/*.py)
[[ ${#scripts[@]} -gt 0 ]] || { echo "error: no scripts in $HERE" >&2; exit 1; }

run_one() {  # path
    local path="$1" name; name="$(basename "$path" .py)"
    local log="$LOGDIR/$name.log" t0 t1 rc=0
    t0=$(date +%s.%N)
    yade -n -x "$path" "$OUT" >"$log" 2>&1 </dev/null || rc=$?
    t1=$(date +%s.%N)
    echo "$rc" >"$LOGDIR/$name.rc"
    printf 'micro_grid %-14s rc=%d %6.1fs  %s\n' "$name" "$rc" "$(awk -v a="$t0" -v b="$t1" 'BEGIN{print b-a}')" \
        "$(grep -a '\[ryade_record\] .*done' "$log" | tail -1 | sed 's/.*done //')"
}

T0=$(date +%s.%N)
running=0
for s in "${scripts[@]}"; do
    run_one "$s" &
    running=$((running + 1))
    if (( running >= JOBS )); then wait -n || true; running=$((running - 1)); fi
done
wait || true
T1=$(date +%s.%N)

fail=0
for s in "${scripts[@]}"; do
    name="$(basename "$s" .py)"
    rc="$(cat "$LOGDIR/$name.rc" 2>/dev/null || echo 255)"
    if [[ "$rc" != 0 ]]; then
        fail=1
        echo "---- FAILED: micro_grid/$name.py (rc=$rc), log tail:" >&2
        grep -av 'If :yref:`Law2_ScGeom6D_CohFrictPhys_CohesionMoment::useIncrementalForm`' "$LOGDIR/$name.log" | tail -n 25 >&2 || true
    elif [[ ! -s "$OUT/$name.scene.json" || ! -s "$OUT/$name.intrs6d.csv.gz" ]]; then
        fail=1
        echo "---- FAILED: micro_grid/$name.py wrote no $name.scene.json / $name.intrs6d.csv.gz" >&2
    fi
done
printf 'regen micro_grid: %d scripts, %.1fs wall, output in %s\n' "${#scripts[@]}" "$(awk -v a="$T0" -v b="$T1" 'BEGIN{print b-a}')" "$OUT"
exit "$fail"
