#!/bin/sh
# The build a game embedding crowdbake makes: formats + runtime + gpu only, with the pipeline,
# the CLI and the tests off, into ${CROWDBAKE_RUNTIME_BUILD_DIR:-build-runtime}. Checks that
# configuring looked for none of the pipeline's dependencies (Assimp, CLI11, OpenMesh), then
# installs it and builds and runs tests/package/consumer against the installed package.
set -eu
cd "$(dirname "$0")/.."
BUILD="${CROWDBAKE_RUNTIME_BUILD_DIR:-build-runtime}"
if [ ! -f "$BUILD/CMakeCache.txt" ]; then
  cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCROWDBAKE_BUILD_PIPELINE=OFF \
    -DCROWDBAKE_BUILD_CLI=OFF -DCROWDBAKE_BUILD_TESTS=OFF >/dev/null
fi
for dependency in assimp_DIR CLI11_DIR OpenMesh GTest_DIR; do
  if grep -q "^$dependency" "$BUILD/CMakeCache.txt"; then
    echo "runtime-only build: configuring looked for $dependency"
    exit 1
  fi
done
cmake --build "$BUILD" -j "${CROWDBAKE_JOBS:-$(nproc)}" >"$BUILD/build.log" 2>&1 || {
  tail -n 40 "$BUILD/build.log"
  exit 1
}
status=0
tests/package/install_and_consume.sh "$BUILD" "$BUILD/consume" \
  tests/data/packs/v1.1/spectator_draco.crowdpack || status=$?
[ "$status" -eq 77 ] && status=0  # no Vulkan device: host_embed said so and skipped
[ "$status" -eq 0 ] && echo "runtime-only build: built, installed and consumed ($BUILD)"
exit "$status"
