#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "geometry_codec.h"

namespace crowdbake::pack_io {

uint64_t GeometryLayout::decoded_bytes() const {
  uint64_t per_vertex = 3 * sizeof(float);
  if (has(kAttrNormals)) per_vertex += 3 * sizeof(float);
  if (has(kAttrUvs)) per_vertex += 2 * sizeof(float);
  if (has(kAttrSkin)) per_vertex += 4 * sizeof(uint16_t) + 4 * sizeof(float);
  if (has(kAttrRegions)) per_vertex += 1;
  uint64_t per_triangle = 3 * sizeof(uint32_t);
  if (has(kAttrTriangleMaterial)) per_triangle += sizeof(uint16_t);
  // note: counts are at most 2^25, so neither product can overflow 64 bits.
  return per_vertex * vertex_count + per_triangle * triangle_count;
}

GeometryLayout make_geometry_layout(const PackGeometry& g, const PackWriteOptions& options) {
  GeometryLayout layout;
  layout.codec = options.codec;
  layout.vertex_count = g.vertex_count();
  layout.triangle_count = g.triangle_count();
  layout.threads = options.threads;
  if (!g.normals.empty()) layout.attributes |= kAttrNormals;
  if (!g.uvs.empty()) layout.attributes |= kAttrUvs;
  if (!g.joints.empty()) layout.attributes |= kAttrSkin;
  if (!g.regions.empty()) layout.attributes |= kAttrRegions;
  if (!g.triangle_material.empty()) layout.attributes |= kAttrTriangleMaterial;
  if (options.codec != GeometryCodec::kRaw) {
    layout.position_bits = static_cast<uint8_t>(options.position_bits);
    layout.normal_bits = layout.has(kAttrNormals) ? static_cast<uint8_t>(options.normal_bits) : 0;
    layout.uv_bits = layout.has(kAttrUvs) ? static_cast<uint8_t>(options.uv_bits) : 0;
    layout.weight_bits = layout.has(kAttrSkin) ? static_cast<uint8_t>(options.weight_bits) : 0;
  }
  return layout;
}

Grid make_grid(const std::vector<float>& values, int dims, int bits) {
  Grid grid;
  float lo[3], hi[3];
  for (int c = 0; c < dims; ++c) lo[c] = std::numeric_limits<float>::max(), hi[c] = -lo[c];
  for (size_t i = 0; i < values.size(); ++i) {
    const int c = static_cast<int>(i % dims);
    lo[c] = std::min(lo[c], values[i]);
    hi[c] = std::max(hi[c], values[i]);
  }
  float range = 0.0f;
  for (int c = 0; c < dims; ++c) {
    grid.origin[c] = values.empty() ? 0.0f : lo[c];
    if (!values.empty()) range = std::max(range, hi[c] - lo[c]);
  }
  // note: a flat attribute (all equal) still needs a nonzero step.
  grid.range = range > 0.0f && std::isfinite(range) ? range : 1.0f;
  grid.max_q = (1u << bits) - 1;
  return grid;
}

uint32_t quantize(float v, float origin, const Grid& g) {
  const double q = std::floor((static_cast<double>(v) - origin) / g.range * g.max_q + 0.5);
  return static_cast<uint32_t>(std::min<double>(std::max(q, 0.0), g.max_q));
}

float dequantize(uint32_t q, float origin, const Grid& g) {
  return static_cast<float>(origin + static_cast<double>(q) * g.range / g.max_q);
}

void put_grid(ByteWriter& out, const Grid& grid, int dims) {
  for (int c = 0; c < dims; ++c) out.f32(grid.origin[c]);
  out.f32(grid.range);
}

bool get_grid(ByteReader& in, Grid& grid, int dims, int bits, const char* field) {
  for (int c = 0; c < dims; ++c) in.f32(grid.origin[c], field);
  in.f32(grid.range, field);
  if (!in.ok()) return false;
  if (!(grid.range > 0.0f))
    return in.fail(std::string(field) + ": quantisation range " + std::to_string(grid.range) +
                   " is not positive");
  grid.max_q = (1u << bits) - 1;
  return true;
}

std::vector<uint16_t> quantize_weights(const std::vector<float>& weights, int bits) {
  const int32_t top = (1 << bits) - 1;
  std::vector<uint16_t> levels(weights.size());
  for (size_t v = 0; v + 4 <= weights.size(); v += 4) {
    int32_t q[4], sum = 0;
    size_t largest = 0;
    for (size_t k = 0; k < 4; ++k) {
      const double w = std::clamp(static_cast<double>(weights[v + k]), 0.0, 1.0);
      q[k] = static_cast<int32_t>(std::lround(w * top));
      sum += q[k];
      if (weights[v + k] > weights[v + largest]) largest = k;
    }
    // note: rounding four weights that sum to 1 leaves the sum within 2 of top; moving the
    // difference onto the largest (at least top / 4) keeps every level in [0, top].
    if (sum > 0) q[largest] = std::clamp(q[largest] + top - sum, 0, top);
    for (size_t k = 0; k < 4; ++k) levels[v + k] = static_cast<uint16_t>(q[k]);
  }
  return levels;
}

std::vector<float> dequantize_weights(const std::vector<uint16_t>& levels, int bits) {
  const double top = static_cast<double>((1 << bits) - 1);
  std::vector<float> weights(levels.size());
  for (size_t i = 0; i < levels.size(); ++i)
    weights[i] = static_cast<float>(std::min(1.0, levels[i] / top));
  return weights;
}

}  // namespace crowdbake::pack_io

namespace crowdbake {

std::vector<float> stored_weights(const PackGeometry& geometry, const PackWriteOptions& options) {
  const pack_io::GeometryLayout layout = pack_io::make_geometry_layout(geometry, options);
  if (layout.weight_bits == 0) return geometry.weights;
  return pack_io::dequantize_weights(
      pack_io::quantize_weights(geometry.weights, layout.weight_bits), layout.weight_bits);
}

}  // namespace crowdbake
