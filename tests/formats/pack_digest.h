// Digests of a pack's decoded content, one per part, for frozen packs (tests/data/packs):
// they depend only on what the reader returns, never on how the bytes were laid out, so a
// pack written by an older writer keeps its digests as long as today's reader decodes the
// same content.
#pragma once

#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <type_traits>
#include <vector>

#include "crowdbake/formats/pack.h"

namespace crowdbake::test {

class Fnv1a {
 public:
  void bytes(const void* data, size_t size) {
    const auto* p = static_cast<const uint8_t*>(data);
    for (size_t i = 0; i < size; ++i) hash_ = (hash_ ^ p[i]) * 0x100000001b3ull;
  }
  template <typename T>
  void value(const T& v) {
    static_assert(std::is_arithmetic_v<T>);
    bytes(&v, sizeof v);
  }
  template <typename T, size_t N>
  void value(const std::array<T, N>& a) {
    for (const T& v : a) value(v);
  }
  void value(const std::string& s) {
    value(uint64_t{s.size()});
    bytes(s.data(), s.size());
  }
  template <typename T>
  void value(const std::vector<T>& v) {
    value(uint64_t{v.size()});
    for (const T& x : v) value(x);
  }
  std::string hex() const {
    char out[17];
    std::snprintf(out, sizeof out, "%016llx", static_cast<unsigned long long>(hash_));
    return out;
  }

 private:
  uint64_t hash_ = 0xcbf29ce484222325ull;
};

inline std::map<std::string, std::string> pack_digests(const PackContents& c) {
  std::map<std::string, std::string> out;
  Fnv1a tables;
  tables.value(c.name);
  tables.value(c.settings_json);
  for (const PackJoint& j : c.joints) {
    tables.value(j.name), tables.value(j.parent), tables.value(j.inverse_bind);
    tables.value(j.rest_translation), tables.value(j.rest_rotation), tables.value(j.rest_scale);
  }
  for (const PackClip& k : c.clips) {
    tables.value(k.name), tables.value(k.first_row), tables.value(k.frame_count);
    tables.value(k.fps), tables.value(k.duration), tables.value(k.looping);
    tables.value(k.root_motion);
  }
  for (const PackMaterial& m : c.materials)
    tables.value(m.name), tables.value(m.base_color), tables.value(m.base_color_texture);
  tables.value(c.bounds.min), tables.value(c.bounds.max), tables.value(c.bounds.radius);
  out["tables"] = tables.hex();
  Fnv1a geometry;
  const PackGeometry& g = c.geometry;
  geometry.value(g.positions), geometry.value(g.normals), geometry.value(g.uvs);
  geometry.value(g.joints), geometry.value(g.weights), geometry.value(g.regions);
  geometry.value(g.triangles), geometry.value(g.triangle_material);
  out["geometry"] = geometry.hex();
  Fnv1a progressive;
  progressive.value(c.progressive.collapse_to), progressive.value(c.progressive.triangle_count);
  progressive.value(c.progressive.group_start), progressive.value(c.progressive.min_vertices);
  out["progressive"] = progressive.hex();
  Fnv1a errors;
  errors.value(c.level_errors.vertices), errors.value(c.level_errors.max_error);
  errors.value(c.level_errors.rms_error);
  out["level_errors"] = errors.hex();
  Fnv1a animation;
  const AnimationTexture& a = c.animation;
  animation.value(static_cast<uint32_t>(a.encoding)), animation.value(a.joints);
  animation.value(a.texels_per_joint), animation.value(a.bytes_per_texel), animation.value(a.rows);
  animation.value(a.decode_params), animation.value(a.data);
  out["animation"] = animation.hex();
  Fnv1a partition;
  const PartitionMask& p = c.partition;
  partition.value(p.width), partition.value(p.height), partition.value(p.texels);
  partition.value(p.neck_height), partition.value(p.waist_height), partition.value(p.up_axis);
  out["partition"] = partition.hex();
  // note: only packs with vertex colours (1.7) have this entry, as with images below.
  if (!c.vertex_colors.empty()) {
    Fnv1a colors;
    colors.value(c.vertex_colors);
    out["vertex_colors"] = colors.hex();
  }
  // note: only packs with images have this entry, so the digests of older sets stay as frozen.
  if (!c.images.empty() || !c.variant_images.empty()) {
    Fnv1a images;
    for (const PackImage& image : c.images)
      images.value(image.name), images.value(image.mime_type), images.value(image.data);
    images.value(c.variant_images.first), images.value(c.variant_images.count);
    out["images"] = images.hex();
  }
  return out;
}

}  // namespace crowdbake::test
