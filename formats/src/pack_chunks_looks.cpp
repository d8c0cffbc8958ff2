// The looks of packs 1.7 and 1.8 (docs/pack-format.md 3.12-3.14): VCOL, the vertices'
// colours, VARS, the variant images of each partition region, and IMPS, the impostor.
#include <cmath>
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

// --- IMPS ------------------------------------------------------------------------------

void encode_impostor(const PackImpostor& m, ByteWriter& out) {
  out.u32(m.views);
  out.u32(m.frames);
  out.u32(m.width);
  out.u32(m.height);
  out.f32(m.half_width);
  out.f32(m.bottom);
  out.f32(m.top);
  out.u32(static_cast<uint32_t>(m.frame_of_row.size()));
  for (uint32_t f : m.frame_of_row) out.u32(f);
  for (uint32_t t : m.texels) out.u32(t);
}

bool decode_impostor(ByteReader& in, PackImpostor& out) {
  in.u32(out.views, "views");
  in.u32(out.frames, "frames");
  in.u32(out.width, "width");
  in.u32(out.height, "height");
  in.f32(out.half_width, "half width");
  in.f32(out.bottom, "bottom");
  in.f32(out.top, "top");
  uint32_t rows = 0;
  in.u32(rows, "rows");
  if (!in.ok()) return false;
  if (const std::string problem = impostor_shape_problem(out); !problem.empty())
    return in.fail(problem);
  if (!in.read_array(out.frame_of_row, rows, "frame of row")) return false;
  const uint64_t words = 2 * uint64_t{out.views} * out.frames * out.cell_texels();
  if (!in.read_array(out.texels, words, "texels")) return false;
  return in.expect_end();
}

std::string impostor_shape_problem(const PackImpostor& m) {
  if (m.views == 0 || m.views > kMaxImpostorSide || m.width == 0 || m.width > kMaxImpostorSide ||
      m.height == 0 || m.height > kMaxImpostorSide || m.frames == 0 ||
      m.frames > kMaxImpostorFrames)
    return std::to_string(m.views) + " views, " + std::to_string(m.frames) + " frames of " +
           std::to_string(m.width) + "x" + std::to_string(m.height) + " texels: out of range";
  if (uint64_t{m.views} * m.frames * m.cell_texels() > kMaxImpostorTexels)
    return "more than " + std::to_string(kMaxImpostorTexels) + " texels";
  if (!(std::isfinite(m.half_width) && m.half_width > 0.0f && std::isfinite(m.bottom) &&
        std::isfinite(m.top) && m.top > m.bottom))
    return "the cell's rectangle is not finite or has no area";
  return "";
}

}  // namespace crowdbake::pack_io
