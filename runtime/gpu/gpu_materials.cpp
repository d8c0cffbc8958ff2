// A pack's materials as the colour pass reads them: the factor in display space, the texture
// transform, the alpha cutoff and the image layer of each material; and the images decoded
// (crowdbake_formats' decode_pack_image), resampled to one size with stb_image_resize, and
// mip-mapped.
#include <stb_image_resize.h>

#include <algorithm>
#include <cmath>

#include "crowdbake/formats/pack_image.h"
#include "crowdbake/runtime/gpu/crowd_draw.h"

namespace crowdbake::runtime::gpu {
namespace {

// The sRGB transfer function (IEC 61966-2-1): the renderer shades in display values.
float linear_to_srgb(float c) {
  if (!(c > 0.0f)) return 0.0f;
  if (c >= 1.0f) return 1.0f;
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

GpuMaterial untextured_white() {
  GpuMaterial m{};
  for (float& c : m.color) c = 1.0f;
  m.uv_u[0] = 1.0f;
  m.uv_u[3] = -1.0f;
  m.uv_v[1] = 1.0f;
  m.uv_v[3] = -1.0f;
  return m;
}

Status resize(const uint8_t* in, uint32_t in_w, uint32_t in_h, uint8_t* out, uint32_t w,
              uint32_t h) {
  if (in_w == w && in_h == h) {
    std::copy(in, in + size_t{w} * h * 4, out);
    return {};
  }
  // note: the images hold sRGB colours and straight alpha, which is how stb filters them here.
  if (!stbir_resize_uint8_srgb(in, static_cast<int>(in_w), static_cast<int>(in_h), 0, out,
                               static_cast<int>(w), static_cast<int>(h), 0, 4, 3, 0))
    return {StatusCode::kInvalidArgument, "cannot resample a material image"};
  return {};
}

}  // namespace

Status make_gpu_materials(const PackContents& pack, GpuMaterials& out) {
  out = GpuMaterials{};
  for (const PackMaterial& in : pack.materials) {
    GpuMaterial m = untextured_white();
    for (int c = 0; c < 3; ++c) m.color[c] = linear_to_srgb(in.base_color[c]);
    m.color[3] = std::clamp(in.base_color[3], 0.0f, 1.0f);
    if (in.base_color_image >= 0 && static_cast<size_t>(in.base_color_image) < pack.images.size()) {
      const auto& t = in.uv_transform;
      m.uv_u[0] = t[0];
      m.uv_u[1] = t[1];
      m.uv_u[2] = t[2];
      m.uv_u[3] = static_cast<float>(in.base_color_image);
      m.uv_v[0] = t[3];
      m.uv_v[1] = t[4];
      m.uv_v[2] = t[5];
    }
    // note: blended materials are drawn opaque (the crowd pass has no sorted transparency).
    if (in.alpha_mode == AlphaMode::kMask) m.uv_v[3] = in.alpha_cutoff;
    out.materials.push_back(m);
  }
  if (out.materials.empty()) out.materials.push_back(untextured_white());

  if (pack.images.empty()) {
    out.rgba.assign(4, 255);
    out.level_offsets = {0};
    return {};
  }
  for (const PackImage& image : pack.images) {
    out.width = std::max(out.width, std::min(image.width, kMaxMaterialImageSide));
    out.height = std::max(out.height, std::min(image.height, kMaxMaterialImageSide));
  }
  out.layers = static_cast<uint32_t>(pack.images.size());
  const uint32_t levels =
      1 + static_cast<uint32_t>(std::floor(std::log2(std::max(out.width, out.height))));
  size_t total = 0;
  for (uint32_t l = 0; l < levels; ++l) {
    out.level_offsets.push_back(total);
    total += size_t{std::max(out.width >> l, 1u)} * std::max(out.height >> l, 1u) * 4 * out.layers;
  }
  out.rgba.resize(total);
  std::vector<uint8_t> pixels;
  for (uint32_t i = 0; i < out.layers; ++i) {
    const PackImage& image = pack.images[i];
    std::string why;
    if (!decode_pack_image(image, pixels, why))
      return {StatusCode::kInvalidPack,
              "image " + std::to_string(i) + " '" + image.name + "' does not decode: " + why};
    // note: level 0 comes from the image, each further level from the level above (a quarter
    // of the work each; resampling every level from the full image took 0.9 s at 1024²).
    const uint8_t* src = pixels.data();
    uint32_t src_w = image.width, src_h = image.height;
    for (uint32_t l = 0; l < levels; ++l) {
      const uint32_t w = std::max(out.width >> l, 1u), h = std::max(out.height >> l, 1u);
      uint8_t* dst = out.rgba.data() + out.level_offsets[l] + size_t{w} * h * 4 * i;
      if (Status s = resize(src, src_w, src_h, dst, w, h); !s) return s;
      src = dst;
      src_w = w;
      src_h = h;
    }
  }
  return {};
}

}  // namespace crowdbake::runtime::gpu
