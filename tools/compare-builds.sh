#!/usr/bin/env bash
# Proves that a change left every result bitwise the same: runs every scene of scenes/ with two
# builds (before and after) and compares their checkpoints byte for byte (x, v, f, the viscous
# histories, every component's records: docs/design.md, section 1, "checkpoint and restart"), then
# runs fascia-dump's cases (every built-in law in HEML and TLED, tetrahedra and hexahedra, Prony
# series, fibres, groups, 1 and 2 threads) with both and compares the records.
#
#   tools/compare-builds.sh BEFORE_BUILD AFTER_BUILD [STEPS]
#
# STEPS: steps per scene (default 200). Exit 0 when everything is bitwise the same, 1 otherwise.
# The scenes are run from this checkout (both builds read the same files). A case that only the
# after build has (a new law) is listed by --compare as new, not as a difference.
set -uo pipefail
before=${1:?usage: compare-builds.sh BEFORE_BUILD AFTER_BUILD [STEPS]}
after=${2:?usage: compare-builds.sh BEFORE_BUILD AFTER_BUILD [STEPS]}
steps=${3:-200}
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/fascia-compare.XXXXXX")
trap 'rm -rf "$work"' EXIT
status=0
same=0
for scene in $(cd "$root" && find scenes -name '*.xml' | sort); do
    tag=$(echo "$scene" | tr '/' '_')
    for side in before after; do
        build=$before
        [ "$side" = after ] && build=$after
        mkdir -p "$work/$side/$tag"
        "$build/bin/fascia-run" "$root/$scene" --steps "$steps" --quiet --threads 2 --output "$work/$side/$tag" \
            --checkpoint "$work/$side/$tag.ckpt" > "$work/$side/$tag.log" 2>&1
        echo $? > "$work/$side/$tag.rc"
    done
    if ! cmp -s "$work/before/$tag.rc" "$work/after/$tag.rc"; then
        echo "DIFFERENT exit code: $scene (before $(cat "$work/before/$tag.rc"), after $(cat "$work/after/$tag.rc"))"
        status=1
    elif [ ! -f "$work/before/$tag.ckpt" ]; then
        echo "no checkpoint (exit $(cat "$work/before/$tag.rc") in both): $scene"
    elif cmp -s "$work/before/$tag.ckpt" "$work/after/$tag.ckpt"; then
        same=$((same + 1))
        echo "same: $scene (exit $(cat "$work/after/$tag.rc"), $(stat -c %s "$work/after/$tag.ckpt") bytes)"
    else
        echo "DIFFERENT checkpoint: $scene"
        status=1
    fi
done
echo "scenes: $same checkpoints bitwise the same after $steps steps"
"$before/bin/fascia-dump" --steps 30 --every 10 "$work/before.dump" > /dev/null 2>&1 || true
"$after/bin/fascia-dump" --steps 30 --every 10 "$work/after.dump" > /dev/null 2>&1 || true
"$after/bin/fascia-dump" --compare "$work/before.dump" "$work/after.dump" > "$work/compare.txt"
# --compare accepts differences below 1e-12; here only bitwise counts
grep -E " differs |missing in" "$work/compare.txt" && status=1
echo "fascia-dump: $(grep -c " bitwise " "$work/compare.txt") cases bitwise the same, $(grep -c " differs " "$work/compare.txt") differ, $(grep -c "only in" "$work/compare.txt") new"
exit $status
