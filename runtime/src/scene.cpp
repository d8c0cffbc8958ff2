// Scene helpers shared by scene.json loading and crowds built from code.
#include "crowdbake/runtime/scene.h"

#include <algorithm>
#include <cmath>

#include "crowdbake/runtime/reconstruct_job.h"

namespace crowdbake::runtime {

bool InstanceArrays::consistent() const {
  const size_t n = type.size();
  return position.size() == 3 * n && rotation.size() == 4 * n && scale.size() == n &&
         clip.size() == n && speed.size() == n && time_offset.size() == n && textures.size() == n &&
         neck_height.size() == n && waist_height.size() == n && color.size() == 3 * n;
}

void InstanceArrays::clear() { *this = InstanceArrays{}; }

void InstanceArrays::reserve(size_t n) {
  type.reserve(n);
  position.reserve(3 * n);
  rotation.reserve(4 * n);
  scale.reserve(n);
  clip.reserve(n);
  speed.reserve(n);
  time_offset.reserve(n);
  textures.reserve(n);
  neck_height.reserve(n);
  waist_height.reserve(n);
  color.reserve(3 * n);
}

void InstanceArrays::add(const Instance& in) {
  type.push_back(in.type);
  position.insert(position.end(), in.position.begin(), in.position.end());
  rotation.insert(rotation.end(), in.rotation.begin(), in.rotation.end());
  scale.push_back(in.scale);
  clip.push_back(in.clip);
  speed.push_back(in.speed);
  time_offset.push_back(in.time_offset);
  textures.push_back(uint32_t{in.textures[0]} | uint32_t{in.textures[1]} << 8 |
                     uint32_t{in.textures[2]} << 16);
  neck_height.push_back(in.neck_height);
  waist_height.push_back(in.waist_height);
  color.insert(color.end(), in.color.begin(), in.color.end());
}

Instance InstanceArrays::get(size_t i) const {
  Instance out;
  out.type = type[i];
  for (int k = 0; k < 3; ++k) out.position[k] = position[3 * i + k];
  for (int k = 0; k < 4; ++k) out.rotation[k] = rotation[4 * i + k];
  out.scale = scale[i];
  out.clip = clip[i];
  out.speed = speed[i];
  out.time_offset = time_offset[i];
  for (int k = 0; k < 3; ++k) out.textures[k] = static_cast<uint8_t>(textures[i] >> (8 * k));
  out.neck_height = neck_height[i];
  out.waist_height = waist_height[i];
  for (int k = 0; k < 3; ++k) out.color[k] = color[3 * i + k];
  return out;
}

int32_t Scene::find_type(std::string_view name) const {
  for (size_t i = 0; i < types.size(); ++i)
    if (types[i].name == name) return static_cast<int32_t>(i);
  return -1;
}

int32_t Scene::find_clip(uint32_t type, std::string_view name) const {
  if (type >= types.size()) return -1;
  const int32_t local = types[type].pack.find_clip(name);
  return local < 0 ? -1 : static_cast<int32_t>(types[type].first_clip) + local;
}

Camera Scene::camera_at_time(float time) const { return camera_at(camera, camera_path, time); }

Shading resolved_shading(const CharacterType& type) {
  if (type.shading != Shading::kAuto) return type.shading;
  // note: a pack with variant images has its own looks per region.
  if (!type.pack.contents().variant_images.empty()) return Shading::kMaterial;
  const TextureVariants& v = type.texture_variants;
  return v.head > 1 || v.upper_body > 1 || v.trousers > 1 ? Shading::kSwatches : Shading::kMaterial;
}

Status add_character_type(Scene& scene, std::string name, Pack pack,
                          const TextureVariants& variants, uint32_t* index) {
  if (name.empty()) return {StatusCode::kInvalidArgument, "character type name is empty"};
  if (scene.find_type(name) >= 0)
    return {StatusCode::kInvalidArgument, "character type '" + name + "' exists already"};
  if (!pack.is_open())
    return {StatusCode::kInvalidArgument, "character type '" + name + "': the pack is not open"};
  for (uint32_t v : {variants.head, variants.upper_body, variants.trousers})
    if (v < 1 || v > 256)
      return {StatusCode::kInvalidArgument,
              "character type '" + name + "': texture variant counts must be 1..256"};
  CharacterType t;
  t.name = std::move(name);
  t.texture_variants = variants;
  t.pack_path = pack.source_name();
  t.pack = std::move(pack);
  t.first_clip = static_cast<uint32_t>(scene.clips.size());
  const uint32_t type_index = static_cast<uint32_t>(scene.types.size());
  for (const PackClip& c : t.pack.contents().clips) scene.clips.push_back({&c, type_index});
  scene.types.push_back(std::move(t));
  if (index) *index = type_index;
  return {};
}

LodType make_lod_type(const Pack& pack, const LodSettings& settings) {
  LodType t;
  t.min_vertices = pack.min_vertices();
  t.max_vertices = pack.max_vertices();
  t.triangles = pack.counts().triangles;
  const PackLevelErrors& errors = pack.contents().level_errors;
  t.error_vertices = Span<const uint32_t>(errors.vertices.data(), errors.vertices.size());
  t.error_max = Span<const float>(errors.max_error.data(), errors.max_error.size());
  t.radius = pack.bounds_radius();
  ProgressiveView view = progressive_view(pack.contents());
  view.vertex_count = pack.max_vertices();
  t.level_count = std::min(settings.discrete_level_count, kMaxDiscreteLevels);
  for (uint32_t k = 0; k < t.level_count; ++k) {
    const double wanted = std::floor(double{settings.discrete_levels[k]} * t.max_vertices);
    const uint32_t n = static_cast<uint32_t>(std::clamp(wanted, static_cast<double>(t.min_vertices),
                                                        static_cast<double>(t.max_vertices)));
    t.levels[k] = usable_vertices(view, n);
  }
  return t;
}

TypeBounds make_type_bounds(const Pack& pack) {
  TypeBounds b;
  const std::array<float, 3> c = pack.bounds_center();
  for (int k = 0; k < 3; ++k) b.center[k] = c[k];
  b.radius = pack.bounds_radius();
  return b;
}

}  // namespace crowdbake::runtime
