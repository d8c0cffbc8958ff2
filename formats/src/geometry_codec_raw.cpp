// The raw GEOM codec: every array verbatim, 4-byte aligned, in a fixed order. The
// reference for the other codecs and the fastest to decode (a memcpy per array).
#include "geometry_codec.h"

namespace crowdbake::pack_io {

void encode_geometry_raw(const PackGeometry& g, const GeometryLayout& layout, ByteWriter& out) {
  out.array(g.positions);
  if (layout.has(kAttrNormals)) out.array(g.normals);
  if (layout.has(kAttrUvs)) out.array(g.uvs);
  if (layout.has(kAttrSkin)) {
    out.array(g.joints);
    out.array(g.weights);
  }
  if (layout.has(kAttrRegions)) out.array(g.regions);
  out.zero_pad(4);
  out.array(g.triangles);
  if (layout.has(kAttrTriangleMaterial)) out.array(g.triangle_material);
  out.zero_pad(4);
}

bool decode_geometry_raw(ByteReader& in, const GeometryLayout& layout, PackGeometry& out) {
  const uint64_t v = layout.vertex_count, t = layout.triangle_count;
  out = PackGeometry{};
  in.read_array(out.positions, 3 * v, "positions");
  if (layout.has(kAttrNormals)) in.read_array(out.normals, 3 * v, "normals");
  if (layout.has(kAttrUvs)) in.read_array(out.uvs, 2 * v, "uvs");
  if (layout.has(kAttrSkin)) {
    in.read_array(out.joints, 4 * v, "joints");
    in.read_array(out.weights, 4 * v, "weights");
  }
  if (layout.has(kAttrRegions)) in.read_array(out.regions, v, "regions");
  in.zero_pad(4, "padding after the vertex arrays");
  in.read_array(out.triangles, 3 * t, "triangles");
  if (layout.has(kAttrTriangleMaterial))
    in.read_array(out.triangle_material, t, "triangle materials");
  in.zero_pad(4, "padding after the triangle arrays");
  return in.ok();
}

}  // namespace crowdbake::pack_io
