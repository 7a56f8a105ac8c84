#!/usr/bin/env bash
# Regenerate all goldens into a temporary directory and compare them with golden/{micro,meso,pack}.
# .gz files are compared after decompression (json/csv as text). Prints OK / DIFFERS / MISSING /
# EXTRA per file and exits non-zero on any difference or missing file.
set -euo pipefail

if ! command -v yade >/dev/null 2>&1; then
    echo "error: 'yade' not found. Install Debian YADE 2023.02a with:" >&2
    echo "    apt-get install -y --no-install-recommends yade" >&2
    exit 3
fi

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/.." && pwd)"
GOLD="$ROOT/golden"
TMP="$(mktemp -d "${TMPDIR:-/tmp}/ryade_check_goldens.XXXXXX")"
cleanup() { rm -rf "$TMP"; }
trap cleanup EXIT

"$HERE/regen.sh" "$TMP"
"$HERE/examples/run_all.sh" yade "$TMP/examples"
"$HERE/micro_grid/regen.sh" "$TMP/micro_grid" >/dev/null

content() {  # print the (decompressed) content of a file
    case "$1" in
        *.gz) gzip -dc -- "$1" ;;
        *) cat -- "$1" ;;
    esac
}

bad=0; n=0
for kind in micro meso pack export energy examples micro_grid; do
    names="$( { [[ -d "$GOLD/$kind" ]] && ls -1 "$GOLD/$kind"; ls -1 "$TMP/$kind"; } | grep -v '\.tmp[0-9]*$' | sort -u )"
    if [[ -z "$names" ]]; then echo "MISSING  $kind/ (no files at all)"; bad=1; continue; fi
    while IFS= read -r f; do
        n=$((n + 1))
        g="$GOLD/$kind/$f"; t="$TMP/$kind/$f"
        if [[ ! -f "$g" ]]; then echo "EXTRA    $kind/$f (regenerated, not in golden/)"; bad=1; continue; fi
        if [[ ! -f "$t" ]]; then echo "MISSING  $kind/$f (in golden/, not regenerated)"; bad=1; continue; fi
        if cmp -s <(content "$g") <(content "$t"); then
            echo "OK       $kind/$f"
        else
            echo "DIFFERS  $kind/$f"; bad=1
        fi
    done <<<"$names"
done
if [[ $bad -ne 0 ]]; then echo "check_goldens: FAILED ($n files checked)"; exit 1; fi
echo "check_goldens: all $n files identical"
