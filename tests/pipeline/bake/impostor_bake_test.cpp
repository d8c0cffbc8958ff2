// bake_impostor: the spectator's impostor has the shape asked for, covers where the skinned
// mesh is, shows opposite views as mirror images, survives the pack round trip, and is off by
// default.
#include "crowdbake/pipeline/impostor_bake.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "crowdbake/formats/animation_codec.h"
#include "crowdbake/formats/pack.h"
#include "pack_bytes.h"
#include "pipeline_calls.h"
#include "spectator_character.h"

namespace crowdbake {
namespace {

// The spectator baked once with the default settings (no impostor), fast level errors.
const PackContents& spectator_pack() {
  static const PackContents pack = [] {
    BakeSettings settings;
    settings.level_errors.samples = 0;
    BakeReport report;
    return test::build_pack_or_throw(samples::make_spectator_character(), settings, report);
  }();
  return pack;
}

PackImpostor bake(const ImpostorOptions& options) {
  PackImpostor out;
  const Status s = bake_impostor(spectator_pack(), options, out);
  EXPECT_TRUE(s.ok()) << s.message();
  return out;
}

bool covered(const PackImpostor& m, uint32_t view, uint32_t frame, uint32_t x, uint32_t y) {
  const size_t texel =
      (size_t{view} * m.frames + frame) * m.cell_texels() + size_t{y} * m.width + x;
  return ((m.texels[2 * texel + 1] >> 16) & 0xFFu) != PackImpostor::kEmptyTexel;
}

TEST(ImpostorBake, OffByDefault) {
  EXPECT_TRUE(spectator_pack().impostor.empty());
  EXPECT_TRUE(bake(ImpostorOptions{}).empty());
}

TEST(ImpostorBake, HasTheShapeAskedForAndAFrameForEveryRow) {
  const PackContents& pack = spectator_pack();
  const PackImpostor m = bake({8, 4, 32});
  ASSERT_FALSE(m.empty());
  EXPECT_EQ(m.views, 8u);
  EXPECT_EQ(m.height, 32u);
  uint32_t frames = 0;
  for (const PackClip& clip : pack.clips) frames += std::min(4u, clip.frame_count);
  EXPECT_EQ(m.frames, frames);
  ASSERT_EQ(m.frame_of_row.size(), pack.animation.rows);
  // Each clip's rows show that clip's frames, in order (the first row its first frame).
  uint32_t first = 0;
  for (const PackClip& clip : pack.clips) {
    const uint32_t k = std::min(4u, clip.frame_count);
    EXPECT_EQ(m.frame_of_row[clip.first_row], first) << clip.name;
    for (uint32_t r = clip.first_row; r < clip.first_row + clip.frame_count; ++r) {
      EXPECT_GE(m.frame_of_row[r], first);
      EXPECT_LT(m.frame_of_row[r], first + k);
    }
    first += k;
  }
  EXPECT_EQ(m.texels.size(), 2 * size_t{m.views} * m.frames * m.cell_texels());
  EXPECT_GT(m.width, 4u);
  EXPECT_LT(m.width, 64u);
}

// Every vertex of the skinned mesh lies inside the cell, and in every cell the covered texels
// span the mesh's extent along the up axis.
TEST(ImpostorBake, CellsCoverTheSkinnedMesh) {
  const PackContents& pack = spectator_pack();
  const PackImpostor m = bake({8, 4, 32});
  ASSERT_FALSE(m.empty());
  const double texel_height = (m.top - m.bottom) / m.height;
  // The row each frame was drawn at: clip frames evenly spaced from its first row.
  std::vector<uint32_t> rows;
  for (const PackClip& clip : pack.clips) {
    const uint32_t k = std::min(4u, clip.frame_count);
    for (uint32_t i = 0; i < k; ++i) rows.push_back(clip.first_row + i * clip.frame_count / k);
  }
  ASSERT_EQ(rows.size(), m.frames);
  for (uint32_t f = 0; f < m.frames; ++f) {
    const uint32_t row = rows[f];
    EXPECT_EQ(m.frame_of_row[row], f);
    std::vector<float> matrices(12 * size_t{pack.animation.joints});
    for (uint32_t j = 0; j < pack.animation.joints; ++j)
      decode_joint(pack.animation, row, j, &matrices[12 * j]);
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    const PackGeometry& g = pack.geometry;
    for (uint32_t v = 0; v < g.vertex_count(); ++v) {
      double y = 0.0;  // up is +Y for the spectator
      for (int k = 0; k < 4; ++k) {
        const float* r = &matrices[12 * g.joints[4 * v + k]];
        y += g.weights[4 * v + k] * (r[4] * g.positions[3 * v] + r[5] * g.positions[3 * v + 1] +
                                     r[6] * g.positions[3 * v + 2] + r[7]);
      }
      lo = std::min(lo, y), hi = std::max(hi, y);
    }
    EXPECT_GE(lo, m.bottom);
    EXPECT_LE(hi, m.top);
    for (uint32_t v = 0; v < m.views; ++v) {
      uint32_t top_row = m.height, bottom_row = 0;
      for (uint32_t y = 0; y < m.height; ++y)
        for (uint32_t x = 0; x < m.width; ++x)
          if (covered(m, v, f, x, y)) top_row = std::min(top_row, y), bottom_row = y;
      ASSERT_LT(top_row, m.height) << "view " << v << " frame " << f << " is empty";
      // note: covered texels stay inside the mesh's extent and span nearly all of it (a thin
      // tip, a raised finger, may cover no texel centre).
      const double top_y = m.top - (top_row + 0.5) * texel_height;
      const double bottom_y = m.top - (bottom_row + 0.5) * texel_height;
      EXPECT_LE(top_y, hi + 0.5 * texel_height);
      EXPECT_GE(bottom_y, lo - 0.5 * texel_height);
      EXPECT_GT(top_y - bottom_y, 0.9 * (hi - lo)) << "view " << v << " frame " << f;
    }
  }
}

// Orthographic views from opposite sides see the same silhouette, mirrored.
TEST(ImpostorBake, OppositeViewsAreMirrorImages) {
  const PackImpostor m = bake({8, 2, 48});
  ASSERT_FALSE(m.empty());
  size_t agree = 0, total = 0;
  for (uint32_t v = 0; v < m.views / 2; ++v)
    for (uint32_t f = 0; f < m.frames; ++f)
      for (uint32_t y = 0; y < m.height; ++y)
        for (uint32_t x = 0; x < m.width; ++x) {
          const bool a = covered(m, v, f, x, y);
          const bool b = covered(m, v + m.views / 2, f, m.width - 1 - x, y);
          agree += a == b, total += a || b;
        }
  ASSERT_GT(total, 0u);
  EXPECT_GT(static_cast<double>(agree) / total, 0.97) << agree << " of " << total;
}

TEST(ImpostorBake, IsDeterministicAndSurvivesThePackRoundTrip) {
  PackContents pack = spectator_pack();
  pack.impostor = bake({6, 3, 24});
  EXPECT_EQ(bake({6, 3, 24}).texels, pack.impostor.texels);
  const std::vector<uint8_t> bytes = test::pack_bytes(pack);
  PackContents back;
  ASSERT_TRUE(read_pack(bytes.data(), bytes.size(), back).ok());
  EXPECT_EQ(back.impostor.views, 6u);
  EXPECT_EQ(back.impostor.frames, pack.impostor.frames);
  EXPECT_EQ(back.impostor.half_width, pack.impostor.half_width);
  EXPECT_EQ(back.impostor.frame_of_row, pack.impostor.frame_of_row);
  EXPECT_EQ(back.impostor.texels, pack.impostor.texels);
}

TEST(ImpostorBake, RefusesOptionsOutOfRange) {
  PackImpostor out;
  EXPECT_EQ(bake_impostor(spectator_pack(), {300, 4, 32}, out).code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ(bake_impostor(spectator_pack(), {8, 0, 32}, out).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(bake_impostor(spectator_pack(), {8, 4, 0}, out).code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace crowdbake
