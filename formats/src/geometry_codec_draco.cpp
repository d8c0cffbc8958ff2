// The Draco GEOM codec (the default). The only file that includes Draco headers.
//
// - MESH_SEQUENTIAL_ENCODING with compressed connectivity: vertices and faces keep their
//   order and every face its corner order (Edgebreaker would reorder both; the
//   ProgressiveMesh order is the point of the pack). Tests check the order survives.
//   Vertices without any triangle are a sequential point cloud instead (Draco 1.5.5
//   cannot decode a sequential mesh of zero faces).
// - POSITION and TEX_COORD use Draco's grid quantisation, NORMAL its octahedral one, with
//   the bits of PackWriteOptions; 0 bits leaves the float exact.
// - Joints (uint16 x4), weights and regions (uint8) are GENERIC attributes that Draco
//   never quantises itself (its glTF path has a history of narrowing JOINTS_0 and
//   quantising WEIGHTS_0): weights arrive already as integers of weight_bits
//   (quantize_weights), or as their exact float bits when weight_bits is 0.
// - Per-triangle materials cannot be a mesh attribute (Draco attributes are per point),
//   so they go in a second Draco stream: a sequential point cloud with one uint16 per
//   triangle, entropy-coded.
//
// note: before Draco sees a stream, its header and element counts are parsed here and
// must match the GEOM header, so Draco's own allocations are bounded by counts the
// reader has already limited.
#include <draco/compression/decode.h>
#include <draco/compression/encode.h>

#include <cstring>
#include <memory>
#include <stdexcept>

#include "geometry_codec.h"

namespace crowdbake::pack_io {
namespace {

// Unique ids of the attributes in the mesh stream (the decoder looks them up by id).
enum DracoAttributeId : uint32_t {
  kIdPosition = 0,
  kIdNormal = 1,
  kIdUv = 2,
  kIdJoints = 3,
  kIdWeights = 4,
  kIdRegions = 5,
  kIdMaterial = 0,  // in the material point cloud
};

constexpr uint8_t kDracoMesh = 1, kDracoPointCloud = 0, kDracoSequential = 0;

template <typename T>
void add_attribute(draco::PointCloud& pc, draco::GeometryAttribute::Type type,
                   draco::DataType data_type, int components, uint32_t unique_id,
                   const std::vector<T>& values) {
  draco::GeometryAttribute ga;
  ga.Init(type, nullptr, static_cast<uint8_t>(components), data_type, false,
          static_cast<int64_t>(sizeof(T) * components), 0);
  const uint32_t count = pc.num_points();
  const int id = pc.AddAttribute(ga, /*identity_mapping=*/true, count);
  draco::PointAttribute* att = pc.attribute(id);
  att->set_unique_id(unique_id);
  for (uint32_t i = 0; i < count; ++i)
    att->SetAttributeValue(draco::AttributeValueIndex(i),
                           &values[static_cast<size_t>(i) * components]);
}

// Weights travel as their exact float bits, split into 16-bit halves per vertex: the four
// high halves (sign, exponent, top of the mantissa: very repetitive) then the four low
// halves. Draco entropy-codes 16-bit integers quickly; whole 32-bit patterns made its
// symbol coder about 200x slower to encode for a few percent less.
std::vector<uint16_t> split_weights(const std::vector<float>& weights) {
  std::vector<uint16_t> halves(2 * weights.size());
  for (size_t v = 0; v < weights.size() / 4; ++v)
    for (size_t k = 0; k < 4; ++k) {
      uint32_t bits;
      std::memcpy(&bits, &weights[4 * v + k], 4);
      halves[8 * v + k] = static_cast<uint16_t>(bits >> 16);
      halves[8 * v + 4 + k] = static_cast<uint16_t>(bits & 0xffff);
    }
  return halves;
}

std::vector<float> join_weights(const std::vector<uint16_t>& halves) {
  std::vector<float> weights(halves.size() / 2);
  for (size_t v = 0; v < weights.size() / 4; ++v)
    for (size_t k = 0; k < 4; ++k) {
      const uint32_t bits = uint32_t{halves[8 * v + k]} << 16 | halves[8 * v + 4 + k];
      std::memcpy(&weights[4 * v + k], &bits, 4);
    }
  return weights;
}

std::vector<uint8_t> to_bytes(const draco::EncoderBuffer& buffer) {
  return std::vector<uint8_t>(buffer.data(), buffer.data() + buffer.size());
}

std::vector<uint8_t> encode_mesh(const PackGeometry& g, const GeometryLayout& layout) {
  draco::Mesh mesh;
  mesh.set_num_points(layout.vertex_count);
  add_attribute(mesh, draco::GeometryAttribute::POSITION, draco::DT_FLOAT32, 3, kIdPosition,
                g.positions);
  if (layout.has(kAttrNormals))
    add_attribute(mesh, draco::GeometryAttribute::NORMAL, draco::DT_FLOAT32, 3, kIdNormal,
                  g.normals);
  if (layout.has(kAttrUvs))
    add_attribute(mesh, draco::GeometryAttribute::TEX_COORD, draco::DT_FLOAT32, 2, kIdUv, g.uvs);
  if (layout.has(kAttrSkin)) {
    add_attribute(mesh, draco::GeometryAttribute::GENERIC, draco::DT_UINT16, 4, kIdJoints,
                  g.joints);
    if (layout.weight_bits)
      add_attribute(mesh, draco::GeometryAttribute::GENERIC, draco::DT_UINT16, 4, kIdWeights,
                    quantize_weights(g.weights, layout.weight_bits));
    else
      add_attribute(mesh, draco::GeometryAttribute::GENERIC, draco::DT_UINT16, 8, kIdWeights,
                    split_weights(g.weights));
  }
  if (layout.has(kAttrRegions))
    add_attribute(mesh, draco::GeometryAttribute::GENERIC, draco::DT_UINT8, 1, kIdRegions,
                  g.regions);
  mesh.SetNumFaces(layout.triangle_count);
  for (uint32_t t = 0; t < layout.triangle_count; ++t) {
    draco::Mesh::Face face;
    for (int c = 0; c < 3; ++c) face[c] = draco::PointIndex(g.triangles[3 * size_t{t} + c]);
    mesh.SetFace(draco::FaceIndex(t), face);
  }

  draco::Encoder encoder;
  encoder.options().SetGlobalBool("compress_connectivity", true);
  if (layout.position_bits)
    encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, layout.position_bits);
  if (layout.normal_bits)
    encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, layout.normal_bits);
  if (layout.uv_bits)
    encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, layout.uv_bits);
  draco::EncoderBuffer buffer;
  draco::Status status;
  if (layout.triangle_count > 0) {
    encoder.SetEncodingMethod(draco::MESH_SEQUENTIAL_ENCODING);
    status = encoder.EncodeMeshToBuffer(mesh, &buffer);
  } else {
    // note: Draco 1.5.5 fails to decode a sequential mesh with zero faces ("Failed to
    // decode geometry data"), so vertices without triangles are a point cloud stream.
    encoder.SetEncodingMethod(draco::POINT_CLOUD_SEQUENTIAL_ENCODING);
    status = encoder.EncodePointCloudToBuffer(mesh, &buffer);
  }
  if (!status.ok())
    throw std::runtime_error("Draco could not encode the mesh: " + status.error_msg_string());
  return to_bytes(buffer);
}

std::vector<uint8_t> encode_materials(const std::vector<uint16_t>& materials) {
  draco::PointCloud pc;
  pc.set_num_points(static_cast<uint32_t>(materials.size()));
  add_attribute(pc, draco::GeometryAttribute::GENERIC, draco::DT_UINT16, 1, kIdMaterial, materials);
  draco::Encoder encoder;
  encoder.SetEncodingMethod(draco::POINT_CLOUD_SEQUENTIAL_ENCODING);
  draco::EncoderBuffer buffer;
  const draco::Status status = encoder.EncodePointCloudToBuffer(pc, &buffer);
  if (!status.ok())
    throw std::runtime_error("Draco could not encode the triangle materials: " +
                             status.error_msg_string());
  return to_bytes(buffer);
}

void put_stream(ByteWriter& out, const std::vector<uint8_t>& bytes) {
  out.u32(static_cast<uint32_t>(bytes.size()));
  out.raw(bytes.data(), bytes.size());
  out.zero_pad(4);
}

// Parses the Draco header (and the counts right after it) of `stream` and checks they
// are what the GEOM header announced. Draco bitstreams: "DRACO", major, minor, encoder
// type, method, u16 flags; then a sequential mesh has varint face and point counts, a
// sequential point cloud an int32 point count.
bool check_draco_header(ByteReader& in, const uint8_t* data, size_t size, uint8_t type,
                        uint32_t expect_points, uint32_t expect_faces, const char* what) {
  ByteReader h(data, size, "");
  uint8_t magic[5] = {}, major = 0, minor = 0, encoder_type = 0, method = 0;
  uint16_t flags = 0;
  for (uint8_t& m : magic) h.u8(m, "magic");
  h.u8(major, "major");
  h.u8(minor, "minor");
  h.u8(encoder_type, "type");
  h.u8(method, "method");
  h.u16(flags, "flags");
  if (!h.ok() || std::memcmp(magic, "DRACO", 5) != 0)
    return in.fail(std::string(what) + ": not a Draco stream");
  const uint8_t want_major = type == kDracoMesh ? draco::kDracoMeshBitstreamVersionMajor
                                                : draco::kDracoPointCloudBitstreamVersionMajor;
  const uint8_t want_minor = type == kDracoMesh ? draco::kDracoMeshBitstreamVersionMinor
                                                : draco::kDracoPointCloudBitstreamVersionMinor;
  if (major != want_major || minor != want_minor)
    return in.fail(std::string(what) + ": Draco bitstream " + std::to_string(major) + "." +
                   std::to_string(minor) + ", this build reads " + std::to_string(want_major) +
                   "." + std::to_string(want_minor));
  if (encoder_type != type || method != kDracoSequential || flags != 0)
    return in.fail(std::string(what) + ": not a sequential Draco " +
                   (type == kDracoMesh ? "mesh" : "point cloud") + " without metadata");
  uint32_t points = 0, faces = 0;
  if (type == kDracoMesh) {
    h.varint(faces, "faces");
    h.varint(points, "points");
  } else {
    h.u32(points, "points");
  }
  if (!h.ok()) return in.fail(std::string(what) + ": Draco stream truncated in its header");
  if (points != expect_points || faces != expect_faces)
    return in.fail(std::string(what) + ": Draco stream holds " + std::to_string(points) +
                   " points and " + std::to_string(faces) + " faces, the GEOM header says " +
                   std::to_string(expect_points) + " and " + std::to_string(expect_faces));
  return true;
}

// Copies attribute `unique_id` of `pc` into `out` (components per point, type T), after
// checking type, component count, mapping and storage size.
template <typename T>
bool get_attribute(ByteReader& in, const draco::PointCloud& pc, uint32_t unique_id,
                   draco::DataType data_type, int components, std::vector<T>& out,
                   const char* what) {
  const draco::PointAttribute* att = pc.GetAttributeByUniqueId(unique_id);
  if (!att) return in.fail(std::string(what) + ": missing from the Draco stream");
  const size_t points = pc.num_points();
  if (att->data_type() != data_type || att->num_components() != components ||
      att->byte_stride() != static_cast<int64_t>(sizeof(T) * components) || att->byte_offset() != 0)
    return in.fail(std::string(what) + ": Draco attribute has the wrong type or component count");
  if (!att->buffer() || att->buffer()->data_size() < att->size() * sizeof(T) * components ||
      (!att->is_mapping_identity() && att->indices_map_size() < points))
    return in.fail(std::string(what) + ": Draco attribute storage is inconsistent");
  out.resize(points * components);
  for (size_t p = 0; p < points; ++p) {
    const draco::AttributeValueIndex index =
        att->mapped_index(draco::PointIndex(static_cast<uint32_t>(p)));
    if (index.value() >= att->size())
      return in.fail(std::string(what) + ": Draco maps point " + std::to_string(p) +
                     " to a missing value");
    std::memcpy(&out[p * components], att->GetAddress(index), sizeof(T) * components);
  }
  return true;
}

}  // namespace

void encode_geometry_draco(const PackGeometry& g, const GeometryLayout& layout, ByteWriter& out) {
  // note: an empty mesh is no stream at all (Draco refuses to encode zero points).
  put_stream(out, layout.vertex_count ? encode_mesh(g, layout) : std::vector<uint8_t>{});
  if (layout.has(kAttrTriangleMaterial))
    put_stream(out, layout.triangle_count ? encode_materials(g.triangle_material)
                                          : std::vector<uint8_t>{});
}

bool decode_geometry_draco(ByteReader& in, const GeometryLayout& layout, PackGeometry& out) {
  out = PackGeometry{};
  uint32_t size = 0;
  if (!in.u32(size, "Draco mesh size")) return false;
  const uint8_t* data = in.cursor();
  if (!in.skip(size, "Draco mesh") || !in.zero_pad(4, "Draco mesh padding")) return false;
  if (layout.vertex_count == 0) {
    if (size != 0) return in.fail("Draco mesh: " + std::to_string(size) + " bytes for no vertices");
    if (layout.triangle_count != 0) return in.fail("triangles without vertices");
  } else {
    const bool points_only = layout.triangle_count == 0;
    if (!check_draco_header(in, data, size, points_only ? kDracoPointCloud : kDracoMesh,
                            layout.vertex_count, layout.triangle_count, "Draco mesh"))
      return false;
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(data), size);
    draco::Decoder decoder;
    std::unique_ptr<draco::PointCloud> mesh;
    if (points_only) {
      auto decoded = decoder.DecodePointCloudFromBuffer(&buffer);
      if (!decoded.ok()) return in.fail("Draco mesh: " + decoded.status().error_msg_string());
      mesh = std::move(decoded).value();
    } else {
      auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
      if (!decoded.ok()) return in.fail("Draco mesh: " + decoded.status().error_msg_string());
      mesh = std::move(decoded).value();
    }
    const auto* faces = dynamic_cast<const draco::Mesh*>(mesh.get());
    if (!mesh || mesh->num_points() != layout.vertex_count ||
        (faces ? faces->num_faces() : 0) != layout.triangle_count)
      return in.fail("Draco mesh: decoded counts differ from the GEOM header");
    std::vector<uint16_t> weight_halves;
    if (!get_attribute(in, *mesh, kIdPosition, draco::DT_FLOAT32, 3, out.positions, "positions"))
      return false;
    if (layout.has(kAttrNormals) &&
        !get_attribute(in, *mesh, kIdNormal, draco::DT_FLOAT32, 3, out.normals, "normals"))
      return false;
    if (layout.has(kAttrUvs) &&
        !get_attribute(in, *mesh, kIdUv, draco::DT_FLOAT32, 2, out.uvs, "uvs"))
      return false;
    if (layout.has(kAttrSkin) &&
        (!get_attribute(in, *mesh, kIdJoints, draco::DT_UINT16, 4, out.joints, "joints") ||
         !get_attribute(in, *mesh, kIdWeights, draco::DT_UINT16, layout.weight_bits ? 4 : 8,
                        weight_halves, "weights")))
      return false;
    if (layout.has(kAttrSkin))
      out.weights = layout.weight_bits ? dequantize_weights(weight_halves, layout.weight_bits)
                                       : join_weights(weight_halves);
    if (layout.has(kAttrRegions) &&
        !get_attribute(in, *mesh, kIdRegions, draco::DT_UINT8, 1, out.regions, "regions"))
      return false;
    out.triangles.resize(3 * size_t{layout.triangle_count});
    for (uint32_t t = 0; t < layout.triangle_count; ++t) {
      const draco::Mesh::Face& face = faces->face(draco::FaceIndex(t));
      for (int c = 0; c < 3; ++c) out.triangles[3 * size_t{t} + c] = face[c].value();
    }
  }
  if (!layout.has(kAttrTriangleMaterial)) return in.ok();
  if (!in.u32(size, "Draco material size")) return false;
  data = in.cursor();
  if (!in.skip(size, "Draco materials") || !in.zero_pad(4, "Draco material padding")) return false;
  if (layout.triangle_count == 0)
    return size == 0 ||
           in.fail("Draco materials: " + std::to_string(size) + " bytes for no triangles");
  if (!check_draco_header(in, data, size, kDracoPointCloud, layout.triangle_count, 0,
                          "Draco materials"))
    return false;
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(data), size);
  draco::Decoder decoder;
  auto decoded = decoder.DecodePointCloudFromBuffer(&buffer);
  if (!decoded.ok()) return in.fail("Draco materials: " + decoded.status().error_msg_string());
  const std::unique_ptr<draco::PointCloud> pc = std::move(decoded).value();
  if (!pc || pc->num_points() != layout.triangle_count)
    return in.fail("Draco materials: decoded count differs from the GEOM header");
  return get_attribute(in, *pc, kIdMaterial, draco::DT_UINT16, 1, out.triangle_material,
                       "triangle materials");
}

}  // namespace crowdbake::pack_io
