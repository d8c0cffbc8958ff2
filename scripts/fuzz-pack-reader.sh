#!/bin/sh
# Fuzzes the pack reader (tests/formats/pack_reader_fuzz.cpp) with libFuzzer for
# SECONDS (default 60), under ASAN and UBSAN, from a seed corpus of real packs.
#   scripts/fuzz-pack-reader.sh [SECONDS]
# Builds in ${CROWDBAKE_FUZZ_BUILD_DIR:-build-fuzz} with clang (Debian: clang,
# libclang-rt-14-dev); exits 77 (skipped) when clang++ is missing. The corpus grows in
# BUILD/fuzz/corpus between runs; a crash leaves its input in BUILD/fuzz/ and fails.
# note: the fuzz build defines FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION, which makes the
# reader ignore checksum mismatches so mutations reach the chunk decoders.
set -eu
cd "$(dirname "$0")/.."
SECONDS_TO_RUN="${1:-60}"
BUILD="${CROWDBAKE_FUZZ_BUILD_DIR:-build-fuzz}"
CXX_CLANG="$(command -v clang++ || true)"
if [ -z "$CXX_CLANG" ]; then
  echo "fuzz-pack-reader: clang++ not found (apt-get install clang libclang-rt-14-dev); skipped"
  exit 77
fi
FLAGS="-fsanitize=address,undefined,fuzzer-no-link -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
FLAGS="$FLAGS -DFUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION"
if [ ! -f "$BUILD/CMakeCache.txt" ]; then
  cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER="$CXX_CLANG" \
    -DCMAKE_CXX_FLAGS="$FLAGS" -DCROWDBAKE_FUZZ=ON >/dev/null
fi
cmake --build "$BUILD" --target pack_reader_fuzz make_pack_corpus
SEEDS="$BUILD/fuzz/seeds"
CORPUS="$BUILD/fuzz/corpus"
rm -rf "$SEEDS"
mkdir -p "$SEEDS" "$CORPUS"
"$BUILD/tests/formats/make_pack_corpus" "$SEEDS"
# -malloc_limit_mb: any single allocation above 64 MiB is a failure (the reader bounds
# what a small input can allocate); -timeout: a single input taking 10 s is a hang.
# note: libFuzzer's progress goes to a log; the summary (or, on failure, the log's end) is printed.
LOG="$BUILD/fuzz/last-run.log"
if "$BUILD/tests/formats/pack_reader_fuzz" "$CORPUS" "$SEEDS" -max_total_time="$SECONDS_TO_RUN" \
  -dict=tests/formats/pack_reader_fuzz.dict -max_len=65536 -rss_limit_mb=2048 -malloc_limit_mb=64 \
  -timeout=10 -print_final_stats=1 -artifact_prefix="$BUILD/fuzz/" >"$LOG" 2>&1; then
  echo "fuzz-pack-reader: ${SECONDS_TO_RUN} s, no crash: $(grep -E '^stat::number_of_executed_units' "$LOG" | awk '{print $2}') inputs, corpus in $CORPUS"
else
  tail -n 60 "$LOG"
  echo "fuzz-pack-reader: FAILED; the crashing input is in $BUILD/fuzz/ (full log: $LOG)"
  exit 1
fi
