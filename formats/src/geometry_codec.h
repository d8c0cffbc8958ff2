// The GEOM chunk's codecs (docs/pack-format.md "GEOM"): one encode/decode pair per
// GeometryCodec, each in its own .cpp (only geometry_codec_draco.cpp sees Draco headers).
//
// The GEOM header (GeometryLayout) is read and checked by pack_reader.cpp before a
// decoder runs: counts within the limits, the decoded size within the expansion bound.
// A decoder reads the rest of the chunk through `in`, fills every array of `out` that
// `layout` announces with exactly the announced sizes, and consumes the whole payload.
// Index ranges and value rules are checked afterwards (validate_geometry), so decoders
// need not; they must only never read or write out of bounds, whatever the bytes.
#pragma once

#include <cstdint>

#include "byte_reader.h"
#include "byte_writer.h"
#include "crowdbake/formats/pack.h"

namespace crowdbake::pack_io {

// GEOM attribute bits (positions are always present).
enum GeometryAttribute : uint32_t {
  kAttrNormals = 1u << 0,
  kAttrUvs = 1u << 1,
  kAttrSkin = 1u << 2,              // joints (uint16 x4) and weights (float x4)
  kAttrRegions = 1u << 3,           // uint8 per vertex
  kAttrTriangleMaterial = 1u << 4,  // uint16 per triangle
  kAttrKnown = (1u << 5) - 1,
};

struct GeometryLayout {
  GeometryCodec codec = GeometryCodec::kRaw;
  uint32_t vertex_count = 0;
  uint32_t triangle_count = 0;
  uint32_t attributes = 0;                                  // GeometryAttribute bits
  uint8_t position_bits = 0, normal_bits = 0, uv_bits = 0;  // 0 = float
  uint8_t weight_bits = 0;  // 0 = float; GEOM v2 only, never for the raw codec
  int threads = 0;          // PackWriteOptions::threads (not stored)

  bool has(uint32_t attribute) const { return (attributes & attribute) != 0; }
  // Bytes of the decoded arrays (what a decoder allocates).
  uint64_t decoded_bytes() const;
};

// The layout write_pack stores for `g` (bits forced to 0 for the raw codec).
GeometryLayout make_geometry_layout(const PackGeometry& g, const PackWriteOptions& options);

// A quantisation grid over the bounding cube of `dims`-component values (the rule Draco
// uses): every component c maps to round((v - origin[c]) / range * max_q), max_q = 2^bits - 1.
struct Grid {
  float origin[3] = {0, 0, 0};
  float range = 1.0f;
  uint32_t max_q = 0;
};
Grid make_grid(const std::vector<float>& values, int dims, int bits);
uint32_t quantize(float v, float origin, const Grid& g);
float dequantize(uint32_t q, float origin, const Grid& g);
// The grid header codecs 1 and 3 store before grid-quantised values: f32 origin[dims], f32
// range. get_grid refuses a range that is not positive, naming `field`.
void put_grid(ByteWriter& out, const Grid& grid, int dims);
bool get_grid(ByteReader& in, Grid& grid, int dims, int bits, const char* field);

// Skin weights as integers of `bits` (1-16), four per vertex summing to 2^bits - 1 (the
// rounding error moved onto each vertex's largest weight), and back.
std::vector<uint16_t> quantize_weights(const std::vector<float>& weights, int bits);
std::vector<float> dequantize_weights(const std::vector<uint16_t>& levels, int bits);

void encode_geometry_raw(const PackGeometry& g, const GeometryLayout& layout, ByteWriter& out);
bool decode_geometry_raw(ByteReader& in, const GeometryLayout& layout, PackGeometry& out);

void encode_geometry_meshopt(const PackGeometry& g, const GeometryLayout& layout, ByteWriter& out);
bool decode_geometry_meshopt(ByteReader& in, const GeometryLayout& layout, PackGeometry& out);

// Codec 3 codes against `progressive` (PROG) when it describes these vertices: the decoder
// must get the same arrays (PROG is read before GEOM).
void encode_geometry_predictive(const PackGeometry& g, const PackProgressive& progressive,
                                const GeometryLayout& layout, ByteWriter& out);
bool decode_geometry_predictive(ByteReader& in, const GeometryLayout& layout,
                                const PackProgressive& progressive, PackGeometry& out);

// Throws std::runtime_error when Draco refuses the mesh.
void encode_geometry_draco(const PackGeometry& g, const GeometryLayout& layout, ByteWriter& out);
bool decode_geometry_draco(ByteReader& in, const GeometryLayout& layout, PackGeometry& out);

}  // namespace crowdbake::pack_io
