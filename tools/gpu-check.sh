#!/usr/bin/env bash
# The prepared GPU check (issue 15): on a machine with an NVIDIA GPU, the CUDA toolkit, CMake, ninja
# and a C++ compiler, but no other dependency and no network, it
#   1. unpacks the dependency bundle made by tools/make-gpu-deps.sh (Eigen, TinyXML2, Catch2);
#   2. configures a build without VTK (FASCIA_WITH_VTK=OFF, FASCIA_WITH_CUDA=ON) that takes those
#      three from the bundle only (their *_DIR given explicitly);
#   3. builds only what the GPU tests need, on all cores;
#   4. runs the GPU tests (test_cuda_device) and the CPU emulation test (test_cuda_emulation);
#   5. writes SUMMARY.txt and the logs into OUT_DIR.
# Usage: tools/gpu-check.sh OUT_DIR [BUNDLE]   (BUNDLE: tools/gpu-deps.tar.gz or an unpacked folder;
# default tools/gpu-deps.tar.gz, else tools/gpu-deps). Exit 0 when every test ran and passed; 77
# when the GPU tests were skipped (no usable device); 1 otherwise. Planned to finish well within 6
# minutes on 16 cores (the build is about 60 translation units and one .cu file).
set -uo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
out=${1:?usage: tools/gpu-check.sh OUT_DIR [BUNDLE]}
mkdir -p "$out"
out=$(cd "$out" && pwd)
bundle=${2:-}
[ -z "$bundle" ] && { [ -f "$src/tools/gpu-deps.tar.gz" ] && bundle=$src/tools/gpu-deps.tar.gz || bundle=$src/tools/gpu-deps; }
build=${FASCIA_GPU_BUILD:-$src/build-gpu}
t0=$(date +%s)
summary=$out/SUMMARY.txt
say() { echo "$*" | tee -a "$summary"; }
: > "$summary"
say "fascia gpu-check $(date -u +%FT%TZ), commit $(git -C "$src" rev-parse --short HEAD 2>/dev/null || echo unknown)"

if [ -f "$bundle" ]; then
    mkdir -p "$build"
    tar -C "$build" -xzf "$bundle" || { say "cannot unpack $bundle"; exit 1; }
    deps=$build/gpu-deps
else
    deps=$(cd "$bundle" && pwd) || { say "no bundle at $bundle (make it with tools/make-gpu-deps.sh)"; exit 1; }
fi
say "bundle: $deps"
nproc=$(nproc)
(nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader || echo "nvidia-smi failed") > "$out/gpu.txt" 2>&1
say "gpu: $(head -1 "$out/gpu.txt")"
say "toolkit: $(nvcc --version 2>/dev/null | tail -2 | head -1)"

cmake -S "$src" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DFASCIA_WITH_VTK=OFF -DFASCIA_WITH_CUDA=ON \
      -DEigen3_DIR="$deps/share/eigen3/cmake" -Dtinyxml2_DIR="$deps/lib/cmake/tinyxml2" -DCatch2_DIR="$deps/lib/cmake/Catch2" \
      > "$out/configure.log" 2>&1 || { say "configure failed (configure.log)"; tail -20 "$out/configure.log" >> "$summary"; exit 1; }
say "found: $(grep -E '^(Eigen3|tinyxml2|Catch2)_DIR' "$build/CMakeCache.txt" | tr '\n' ' ')"
targets="test_cuda_device test_cuda_emulation fascia_cuda fascia_tled fascia_mechanics fascia_meshio fascia_viscoelastic fascia_materials fascia_elements"
cmake --build "$build" -j"$nproc" --target $targets > "$out/build.log" 2>&1 || { say "build failed (build.log)"; grep -E "error" "$out/build.log" | head -20 >> "$summary"; exit 1; }
say "built in $(( $(date +%s) - t0 )) s"

export LD_LIBRARY_PATH="$deps/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
rc=0
for t in test_cuda_emulation test_cuda_device; do
    "$build/bin/tests/$t" -r compact > "$out/$t.log" 2>&1
    r=$?
    say "$t: exit $r, $(grep -E 'Passed|Failed|passed|failed' "$out/$t.log" | tail -1)"
    if [ "$t" = test_cuda_device ] && [ $r -eq 77 ]; then rc=77; elif [ $r -ne 0 ]; then rc=1; fi
done
say "total $(( $(date +%s) - t0 )) s, exit $rc"
exit $rc
