// Small real packs for fuzz seeds and fuzz fixtures: the hand-built test character
// (tests/formats/pack_test_contents.h) with a short animation, so a pack is a few KB.
#pragma once

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

}  // namespace crowdbake::fuzz
