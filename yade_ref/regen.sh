#!/usr/bin/env bash
# Regenerate the ryade golden files with the installed YADE 2023.02a.
#   yade_ref/regen.sh OUTDIR     -> OUTDIR/micro/<scene>.* and OUTDIR/meso/settle.*
#   yade_ref/regen.sh golden     -> refresh the committed goldens in place
# Every script runs as `yade -n -x <script> <outdir>` with one thread (OMP_NUM_THREADS=1);
# independent scripts run in parallel (RYADE_REGEN_JOBS, default: number of CPUs).
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
mkdir -p "$OUT/micro" "$OUT/meso" "$OUT/pack" "$OUT/export" "$OUT/energy"
OUT="$(cd "$OUT" && pwd)"

export OMP_NUM_THREADS=1
export OMP_WAIT_POLICY=PASSIVE
JOBS="${RYADE_REGEN_JOBS:-$(nproc 2>/dev/null || echo 1)}"
[[ "$JOBS" =~ ^[1-9][0-9]*$ ]] || JOBS=1

LOGDIR="$(mktemp -d "${TMPDIR:-/tmp}/ryade_regen_logs.XXXXXX")"
cleanup() { rm -rf "$LOGDIR"; }
trap cleanup EXIT

scripts=()
for s in "$HERE"/micro/*.py; do scripts+=("micro:$s"); done
for s in "$HERE"/meso/*.py; do scripts+=("meso:$s"); done
for s in "$HERE"/pack/*.py; do scripts+=("pack:$s"); done
for s in "$HERE"/export/*.py; do scripts+=("export:$s"); done
for s in "$HERE"/energy/*.py; do scripts+=("energy:$s"); done
[[ ${#scripts[@]} -gt 0 ]] || { echo "error: no scripts under $HERE/{micro,meso}" >&2; exit 1; }

run_one() {  # kind:path
    local kind="${1%%:*}" path="${1#*:}"
    local name; name="$(basename "$path" .py)"
    local log="$LOGDIR/$kind.$name.log"
    local t0 t1 rc=0
    t0=$(date +%s.%N)
    yade -n -x "$path" "$OUT/$kind" >"$log" 2>&1 </dev/null || rc=$?
    t1=$(date +%s.%N)
    echo "$rc" >"$LOGDIR/$kind.$name.rc"
    printf '%-6s %-14s rc=%d %6.1fs  %s\n' "$kind" "$name" "$rc" "$(awk -v a="$t0" -v b="$t1" 'BEGIN{print b-a}')" \
        "$(grep -a '\[ryade_record\] .*done' "$log" | tail -1 | sed 's/.*done //')"
}

T0=$(date +%s.%N)
running=0
# start the slowest (meso) first
for ((i=${#scripts[@]}-1; i>=0; i--)); do
    run_one "${scripts[$i]}" &
    running=$((running + 1))
    if (( running >= JOBS )); then wait -n || true; running=$((running - 1)); fi
done
wait || true
T1=$(date +%s.%N)

fail=0
for item in "${scripts[@]}"; do
    kind="${item%%:*}"; name="$(basename "${item#*:}" .py)"
    rc="$(cat "$LOGDIR/$kind.$name.rc" 2>/dev/null || echo 255)"
    if [[ "$rc" != 0 ]]; then
        fail=1
        echo "---- FAILED: $kind/$name.py (rc=$rc), log tail:" >&2
        tail -n 25 "$LOGDIR/$kind.$name.log" >&2 || true
    elif [[ "$kind" != pack && "$kind" != export && "$kind" != energy && ! -s "$OUT/$kind/$name.scene.json" ]]; then
        fail=1
        echo "---- FAILED: $kind/$name.py wrote no $name.scene.json" >&2
    fi
done
printf 'regen: %d scripts, %.1fs wall, output in %s\n' "${#scripts[@]}" "$(awk -v a="$T0" -v b="$T1" 'BEGIN{print b-a}')" "$OUT"
exit "$fail"
