#!/usr/bin/env bash
# Run every example of list.txt through run_example.py with ENGINE ("yade" or "compat") into OUTDIR.
#   yade_ref/examples/run_all.sh yade OUTDIR       # the goldens (golden/examples)
#   yade_ref/examples/run_all.sh compat OUTDIR     # ryade's compat layer
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"
EX="${YADE_EXAMPLES:-/usr/share/doc/yade/examples}"
[[ $# -eq 2 ]] || { echo "usage: $0 yade|compat OUTDIR" >&2; exit 2; }
[[ -d "$EX" ]] || { echo "error: YADE's examples not found in $EX (apt-get install yade, or set YADE_EXAMPLES)" >&2; exit 3; }
mkdir -p "$2"; OUT="$(cd "$2" && pwd)"
case "$1" in
  yade) RUN=(yade -n -x) ;;
  compat) RUN=("${COMPAT:-$ROOT/target/release/compat}" run) ;;
  *) echo "engine must be yade or compat" >&2; exit 2 ;;
esac
export OMP_NUM_THREADS=1
fail=0
while read -r path steps; do
  [[ -z "$path" || "$path" == \#* ]] && continue
  name="$(basename "$path" .py)"
  mkdir -p "$OUT/work.$name"
  if ! (cd "$OUT/work.$name" && "${RUN[@]}" "$HERE/run_example.py" "$EX/$path" "$OUT/$name.json" "$steps" >"$OUT/work.$name/log.txt" 2>&1 </dev/null); then
    echo "FAILED $1 $path:"; tail -n 12 "$OUT/work.$name/log.txt"; fail=1
  fi
  rm -rf "$OUT/work.$name"
done <"$HERE/list.txt"
exit $fail
