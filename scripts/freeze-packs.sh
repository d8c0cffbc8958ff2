#!/bin/sh
# Freezes a pack set for the format version this build writes: bakes the generated
# characters (never third-party assets) into tests/data/packs/v<major>.<minor>/ and writes
# their decoded-content digests (digests.json). Run it once per shipped format version and
# commit the folder; tests/formats/frozen_pack_test.cpp reads every set with today's reader.
#   scripts/freeze-packs.sh        (after scripts/build.sh)
set -eu
cd "$(dirname "$0")/.."
BUILD="${CROWDBAKE_BUILD_DIR:-build}"
CB="$BUILD/cli/crowdbake"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
"$BUILD/samples/spectator/make_spectator" -o "$WORK/spectator.glb" --detail 0 -q
"$BUILD/samples/limb_chain/make_limb_chain" -o "$WORK/limb.glb" --triangles 400 --joints 4 >/dev/null
SMALL='"level_errors": {"samples": 4, "fps": 0.5}, "partition": {"size": 64}'
# Two 8x8 shirts for the predictive pack's variant images (VARS, 1.7), written here so the
# set needs nothing from outside.
python3 - "$WORK" <<'PY'
import struct, sys, zlib
def png(path, rgb):
    rows = b"".join(b"\0" + bytes(rgb) * 8 for _ in range(8))
    chunk = lambda t, d: struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d))
    open(path, "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 8, 8, 8, 2, 0, 0, 0))
                           + chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))
png(sys.argv[1] + "/red.png", (200, 30, 30))
png(sys.argv[1] + "/blue.png", (30, 30, 200))
PY
echo "{$SMALL, \"animation\": {\"fps\": 10}, \"variants\": {\"upper_body\": [\"red.png\", \"blue.png\"]}}" >"$WORK/predictive.json"
echo "{$SMALL, \"animation\": {\"fps\": 10}, \"geometry\": {\"codec\": \"draco\"}}" >"$WORK/draco.json"
echo "{$SMALL, \"animation\": {\"fps\": 10, \"encoding\": \"float16\"}, \"geometry\": {\"codec\": \"meshopt\"}}" >"$WORK/meshopt.json"
echo "{$SMALL, \"animation\": {\"fps\": 5, \"encoding\": \"float32\"}, \"geometry\": {\"codec\": \"raw\"}}" >"$WORK/raw.json"
# Vertex colours (VCOL, 1.7) on the default codecs.
"$BUILD/samples/limb_chain/make_limb_chain" -o "$WORK/limb_colors.glb" --triangles 400 --joints 4 --vertex-colors >/dev/null
echo "{$SMALL, \"animation\": {\"fps\": 10}}" >"$WORK/colors.json"
"$CB" bake "$WORK/spectator.glb" -o "$WORK/spectator_predictive.crowdpack" --config "$WORK/predictive.json" --quiet
"$CB" bake "$WORK/spectator.glb" -o "$WORK/spectator_draco.crowdpack" --config "$WORK/draco.json" --quiet
"$CB" bake "$WORK/limb.glb" -o "$WORK/limb_meshopt_float16.crowdpack" --config "$WORK/meshopt.json" --quiet
"$CB" bake "$WORK/limb.glb" -o "$WORK/limb_raw_float32.crowdpack" --config "$WORK/raw.json" --quiet
"$CB" bake "$WORK/limb_colors.glb" -o "$WORK/limb_vertex_colors.crowdpack" --config "$WORK/colors.json" --quiet
VERSION="$(od -A n -t u2 -j 8 -N 4 "$WORK/limb_raw_float32.crowdpack" |
  awk '{print $1 "." $2}')"
[ -n "$VERSION" ] || { echo "freeze-packs: could not read the format version" >&2; exit 1; }
OUT="tests/data/packs/v$VERSION"
mkdir -p "$OUT"
cp "$WORK"/*.crowdpack "$OUT"/
(cd "$OUT" && "$OLDPWD/$BUILD/tests/formats/write_pack_digests" *.crowdpack) >"$OUT/digests.json"
echo "froze $(ls "$OUT"/*.crowdpack | wc -l) packs in $OUT"
