// Scenes for the drawing tests (draw_*, renderer_*): the hand-built small pack of
// runtime_test_support.h re-encoded in each animation encoding, and crowds of the generated
// spectator, both built from code.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "crowdbake/formats/animation_codec.h"
#include "crowdbake/formats/pack.h"
#include "crowdbake/runtime/byte_source.h"
#include "crowdbake/runtime/pack.h"
#include "crowdbake/runtime/scene.h"
#include "pack_bytes.h"
#include "runtime/runtime_test_support.h"

namespace crowdbake::test {

// The small pack (3 joints, 8 rows, a 6x6 sheet) with its animation in `encoding`.
inline std::vector<uint8_t> small_pack_bytes_encoded(AnimationEncoding encoding,
                                                     uint32_t grid = 6) {
  PackContents c = make_small_pack(grid);
  std::vector<double> matrices;
  for (uint32_t r = 0; r < c.animation.rows; ++r)
    for (uint32_t j = 0; j < c.animation.joints; ++j) {
      float m[12];
      small_pack_matrix(r, j, m);
      matrices.insert(matrices.end(), m, m + 12);
    }
  c.animation =
      encode_animation_texture(encoding, c.animation.joints, c.animation.rows, matrices.data());
  PackWriteOptions options;
  options.codec = GeometryCodec::kRaw;
  return test::pack_bytes(c, options);
}

inline runtime::Status add_pack_bytes(runtime::Scene& scene, const std::string& name,
                                      std::vector<uint8_t> bytes,
                                      const runtime::TextureVariants& variants = {}) {
  runtime::Pack pack;
  if (runtime::Status s = runtime::Pack::open(runtime::make_memory_source(std::move(bytes), name),
                                              pack, runtime::kPackAll);
      !s)
    return s;
  return runtime::add_character_type(scene, name, std::move(pack), variants);
}

inline runtime::Status add_pack_file(runtime::Scene& scene, const std::string& name,
                                     const std::string& path,
                                     const runtime::TextureVariants& variants = {}) {
  runtime::Pack pack;
  if (runtime::Status s = runtime::Pack::open_file(path, pack, runtime::kPackAll); !s) return s;
  return runtime::add_character_type(scene, name, std::move(pack), variants);
}

// A rows x columns grid of instances of `type`, `spacing` apart, facing the camera (+Z),
// cycling through the type's clips with different offsets, texture variants and colours.
inline void add_grid(runtime::Scene& scene, uint32_t type, uint32_t rows, uint32_t columns,
                     float spacing, float z0 = 0.0f) {
  const runtime::CharacterType& t = scene.types[type];
  const uint32_t clips = static_cast<uint32_t>(t.pack.contents().clips.size());
  const PartitionMask& mask = t.pack.contents().partition;
  for (uint32_t r = 0; r < rows; ++r)
    for (uint32_t c = 0; c < columns; ++c) {
      const uint32_t k = r * columns + c;
      runtime::Instance i;
      i.type = type;
      i.position = {(static_cast<float>(c) - 0.5f * static_cast<float>(columns - 1)) * spacing,
                    0.0f, z0 - static_cast<float>(r) * spacing};
      const float yaw = 0.3f * static_cast<float>(k % 5) - 0.6f;
      i.rotation = {0.0f, std::sin(yaw / 2), 0.0f, std::cos(yaw / 2)};
      i.clip = t.first_clip + k % clips;
      i.speed = 0.8f + 0.1f * static_cast<float>(k % 4);
      i.time_offset = 0.37f * static_cast<float>(k);
      i.textures = {static_cast<uint8_t>(k % t.texture_variants.head),
                    static_cast<uint8_t>((k / 2) % t.texture_variants.upper_body),
                    static_cast<uint8_t>((k / 3) % t.texture_variants.trousers)};
      i.neck_height = mask.neck_height;
      i.waist_height = mask.waist_height;
      i.color = {20.0f * static_cast<float>(k % 7) - 60.0f,
                 0.8f + 0.05f * static_cast<float>(k % 5),
                 0.9f + 0.05f * static_cast<float>(k % 4)};
      scene.instances.add(i);
    }
}

// Every animation encoding and both frame filters, for tests that run each combination.
constexpr AnimationEncoding kAllEncodings[] = {
    AnimationEncoding::kFloat32, AnimationEncoding::kFloat16, AnimationEncoding::kQuantized};
constexpr FrameFilter kAllFilters[] = {FrameFilter::kNearest, FrameFilter::kLinear};

// "float16 linear": names one combination (for SCOPED_TRACE).
inline std::string encoding_and_filter(AnimationEncoding encoding, FrameFilter filter) {
  return std::string(animation_encoding_name(encoding)) +
         (filter == FrameFilter::kLinear ? " linear" : " nearest");
}

// The small pack with its animation in `encoding`, `filter` between frames, and a rows x
// columns grid of it (add_grid).
inline runtime::Status add_small_grid(runtime::Scene& scene, AnimationEncoding encoding,
                                      FrameFilter filter, uint32_t rows, uint32_t columns,
                                      float spacing) {
  scene.animation.filter = filter;
  if (runtime::Status s = add_pack_bytes(scene, "small", small_pack_bytes_encoded(encoding)); !s)
    return s;
  add_grid(scene, 0, rows, columns, spacing);
  return {};
}

}  // namespace crowdbake::test
