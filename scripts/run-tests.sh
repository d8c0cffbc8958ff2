#!/bin/sh
# The README's test command: installs dependencies, builds, runs every test, builds the
# runtime alone as a game would (scripts/build-runtime-only.sh), then fuzzes every fuzz
# target for a short while (libFuzzer under ASAN/UBSAN, scripts/fuzz.sh).
set -eu
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
./scripts/build.sh
BUILD="${CROWDBAKE_BUILD_DIR:-build}"
# install-deps.sh installed lavapipe, so a GPU test that finds no Vulkan device is a failure here,
# not a skip (a user's build without the packages still skips them).
export CROWDBAKE_REQUIRE_VULKAN="${CROWDBAKE_REQUIRE_VULKAN:-1}"
ctest --test-dir "$BUILD" --output-on-failure -j "${CROWDBAKE_JOBS:-$(nproc)}"
# A game's build: the runtime alone, installed and used through find_package(crowdbake).
./scripts/build-runtime-only.sh
for target in $(./scripts/fuzz.sh --list); do
  ./scripts/fuzz.sh "$target" "${CROWDBAKE_FUZZ_SECONDS:-15}"
done
