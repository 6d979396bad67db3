#!/usr/bin/env bash
# usage: examples_from_install.sh BUILD_DIR SOURCE_DIR
# A new user's path, end to end: installs Fascia to a temporary prefix, builds every example from
# the copy installed in share/fascia/examples with the consumer's own default flags (no build type,
# no -march), and runs each on a scene that writes output, whose result is checked:
#   - examples/plugin: Release by default (with the package's message), its conformance program,
#     the corotational beam's settled deflection against the value its scene states, the Yeoh
#     beams of HEML and TLED alike, the plugin found by FASCIA_PLUGIN_PATH and by a path;
#   - examples/haptics built for another machine (-march=x86-64) than the library (-march=native):
#     tool poses and Eigen vectors cross the boundary (the case that crashed in BaseTool::pose());
#   - examples/python/build_scene.py run with the installed Python package alone (when it is built);
#   - a program built with pkg-config alone, also for x86-64 (tests/install/AbiProbe.cpp);
#   - a unit that sees another Eigen alignment is refused at compile time, naming it.
set -euo pipefail
build=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAILED: $*" >&2; exit 1; }
step() { echo "== $*"; }
logged() {  # logged NAME command...: runs it into $work/NAME.log, prints the log on failure
  local name=$1; shift
  "$@" > "$work/$name.log" 2>&1 || { cat "$work/$name.log"; fail "$name"; }
}

step "install"
prefix=$work/prefix
logged install cmake --install "$build" --prefix "$prefix"
share=$prefix/share/fascia
libdir=$(sed -n 's/^CMAKE_INSTALL_LIBDIR:[A-Z]*=//p' "$build/CMakeCache.txt")
for f in $libdir/cmake/Fascia/FasciaConfig.cmake $libdir/cmake/Fascia/FasciaConfigVersion.cmake $libdir/pkgconfig/fascia.pc; do
  [ -f "$prefix/$f" ] || fail "no $f installed"
done
grep -q "^FASCIA_NATIVE:BOOL=ON" "$build/CMakeCache.txt" && echo "the library is built with -march=native"
examples=$(cd "$share/examples" && ls -d */ | tr -d / | sort | tr '\n' ' ')
[ "$examples" = "haptics plugin python " ] || fail "share/fascia/examples holds '$examples': give every example its case here"
for e in $examples; do [ -f "$share/examples/$e/README.md" ] || fail "examples/$e has no README.md"; done

step "examples/plugin: configured with no build type and no flags"
logged configure-plugin cmake -S "$share/examples/plugin" -B "$work/plugin" -DCMAKE_PREFIX_PATH="$prefix"
grep -q "Fascia: no CMAKE_BUILD_TYPE given, building Release" "$work/configure-plugin.log" || { cat "$work/configure-plugin.log"; fail "no Release message"; }
grep -q "^CMAKE_BUILD_TYPE:STRING=Release$" "$work/plugin/CMakeCache.txt" || fail "the example's build type is not Release"
logged build-plugin cmake --build "$work/plugin" -j 2
lib="$work/plugin/libfascia_example.so"
[ -f "$lib" ] || fail "the example plugin was not built"
logged conformance "$work/plugin/example_conformance"

run="$prefix/bin/fascia-run"
list=$(FASCIA_PLUGIN_PATH="$work/plugin" "$run" --list)
for c in CorotationalTetForceField Yeoh; do
  echo "$list" | grep -q "^$c .*example.plugin" || { echo "$list"; fail "--list does not show $c"; }
done
echo "$list" | grep -q "^SemiImplicitEuler " || fail "--list does not show the installed built-in plugins"

# lastZ CSV: the mean of the z displacement columns of the last row of a Monitor's CSV
lastZ() {
  awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i ~ /_z \[m\]$/) z[i] = 1; next }
           { last = $0 } END { n = split(last, v, ","); s = 0; k = 0; for (i in z) { s += v[i]; ++k }; printf "%.6g\n", s / k }' "$1"
}
# zAt CSV T: the same for the first row at time T or later
zAt() { awk -F, -v t="$2" 'NR == 1 || ($1 + 0 >= t && !done) { print; if (NR > 1) done = 1 }' "$1" > "$1.at"; lastZ "$1.at"; }
within() { awk -v a="$1" -v b="$2" -v tol="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; m = b < 0 ? -b : b; exit !(d <= tol * m) }'; }

step "examples/plugin: the corotational beam"
mkdir -p "$work/out-corotational"
FASCIA_PLUGIN_PATH="$work/plugin" "$run" "$share/examples/plugin/corotational.xml" --quiet --output "$work/out-corotational" \
  > "$work/corotational.log" 2>&1 || { cat "$work/corotational.log"; fail "corotational.xml"; }
grep -q "warning" "$work/corotational.log" && { cat "$work/corotational.log"; fail "the corotational run warned"; }
tip=$(lastZ "$work/out-corotational/tip.csv")
before=$(zAt "$work/out-corotational/tip.csv" 0.9)
stated=$(sed -n 's/.*Expect:.*settles \([0-9.]*\) cm below.*/\1/p' "$share/examples/plugin/corotational.xml")
[ -n "$stated" ] || fail "corotational.xml states no settled deflection ('Expect: ... settles X cm below')"
echo "free end: $tip m (at 0.9 s: $before m); stated: $stated cm"
within "$tip" "-$(awk -v c="$stated" 'BEGIN { print c / 100 }')" 0.02 || fail "the free end settles at $tip m, not -$stated cm"
within "$tip" "$before" 0.0001 || fail "the free end has not settled: $before m at 0.9 s, then $tip m"

step "examples/plugin: the Yeoh beams in HEML and TLED"
mkdir -p "$work/out-yeoh"
FASCIA_PLUGIN_PATH="$work/plugin" "$run" "$share/examples/plugin/yeoh.xml" --quiet --output "$work/out-yeoh" \
  > "$work/yeoh.log" 2>&1 || { cat "$work/yeoh.log"; fail "yeoh.xml"; }
heml=$(lastZ "$work/out-yeoh/hemlTip.csv")
tled=$(lastZ "$work/out-yeoh/tledTip.csv")
echo "free ends: HEML $heml m, TLED $tled m"
stated=$(sed -n 's/.*both free ends are \([0-9.]*\) cm below.*/\1/p' "$share/examples/plugin/yeoh.xml")
[ -n "$stated" ] || fail "yeoh.xml states no deflection ('both free ends are X cm below')"
within "$heml" "-$(awk -v c="$stated" 'BEGIN { print c / 100 }')" 0.02 || fail "the HEML beam's free end is at $heml m, not -$stated cm"
within "$heml" "$tled" 0.000001 || fail "the Yeoh beams differ beyond six digits: HEML $heml m, TLED $tled m"

step "examples/plugin: loaded by <RequiredPlugin> with a path"
sed "s|<Node name=\"beam\">|<RequiredPlugin name=\"$lib\"/><Node name=\"beam\">|" "$share/examples/plugin/corotational.xml" > "$work/scene.xml"
out=$("$run" "$work/scene.xml" --steps 10 --quiet --output "$work/out-path")
echo "$out" | grep -q "^fascia-run: 10 steps" || { echo "$out"; fail "RequiredPlugin by path"; }

step "examples/haptics: built for x86-64 against a native library"
logged configure-haptics cmake -S "$share/examples/haptics" -B "$work/haptics" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_CXX_FLAGS=-march=x86-64
logged build-haptics cmake --build "$work/haptics" -j 2
[ -x "$work/haptics/fascia-haptics-demo" ] || fail "the haptics example was not built"
logged run-haptics cmake -DDEMO="$work/haptics/fascia-haptics-demo" -DSCENE="$share/scenes/interaction/haptics.xml" \
  -DWORK="$work/out-haptics" -P "$src/tests/haptics/RunHaptics.cmake"
grep "peak_force_n" "$work/run-haptics.log"

step "examples/python: a scene built in Python, with the installed package alone"
pydir=$(ls -d "$prefix"/lib/python3*/dist-packages 2>/dev/null | head -n 1 || true)
if [ -n "$pydir" ] && [ -d "$pydir/fascia" ]; then
  (cd "$work" && PYTHONPATH="$pydir" PYTHONDONTWRITEBYTECODE=1 /usr/bin/python3 "$share/examples/python/build_scene.py" \
     "$work/out-python") > "$work/run-python.log" 2>&1 || { cat "$work/run-python.log"; fail "examples/python/build_scene.py"; }
  grep -q "t = 0.200 s" "$work/run-python.log" || { cat "$work/run-python.log"; fail "build_scene.py did not run to 0.2 s"; }
  [ -s "$work/out-python/probe.csv" ] || fail "build_scene.py wrote no probe.csv"
else
  echo "(no Python package installed: the module is not built here)"
fi

step "a program built with pkg-config alone, for x86-64"
export PKG_CONFIG_PATH="$prefix/$libdir/pkgconfig"
flags=$(pkg-config --cflags --libs fascia) || fail "pkg-config --cflags --libs fascia"
logged build-probe c++ -std=c++17 -O2 -march=x86-64 "$src/tests/install/AbiProbe.cpp" -o "$work/abi-probe" $flags
"$work/abi-probe" "$share/scenes/interaction/haptics.xml" || fail "the ABI probe (pose and vectors across the boundary)"

step "another Eigen alignment is refused at compile time"
printf '#include "fascia/sim/Tool.h"\nint main() { return 0; }\n' > "$work/align.cpp"
if c++ -std=c++17 -fsyntax-only "$work/align.cpp" $flags -DEIGEN_MAX_ALIGN_BYTES=32 > "$work/align.log" 2>&1; then
  fail "a unit with EIGEN_MAX_ALIGN_BYTES=32 compiled"
fi
grep -q "EigenAlignmentCheck<32" "$work/align.log" || { cat "$work/align.log"; fail "the refusal does not name the alignment seen (32)"; }
grep -q "another EIGEN_MAX_ALIGN_BYTES" "$work/align.log" || { cat "$work/align.log"; fail "the refusal does not say what is wrong"; }
# without vectorisation Eigen's static bound is 0 (a Quaterniond 8-byte aligned): refused too
if c++ -std=c++17 -fsyntax-only "$work/align.cpp" $flags -DEIGEN_DONT_VECTORIZE > "$work/novec.log" 2>&1; then
  fail "a unit with EIGEN_DONT_VECTORIZE compiled"
fi
grep -q "EigenAlignmentCheck<16, 0>" "$work/novec.log" || { cat "$work/novec.log"; fail "the refusal does not name the static alignment seen (0)"; }
echo "every example built from the install and checked"
