#!/bin/bash
# Instructions per fast-path step of scene (b) (r05 G medium, seed 1: approach, seating and one load
# cycle, 4,166 steps), counted by valgrind's callgrind inside one function (by default the whole
# step, `FastSim::step`). The count does not move with the machine's load, so it shows exact
# speed-ups of 1 % that timings on the shared VM cannot (compare two builds: same count of steps,
# byte-identical histories). valgrind has no AVX-512: the four-lane paths run there.
#   bench/instr_count.sh [DIR] [GLOB]
# DIR: a folder holding the `yade` package to measure (default: the installed one); GLOB: the
# function to count in, e.g. '*GridPart*forces*' for the geogrid's phase. Needs valgrind.
set -euo pipefail
dir=${1:-}
glob=${2:-*FastSim*step*}
command -v valgrind >/dev/null || { echo "instr_count.sh: valgrind not found (apt-get install valgrind)" >&2; exit 2; }
root=$(cd "$(dirname "$0")/.." && pwd)
py=$(python3 -c 'import sys; print(sys.executable)')
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cat > "$tmp/py" <<WRAP
#!/bin/bash
exec valgrind --tool=callgrind --callgrind-out-file=$tmp/cg.out '--toggle-collect=$glob' $py "\$@"
WRAP
chmod +x "$tmp/py"
cd "$root"
RYADE_PYTHON="$tmp/py" PYTHONPATH="${dir}${PYTHONPATH:+:$PYTHONPATH}" RYADE_FAST=on compat run yade_ref/study/study.py \
  --import-specimen bench/scenes/r05_G_medium_s1.specimen.json --cycles 1 --controller native \
  --out "$tmp/out" > "$tmp/log" 2>&1 || { tail -5 "$tmp/log" >&2; exit 1; }
n=$(grep -o 'Collected : [0-9]*' "$tmp/log" | grep -o '[0-9]*$')
steps=$(awk '/^\[study\] (approach|seating|cycles) / {s += $3} END {print s}' "$tmp/log")
echo "instructions in '$glob': $n ($(( n / steps )) per step over $steps steps); history sha1 $(sha1sum < "$tmp/out/history.csv" | cut -c1-12)"
