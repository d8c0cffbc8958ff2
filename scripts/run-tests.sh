#!/bin/sh
# The README's test command: installs dependencies, builds, runs every test.
set -eu
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
./scripts/build.sh
BUILD="${CROWDBAKE_BUILD_DIR:-build}"
ctest --test-dir "$BUILD" --output-on-failure -j "${CROWDBAKE_JOBS:-$(nproc)}"
