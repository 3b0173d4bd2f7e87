#!/bin/sh
# The drawing aids' demo: the studio, headless, replays aids_demo.track.json (a pear-shaped object
# drawn with a 6-fold rotation, smoothing, an over-sketch, the plane guide and end snapping),
# surfaces it, and writes the sketch, the surface, its last frame and a 12-frame turntable.
#
#   tools/sketchsurf-studio/demo/aids_demo.sh [OUT_DIR]        (default: aids_demo)
#
# SKETCHSURF_STUDIO and SKETCHSURF name the binaries (default: build/tools/...).
set -eu
here=$(dirname "$0")
out=${1:-aids_demo}
studio=${SKETCHSURF_STUDIO:-build/tools/sketchsurf-studio}
cli=${SKETCHSURF:-build/tools/sketchsurf}
mkdir -p "$out"
"$studio" --headless --no-autosave --quiet --replay "$here/aids_demo.track.json" --size 960x600 \
  --screenshot "$out/studio.png" --save "$out/aids_demo.json" --save-surface "$out/aids_demo.ply"
"$cli" render "$out/aids_demo.json" --mesh "$out/aids_demo.ply" --regions --turntable 12 \
  --size 480x480 -o "$out/turntable.png" --quiet
echo "aids demo: $out/aids_demo.json, $out/aids_demo.ply, $out/studio.png, $out/turntable_000.png ... turntable_011.png"
