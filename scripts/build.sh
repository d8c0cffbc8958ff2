#!/bin/sh
# Configures and builds crowdbake (Release) into ${CROWDBAKE_BUILD_DIR:-build}: everything, or
# only the targets named (scripts/build.sh crowdbake make_spectator).
set -eu
cd "$(dirname "$0")/.."
BUILD="${CROWDBAKE_BUILD_DIR:-build}"
if [ ! -f "$BUILD/CMakeCache.txt" ]; then
  cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
if [ "$#" -gt 0 ]; then
  cmake --build "$BUILD" -j "${CROWDBAKE_JOBS:-$(nproc)}" --target "$@"
else
  cmake --build "$BUILD" -j "${CROWDBAKE_JOBS:-$(nproc)}"
fi
