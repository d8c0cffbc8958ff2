// The per-vertex and per-region looks of packs 1.7 (docs/pack-format.md 3.12, 3.13): VCOL,
// the vertices' colours, and VARS, the variant images of each partition region.
#include <string>

#include "crowdbake/formats/pack_format.h"
#include "pack_chunks.h"

namespace crowdbake::pack_io {

using namespace pack_format;

// --- VCOL ------------------------------------------------------------------------------

void encode_vertex_colors(const std::vector<uint32_t>& colors, ByteWriter& out) {
  out.u32(static_cast<uint32_t>(colors.size()));
  for (uint32_t c : colors) out.u32(c);
}

bool decode_vertex_colors(ByteReader& in, std::vector<uint32_t>& out) {
  uint32_t count = 0;
  if (!in.u32(count, "vertex count")) return false;
  if (count > kMaxVertices)
    return in.fail("vertex count " + std::to_string(count) + " exceeds the limit");
  if (!in.count_fits(count, 4, "colours")) return false;
  out.resize(count);
  for (uint32_t& c : out) in.u32(c, "colour");
  return in.expect_end();
}

// --- VARS ------------------------------------------------------------------------------

void encode_variant_images(const PackVariantImages& v, ByteWriter& out) {
  for (int r = 0; r < 3; ++r) {
    out.u32(v.first[r]);
    out.u32(v.count[r]);
  }
}

bool decode_variant_images(ByteReader& in, PackVariantImages& out) {
  for (int r = 0; r < 3 && in.ok(); ++r) {
    in.set_item("region", static_cast<size_t>(r));
    in.u32(out.first[r], "first image");
    in.u32(out.count[r], "image count");
    if (in.ok() && out.count[r] > kMaxVariantImages)
      return in.fail("has " + std::to_string(out.count[r]) +
                     " variant images, above the limit of " + std::to_string(kMaxVariantImages));
  }
  in.clear_item();
  return in.expect_end();
}

}  // namespace crowdbake::pack_io
