#!/bin/sh
# Bakes the shared CesiumMan (CC-BY 4.0, Cesium; see its SOURCE.md) with variant images for its
# upper body and trousers, made from its own texture by samples/variants/make_variant_images
# (hue shifts), and renders a row of CesiumMen wearing them: docs/variant-images.png.
# Usage: scripts/render-variants.sh [BUILD_DIR] [ASSETS_DIR]   (after scripts/build.sh)
set -eu
cd "$(dirname "$0")/.."
build=${1:-build}
assets=${2:-../shared/assets}
if [ ! -f "$assets/CesiumMan/CesiumMan.glb" ]; then
  echo "render-variants: no shared assets at $assets; nothing to render" >&2
  exit 0
fi
work=out/variants
mkdir -p "$work"
"$build/cli/crowdbake" bake "$assets/CesiumMan/CesiumMan.glb" -o "$work/plain.crowdpack" --quiet
"$build/samples/variants/make_variant_images" "$work/plain.crowdpack" -o "$work" \
  --hue 60 --hue 150 --hue 240 >/dev/null
cat >"$work/config.json" <<'JSON'
{"variants": {"upper_body": ["hue150.png", "hue240.png"], "trousers": ["hue60.png"]}}
JSON
"$build/cli/crowdbake" bake "$assets/CesiumMan/CesiumMan.glb" -o "$work/CesiumMan.crowdpack" \
  --config "$work/config.json" --quiet
# Six CesiumMen: each upper-body variant (0 = its own texture) with each trousers variant.
python3 - "$work" <<'PY'
import json, sys
work = sys.argv[1]
instances = []
for k, (upper, trousers) in enumerate([(0, 0), (1, 0), (2, 0), (0, 1), (1, 1), (2, 1)]):
    instances.append({"position": [0.9 * (k - 2.5), 0, 0], "clip": "animation_0",
                      "time_offset": 0.25 * k, "textures": {"upper_body": upper, "trousers": trousers}})
scene = {"version": 1, "lod": {"mode": "full"},
         "camera": {"position": [0.0, 1.0, 3.3], "target": [0.0, 0.75, 0.0], "fov_degrees": 42,
                    "near": 0.1, "far": 50, "resolution": [1280, 440]},
         "character_types": [{"name": "CesiumMan", "pack": "CesiumMan.crowdpack"}],
         "instances": instances}
json.dump(scene, open(f"{work}/scene.json", "w"), indent=1)
PY
"$build/cli/crowdbake" render "$work/scene.json" -o docs/variant-images.png --time 0.5 --msaa 4 --quiet
echo "wrote docs/variant-images.png"
