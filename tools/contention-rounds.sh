#!/bin/bash
# The contention rounds (docs/performance.md, "Issue 17: a step team of our own"): per round,
# 2 threads and 1 thread of a new and an old build, alternating, under a competing busy process:
# TLED neo-Hookean at 20,250 and 196,608 tetrahedra (fascia-bench --contend) and the abdomen scene
# (fascia-run, a busy loop pinned to core 1). Prints ns per element-step and ms per step.
#   tools/contention-rounds.sh NEW_BUILD OLD_BUILD [ROUNDS]   (build folders with bin/ and lib/)
# Each build runs on its own libraries (LD_LIBRARY_PATH): a copied build's binaries otherwise load
# the libraries of the tree they were built in (CMake's RUNPATH; docs/performance.md, lesson 17).
set -eu
NEW=$(realpath "$1"); OLD=$(realpath "$2"); ROUNDS=${3:-4}
SCENE=$(dirname "$(realpath "$0")")/../scenes/heml/abdomen.xml
env_of() { echo "LD_LIBRARY_PATH=$1/lib:$1/lib/fascia/plugins"; }
bench() {  # build cube steps threads
    env "$(env_of "$1")" "$1/bin/fascia-bench" --forcefield TLED --material NeoHookean --cube "$2" --steps "$3" --repeat 3 \
        --threads "$4" --contend 2>&1 | grep -o '"ns_per_element_step": [0-9.]*' | awk '{print $2}'
}
abdomen() {  # build threads
    local out; out=$(mktemp -d)
    taskset -c 1 bash -c 'while :; do :; done' &
    local spin=$!
    sleep 0.2
    env "$(env_of "$1")" "$1/bin/fascia-run" "$SCENE" --threads "$2" --quiet --output "$out" 2>&1 | grep -o "[0-9.]* ms/step" || true
    kill "$spin"; wait "$spin" 2>/dev/null || true
    rm -rf "$out"
}
for r in $(seq 1 "$ROUNDS"); do
    for size in "15 400" "32 60"; do
        set -- $size
        echo "round $r cube $1: new2 $(bench "$NEW" "$1" "$2" 2) new1 $(bench "$NEW" "$1" "$2" 1) old2 $(bench "$OLD" "$1" "$2" 2) old1 $(bench "$OLD" "$1" "$2" 1)"
    done
    echo "round $r abdomen: new2 $(abdomen "$NEW" 2) new1 $(abdomen "$NEW" 1) old2 $(abdomen "$OLD" 2) old1 $(abdomen "$OLD" 1)"
done
