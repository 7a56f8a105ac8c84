#!/usr/bin/env bash
# Regenerate the grid goldens into a temporary directory and compare them with golden/micro_grid
# (.gz files after decompression). Prints OK / DIFFERS / MISSING / EXTRA per file; non-zero exit on any
# difference. (yade_ref/check_goldens.sh does not cover golden/micro_grid.)
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
GOLD="$(cd "$HERE/../.." && pwd)/golden/micro_grid"
TMP="$(mktemp -d "${TMPDIR:-/tmp}/ryade_check_grid.XXXXXX")"
cleanup() { rm -rf "$TMP"; }
trap cleanup EXIT

"$HERE/regen.sh" "$TMP"

content() { case "$1" in *.gz) gzip -dc -- "$1" ;; *) cat -- "$1" ;; esac; }

bad=0; n=0
names="$( { [[ -d "$GOLD" ]] && ls -1 "$GOLD"; ls -1 "$TMP"; } | grep -v '\.tmp[0-9]*$' | sort -u )"
while IFS= read -r f; do
    [[ -n "$f" ]] || continue
    n=$((n + 1))
    g="$GOLD/$f"; t="$TMP/$f"
    if [[ ! -f "$g" ]]; then echo "EXTRA    micro_grid/$f"; bad=1; continue; fi
    if [[ ! -f "$t" ]]; then echo "MISSING  micro_grid/$f"; bad=1; continue; fi
    if cmp -s <(content "$g") <(content "$t"); then echo "OK       micro_grid/$f"; else echo "DIFFERS  micro_grid/$f"; bad=1; fi
done <<<"$names"
if [[ $bad -ne 0 ]]; then echo "check micro_grid: FAILED ($n files checked)"; exit 1; fi
echo "check micro_grid: all $n files identical"
