// Small real packs for fuzz seeds and fuzz fixtures: the hand-built test character
// (tests/formats/pack_test_contents.h) with a short animation, so a pack is a few KB.
#pragma once

#include <cmath>
#include <vector>

#include "crowdbake/formats/animation_codec.h"
#include "crowdbake/formats/pack.h"
#include "formats/pack_test_contents.h"

namespace crowdbake::fuzz {

inline PackContents small_pack_contents(uint32_t grid, uint32_t seed) {
  PackContents c = test::make_test_contents(grid, seed);
  uint32_t row = 0;
  for (uint32_t k = 0; k < c.clips.size(); ++k) {
    PackClip& clip = c.clips[k];
    clip.first_row = row;
    clip.frame_count = k + 1;
    clip.duration = k / clip.fps;
    if (!clip.root_motion.empty()) clip.root_motion.resize(3 * clip.frame_count);
    row += clip.frame_count;
  }
  c.animation.rows = row;
  c.animation.data.resize(size_t{row} * c.animation.joints * 3 * 16);
  c.partition.width = 16;
  c.partition.height = 8;
  c.partition.texels.resize(16 * 8);
  return c;
}

// The small pack with one 200-frame clip of quantized motion (each joint turning about its
// parent on a slow sine, with jitter), so that a bounded write_pack() stores it as ANIM v3.
inline PackContents bounded_animation_contents(uint32_t seed) {
  PackContents c = small_pack_contents(3, seed);
  const uint32_t rows = 200, joints = static_cast<uint32_t>(c.joints.size());
  c.clips.resize(1);
  c.clips[0].first_row = 0;
  c.clips[0].frame_count = rows;
  c.clips[0].duration = (rows - 1) / c.clips[0].fps;
  c.clips[0].root_motion.clear();
  std::vector<double> m(size_t{rows} * joints * 12, 0.0);
  for (uint32_t r = 0; r < rows; ++r)
    for (uint32_t j = 0; j < joints; ++j) {
      double* out = &m[(size_t{r} * joints + j) * 12];
      const double a = 0.5 * std::sin(0.1 * r + j);
      const double parent_turn = j == 0 ? 0.0 : 0.5 * std::sin(0.1 * r + j - 1);
      // note: turns about +Z accumulate down the chain; a little deterministic jitter keeps
      // the lossless coding from being the smaller.
      const double jitter =
          0.004 * (static_cast<double>((r * 7919u + j * 104729u) % 97u) / 97.0 - 0.5);
      const double t = a + parent_turn + jitter;
      out[0] = std::cos(t), out[1] = -std::sin(t), out[3] = 0.1 * j;
      out[4] = std::sin(t), out[5] = std::cos(t), out[7] = 0.3 * j;
      out[10] = 1.0;
    }
  c.animation = encode_animation_texture(AnimationEncoding::kQuantized, joints, rows, m.data());
  return c;
}

}  // namespace crowdbake::fuzz
