#!/bin/sh
# The render benchmark on whatever Vulkan device this machine has (a real GPU when one is
# present, else lavapipe): 100,000 seats at 1920x1080 with 4x MSAA, error-driven LoD at 0.5, 1
# and 2 px plus budget and discrete rows, against full resolution; then one 1,000,000-seat
# frame of the default settings. Prints the device and a short table; the CSVs land in
# $OUT (default out/gpu-bench). Record GPU results in docs/performance.md with the device name.
#   scripts/gpu-bench.sh            # builds first (scripts/build.sh) if crowdbake is missing
#   CROWDBAKE_BUILD_DIR=build-x scripts/gpu-bench.sh
set -eu
cd "$(dirname "$0")/.."
BUILD="${CROWDBAKE_BUILD_DIR:-build}"
OUT="${OUT:-out/gpu-bench}"
crowdbake="$BUILD/cli/crowdbake"
[ -x "$crowdbake" ] || ./scripts/build.sh
mkdir -p "$OUT"

vulkaninfo --summary 2>/dev/null | grep -E "deviceName|driverName" || true

# 100k seats: every mode once against full resolution (one frame each after a warm-up).
"$crowdbake" bench render --sizes 100000 --budgets 3000000,10000000 --pixel-errors 0.5,1,2 \
  --resolution 1920x1080 --frames 3 --pop-size 0 --out "$OUT" --plot "" | tee "$OUT/table.txt"

# 1M seats, default settings (error-driven, 1 px, cap 1,000,000 vertices): the frame's stats.
"$BUILD/samples/spectator/make_spectator" -o "$OUT/spectator.glb"
"$crowdbake" bake "$OUT/spectator.glb" -o "$OUT/spectator.crowdpack" --quiet
python3 - "$OUT" <<'EOF'
import json, math, sys
out = sys.argv[1]
rows, cols = 500, 2000
w, depth, h = cols * 0.55, rows * 0.85, rows * 0.4 + 1.8
d = 1.08 * (w / 2 + 1) / (math.tan(math.radians(25)) * 1920 / 1080)
scene = {"version": 1,
         "camera": {"position": [w / 2, 1.6 + h * 0.25, d], "target": [w / 2, h / 2, -depth / 2],
                    "fov_degrees": 50, "near": 0.5, "far": 4000, "resolution": [1920, 1080]},
         "character_types": [{"name": "spectator", "pack": "spectator.crowdpack",
                              "texture_variants": {"head": 4, "upper_body": 6, "trousers": 3}}],
         "generators": [{"kind": "seat_grid", "type": "spectator", "origin": [0, 0, 0],
                         "rows": rows, "columns": cols, "spacing": [0.55, 0.85], "row_rise": 0.4,
                         "seed": 7, "clips": ["idle", "clap", "cheer"], "time_offset": [0, 3],
                         "textures": "random"}]}
json.dump(scene, open(out + "/stand-1m.json", "w"))
EOF
"$crowdbake" render "$OUT/stand-1m.json" -o "$OUT/stand-1m.png" --time 1 --stats "$OUT/stand-1m.stats.json" --quiet
python3 - "$OUT/stand-1m.stats.json" <<'EOF'
import json, sys
j = json.load(open(sys.argv[1]))
f = j["frames"][0]
print("1M seats on %s: visible %d, drawn %d, %d triangles, GPU %.1f ms, %.0f MB GPU memory"
      % (j["device"], f["visible"], f["drawn"], f["triangles"], f["gpu_ms"],
         f["gpu_bytes"]["total"] / 1e6))
EOF
