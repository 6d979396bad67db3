#!/bin/sh
# `make sanitize`: configures BUILD_DIR with FASCIA_SANITIZE=ON (ASan + UBSan, -fno-sanitize-recover,
# -O1 -g1) and the compiler CXX, builds everything with JOBS jobs, runs the whole ctest suite
# under the sanitizers and prints how long the build and the tests took.
#   tests/sanitizer/Sanitize.sh BUILD_DIR CXX JOBS [cmake options...]
set -u
build=${1:?usage: Sanitize.sh BUILD_DIR CXX JOBS [cmake options...]}
cxx=${2:?usage}
jobs=${3:?usage}
shift 3
here=$(cd "$(dirname "$0")" && pwd)
launcher=""
command -v ccache > /dev/null 2>&1 && launcher=-DCMAKE_CXX_COMPILER_LAUNCHER=ccache
start=$(date +%s)
# -O1 -g1 instead of RelWithDebInfo's -O2 -g: the instrumented build is the slow part of this target
# (TLEDForceField.cpp compiles in 18.7 s instead of 33.0 s), and -O1 keeps the stack traces exact
cmake -S "$here/../.." -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER="$cxx" \
      "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" -DFASCIA_SANITIZE=ON $launcher "$@" || exit 1
cmake --build "$build" -j "$jobs" || exit 1
built=$(date +%s)
# leaks are errors; the suppressions say why each one is not ours (tests/sanitizer/lsan.supp)
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:detect_stack_use_after_return=0:strict_string_checks=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:suppressions=$here/ubsan.supp"
export LSAN_OPTIONS="suppressions=$here/lsan.supp:print_suppressions=0"
# the Hertz test's default meshes take some 50 s of CPU, 20 times more under the sanitizers: here
# the 4- and 6-cell meshes with the coarser far field, held to 10 % (plugins/contact/tests/TestHertz.cpp)
export FASCIA_HERTZ_CELLS="4 6" FASCIA_HERTZ_GROWTH=1.5 FASCIA_HERTZ_BOUND=0.1
(cd "$build" && ctest --output-on-failure -j "$jobs")
rc=$?
end=$(date +%s)
echo "make sanitize: build $((built - start)) s, ctest $((end - built)) s, exit $rc"
exit $rc
