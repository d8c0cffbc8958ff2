// The meshoptimizer GEOM codec: each vertex attribute is its own stream through
// meshopt_encodeVertexBuffer (positions, normals and UVs first quantised to integers on
// a grid over their bounding cube, like Draco does); triangles through the index codec.
//
// note: meshopt_encodeIndexBuffer keeps triangle order and winding but may rotate a
// triangle's corners (verified: about half the triangles of an ordered grid come back
// rotated). The ProgressiveMesh order must survive exactly, so the writer encodes both
// ways and keeps the smaller: the index *sequence* codec (exact, no rotation), or the
// index *buffer* codec plus 2 bits per triangle saying how to rotate each one back.
#include <meshoptimizer.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "geometry_codec.h"

namespace crowdbake::pack_io {
namespace {

enum IndexMode : uint8_t { kIndexSequence = 0, kIndexBufferRotated = 1 };

void put_stream(ByteWriter& out, const void* elements, size_t count, size_t stride) {
  if (count == 0) {
    out.u32(0);
    return;
  }
  std::vector<uint8_t> buffer(meshopt_encodeVertexBufferBound(count, stride));
  const size_t size =
      meshopt_encodeVertexBuffer(buffer.data(), buffer.size(), elements, count, stride);
  if (size == 0) throw std::runtime_error("meshopt_encodeVertexBuffer failed");
  out.u32(static_cast<uint32_t>(size));
  out.raw(buffer.data(), size);
  out.zero_pad(4);
}

// Decodes one stream of `count` elements of `stride` bytes into `elements`.
bool get_stream(ByteReader& in, std::vector<uint8_t>& elements, size_t count, size_t stride,
                const char* field) {
  uint32_t size = 0;
  if (!in.u32(size, field)) return false;
  if (count == 0) {
    elements.clear();
    return size == 0 || in.fail(std::string(field) + ": " + std::to_string(size) +
                                " encoded bytes for an empty stream");
  }
  const uint8_t* data = in.cursor();
  if (!in.skip(size, field)) return false;
  elements.assign(count * stride, 0);
  const int rc = meshopt_decodeVertexBuffer(elements.data(), count, stride, data, size);
  if (rc != 0)
    return in.fail(std::string(field) +
                   ": meshoptimizer's vertex decoder rejected the stream (error " +
                   std::to_string(rc) + ")");
  return in.zero_pad(4, field);
}

template <typename T>
T element(const std::vector<uint8_t>& bytes, size_t offset) {
  T v;
  std::memcpy(&v, bytes.data() + offset, sizeof(T));
  return v;
}

// Positions, normals or UVs: floats verbatim (bits == 0) or grid-quantised integers,
// uint16 (bits <= 16, 3-component values padded to 4) or uint32.
void put_float_attribute(ByteWriter& out, const std::vector<float>& values, int dims, int bits) {
  const size_t count = values.size() / dims;
  if (bits == 0) {
    put_stream(out, values.data(), count, dims * sizeof(float));
    return;
  }
  const Grid grid = make_grid(values, dims, bits);
  put_grid(out, grid, dims);
  const bool narrow = bits <= 16;
  const size_t lanes = narrow && dims == 3 ? 4 : dims;
  const size_t lane_bytes = narrow ? 2 : 4;
  std::vector<uint8_t> packed(count * lanes * lane_bytes, 0);
  for (size_t i = 0; i < count; ++i) {
    for (int c = 0; c < dims; ++c) {
      const uint32_t q = quantize(values[i * dims + c], grid.origin[c], grid);
      uint8_t* at = packed.data() + (i * lanes + c) * lane_bytes;
      if (narrow) {
        const uint16_t q16 = static_cast<uint16_t>(q);
        std::memcpy(at, &q16, 2);
      } else {
        std::memcpy(at, &q, 4);
      }
    }
  }
  put_stream(out, packed.data(), count, lanes * lane_bytes);
}

bool get_float_attribute(ByteReader& in, std::vector<float>& values, size_t count, int dims,
                         int bits, const char* field) {
  std::vector<uint8_t> bytes;
  if (bits == 0) {
    if (!get_stream(in, bytes, count, dims * sizeof(float), field)) return false;
    values.resize(count * dims);
    if (!bytes.empty()) std::memcpy(values.data(), bytes.data(), bytes.size());
    return true;
  }
  Grid grid;
  if (!get_grid(in, grid, dims, bits, field)) return false;
  const bool narrow = bits <= 16;
  const size_t lanes = narrow && dims == 3 ? 4 : dims;
  const size_t lane_bytes = narrow ? 2 : 4;
  if (!get_stream(in, bytes, count, lanes * lane_bytes, field)) return false;
  values.resize(count * dims);
  for (size_t i = 0; i < count; ++i) {
    for (size_t c = 0; c < lanes; ++c) {
      const size_t at = (i * lanes + c) * lane_bytes;
      const uint32_t q = narrow ? element<uint16_t>(bytes, at) : element<uint32_t>(bytes, at);
      if (c >= static_cast<size_t>(dims)) {
        if (q != 0)
          return in.fail(std::string(field) + ": padding lane of value " + std::to_string(i) +
                         " is not zero");
        continue;
      }
      if (q > grid.max_q)
        return in.fail(std::string(field) + ": value " + std::to_string(i) + " quantised to " +
                       std::to_string(q) + ", above the " + std::to_string(bits) + "-bit maximum");
      values[i * dims + c] = dequantize(q, grid.origin[c], grid);
    }
  }
  return true;
}

// A 1- or 2-byte value per element, widened to a 4-byte lane (the vertex codec needs
// strides that are multiples of 4; the zero padding compresses to almost nothing).
template <typename T>
void put_narrow(ByteWriter& out, const std::vector<T>& values) {
  std::vector<uint32_t> lanes(values.begin(), values.end());
  put_stream(out, lanes.data(), lanes.size(), 4);
}

template <typename T>
bool get_narrow(ByteReader& in, std::vector<T>& values, size_t count, const char* field) {
  std::vector<uint8_t> bytes;
  if (!get_stream(in, bytes, count, 4, field)) return false;
  values.resize(count);
  for (size_t i = 0; i < count; ++i) {
    const uint32_t lane = element<uint32_t>(bytes, 4 * i);
    if (lane > std::numeric_limits<T>::max())
      return in.fail(std::string(field) + ": value " + std::to_string(i) + " (" +
                     std::to_string(lane) + ") does not fit its type");
    values[i] = static_cast<T>(lane);
  }
  return true;
}

// Which rotation r of decoded triangle d gives the original o: o[k] == d[(k + r) % 3].
int rotation_between(const uint32_t* o, const uint32_t* d) {
  for (int r = 0; r < 3; ++r)
    if (o[0] == d[r] && o[1] == d[(r + 1) % 3] && o[2] == d[(r + 2) % 3]) return r;
  return -1;
}

void put_triangles(ByteWriter& out, const std::vector<uint32_t>& triangles, uint32_t vertex_count) {
  const size_t index_count = triangles.size();
  if (index_count == 0) {
    out.u8(kIndexSequence);
    out.zero_pad(4);
    out.u32(0);
    return;
  }
  std::vector<uint8_t> sequence(meshopt_encodeIndexSequenceBound(index_count, vertex_count));
  sequence.resize(
      meshopt_encodeIndexSequence(sequence.data(), sequence.size(), triangles.data(), index_count));
  std::vector<uint8_t> buffer(meshopt_encodeIndexBufferBound(index_count, vertex_count));
  buffer.resize(
      meshopt_encodeIndexBuffer(buffer.data(), buffer.size(), triangles.data(), index_count));
  if (sequence.empty() || buffer.empty())
    throw std::runtime_error("meshoptimizer's index encoder failed");

  std::vector<uint32_t> decoded(index_count);
  if (meshopt_decodeIndexBuffer(decoded.data(), index_count, sizeof(uint32_t), buffer.data(),
                                buffer.size()) != 0)
    throw std::runtime_error("meshoptimizer's index codec does not decode its own output");
  std::vector<uint8_t> rotations((index_count / 3 + 3) / 4, 0);
  for (size_t t = 0; t < index_count / 3; ++t) {
    const int r = rotation_between(&triangles[3 * t], &decoded[3 * t]);
    if (r < 0)
      throw std::runtime_error("meshoptimizer's index codec changed a triangle beyond a rotation");
    rotations[t / 4] |= static_cast<uint8_t>(r << (2 * (t % 4)));
  }
  const size_t rotated_size = (buffer.size() + 3) / 4 * 4 + rotations.size();
  const bool use_buffer = rotated_size < sequence.size();
  out.u8(use_buffer ? kIndexBufferRotated : kIndexSequence);
  out.zero_pad(4);
  const std::vector<uint8_t>& chosen = use_buffer ? buffer : sequence;
  out.u32(static_cast<uint32_t>(chosen.size()));
  out.raw(chosen.data(), chosen.size());
  out.zero_pad(4);
  if (use_buffer) {
    out.raw(rotations.data(), rotations.size());
    out.zero_pad(4);
  }
}

bool get_triangles(ByteReader& in, std::vector<uint32_t>& triangles, size_t triangle_count) {
  uint8_t mode = 0;
  uint32_t size = 0;
  in.u8(mode, "index mode");
  in.zero_pad(4, "index mode padding");
  in.u32(size, "index stream size");
  if (!in.ok()) return false;
  if (mode != kIndexSequence && mode != kIndexBufferRotated)
    return in.fail("unknown index mode " + std::to_string(mode));
  if (triangle_count == 0) {
    triangles.clear();
    return size == 0 || in.fail(std::to_string(size) + " index bytes for no triangles");
  }
  const uint8_t* data = in.cursor();
  if (!in.skip(size, "index stream")) return false;
  const size_t index_count = 3 * triangle_count;
  triangles.assign(index_count, 0);
  const int rc =
      mode == kIndexSequence
          ? meshopt_decodeIndexSequence(triangles.data(), index_count, sizeof(uint32_t), data, size)
          : meshopt_decodeIndexBuffer(triangles.data(), index_count, sizeof(uint32_t), data, size);
  if (rc != 0)
    return in.fail("meshoptimizer's index decoder rejected the triangles (error " +
                   std::to_string(rc) + ")");
  if (!in.zero_pad(4, "index stream padding")) return false;
  if (mode == kIndexSequence) return true;
  const size_t rotation_bytes = (triangle_count + 3) / 4;
  const uint8_t* rotations = in.cursor();
  if (!in.skip(rotation_bytes, "triangle rotations")) return false;
  for (size_t t = 0; t < triangle_count; ++t) {
    const int r = (rotations[t / 4] >> (2 * (t % 4))) & 3;
    if (r == 3) return in.fail("triangle " + std::to_string(t) + ": rotation 3 is not a rotation");
    if (r == 0) continue;
    uint32_t* tri = &triangles[3 * t];
    const uint32_t d[3] = {tri[0], tri[1], tri[2]};
    for (int k = 0; k < 3; ++k) tri[k] = d[(k + r) % 3];
  }
  // note: the unused 2-bit slots of the last byte must be zero too (one encoding per pack).
  if (triangle_count % 4 != 0 && (rotations[rotation_bytes - 1] >> (2 * (triangle_count % 4))) != 0)
    return in.fail("triangle rotations: unused bits are not zero");
  return in.zero_pad(4, "triangle rotation padding");
}

}  // namespace

void encode_geometry_meshopt(const PackGeometry& g, const GeometryLayout& layout, ByteWriter& out) {
  const size_t v = layout.vertex_count;
  put_float_attribute(out, g.positions, 3, layout.position_bits);
  if (layout.has(kAttrNormals)) put_float_attribute(out, g.normals, 3, layout.normal_bits);
  if (layout.has(kAttrUvs)) put_float_attribute(out, g.uvs, 2, layout.uv_bits);
  if (layout.has(kAttrSkin)) {
    put_stream(out, g.joints.data(), v, 4 * sizeof(uint16_t));
    if (layout.weight_bits) {
      const std::vector<uint16_t> levels = quantize_weights(g.weights, layout.weight_bits);
      put_stream(out, levels.data(), v, 4 * sizeof(uint16_t));
    } else {
      put_stream(out, g.weights.data(), v, 4 * sizeof(float));
    }
  }
  if (layout.has(kAttrRegions)) put_narrow(out, g.regions);
  put_triangles(out, g.triangles, layout.vertex_count);
  if (layout.has(kAttrTriangleMaterial)) put_narrow(out, g.triangle_material);
}

bool decode_geometry_meshopt(ByteReader& in, const GeometryLayout& layout, PackGeometry& out) {
  const size_t v = layout.vertex_count;
  out = PackGeometry{};
  if (!get_float_attribute(in, out.positions, v, 3, layout.position_bits, "positions"))
    return false;
  if (layout.has(kAttrNormals) &&
      !get_float_attribute(in, out.normals, v, 3, layout.normal_bits, "normals"))
    return false;
  if (layout.has(kAttrUvs) && !get_float_attribute(in, out.uvs, v, 2, layout.uv_bits, "uvs"))
    return false;
  if (layout.has(kAttrSkin)) {
    std::vector<uint8_t> bytes;
    if (!get_stream(in, bytes, v, 4 * sizeof(uint16_t), "joints")) return false;
    out.joints.resize(4 * v);
    if (v) std::memcpy(out.joints.data(), bytes.data(), bytes.size());
    if (layout.weight_bits) {
      if (!get_stream(in, bytes, v, 4 * sizeof(uint16_t), "weights")) return false;
      std::vector<uint16_t> levels(4 * v);
      if (v) std::memcpy(levels.data(), bytes.data(), bytes.size());
      out.weights = dequantize_weights(levels, layout.weight_bits);
    } else {
      if (!get_stream(in, bytes, v, 4 * sizeof(float), "weights")) return false;
      out.weights.resize(4 * v);
      if (v) std::memcpy(out.weights.data(), bytes.data(), bytes.size());
    }
  }
  if (layout.has(kAttrRegions) && !get_narrow(in, out.regions, v, "regions")) return false;
  if (!get_triangles(in, out.triangles, layout.triangle_count)) return false;
  if (layout.has(kAttrTriangleMaterial) &&
      !get_narrow(in, out.triangle_material, layout.triangle_count, "triangle materials"))
    return false;
  return in.ok();
}

}  // namespace crowdbake::pack_io
