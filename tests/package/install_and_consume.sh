#!/bin/sh
# install_and_consume.sh BUILD WORK PACK: installs the crowdbake build in BUILD into WORK/prefix,
# checks that the installed CMake package points into the prefix only, then builds the
# consumer project (a game's build: find_package(crowdbake CONFIG)) against it and runs its
# programs on PACK. With the CLI installed, the installed command reads PACK too.
# Exit 0 passed, 1 failed, 77 no Vulkan device for host_embed (unless CROWDBAKE_REQUIRE_VULKAN=1).
set -eu
BUILD="$1"
WORK="$2"
PACK="$3"
HERE="$(cd "$(dirname "$0")" && pwd)"
SOURCE="$(cd "$HERE/../.." && pwd)"
rm -rf "$WORK"
mkdir -p "$WORK"
WORK="$(cd "$WORK" && pwd)"
PREFIX="$WORK/prefix"
cmake --install "$BUILD" --prefix "$PREFIX" >"$WORK/install.log"
PACKAGE="$PREFIX/lib/cmake/crowdbake"
[ -f "$PACKAGE/crowdbakeConfig.cmake" ] || { echo "no $PACKAGE/crowdbakeConfig.cmake"; exit 1; }
if grep -rn "$SOURCE" "$PACKAGE"; then
  echo "the installed package refers to the source or build tree (above)"
  exit 1
fi
cmake -S "$HERE/consumer" -B "$WORK/consumer" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$PREFIX" -DHOST_EMBED_SOURCE="$SOURCE/samples/host_embed/main.cpp" \
  >"$WORK/consumer-configure.log" || { cat "$WORK/consumer-configure.log"; exit 1; }
cmake --build "$WORK/consumer" >"$WORK/consumer-build.log" 2>&1 || {
  tail -n 40 "$WORK/consumer-build.log"
  exit 1
}
"$WORK/consumer/pack_summary" "$PACK"
if [ -x "$PREFIX/bin/crowdbake" ]; then
  "$PREFIX/bin/crowdbake" inspect "$PACK" --json >/dev/null
  echo "installed crowdbake reads the pack"
fi
"$WORK/consumer/host_embed" "$PACK" "$WORK/host_embed.ppm"
