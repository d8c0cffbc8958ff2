#!/bin/sh
# Configures and builds crowdbake (Release) into ${CROWDBAKE_BUILD_DIR:-build}.
set -eu
cd "$(dirname "$0")/.."
BUILD="${CROWDBAKE_BUILD_DIR:-build}"
if [ ! -f "$BUILD/CMakeCache.txt" ]; then
  cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build "$BUILD" -j "${CROWDBAKE_JOBS:-$(nproc)}"
