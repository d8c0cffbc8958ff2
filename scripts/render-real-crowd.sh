#!/bin/sh
# Bakes a few of the shared characters (CesiumMan, the Fox and CC0 Quaternius characters; see
# each asset's SOURCE.md for its licence and attribution) with the default settings and renders
# them as one small crowd with their own materials: docs/real-crowd.png. Then bakes CesiumMan
# (CC-BY 4.0, Cesium) with variant images for its upper body and trousers, made from its own
# texture by samples/variants/make_variant_images (hue shifts), and renders a row of CesiumMen
# wearing them: docs/variant-images.png.
# Usage: scripts/render-real-crowd.sh [BUILD_DIR] [ASSETS_DIR]   (after scripts/build.sh)
set -eu
cd "$(dirname "$0")/.."
build=${1:-build}
assets=${2:-../shared/assets}
if [ ! -f "$assets/MANIFEST.json" ]; then
  echo "render-real-crowd: no shared assets at $assets; nothing to render" >&2
  exit 0
fi
work=out/real-crowd
mkdir -p "$work"
chars="CesiumMan/CesiumMan.glb Quaternius_MaleCasual/Male_Casual.fbx
  Quaternius_FemaleCasual/Female_Casual.fbx Quaternius_Cowboy/Cowboy.fbx
  Quaternius_Knight/KnightCharacter.fbx Quaternius_Goblin/Goblin.fbx Quaternius_Zombie/Zombie.fbx
  Quaternius_Skeleton/Skeleton.fbx Fox/Fox.glb"
packs=""
for c in $chars; do
  name=$(basename "$c" | sed 's/\.[^.]*$//')
  "$build/cli/crowdbake" bake "$assets/$c" -o "$work/$name.crowdpack" --quiet
  "$build/cli/crowdbake" inspect "$work/$name.crowdpack" --json >"$work/$name.json"
  packs="$packs $name"
done
python3 - "$work" $packs <<'PY'
import json, math, sys
work, names = sys.argv[1], sys.argv[2:]
types, instances = [], []
for column, name in enumerate(names):
    info = json.load(open(f"{work}/{name}.json"))
    lo, hi = info["bounds"]["min"], info["bounds"]["max"]
    height = max(hi[1] - lo[1], 1e-6)
    scale = (0.7 if name == "Fox" else 1.75) / height
    clips = [c["name"] for c in info["clips"]]
    def pick(*words):
        for w in words:
            for c in clips:
                if w in c.lower():
                    return c
        return clips[0]
    types.append({"name": name, "pack": f"{name}.crowdpack", "shading": "material"})
    for row, (clip, z) in enumerate([(pick("idle", "survey"), 0.0), (pick("walk"), -1.6),
                                      (pick("wave", "run", "punch", "attack"), -3.2)]):
        instances.append({"type": name, "position": [1.1 * (column - (len(names) - 1) / 2), 0, z],
                          "scale": scale, "clip": clip, "time_offset": 0.3 * (row + column)})
# note: full resolution: 27 close-up characters need no LoD.
scene = {"version": 1, "lod": {"mode": "full"},
         "camera": {"position": [0.0, 1.9, 5.6], "target": [0.0, 0.85, -1.4], "fov_degrees": 50,
                    "near": 0.1, "far": 100, "resolution": [1280, 720]},
         "character_types": types, "instances": instances}
json.dump(scene, open(f"{work}/scene.json", "w"), indent=1)
PY
"$build/cli/crowdbake" render "$work/scene.json" -o docs/real-crowd.png --time 0.8 --msaa 4 --quiet
echo "wrote docs/real-crowd.png"

# Variant images (docs/materials.md, "Variant images").
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
