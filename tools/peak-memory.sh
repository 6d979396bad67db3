#!/usr/bin/env bash
# Peak memory per element of a GridMesh scene (the targets: at most 250 B per element for HEML and
# 300 B for TLED at 2M tetrahedra; docs/performance.md, "Peak memory, HEML"): fascia-bench --scene writes the case's scene (the one it times), and
# fascia-run runs a few steps of it under /usr/bin/time -v, whose "Maximum resident set size" is the
# peak. A one-cell cube run the same way gives the baseline (libraries, plugins, the process itself).
# Usage: tools/peak-memory.sh [BUILD_DIR] [HEML|TLED] [CUBE] [STEPS] [extra fascia-bench case options]
#   e.g. tools/peak-memory.sh build TLED 32      (196,608 tetrahedra)
#        tools/peak-memory.sh build HEML 70 5    (2,058,000 tetrahedra: several GB)
#        tools/peak-memory.sh build TLED 32 10 --viscous
# Prints one JSON line: forcefield, cube, elements, steps, peak_rss_bytes, baseline_rss_bytes,
# bytes_per_element (peak / elements) and bytes_per_element_above_baseline.
set -euo pipefail
build=${1:-build}
ff=${2:-TLED}
cube=${3:-32}
steps=${4:-10}
shift $(( $# < 4 ? $# : 4 ))
bench=$build/bin/fascia-bench
run=$build/bin/fascia-run
[ -x "$bench" ] && [ -x "$run" ] || { echo "peak-memory.sh: no $bench or $run (build fascia-bench and fascia-run)" >&2; exit 1; }
[ -x /usr/bin/time ] || { echo "peak-memory.sh: needs /usr/bin/time (GNU time)" >&2; exit 1; }
material=NeoHookean
[ "$ff" = HEML ] && material=CompressibleNeoHookean
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# peak RSS (bytes) of fascia-run on the scene of a cube of $1 cells
peak() {
    "$bench" --forcefield "$ff" --material "$material" --cube "$1" "${@:2}" --scene > "$tmp/scene.xml"
    /usr/bin/time -v "$run" "$tmp/scene.xml" --steps "$steps" --quiet --output "$tmp/out" > /dev/null 2> "$tmp/time.txt" || {
        cat "$tmp/time.txt" >&2
        exit 1
    }
    awk -F': ' '/Maximum resident set size/ { print $2 * 1024 }' "$tmp/time.txt"
}

elements=$(( 6 * cube * cube * cube ))  # GridMesh tetrahedra6: 6 per cell
for a in "$@"; do
    case "$a" in hexahedra) elements=$(( cube * cube * cube ));; tetrahedra5) elements=$(( 5 * cube * cube * cube ));; esac
done
base=$(peak 1 "$@")
rss=$(peak "$cube" "$@")
awk -v ff="$ff" -v cube="$cube" -v n="$elements" -v steps="$steps" -v rss="$rss" -v base="$base" 'BEGIN {
    printf "{\"forcefield\": \"%s\", \"cube\": %d, \"elements\": %d, \"steps\": %d, \"peak_rss_bytes\": %d, ", ff, cube, n, steps, rss
    printf "\"baseline_rss_bytes\": %d, \"bytes_per_element\": %.1f, \"bytes_per_element_above_baseline\": %.1f}\n", base, rss / n, (rss - base) / n
}'
