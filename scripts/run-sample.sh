#!/bin/sh
# The README's main command: installs dependencies, builds, and runs the main job on the
# bundled sample: generate the spectator character, inspect it, bake it into a pack,
# write a 25% level of detail, print the accuracy/time table of the simplifier, and render a
# crowd of the baked pack (samples/scenes/crowd.json) with Vulkan (lavapipe without a GPU).
# Outputs go to out/.
set -eu
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
# note: only what this script runs, not the test suite.
./scripts/build.sh crowdbake make_spectator
BUILD="${CROWDBAKE_BUILD_DIR:-build}"
# The accuracy table's peer: the pinned gltfpack from npm (its row stays empty, saying why,
# when npm or the registry cannot be had).
./scripts/gltfpack/install.sh "$BUILD/npm-gltfpack" || true
crowdbake="$BUILD/cli/crowdbake"
mkdir -p out

"$BUILD/samples/spectator/make_spectator" -o out/spectator.glb
"$crowdbake" inspect out/spectator.glb
"$crowdbake" bake out/spectator.glb -o out/spectator.crowdpack --report out/spectator.bake.json \
  --preview out/spectator-preview.png --quiet
echo "baked out/spectator.crowdpack ($(wc -c < out/spectator.crowdpack) bytes); report in out/spectator.bake.json; levels x clips in out/spectator-preview.png"
"$crowdbake" lod out/spectator.glb --ratio 0.25 -o out/spectator-lod25.glb
# note: --quick measures every 6th frame with fewer settings; the full table over every
# shared asset is `crowdbake bench simplify` (docs/accuracy.md).
"$crowdbake" bench simplify --quick --spectator-only --out out/bench --plot out/accuracy-vs-time.png
# note: the scene reads out/spectator.crowdpack, baked above.
"$crowdbake" render samples/scenes/crowd.json -o out/crowd.png --time 1.5
echo "the crowd picture is out/crowd.png"
