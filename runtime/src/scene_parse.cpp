// scene.json → Scene (docs/scene-format.md). Three stages, so a file's own mistakes are
// reported before any pack is opened: (1) read every key into plain structs, checking types,
// ranges and unknown keys; (2) open the packs; (3) resolve names against the packs (clips)
// and build the instance arrays, listed instances first, then each generator in order; then
// every section in SceneLoadOptions::sections resolves its key. Stage 1 is scene_file.cpp.
// Problems are thrown as json_reader::JsonError (kInvalidScene) and returned as a Status at the
// boundary.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <new>
#include <sstream>

#include "crowdbake/base/json_reader.h"
#include "crowdbake/base/random.h"
#include "crowdbake/runtime/scene.h"
#include "scene_file.h"

namespace crowdbake::runtime {
namespace {

using namespace scene_file;
using namespace json_reader;
using scene_file::fail;

// Generators' draws (the same on every platform, base/random.h).
class Random {
 public:
  explicit Random(uint64_t seed) : bits_(seed) {}
  uint64_t next() { return bits_.next(); }
  float unit() { return bits_.next_float(); }  // [0, 1)
  float in(const Range& r) { return r.lo + (r.hi - r.lo) * unit(); }
  uint32_t below(uint32_t n) {
    return std::min(n - 1, static_cast<uint32_t>(unit() * static_cast<float>(n)));
  }

 private:
  SplitMix64 bits_;
};

uint64_t mix(uint64_t seed, uint64_t index, uint64_t stream) {
  Random r(seed ^ (index * 0xD1B54A32D192ED03ull) ^ (stream * 0x8CB92BA72F3D8DD7ull));
  return r.next();
}

// ---- Stages 2 and 3: packs, names, instances --------------------------------------------

struct Resolved {
  uint32_t type = 0;
  std::vector<uint32_t> clips;  // Scene::clips indices
  float neck = 0.0f, waist = 0.0f;
};

Resolved resolve(const Scene& scene, const RawAttributes& a) {
  Resolved r;
  if (a.type.empty()) {
    if (scene.types.size() != 1)
      fail(a.path + ".type", "missing (required when the scene has several character types)");
    r.type = 0;
  } else {
    const int32_t t = scene.find_type(a.type);
    if (t < 0) {
      std::string names;
      for (const CharacterType& ct : scene.types) names += (names.empty() ? "" : ", ") + ct.name;
      fail(a.path + ".type", "unknown character type \"" + a.type + "\" (types: " + names + ")");
    }
    r.type = static_cast<uint32_t>(t);
  }
  const CharacterType& type = scene.types[r.type];
  const bool several = a.clips.size() > 1;
  for (size_t k = 0; k < a.clips.size(); ++k) {
    const int32_t c = scene.find_clip(r.type, a.clips[k]);
    if (c < 0)
      fail(several ? item_path(a.path + ".clips", k) : a.path + ".clip",
           "character type '" + type.name + "' has no clip \"" + a.clips[k] +
               "\" (its clips: " + type.pack.clip_names() + ")");
    r.clips.push_back(static_cast<uint32_t>(c));
  }
  if (r.clips.empty()) r.clips.push_back(type.first_clip);
  const TextureVariants& v = type.texture_variants;
  const uint32_t counts[3] = {v.head, v.upper_body, v.trousers};
  const char* names[3] = {"head", "upper_body", "trousers"};
  for (int k = 0; k < 3; ++k)
    if (!a.textures.random[k] && a.textures.value[k] >= counts[k])
      fail(a.textures.path + "." + names[k],
           "variant " + std::to_string(a.textures.value[k]) + " is out of range: character type '" +
               type.name + "' has " + std::to_string(counts[k]) + " " + names[k] +
               " variant(s) (character_types texture_variants)");
  const PartitionMask& part = type.pack.contents().partition;
  r.neck = a.neck_height.value_or(part.neck_height);
  r.waist = a.waist_height.value_or(part.waist_height);
  if (r.waist > r.neck)
    fail(a.path + (a.waist_height ? ".waist_height" : ".neck_height"),
         "waist height " + show(r.waist) + " is above neck height " + show(r.neck));
  return r;
}

// Draws one instance's attributes (always the same number of draws, in the same order, so
// changing one attribute's range does not reshuffle the others).
Instance make_instance(const Scene& scene, const RawAttributes& a, const Resolved& r, Random& rng) {
  Instance in;
  in.type = r.type;
  const uint32_t pick = rng.below(static_cast<uint32_t>(r.clips.size()));
  in.clip = r.clips[pick];
  in.speed = rng.in(a.speed);
  in.time_offset = rng.in(a.time_offset);
  in.scale = rng.in(a.scale);
  const TextureVariants& v = scene.types[r.type].texture_variants;
  const uint32_t counts[3] = {v.head, v.upper_body, v.trousers};
  for (int k = 0; k < 3; ++k) {
    const uint32_t drawn = rng.below(counts[k]);
    in.textures[k] = static_cast<uint8_t>(
        a.textures.random[k] ? drawn : static_cast<uint32_t>(a.textures.value[k]));
  }
  const float h = rng.unit() * 2.0f - 1.0f, s = rng.unit() * 2.0f - 1.0f,
              b = rng.unit() * 2.0f - 1.0f;
  in.color = {a.color[0] + h * a.color_variation[0], a.color[1] * (1.0f + s * a.color_variation[1]),
              a.color[2] * (1.0f + b * a.color_variation[2])};
  in.neck_height = r.neck;
  in.waist_height = r.waist;
  return in;
}

void open_packs(const RawScene& raw, const std::string& base_dir, const SceneLoadOptions& options,
                Scene& scene) {
  for (const RawType& t : raw.types) {
    std::filesystem::path p(t.pack);
    if (p.is_relative() && !base_dir.empty()) p = std::filesystem::path(base_dir) / p;
    Pack pack;
    const Status s =
        Pack::open_file(p.lexically_normal().string(), pack, options.pack_parts | kPackPartition);
    if (!s) fail(t.path + ".pack", s.message(), s.code());
    if (pack.contents().clips.empty())
      fail(t.path + ".pack", pack.source_name() + ": the pack has no clips to play");
    // note: without texture_variants a pack's variant images are its variants (0: its own).
    TextureVariants variants = t.variants;
    const PackVariantImages& images = pack.contents().variant_images;
    if (!t.variants_given && !images.empty())
      variants = {1 + images.count[0], 1 + images.count[1], 1 + images.count[2]};
    uint32_t index = 0;
    const Status added = add_character_type(scene, t.name, std::move(pack), variants, &index);
    if (!added) fail(t.path, added.message());
    scene.types[index].shading = t.shading;
  }
}

// Places a relaxation generator's people through the caller's placer (crowdbake_crowd).
void build_relaxation(const RawGenerator& g, const Resolved& r, const SceneLoadOptions& options,
                      Scene& scene) {
  if (!options.relaxation)
    fail(g.path + ".kind",
         "relaxation placement needs a placer: load the scene with crowdbake_scene_effects' "
         "crowd_scene_load_options() (SceneLoadOptions::relaxation)");
  RelaxationResult placed;
  const Status s = options.relaxation(g.relax, placed);
  if (!s) fail(g.path, s.message());
  if (placed.positions.size() != g.count || placed.yaw_degrees.size() != g.count)
    fail(g.path, "the placer returned " + std::to_string(placed.positions.size()) +
                     " positions for " + std::to_string(g.count) + " people");
  for (uint32_t k = 0; k < g.count; ++k) {
    Random rng(mix(g.seed, k, 2));
    Instance in = make_instance(scene, g.a, r, rng);
    in.position = {placed.positions[k][0], g.y, placed.positions[k][1]};
    in.rotation = yaw_quaternion(placed.yaw_degrees[k]);
    scene.instances.add(in);
  }
}

void build_instances(const RawScene& raw, const SceneLoadOptions& options, Scene& scene) {
  InstanceArrays& out = scene.instances;
  uint64_t total = raw.instances.size();
  for (const RawGenerator& g : raw.generators)
    total += g.grid ? uint64_t{g.rows} * g.columns : g.count;
  out.reserve(static_cast<size_t>(total));
  for (const RawInstance& ri : raw.instances) {
    const Resolved r = resolve(scene, ri.a);
    Random rng(0);
    Instance in = make_instance(scene, ri.a, r, rng);
    in.position = ri.position;
    in.rotation = ri.rotation;
    out.add(in);
  }
  for (const RawGenerator& g : raw.generators) {
    const Resolved r = resolve(scene, g.a);
    const uint32_t first = static_cast<uint32_t>(out.size());
    if (g.relaxation) {
      build_relaxation(g, r, options, scene);
    } else if (g.grid) {
      const float yaw = g.yaw_degrees * kPi / 180.0f;
      const float c = std::cos(yaw), s = std::sin(yaw);
      const std::array<float, 4> rotation = yaw_quaternion(g.yaw_degrees);
      for (uint32_t row = 0; row < g.rows; ++row) {
        for (uint32_t col = 0; col < g.columns; ++col) {
          const uint64_t seat = uint64_t{row} * g.columns + col;
          Random gaps(mix(g.seed, seat, 1));
          if (gaps.unit() < g.empty_probability) continue;
          Random rng(mix(g.seed, seat, 2));
          Instance in = make_instance(scene, g.a, r, rng);
          // note: seats go along +X of the grid, rows back along -Z and up by row_rise; the
          // crowd faces +Z of the grid (the spectator faces +Z), turned by yaw about +Y.
          const float lx = static_cast<float>(col) * g.spacing[0];
          const float lz = -static_cast<float>(row) * g.spacing[1];
          in.position = {g.origin[0] + c * lx + s * lz,
                         g.origin[1] + static_cast<float>(row) * g.row_rise,
                         g.origin[2] - s * lx + c * lz};
          in.rotation = rotation;
          out.add(in);
        }
      }
      if (g.stand) add_stand(g.shape(), *g.stand, scene.static_geometry);
    } else {
      for (uint32_t k = 0; k < g.count; ++k) {
        Random rng(mix(g.seed, k, 2));
        Instance in = make_instance(scene, g.a, r, rng);
        Random place(mix(g.seed, k, 3));
        const float x = g.rect_min[0] + (g.rect_max[0] - g.rect_min[0]) * place.unit();
        const float z = g.rect_min[1] + (g.rect_max[1] - g.rect_min[1]) * place.unit();
        const float yaw = place.unit() * 360.0f - 180.0f;
        in.position = {x, g.y, z};
        in.rotation = yaw_quaternion(g.random_yaw ? yaw : g.yaw_degrees);
        out.add(in);
      }
    }
    scene.generated.push_back({first, static_cast<uint32_t>(out.size()) - first, g.relaxation});
  }
  if (raw.pitch) add_pitch(*raw.pitch, scene.static_geometry);
}

void build(const Json& root, const std::string& base_dir, const SceneLoadOptions& options,
           Scene& out) {
  RawScene raw = read_scene_file(root, options);
  Scene scene;
  scene.camera = raw.camera;
  scene.camera_path = raw.path;
  scene.lod = raw.lod;
  scene.animation = raw.animation;
  open_packs(raw, base_dir, options, scene);
  build_instances(raw, options, scene);
  for (size_t i = 0; i < options.sections.size(); ++i) {
    if (!options.sections[i].resolve) continue;
    const Status resolved = options.sections[i].resolve(std::move(raw.sections[i]), scene);
    if (!resolved) throw JsonError{"", resolved.message(), resolved.code()};
  }
  out = std::move(scene);
}

}  // namespace

Status parse_scene(std::string_view text, const std::string& name, const std::string& base_dir,
                   Scene& out, const SceneLoadOptions& options) {
  try {
    Json root;
    const Status parsed = parse_json(text, name, StatusCode::kInvalidScene, root);
    if (!parsed) return parsed;
    return read_json(name, StatusCode::kInvalidScene, [&] { build(root, base_dir, options, out); });
  } catch (const std::bad_alloc&) {
    return {StatusCode::kOutOfMemory, name + ": out of memory while loading the scene"};
  } catch (const std::exception& e) {
    return {StatusCode::kInvalidScene, name + ": " + e.what()};
  }
}

Status load_scene(const std::string& path, Scene& out, const SceneLoadOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {StatusCode::kIoError, path + ": cannot open: " + std::strerror(errno)};
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return {StatusCode::kIoError, path + ": read failed"};
  const std::filesystem::path base = std::filesystem::path(path).parent_path();
  return parse_scene(text.str(), path, base.string(), out, options);
}

}  // namespace crowdbake::runtime
