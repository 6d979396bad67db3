#!/usr/bin/env bash
# usage: install_example.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAILED: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$work/prefix" > "$work/install.log" || { cat "$work/install.log"; fail "install"; }
[ -f "$work/prefix/lib/cmake/Fascia/FasciaConfig.cmake" ] || fail "no FasciaConfig.cmake installed"
[ -f "$work/prefix/lib/cmake/Fascia/FasciaConfigVersion.cmake" ] || fail "no version file installed"

cmake -S "$src/examples/plugin" -B "$work/example" -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$work/prefix" > "$work/configure.log" 2>&1 || { cat "$work/configure.log"; fail "configure example"; }
cmake --build "$work/example" -j 2 > "$work/build.log" 2>&1 || { cat "$work/build.log"; fail "build example"; }
lib="$work/example/libfascia_example.so"
[ -f "$lib" ] || fail "the example plugin was not built"

# the haptics example (an embedding program, no plugin) builds against the installed package too
cmake -S "$src/examples/haptics" -B "$work/haptics" -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$work/prefix" > "$work/configure-haptics.log" 2>&1 || { cat "$work/configure-haptics.log"; fail "configure the haptics example"; }
cmake --build "$work/haptics" -j 2 > "$work/build-haptics.log" 2>&1 || { cat "$work/build-haptics.log"; fail "build the haptics example"; }
[ -x "$work/haptics/fascia-haptics-demo" ] || fail "the haptics example was not built"

# the plugin's own conformance program: its force field and its material (in HEML and TLED)
"$work/example/example_conformance" || fail "the example's conformance checks"

# the installed runner finds its own plugins, and the example through FASCIA_PLUGIN_PATH
list=$(FASCIA_PLUGIN_PATH="$work/example" "$work/prefix/bin/fascia-run" --list)
for c in CorotationalTetForceField Yeoh; do
  echo "$list" | grep -q "^$c .*example.plugin" || { echo "$list"; fail "--list does not show $c"; }
done
echo "$list" | grep -q "^SemiImplicitEuler " || fail "--list does not show the installed built-in plugins"

for scene in corotational yeoh; do
  out=$(FASCIA_PLUGIN_PATH="$work/example" "$work/prefix/bin/fascia-run" "$src/examples/plugin/$scene.xml" --steps 200 --quiet)
  echo "$out" | grep -q "^fascia-run: 200 steps" || { echo "$out"; fail "the example scene $scene did not run"; }
done

# and by <RequiredPlugin> with a path, without the environment variable
sed "s|<Node name=\"beam\">|<RequiredPlugin name=\"$lib\"/><Node name=\"beam\">|" "$src/examples/plugin/corotational.xml" > "$work/scene.xml"
out=$("$work/prefix/bin/fascia-run" "$work/scene.xml" --steps 10 --quiet)
echo "$out" | grep -q "^fascia-run: 10 steps" || { echo "$out"; fail "RequiredPlugin by path"; }
echo "install, out-of-tree build, conformance and run: ok"
