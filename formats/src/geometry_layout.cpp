#include <stdexcept>

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
  if (!g.normals.empty()) layout.attributes |= kAttrNormals;
  if (!g.uvs.empty()) layout.attributes |= kAttrUvs;
  if (!g.joints.empty()) layout.attributes |= kAttrSkin;
  if (!g.regions.empty()) layout.attributes |= kAttrRegions;
  if (!g.triangle_material.empty()) layout.attributes |= kAttrTriangleMaterial;
  if (options.codec != GeometryCodec::kRaw) {
    layout.position_bits = static_cast<uint8_t>(options.position_bits);
    layout.normal_bits = layout.has(kAttrNormals) ? static_cast<uint8_t>(options.normal_bits) : 0;
    layout.uv_bits = layout.has(kAttrUvs) ? static_cast<uint8_t>(options.uv_bits) : 0;
  }
  return layout;
}

}  // namespace crowdbake::pack_io
