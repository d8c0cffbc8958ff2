#!/bin/sh
# The README's main command: installs dependencies, builds, generates the bundled
# spectator character and inspects it. Outputs go to out/.
set -eu
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
./scripts/build.sh
BUILD="${CROWDBAKE_BUILD_DIR:-build}"
mkdir -p out
"$BUILD/samples/spectator/make_spectator" -o out/spectator.glb
"$BUILD/cli/crowdbake" inspect out/spectator.glb
