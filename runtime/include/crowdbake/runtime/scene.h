// Scene: character types (packs), the crowd's instances as parallel arrays, a camera, and
// the LoD and animation settings — loaded from a scene.json (docs/scene-format.md) or built
// from code.
//
// Instance state is kept as parallel arrays (InstanceArrays): one tightly packed array per
// attribute, instance i at index i (3 or 4 floats per instance for vectors), so each array
// uploads to a GPU buffer as is (read it as float[] / uint[] in std430).
#pragma once

#include <any>
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "crowdbake/formats/animation_codec.h"
#include "crowdbake/runtime/animate_job.h"
#include "crowdbake/runtime/camera.h"
#include "crowdbake/runtime/cull_job.h"
#include "crowdbake/runtime/lod_select_job.h"
#include "crowdbake/runtime/pack.h"
#include "crowdbake/runtime/scene_extensions.h"
#include "crowdbake/runtime/static_geometry.h"
#include "crowdbake/runtime/status.h"

namespace crowdbake::runtime {

// Instances [first, first + count) came from one generator (Scene::generated, in order).
struct InstanceRange {
  uint32_t first = 0, count = 0;
  bool relaxation = false;  // a "relaxation" generator (placed by SceneLoadOptions::relaxation)
};

// Upper bound on instances in one scene (generators are checked against it before anything
// is allocated).
constexpr uint32_t kMaxInstances = 1u << 24;

// How many texture variants a character type has per partition region (docs/design.md §3.7);
// an instance's texture choice for a region is in [0, count).
struct TextureVariants {
  uint32_t head = 1, upper_body = 1, trousers = 1;  // each 1..256
};

// Where a character type's colours come from (docs/scene-format.md "shading"): its pack's own
// materials (base colour texture × factor), or the generated swatches, whose per-region
// variants give a crowd of one character many looks (seed Algorithm 3). Auto: swatches when the
// type has more than one texture variant in some region, its materials otherwise. The
// instance's HSB variation applies on top of either.
enum class Shading : uint8_t { kAuto, kMaterial, kSwatches };

// note: Scene::clips points into each type's pack: add types with add_character_type and do
// not replace a type's pack afterwards.
struct CharacterType {
  std::string name;
  std::string pack_path;  // as opened (scene files: resolved against the scene's folder)
  TextureVariants texture_variants;
  Shading shading = Shading::kAuto;
  Pack pack;
  uint32_t first_clip = 0;  // index of the type's clip 0 in Scene::clips
};

// kMaterial or kSwatches: what kAuto means for this type.
Shading resolved_shading(const CharacterType& type);

struct AnimationSettings {
  FrameFilter filter = FrameFilter::kNearest;  // nearest (seed Algorithm 2) or interpolated
  bool root_motion = true;                     // apply the clips' root motion (frame.h)
};

// One instance, for building crowds from code (InstanceArrays::add / get).
struct Instance {
  uint32_t type = 0;                                      // index into Scene::types
  Vec3 position{0.0f, 0.0f, 0.0f};                        // world units
  std::array<float, 4> rotation{0.0f, 0.0f, 0.0f, 1.0f};  // unit quaternion x, y, z, w
  float scale = 1.0f;                                     // uniform, > 0
  uint32_t clip = 0;                         // index into Scene::clips (a clip of `type`)
  float speed = 1.0f;                        // playback speed, >= 0
  float time_offset = 0.0f;                  // seconds, >= 0
  std::array<uint8_t, 3> textures{0, 0, 0};  // variant per region: head, upper body, trousers
  float neck_height = 0.0f;                  // partition heights along the pack's up axis, bind
  float waist_height = 0.0f;                 // pose, model units (waist <= neck)
  Vec3 color{0.0f, 1.0f, 1.0f};  // hue shift (degrees), saturation and brightness scales
};

struct InstanceArrays {
  std::vector<uint32_t> type;
  std::vector<float> position;  // 3 per instance
  std::vector<float> rotation;  // 4 per instance: x, y, z, w
  std::vector<float> scale;
  std::vector<uint32_t> clip;  // index into Scene::clips
  std::vector<float> speed;
  std::vector<float> time_offset;
  std::vector<uint32_t> textures;  // head | upper_body << 8 | trousers << 16
  std::vector<float> neck_height;
  std::vector<float> waist_height;
  std::vector<float> color;  // 3 per instance: hue shift (deg), saturation, brightness

  size_t size() const { return type.size(); }
  // True when every array has the length size() instances need (3 or 4 per instance for
  // vectors). The CPU reference path refuses inconsistent arrays.
  bool consistent() const;
  void clear();
  void reserve(size_t n);
  void add(const Instance& instance);
  // Instance i (i < size()).
  Instance get(size_t i) const;
};

struct Scene {
  Camera camera;
  std::vector<CameraKey> camera_path;  // empty: the camera stays put
  LodSettings lod;
  AnimationSettings animation;
  std::vector<CharacterType> types;
  std::vector<ClipRef> clips;  // every type's clips, type by type (CharacterType::first_clip)
  InstanceArrays instances;
  // What the sections read by other libraries made of their keys (SceneSection::resolve), by
  // key: "effects" holds crowdbake_scene_effects' declaration (effects/scene_effects.h).
  std::map<std::string, std::any, std::less<>> sections;
  // Per scene.json generator, in file order: the instances it made.
  std::vector<InstanceRange> generated;
  // Stands and pitch (seat_grid "stand", "pitch"): drawn with the crowd, never animated.
  StaticGeometry static_geometry;

  // Index of the type with this name, or -1.
  int32_t find_type(std::string_view name) const;
  // Scene::clips index of the type's clip with this name, or -1.
  int32_t find_clip(uint32_t type, std::string_view name) const;
  // The camera at a time (camera_at over camera_path).
  Camera camera_at_time(float time) const;
};

// Adds a character type to a scene built from code and appends its clips to Scene::clips.
// Returns its type index in *index (may be null).
// Returns kInvalidArgument when the name is empty or taken, the pack is not open or a
// texture variant count is outside 1..256.
// pack: an open pack, moved in
Status add_character_type(Scene& scene, std::string name, Pack pack,
                          const TextureVariants& variants = {}, uint32_t* index = nullptr);

struct SceneLoadOptions {
  // Pack parts to load for every type (PackPart flags). The tables are always read, and so
  // is PART (the partition heights are the instances' default neck/waist heights).
  uint32_t pack_parts = kPackAll;
  // Places "relaxation" generators (crowd-patches Lloyd relaxation). The runtime core has no
  // placement of its own: crowdbake_scene_effects' crowd_scene_load_options() sets this; a
  // scene with a relaxation generator and no placer fails to load, saying so.
  RelaxationPlacer relaxation;
  // Readers of top-level keys the core does not know (scene_extensions.h), each key once.
  // crowd_scene_load_options() adds the "effects" reader.
  std::vector<SceneSection> sections;
};

// Reads and checks a scene file, opens its packs (paths relative to the file's folder) and
// builds the instances (listed and generated).
// Returns kIoError when the file cannot be read, kInvalidScene for a problem in the file
// (message: "<file>: <key path>: <problem>", e.g. "scene.json: instances[3].clip: type
// 'spectator' has no clip 'dance' (its clips: idle, sit, ...)"), or a pack's kInvalidPack /
// kIoError prefixed with the key that names it. `out` is replaced only on success.
// path: scene.json
Status load_scene(const std::string& path, Scene& out, const SceneLoadOptions& options = {});

// load_scene on text already in memory.
// json: the file's contents
// name: what messages call the file
// base_dir: folder that relative pack paths start from
Status parse_scene(std::string_view json, const std::string& name, const std::string& base_dir,
                   Scene& out, const SceneLoadOptions& options = {});

// LoD selection's view of a type (LodSelectJob::types): LoD range, triangle count and the
// discrete levels of `settings` (fractions of max_vertices, clamped to the range, rounded
// down to a collapse-group start; needs only the pack's tables).
LodType make_lod_type(const Pack& pack, const LodSettings& settings);

// Culling's view of a type (CullJob::bounds).
TypeBounds make_type_bounds(const Pack& pack);

}  // namespace crowdbake::runtime
