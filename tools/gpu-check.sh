#!/usr/bin/env bash
# The prepared GPU check (docs/performance.md, "The step on a GPU"): on a machine with an NVIDIA GPU, the CUDA toolkit, CMake, ninja
# and a C++ compiler, but no other dependency and no network, it
#   1. unpacks the dependency bundle made by tools/make-gpu-deps.sh (Eigen, TinyXML2, Catch2);
#   2. configures a build without VTK (FASCIA_WITH_VTK=OFF, FASCIA_WITH_CUDA=ON) that takes those
#      three from the bundle only (their *_DIR given explicitly);
#   3. builds only what the GPU tests and fascia-bench need, on all cores;
#   4. runs the GPU tests (test_cuda_device) and the CPU emulation test (test_cuda_emulation)
#      through ctest, one case a process, on all cores (ctest.log; the per-case output of any
#      failure in failures.log);
#   5. runs `fascia-bench --suite gpu` (bench.json: one JSON object a case; bench.log its errors),
#      then the split of a step between its kernels (the corner forces by element and in node
#      order, CudaStep forceOrder) and two other block sizes at 2M tetrahedra,
#      unless FASCIA_GPU_BENCH=0, for at most FASCIA_GPU_BENCH_SECONDS (default 240; the quick
#      figures come first, each line is written when it is done);
#   6. writes SUMMARY.txt into OUT_DIR.
# Usage: tools/gpu-check.sh OUT_DIR [BUNDLE]   (BUNDLE: tools/gpu-deps.tar.gz or an unpacked folder;
# default tools/gpu-deps.tar.gz, else tools/gpu-deps). Exit 0 when every test ran and passed; 77
# when the GPU tests were skipped (no usable device); 1 otherwise. Planned to finish within 6
# minutes on 16 cores (the build is about 60 translation units and one .cu file; FASCIA_GPU_CUBES
# gives the bench's large sizes, default 150: 20.25M tetrahedra).
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
targets="test_cuda_device test_cuda_emulation fascia-bench fascia_cuda fascia_tled fascia_heml fascia_mechanics fascia_meshio fascia_viscoelastic fascia_materials fascia_elements"
cmake --build "$build" -j"$nproc" --target $targets > "$out/build.log" 2>&1 || { say "build failed (build.log)"; grep -E "error" "$out/build.log" | head -20 >> "$summary"; exit 1; }
say "built in $(( $(date +%s) - t0 )) s"

export LD_LIBRARY_PATH="$deps/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
rc=0
# (labels cuda-emulation and cuda-device: every case of both tests, one process a case)
(cd "$build" && ctest -L cuda- -j"$nproc" --timeout 300 > "$out/ctest.log" 2>&1)
r=$?
devcases=$(cd "$build" && ctest -N -L cuda-device | grep -c 'Test *#')
say "ctest -L cuda- -j$nproc: exit $r, $(grep -E 'tests passed|tests failed' "$out/ctest.log" | tail -1)"
# (param_coverage, which ctest brings in with the fixture, is skipped on any partial run: not a GPU case)
skipped=$(grep '(Skipped)' "$out/ctest.log" | grep -vc 'param_coverage')
say "  device cases: $devcases, skipped: $skipped"
grep -E '\*\*\*Failed|Not Run|Timeout|No tests' "$out/ctest.log" | head -20 | tee -a "$summary"
if [ $r -ne 0 ] || [ "$devcases" -eq 0 ]; then
    rc=1
    (cd "$build" && ctest -L cuda- --rerun-failed --output-on-failure > "$out/failures.log" 2>&1)
elif [ "$skipped" -gt 0 ]; then
    rc=77
fi
say "tests done at $(( $(date +%s) - t0 )) s"
if [ "${FASCIA_GPU_BENCH:-1}" != 0 ]; then
    (cd "$src" && timeout "${FASCIA_GPU_BENCH_SECONDS:-240}" "$build/bin/fascia-bench" --suite gpu --cubes "${FASCIA_GPU_CUBES:-150}" \
        > "$out/bench.json" 2> "$out/bench.log")
    b=$?
    say "fascia-bench --suite gpu: exit $b ($(wc -l < "$out/bench.json") cases)"
    # one line a case: device, precision, material, elements, ns per element-step, rates
    sed -E 's/.*"material": "([^"]*)".*"elements": ([0-9]+).*"precision": "([^"]*)"(, "device": "cuda")?.*"ns_per_element_step": ([0-9.]+), "steps_per_s": ([0-9]+), "element_steps_per_s": ([0-9.e+]+).*/  \3 \1 \2 el: \5 ns\/el-step, \6 steps\/s, \7 el-steps\/s\4/' \
        "$out/bench.json" | tee -a "$summary"
    # the split of a step between its two kernels (FASCIA_CUDA_TIMING: each pass timed and waited
    # for), and other block sizes than the default 256, at 2M tetrahedra (appended to bench.json and
    # bench.log)
    # (and with the corner forces in node order, CudaStep forceOrder: which of the two kernels gains)
    for p in float double; do
        for order in element node; do
            (cd "$src" && FASCIA_CUDA_TIMING=1 timeout 60 "$build/bin/fascia-bench" --device cuda --forcefield TLED --material NeoHookean \
                --cube 70 --precision $p --steps 100 --repeat 1 --cuda-forces $order >> "$out/bench.json" 2>> "$out/bench.log")
            say "  $p, 2.06M tetrahedra, forces by $order: $(grep cuda-timing "$out/bench.log" | tail -1)"
        done
    done
    for b in 128 512; do
        (cd "$src" && timeout 60 "$build/bin/fascia-bench" --device cuda --forcefield TLED --material NeoHookean \
            --cube 70 --precision float --steps 500 --repeat 3 --cuda-block $b >> "$out/bench.json" 2>> "$out/bench.log")
        say "  float, 2.06M tetrahedra, block $b: $(tail -1 "$out/bench.json" | grep -oE '"ns_per_element_step": [0-9.]+')"
    done
fi
# with FASCIA_GPU_NCU=1 and Nsight Compute (ncu) on the PATH or in the toolkit: the kernels' own
# DRAM traffic, time and occupancy at 2M tetrahedra in float (ncu.txt), for the bandwidth reached
ncu=$(command -v ncu || ls /usr/local/cuda/bin/ncu 2>/dev/null | head -1)
if [ "${FASCIA_GPU_NCU:-0}" = 1 ] && [ -n "$ncu" ]; then
    (cd "$src" && timeout 120 "$ncu" --launch-skip 20 --launch-count 4 \
        --metrics gpu__time_duration.sum,dram__bytes_read.sum,dram__bytes_write.sum,dram__throughput.avg.pct_of_peak_sustained_elapsed,lts__t_bytes.sum,sm__warps_active.avg.pct_of_peak_sustained_active,launch__registers_per_thread,launch__occupancy_limit_registers \
        "$build/bin/fascia-bench" --device cuda --forcefield TLED --material NeoHookean --cube 70 --precision float --steps 20 --repeat 1 \
        > "$out/ncu.txt" 2>&1)
    say "ncu: exit $? (ncu.txt)"
fi
# (at most 8 files come back from a GPU lease; the configure log matters only when configuring failed,
# and then the script stopped there)
rm -f "$out/configure.log"
say "total $(( $(date +%s) - t0 )) s, exit $rc"
exit $rc
