#!/bin/sh
# Fuzz targets (tests/fuzz, docs/robustness.md) under libFuzzer with ASAN and UBSAN.
#   scripts/fuzz.sh --list             the target names, one per line
#   scripts/fuzz.sh TARGET [SECONDS]   fuzzes TARGET for SECONDS (default 60); non-zero on a crash
# Builds in ${CROWDBAKE_FUZZ_BUILD_DIR:-build-fuzz} with clang (Debian: clang,
# libclang-rt-14-dev); exits 77 (skipped) when clang++ is missing. Each target's corpus grows
# in BUILD/fuzz/TARGET/corpus between runs; a crash leaves its input in BUILD/fuzz/TARGET/
# and fails. The fuzz build defines FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION, which makes the
# pack reader ignore checksum mismatches so mutations reach the chunk decoders.
set -eu
cd "$(dirname "$0")/.."
TARGETS="pack_reader pack_load gltf_import assimp_import assimp_scene scene bake_config pose_ranges"
if [ "${1:-}" = "--list" ]; then
  for t in $TARGETS; do echo "$t"; done
  exit 0
fi
TARGET="${1:-}"
SECONDS_TO_RUN="${2:-60}"
case " $TARGETS " in
  *" $TARGET "*) ;;
  *)
    echo "usage: scripts/fuzz.sh --list | TARGET [SECONDS]; targets: $TARGETS" >&2
    exit 2
    ;;
esac
BUILD="${CROWDBAKE_FUZZ_BUILD_DIR:-build-fuzz}"
CXX_CLANG="$(command -v clang++ || true)"
if [ -z "$CXX_CLANG" ]; then
  echo "fuzz: clang++ not found (apt-get install clang libclang-rt-14-dev); skipped"
  exit 77
fi
FLAGS="-fsanitize=address,undefined,fuzzer-no-link -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
FLAGS="$FLAGS -DFUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION"
if [ ! -f "$BUILD/CMakeCache.txt" ]; then
  cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER="$CXX_CLANG" \
    -DCMAKE_CXX_FLAGS="$FLAGS" -DCROWDBAKE_FUZZ=ON >/dev/null
fi
cmake --build "$BUILD" -j "${CROWDBAKE_JOBS:-$(nproc)}" --target "${TARGET}_fuzz" make_fuzz_seeds >/dev/null
DIR="$BUILD/fuzz/$TARGET"
SEEDS="$DIR/seeds"
CORPUS="$DIR/corpus"
rm -rf "$SEEDS"
mkdir -p "$SEEDS" "$CORPUS"
[ -d "tests/fuzz/seeds/$TARGET" ] && cp tests/fuzz/seeds/"$TARGET"/* "$SEEDS"/
case "$TARGET" in
  pack_*) "$BUILD/tests/fuzz/make_fuzz_seeds" packs "$SEEDS" >/dev/null ;;
  gltf_import) "$BUILD/tests/fuzz/make_fuzz_seeds" gltf "$SEEDS" >/dev/null ;;
esac
# -malloc_limit_mb: a single allocation above it is a failure (readers bound what a small
# input can allocate); -timeout: a single input taking that long is a hang.
OPTIONS="-max_len=65536 -rss_limit_mb=3072 -malloc_limit_mb=128 -timeout=20"
case "$TARGET" in
  pack_*) OPTIONS="$OPTIONS -dict=tests/fuzz/pack.dict" ;;
  scene | bake_config | pose_ranges | gltf_import) OPTIONS="$OPTIONS -dict=tests/fuzz/json.dict" ;;
esac
case "$TARGET" in
  # A scene may ask for 2^24 instances in a few bytes (the documented limit): each instance
  # array is then up to 256 MiB, and parsing it takes seconds under the sanitizers.
  scene) OPTIONS="$OPTIONS -malloc_limit_mb=512 -timeout=60" ;;
  # Assimp's allocations happen in the import's child process, where libFuzzer's malloc
  # limit would report the parent's input as a crash: the allocator refuses big blocks instead.
  assimp_import)
    OPTIONS="$OPTIONS -malloc_limit_mb=0"
    export ASAN_OPTIONS="${ASAN_OPTIONS:-}:allocator_may_return_null=1:max_allocation_size_mb=1024"
    ;;
esac
LOG="$DIR/last-run.log"
# shellcheck disable=SC2086
if "$BUILD/tests/fuzz/${TARGET}_fuzz" "$CORPUS" "$SEEDS" -max_total_time="$SECONDS_TO_RUN" \
  $OPTIONS -print_final_stats=1 -artifact_prefix="$DIR/" >"$LOG" 2>&1; then
  echo "fuzz $TARGET: ${SECONDS_TO_RUN} s, no crash: $(grep -E '^stat::number_of_executed_units' "$LOG" | awk '{print $2}') inputs, corpus in $CORPUS"
else
  tail -n 60 "$LOG"
  echo "fuzz $TARGET: FAILED; the crashing input is in $DIR/ (full log: $LOG)"
  exit 1
fi
