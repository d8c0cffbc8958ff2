#include "cli/image_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

#include "crowdbake/pipeline/error.h"

namespace crowdbake::cli {
namespace {

void check_same_size(const RgbaImage& a, const RgbaImage& b) {
  if (!a.valid() || !b.valid())
    throw Error(Error::Kind::kUsage, "image", "cannot compare an image without pixels");
  if (a.width != b.width || a.height != b.height)
    throw Error(Error::Kind::kUsage, "image",
                "cannot compare images of different sizes: " + std::to_string(a.width) + "x" +
                    std::to_string(a.height) + " and " + std::to_string(b.width) + "x" +
                    std::to_string(b.height));
}

size_t channel_count(const RgbaImage& image) { return size_t{image.width} * image.height * 3; }

}  // namespace

double mean_abs_diff(const RgbaImage& a, const RgbaImage& b) {
  check_same_size(a, b);
  uint64_t sum = 0;
  for (size_t i = 0; i < a.rgba.size(); i += 4)
    for (size_t c = 0; c < 3; ++c)
      sum += static_cast<uint64_t>(std::abs(a.rgba[i + c] - b.rgba[i + c]));
  return static_cast<double>(sum) / static_cast<double>(channel_count(a));
}

double psnr(const RgbaImage& a, const RgbaImage& b) {
  check_same_size(a, b);
  uint64_t sum = 0;
  for (size_t i = 0; i < a.rgba.size(); i += 4)
    for (size_t c = 0; c < 3; ++c) {
      const int64_t d = int64_t{a.rgba[i + c]} - int64_t{b.rgba[i + c]};
      sum += static_cast<uint64_t>(d * d);
    }
  if (sum == 0) return std::numeric_limits<double>::infinity();
  const double mse = static_cast<double>(sum) / static_cast<double>(channel_count(a));
  return 10.0 * std::log10(255.0 * 255.0 / mse);
}

double change_difference(const RgbaImage& a0, const RgbaImage& a1, const RgbaImage& b0,
                         const RgbaImage& b1) {
  check_same_size(a0, a1);
  check_same_size(a0, b0);
  check_same_size(a0, b1);
  uint64_t sum = 0;
  for (size_t i = 0; i < a0.rgba.size(); i += 4)
    for (size_t c = 0; c < 3; ++c) {
      const int da = int{a1.rgba[i + c]} - int{a0.rgba[i + c]};
      const int db = int{b1.rgba[i + c]} - int{b0.rgba[i + c]};
      sum += static_cast<uint64_t>(std::abs(da - db));
    }
  return static_cast<double>(sum) / static_cast<double>(channel_count(a0));
}

double change_outliers(const RgbaImage& a0, const RgbaImage& a1, const RgbaImage& b0,
                       const RgbaImage& b1, int threshold) {
  check_same_size(a0, a1);
  check_same_size(a0, b0);
  check_same_size(a0, b1);
  size_t count = 0;
  for (size_t i = 0; i < a0.rgba.size(); i += 4) {
    int worst = 0;
    for (size_t c = 0; c < 3; ++c) {
      const int da = int{a1.rgba[i + c]} - int{a0.rgba[i + c]};
      const int db = int{b1.rgba[i + c]} - int{b0.rgba[i + c]};
      worst = std::max(worst, std::abs(da - db));
    }
    count += worst > threshold;
  }
  return static_cast<double>(count) / static_cast<double>(size_t{a0.width} * a0.height);
}

}  // namespace crowdbake::cli
