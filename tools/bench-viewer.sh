#!/bin/bash
# The viewer's cost (issue 34; docs/performance.md, "Viewer"): the simulation's ms per step with
# fascia-view open and playing under Xvfb against fascia-run on the same scene, alternating, and
# the render time of a frame of a 100k-triangle surface (paused: the window draws, nothing steps).
# usage: tools/bench-viewer.sh [BUILD_DIR] [ROUNDS] [SECONDS]
set -euo pipefail
build=${1:-build}
rounds=${2:-3}
seconds=${3:-10}
scene=scenes/heml/abdomen.xml
threads=1   # the simulation on one core, the render thread on the other (2-core machine)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for r in $(seq "$rounds"); do
  run=$("$build/bin/fascia-run" "$scene" --time 1 --threads $threads --quiet --output "$tmp/run" | sed -n 's/.* \([0-9.]*\) ms\/step.*/\1/p')
  view=$(xvfb-run -a -s "-screen 0 1280x1024x24" "$build/bin/fascia-view" "$scene" --play --threads $threads \
         --quit-after "$seconds" --output "$tmp/view" | sed -n 's/.*steps, \([0-9.]*\) ms\/step, \([0-9]*\) frames, \([0-9.]*\) ms.*/\1 \2 \3/p')
  set -- $view
  echo "round $r: fascia-run $run ms/step, fascia-view $1 ms/step (ratio $(echo "$1 / $run" | bc -l | cut -c1-5)), $2 frames, $3 ms a frame"
done
# a 100k-triangle surface: a 155 x 155 x 2 grid of hexahedra has 98,580 boundary triangles
cat > "$tmp/big.xml" <<'XML'
<Node name="root" dt="auto">
  <Node name="slab">
    <GridMesh name="grid" min="0 0 0" max="0.3 0.3 0.01" resolution="155 155 2" element="hexahedra"/>
    <MechanicalObject name="state"/>
    <LumpedMass density="1000"/>
    <NeoHookean mu="3000" kappa="30000"/>
    <TLEDForceField/>
    <CentralDifference/>
  </Node>
</Node>
XML
for r in $(seq "$rounds"); do
  xvfb-run -a -s "-screen 0 1280x1024x24" "$build/bin/fascia-view" "$tmp/big.xml" --quit-after "$seconds" --output "$tmp/big" |
    sed -n "s/.*, \([0-9]*\) frames, \([0-9.]*\) ms.*/round $r: 98,580 triangles, 1024x768: \1 frames, \2 ms a frame to render/p"
done
