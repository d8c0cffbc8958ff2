#!/bin/sh
# Builds samples/cmake_pack with the real crowdbake and checks that the pack is baked,
# not rebaked when nothing changed, and rebaked when the character or config changes.
# Usage: cmake_pack_test.sh CROWDBAKE CHARACTER SOURCE_DIR WORK_DIR
set -eu
crowdbake=$1 character=$2 source=$3 work=$4
rm -rf "$work"
mkdir -p "$work"
cp "$character" "$work/character.glb"
cp -r "$source/samples/cmake_pack" "$work/game"
cp -r "$source/cmake" "$work/cmake"
sed -i 's|${CMAKE_CURRENT_LIST_DIR}/../../cmake|${CMAKE_CURRENT_LIST_DIR}/../cmake|' "$work/game/CMakeLists.txt"

cmake -S "$work/game" -B "$work/build" -G Ninja -DCROWDBAKE_EXECUTABLE="$crowdbake" \
      -DCHARACTER="$work/character.glb" >/dev/null
build() { cmake --build "$work/build" 2>&1; }

out=$(build)
pack="$work/build/packs/spectator.crowdpack"
[ -s "$pack" ] || { echo "FAIL: no pack after the first build"; echo "$out"; exit 1; }
"$crowdbake" inspect "$pack" >/dev/null 2>&1 || true

out=$(build)
case "$out" in *"no work to do"*) ;; *) echo "FAIL: rebuilt with nothing changed:"; echo "$out"; exit 1;; esac

sleep 1
touch "$work/game/bake.json"
out=$(build)
case "$out" in *"Baking"*) ;; *) echo "FAIL: config change did not rebake:"; echo "$out"; exit 1;; esac

sleep 1
touch "$work/game/spectator-ranges.json"
out=$(build)
case "$out" in *"Baking"*) ;; *) echo "FAIL: a file known only from the depfile did not rebake:"; echo "$out"; exit 1;; esac

sleep 1
touch "$work/character.glb"
out=$(build)
case "$out" in *"Baking"*) ;; *) echo "FAIL: character change did not rebake:"; echo "$out"; exit 1;; esac
echo "ok: baked once, skipped when unchanged, rebaked on config, ranges (depfile) and character changes"
