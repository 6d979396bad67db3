#!/bin/bash
# fascia-view's bad input: each a clear message and its documented exit code (docs/viewer.md).
# usage: bad_input.sh FASCIA_VIEW SOURCE_DIR
set -u
view=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failed=0
expect() {  # expect CODE TEXT -- command...
    local code=$1 text=$2
    shift 3
    "$@" > "$tmp/out" 2>&1
    local got=$?
    if [ "$got" != "$code" ] || ! grep -qF -- "$text" "$tmp/out"; then
        echo "FAIL: $* -> exit $got (expected $code), output:"; cat "$tmp/out"; echo "(expected to contain: $text)"
        failed=1
    fi
}
scene=$src/scenes/interaction/palpation.xml
expect 2 "'feel' is a Monitor, not a surface to show" -- "$view" "$scene" --surface feel --screenshot "$tmp/a.png" --output "$tmp"
expect 2 "no component 'liver' in the scene" -- "$view" "$scene" --surface liver --screenshot "$tmp/a.png" --output "$tmp"
expect 2 "no field 'stress' to colour the surface by" -- "$view" "$scene" --field stress --screenshot "$tmp/a.png" --output "$tmp"
expect 1 "cannot write the picture here" -- "$view" "$scene" --screenshot "$tmp/missing/a.png" --output "$tmp"
expect 1 "the picture's path is a folder" -- "$view" "$scene" --screenshot "$tmp" --output "$tmp"
expect 4 "Xvfb is not on PATH" -- env -u DISPLAY PATH=/nonexistent "$view" "$scene" --screenshot "$tmp/a.png" --output "$tmp"
expect 4 "a window needs a display" -- env -u DISPLAY "$view" "$scene" --output "$tmp"
expect 2 "camera 'sideways' is not a view" -- "$view" "$scene" --camera sideways --screenshot "$tmp/a.png" --output "$tmp"
expect 1 "unknown option" -- "$view" "$scene" --frobnicate
cat > "$tmp/points.xml" <<'XML'
<Node name="root" dt="0.001">
  <MechanicalObject name="mo" position="0 0 0  0.01 0 0"/>
</Node>
XML
expect 2 "the scene has no surface to show" -- "$view" "$tmp/points.xml" --screenshot "$tmp/a.png" --output "$tmp"
# the window itself (its event loop, under a private Xvfb): a good scene plays and closes with 0, a
# step that fails (dt 100 times the stable one) pauses it with the message, and it closes with 3
sed -e 's/dt="auto"/dt="0.01"/' "$src/examples/python/cube.xml" > "$tmp/unstable.xml"
if command -v xvfb-run > /dev/null; then
    expect 0 "frames" -- xvfb-run -a "$view" "$src/examples/python/cube.xml" --play --quit-after 2 --output "$tmp"
    grep -qE "^fascia-view: [1-9][0-9]* steps, .* [1-9][0-9]* frames" "$tmp/out" || { echo "FAIL: the window ran no step or drew no frame:"; cat "$tmp/out"; failed=1; }
    expect 3 "the step failed, paused: error: " -- xvfb-run -a "$view" "$tmp/unstable.xml" --play --quit-after 3 --output "$tmp"
else
    echo "xvfb-run is not installed: the window's own checks are left out"
fi
[ -e "$tmp/a.png" ] && { echo "FAIL: a picture was written by a failed run"; failed=1; }
ls "$tmp"/.*.tmp 2>/dev/null && { echo "FAIL: a temporary file was left"; failed=1; }
exit $failed
