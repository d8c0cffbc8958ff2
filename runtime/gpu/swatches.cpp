// The swatch texture array: simple, recognisable colours per region and variant, sampled by
// crowd.frag for types with swatch shading (texture variants for characters without images of
// their own, such as the generated spectator).
#include <algorithm>
#include <cmath>
#include <cstring>

#include "crowd_draw_impl.h"

namespace crowdbake::runtime::gpu {
namespace {

float clamp01(float v) { return std::min(1.0f, std::max(0.0f, v)); }

void hsv_to_rgb(float h, float s, float v, float rgb[3]) {
  const float k[3] = {5.0f, 3.0f, 1.0f};
  for (int i = 0; i < 3; ++i) {
    const float t = std::fmod(k[i] + h * 6.0f, 6.0f);
    rgb[i] = v - v * s * std::max(0.0f, std::min({t, 4.0f - t, 1.0f}));
  }
}

}  // namespace

// Simple, recognisable swatches: skin tones for the head, shirts of
// well-spread hues with stripes on odd variants, dark trousers with a faint weave.
std::vector<uint8_t> make_swatches(uint32_t per_region) {
  const uint32_t n = kSwatchSize;
  std::vector<uint8_t> rgba(static_cast<size_t>(kSwatchRegions) * per_region * n * n * 4);
  static const float skin[][3] = {{0.96f, 0.80f, 0.69f}, {0.87f, 0.67f, 0.52f},
                                  {0.72f, 0.53f, 0.38f}, {0.55f, 0.38f, 0.26f},
                                  {0.38f, 0.26f, 0.18f}, {0.93f, 0.75f, 0.60f}};
  for (uint32_t region = 0; region < kSwatchRegions; ++region) {
    for (uint32_t variant = 0; variant < per_region; ++variant) {
      float base[3];
      if (region == 0) {
        std::memcpy(base, skin[variant % 6], sizeof(base));
      } else {
        // note: golden-ratio hue steps keep neighbouring variants far apart.
        const float hue =
            std::fmod(0.07f + 0.618034f * static_cast<float>(variant + 3 * region), 1.0f);
        if (region == 1)
          hsv_to_rgb(hue, 0.55f + 0.1f * static_cast<float>(variant % 3), 0.85f, base);
        else
          hsv_to_rgb(hue, 0.35f, 0.30f + 0.08f * static_cast<float>(variant % 4), base);
      }
      uint8_t* layer = &rgba[(static_cast<size_t>(region) * per_region + variant) * n * n * 4];
      for (uint32_t y = 0; y < n; ++y) {
        for (uint32_t x = 0; x < n; ++x) {
          float f = 1.0f;
          if (region == 1 && variant % 2 == 1 && (y / 4) % 2 == 1) f = 0.78f;  // stripes
          if (region == 2 && (x + y) % 4 == 0) f = 0.9f;                       // weave
          uint8_t* p = &layer[(static_cast<size_t>(y) * n + x) * 4];
          for (int c = 0; c < 3; ++c)
            p[c] = static_cast<uint8_t>(std::lround(clamp01(base[c] * f) * 255.0f));
          p[3] = 255;
        }
      }
    }
  }
  return rgba;
}

}  // namespace crowdbake::runtime::gpu
