#include "pack_chunks.h"

#include <array>
#include <cstdint>
#include <stdexcept>

#include "animation_bounded_codec.h"
#include "crowdbake/formats/animation_codec.h"
#include "crowdbake/formats/pack_format.h"
#include "geometry_codec.h"
#include "pack_compression.h"
#include "pack_validate.h"

namespace crowdbake::pack_io {
namespace {

using namespace pack_format;

template <size_t N>
void put_floats(ByteWriter& out, const std::array<float, N>& v) {
  for (float x : v) out.f32(x);
}
template <size_t N>
bool get_floats(ByteReader& in, std::array<float, N>& v, const char* field) {
  for (float& x : v)
    if (!in.f32(x, field)) return false;
  return true;
}

// Runs the part's validity check and turns a complaint into a reader error.
bool checked(ByteReader& in, const std::string& problem) {
  return problem.empty() || in.fail(problem);
}

constexpr uint32_t kClipLooping = 1u << 0;
constexpr uint32_t kMaskRaw = 0, kMaskRunLength = 1;

}  // namespace

HeadCounts head_counts(const PackContents& c) {
  HeadCounts h;
  h.joints = static_cast<uint32_t>(c.joints.size());
  h.clips = static_cast<uint32_t>(c.clips.size());
  h.materials = static_cast<uint32_t>(c.materials.size());
  h.vertices = c.geometry.vertex_count();
  h.triangles = c.geometry.triangle_count();
  h.animation_rows = c.animation.rows;
  return h;
}

// --- HEAD ------------------------------------------------------------------------------

void encode_head(const PackContents& c, ByteWriter& out) {
  out.string(c.name, kMaxStringBytes, "name");
  out.string(c.settings_json, kMaxSettingsBytes, "settings_json");
  const HeadCounts h = head_counts(c);
  for (uint32_t v : {h.joints, h.clips, h.materials, h.vertices, h.triangles, h.animation_rows})
    out.u32(v);
}

bool decode_head(ByteReader& in, PackContents& out, HeadCounts& h) {
  in.string(out.name, kMaxStringBytes, "name");
  in.string(out.settings_json, kMaxSettingsBytes, "settings_json");
  in.u32(h.joints, "joint count");
  in.u32(h.clips, "clip count");
  in.u32(h.materials, "material count");
  in.u32(h.vertices, "vertex count");
  in.u32(h.triangles, "triangle count");
  in.u32(h.animation_rows, "animation rows");
  if (!in.ok()) return false;
  if (h.joints > kMaxJoints || h.clips > kMaxClips || h.materials > kMaxMaterials ||
      h.vertices > kMaxVertices || h.triangles > kMaxTriangles)
    return in.fail("a count exceeds the format's limits");
  return in.expect_end();
}

// --- SKEL ------------------------------------------------------------------------------

void encode_skeleton(const std::vector<PackJoint>& joints, ByteWriter& out) {
  out.u32(static_cast<uint32_t>(joints.size()));
  for (const PackJoint& j : joints) {
    out.string(j.name, kMaxStringBytes, "joint name");
    out.i32(j.parent);
    put_floats(out, j.inverse_bind);
    put_floats(out, j.rest_translation);
    put_floats(out, j.rest_rotation);
    put_floats(out, j.rest_scale);
  }
}

bool decode_skeleton(ByteReader& in, std::vector<PackJoint>& out) {
  constexpr size_t kMinJointBytes = 4 + 4 + 22 * 4;
  uint32_t count = 0;
  if (!in.u32(count, "joint count")) return false;
  if (count > kMaxJoints)
    return in.fail("joint count " + std::to_string(count) + " exceeds the limit");
  if (!in.count_fits(count, kMinJointBytes, "joints")) return false;
  out.assign(count, PackJoint{});
  for (uint32_t i = 0; i < count && in.ok(); ++i) {
    PackJoint& j = out[i];
    in.set_item("joint", i);
    in.string(j.name, kMaxStringBytes, "name");
    in.i32(j.parent, "parent");
    get_floats(in, j.inverse_bind, "inverse bind matrix");
    get_floats(in, j.rest_translation, "rest translation");
    get_floats(in, j.rest_rotation, "rest rotation");
    get_floats(in, j.rest_scale, "rest scale");
  }
  in.clear_item();
  return in.expect_end() && checked(in, check_joints(out));
}

// --- CLIP ------------------------------------------------------------------------------

void encode_clips(const std::vector<PackClip>& clips, ByteWriter& out) {
  out.u32(static_cast<uint32_t>(clips.size()));
  for (const PackClip& c : clips) {
    out.string(c.name, kMaxStringBytes, "clip name");
    out.u32(c.first_row);
    out.u32(c.frame_count);
    out.f32(c.fps);
    out.f32(c.duration);
    out.u32(c.looping ? kClipLooping : 0);
    out.u32(static_cast<uint32_t>(c.root_motion.size()));
    out.array(c.root_motion);
  }
}

bool decode_clips(ByteReader& in, std::vector<PackClip>& out) {
  constexpr size_t kMinClipBytes = 7 * 4;
  uint32_t count = 0;
  if (!in.u32(count, "clip count")) return false;
  if (count > kMaxClips)
    return in.fail("clip count " + std::to_string(count) + " exceeds the limit");
  if (!in.count_fits(count, kMinClipBytes, "clips")) return false;
  out.assign(count, PackClip{});
  for (uint32_t i = 0; i < count && in.ok(); ++i) {
    PackClip& c = out[i];
    in.set_item("clip", i);
    uint32_t flags = 0, motion = 0;
    in.string(c.name, kMaxStringBytes, "name");
    in.u32(c.first_row, "first row");
    in.u32(c.frame_count, "frame count");
    in.f32(c.fps, "fps");
    in.f32(c.duration, "duration");
    in.u32(flags, "flags");
    in.u32(motion, "root motion count");
    if (!in.ok()) break;
    if (flags & ~kClipLooping) return in.fail("unknown flags " + std::to_string(flags));
    c.looping = (flags & kClipLooping) != 0;
    in.read_f32_array(c.root_motion, motion, "root motion");
  }
  in.clear_item();
  return in.expect_end() && checked(in, check_clips(out));
}

// --- MATL ------------------------------------------------------------------------------

void encode_materials(const std::vector<PackMaterial>& materials, ByteWriter& out) {
  out.u32(static_cast<uint32_t>(materials.size()));
  for (const PackMaterial& m : materials) {
    out.string(m.name, kMaxStringBytes, "material name");
    put_floats(out, m.base_color);
    out.string(m.base_color_texture, kMaxStringBytes, "base colour texture");
  }
}

// Reads the material count that starts MATL and MATX (each item at least `item_bytes`) and
// sizes `out` to it. note: MATL and MATX fill different fields of the same materials, in
// whichever order a reader meets them; each sizes the list to its count, and a different count
// is an error.
bool read_material_count(ByteReader& in, size_t item_bytes, std::vector<PackMaterial>& out,
                         uint32_t& count) {
  if (!in.u32(count, "material count")) return false;
  if (count > kMaxMaterials)
    return in.fail("material count " + std::to_string(count) + " exceeds the limit");
  if (!in.count_fits(count, item_bytes, "materials")) return false;
  if (!out.empty() && out.size() != count)
    return in.fail("holds " + std::to_string(count) + " materials, the other material chunk " +
                   std::to_string(out.size()));
  out.resize(count);
  return true;
}

bool decode_materials(ByteReader& in, std::vector<PackMaterial>& out) {
  constexpr size_t kMinMaterialBytes = 4 + 16 + 4;
  uint32_t count = 0;
  if (!read_material_count(in, kMinMaterialBytes, out, count)) return false;
  for (uint32_t i = 0; i < count && in.ok(); ++i) {
    in.set_item("material", i);
    in.string(out[i].name, kMaxStringBytes, "name");
    get_floats(in, out[i].base_color, "base colour");
    in.string(out[i].base_color_texture, kMaxStringBytes, "base colour texture");
  }
  in.clear_item();
  return in.expect_end() && checked(in, check_materials(out));
}

// --- MATX ------------------------------------------------------------------------------

void encode_material_extras(const std::vector<PackMaterial>& materials, ByteWriter& out) {
  out.u32(static_cast<uint32_t>(materials.size()));
  for (const PackMaterial& m : materials) {
    out.i32(m.base_color_image);
    put_floats(out, m.uv_transform);
    out.u32(static_cast<uint32_t>(m.alpha_mode));
    out.f32(m.alpha_cutoff);
    out.u32(m.double_sided ? 1 : 0);
  }
}

bool decode_material_extras(ByteReader& in, std::vector<PackMaterial>& out) {
  constexpr size_t kExtraBytes = 4 + 24 + 4 + 4 + 4;
  uint32_t count = 0;
  if (!read_material_count(in, kExtraBytes, out, count)) return false;
  for (uint32_t i = 0; i < count && in.ok(); ++i) {
    PackMaterial& m = out[i];
    uint32_t alpha_mode = 0, double_sided = 0;
    in.set_item("material", i);
    in.i32(m.base_color_image, "image index");
    get_floats(in, m.uv_transform, "texture transform");
    in.u32(alpha_mode, "alpha mode");
    in.f32(m.alpha_cutoff, "alpha cutoff");
    in.u32(double_sided, "double-sided");
    if (!in.ok()) break;
    if (alpha_mode > static_cast<uint32_t>(AlphaMode::kBlend))
      return in.fail("unknown alpha mode " + std::to_string(alpha_mode));
    if (double_sided > 1) return in.fail("double-sided flag " + std::to_string(double_sided));
    m.alpha_mode = static_cast<AlphaMode>(alpha_mode);
    m.double_sided = double_sided == 1;
  }
  in.clear_item();
  return in.expect_end() && checked(in, check_materials(out));
}

// True when some material has more than MATL's fields (the writer then adds MATX).
bool has_material_extras(const std::vector<PackMaterial>& materials) {
  const PackMaterial plain;
  for (const PackMaterial& m : materials)
    if (m.base_color_image != plain.base_color_image || m.uv_transform != plain.uv_transform ||
        m.alpha_mode != plain.alpha_mode || m.alpha_cutoff != plain.alpha_cutoff ||
        m.double_sided != plain.double_sided)
      return true;
  return false;
}

// --- IMGS ------------------------------------------------------------------------------

void encode_images(const std::vector<PackImage>& images, ByteWriter& out) {
  out.u32(static_cast<uint32_t>(images.size()));
  for (const PackImage& m : images) {
    out.string(m.name, kMaxStringBytes, "image name");
    out.string(m.mime_type, kMaxStringBytes, "image type");
    out.u32(m.width);
    out.u32(m.height);
    out.u32(static_cast<uint32_t>(m.data.size()));
    out.array(m.data);
  }
}

bool decode_images(ByteReader& in, std::vector<PackImage>& out) {
  constexpr size_t kMinImageBytes = 4 + 4 + 12;
  uint32_t count = 0;
  if (!in.u32(count, "image count")) return false;
  if (count > kMaxImages)
    return in.fail("image count " + std::to_string(count) + " exceeds the limit");
  if (!in.count_fits(count, kMinImageBytes, "images")) return false;
  out.assign(count, PackImage{});
  for (uint32_t i = 0; i < count && in.ok(); ++i) {
    PackImage& m = out[i];
    uint32_t bytes = 0;
    in.set_item("image", i);
    in.string(m.name, kMaxStringBytes, "name");
    in.string(m.mime_type, kMaxStringBytes, "type");
    in.u32(m.width, "width");
    in.u32(m.height, "height");
    in.u32(bytes, "size");
    if (!in.ok()) break;
    if (bytes > kMaxImageBytes)
      return in.fail(std::to_string(bytes) + " bytes exceed the limit of " +
                     std::to_string(kMaxImageBytes));
    in.read_array(m.data, bytes, "bytes");
  }
  in.clear_item();
  return in.expect_end() && checked(in, check_images(out));
}

// --- BNDS ------------------------------------------------------------------------------

void encode_bounds(const PackBounds& b, ByteWriter& out) {
  put_floats(out, b.min);
  put_floats(out, b.max);
  out.f32(b.radius);
}

bool decode_bounds(ByteReader& in, PackBounds& out) {
  get_floats(in, out.min, "min");
  get_floats(in, out.max, "max");
  in.f32(out.radius, "radius");
  return in.expect_end() && checked(in, check_bounds(out));
}

// --- PROG ------------------------------------------------------------------------------
// Each array as LEB128 varints of small non-negative differences: i - collapse_to[i],
// i - group_start[i], then triangle_count[0] and successive increments (Map is monotone).

void encode_progressive(const PackProgressive& p, ByteWriter& out) {
  const uint32_t v = static_cast<uint32_t>(p.collapse_to.size());
  out.u32(v);
  out.u32(p.min_vertices);
  for (uint32_t i = 0; i < v; ++i) out.varint(i - p.collapse_to[i]);
  for (uint32_t i = 0; i < v; ++i) out.varint(i - p.group_start[i]);
  uint32_t previous = 0;
  for (uint32_t n = 0; n < p.triangle_count.size(); ++n) {
    out.varint(p.triangle_count[n] - previous);
    previous = p.triangle_count[n];
  }
}

bool decode_progressive(ByteReader& in, PackProgressive& out) {
  uint32_t v = 0;
  in.u32(v, "vertex count");
  in.u32(out.min_vertices, "min_vertices");
  if (!in.ok()) return false;
  if (v > kMaxVertices) return in.fail("vertex count " + std::to_string(v) + " exceeds the limit");
  out.collapse_to.clear();
  out.group_start.clear();
  out.triangle_count.clear();
  if (v == 0) return in.expect_end() && checked(in, check_progressive(out));
  // note: every varint takes at least one byte: 3v + 1 of them must still fit.
  if (!in.count_fits(3 * uint64_t{v} + 1, 1, "progressive arrays")) return false;
  out.collapse_to.resize(v);
  out.group_start.resize(v);
  out.triangle_count.resize(size_t{v} + 1);
  for (uint32_t i = 0; i < v; ++i) {
    uint32_t d = 0;
    if (!in.varint(d, "collapse_to")) return false;
    if (d > i) return in.fail("collapse_to[" + std::to_string(i) + "] would be negative");
    out.collapse_to[i] = i - d;
  }
  for (uint32_t i = 0; i < v; ++i) {
    uint32_t d = 0;
    if (!in.varint(d, "group_start")) return false;
    if (d > i) return in.fail("group_start[" + std::to_string(i) + "] would be negative");
    out.group_start[i] = i - d;
  }
  uint64_t total = 0;
  for (uint32_t n = 0; n <= v; ++n) {
    uint32_t d = 0;
    if (!in.varint(d, "triangle_count")) return false;
    total += d;
    if (total > kMaxTriangles) return in.fail("triangle_count exceeds the triangle limit");
    out.triangle_count[n] = static_cast<uint32_t>(total);
  }
  return in.expect_end() && checked(in, check_progressive(out));
}

// --- LERR ------------------------------------------------------------------------------
// A count, then per sample its vertex count (u32), max and RMS error (f32).

void encode_level_errors(const PackLevelErrors& e, ByteWriter& out) {
  out.u32(static_cast<uint32_t>(e.vertices.size()));
  for (size_t k = 0; k < e.vertices.size(); ++k) {
    out.u32(e.vertices[k]);
    out.f32(e.max_error[k]);
    out.f32(e.rms_error[k]);
  }
}

bool decode_level_errors(ByteReader& in, PackLevelErrors& out) {
  uint32_t count = 0;
  if (!in.u32(count, "sample count")) return false;
  if (count > kMaxVertices)
    return in.fail("sample count " + std::to_string(count) + " exceeds the vertex limit");
  if (!in.count_fits(count, 12, "level error samples")) return false;
  out.vertices.resize(count);
  out.max_error.resize(count);
  out.rms_error.resize(count);
  for (uint32_t k = 0; k < count; ++k) {
    in.u32(out.vertices[k], "vertices");
    in.f32(out.max_error[k], "max_error");
    in.f32(out.rms_error[k], "rms_error");
  }
  return in.expect_end() && checked(in, check_level_errors(out));
}

// --- GEOM ------------------------------------------------------------------------------

void encode_geometry(const PackGeometry& g, const PackProgressive& progressive,
                     const PackWriteOptions& options, ByteWriter& out) {
  const GeometryLayout layout = make_geometry_layout(g, options);
  out.u32(static_cast<uint32_t>(layout.codec));
  out.u32(layout.vertex_count);
  out.u32(layout.triangle_count);
  out.u32(layout.attributes);
  out.u8(layout.position_bits);
  out.u8(layout.normal_bits);
  out.u8(layout.uv_bits);
  out.u8(layout.weight_bits);
  for (int i = 0; i < 3; ++i) out.u32(0);
  switch (layout.codec) {
    case GeometryCodec::kDraco:
      encode_geometry_draco(g, layout, out);
      break;
    case GeometryCodec::kMeshopt:
      encode_geometry_meshopt(g, layout, out);
      break;
    case GeometryCodec::kRaw:
      encode_geometry_raw(g, layout, out);
      break;
    case GeometryCodec::kPredictive:
      encode_geometry_predictive(g, progressive, layout, out);
      break;
  }
}

uint32_t geometry_version(const PackGeometry& g, const PackWriteOptions& options) {
  if (options.codec == GeometryCodec::kPredictive) return kGeomVersion;
  return make_geometry_layout(g, options).weight_bits ? kGeomWeightsVersion : kGeomOldestVersion;
}

bool decode_geometry(ByteReader& in, uint32_t version, const PackProgressive& progressive,
                     PackGeometry& out) {
  GeometryLayout layout;
  uint32_t codec = 0, reserved[3] = {};
  in.u32(codec, "codec");
  in.u32(layout.vertex_count, "vertex count");
  in.u32(layout.triangle_count, "triangle count");
  in.u32(layout.attributes, "attributes");
  in.u8(layout.position_bits, "position bits");
  in.u8(layout.normal_bits, "normal bits");
  in.u8(layout.uv_bits, "uv bits");
  in.u8(layout.weight_bits, version >= 2 ? "weight bits" : "reserved");
  for (int i = 0; i < 3; ++i) in.u32(reserved[i], "reserved");
  if (!in.ok()) return false;
  if ((version < 2 && layout.weight_bits) || reserved[0] || reserved[1] || reserved[2])
    return in.fail("reserved header fields are not zero");
  if (codec > static_cast<uint32_t>(GeometryCodec::kPredictive) ||
      (codec == static_cast<uint32_t>(GeometryCodec::kPredictive) && version < 3))
    return in.fail("unknown codec " + std::to_string(codec) + " for GEOM version " +
                   std::to_string(version));
  layout.codec = static_cast<GeometryCodec>(codec);
  if (layout.vertex_count > kMaxVertices || layout.triangle_count > kMaxTriangles)
    return in.fail(std::to_string(layout.vertex_count) + " vertices / " +
                   std::to_string(layout.triangle_count) + " triangles exceed the limits (" +
                   std::to_string(kMaxVertices) + " / " + std::to_string(kMaxTriangles) + ")");
  if (layout.attributes & ~kAttrKnown)
    return in.fail("unknown attribute bits " + std::to_string(layout.attributes));
  const auto bad_bits = [&](uint8_t bits, bool present, uint8_t min) {
    if (layout.codec == GeometryCodec::kRaw || !present) return bits != 0;
    return bits != 0 && (bits < min || bits > kMaxQuantizationBits);
  };
  if (bad_bits(layout.position_bits, true, 1) ||
      bad_bits(layout.normal_bits, layout.has(kAttrNormals), 2) ||
      bad_bits(layout.uv_bits, layout.has(kAttrUvs), 1) || (layout.weight_bits > kMaxWeightBits) ||
      (layout.weight_bits && (layout.codec == GeometryCodec::kRaw || !layout.has(kAttrSkin))))
    return in.fail("quantisation bits " + std::to_string(layout.position_bits) + "/" +
                   std::to_string(layout.normal_bits) + "/" + std::to_string(layout.uv_bits) + "/" +
                   std::to_string(layout.weight_bits) +
                   " are invalid for this codec and attribute set");
  if (layout.codec != GeometryCodec::kRaw) {
    // note: compressed streams may expand; bound what a small hostile chunk can allocate.
    const uint64_t limit = kGeomExpansionSlack + kGeomExpansionRatio * uint64_t{in.remaining()};
    if (layout.decoded_bytes() > limit)
      return in.fail("would decode to " + std::to_string(layout.decoded_bytes()) + " bytes from " +
                     std::to_string(in.remaining()) + " (more than the format's expansion limit)");
  }
  bool ok = false;
  switch (layout.codec) {
    case GeometryCodec::kDraco:
      ok = decode_geometry_draco(in, layout, out);
      break;
    case GeometryCodec::kMeshopt:
      ok = decode_geometry_meshopt(in, layout, out);
      break;
    case GeometryCodec::kRaw:
      ok = decode_geometry_raw(in, layout, out);
      break;
    case GeometryCodec::kPredictive:
      ok = decode_geometry_predictive(in, layout, progressive, out);
      break;
  }
  if (!ok) return in.fail("decoding failed");  // note: keeps the codec's own message
  if (out.vertex_count() != layout.vertex_count || out.triangle_count() != layout.triangle_count)
    return in.fail("decoded counts differ from the header");
  return in.expect_end() && checked(in, check_geometry(out));
}

// --- ANIM ------------------------------------------------------------------------------

// v1: the texels as they are. v2: a u32 compression field (1 = zstd) and a reserved u32
// after the data size, and the texels as one zstd frame (u64 size, then the frame). v3 adds
// compression 2: the error-bounded coding's stream as one zstd frame.
void encode_animation(const AnimationTexture& a, bool compressed,
                      const std::vector<uint8_t>* bounded_frame, ByteWriter& out) {
  const bool bounded = bounded_frame != nullptr;
  out.u32(static_cast<uint32_t>(a.encoding));
  out.u32(a.joints);
  out.u32(a.texels_per_joint);
  out.u32(a.bytes_per_texel);
  out.u32(a.rows);
  out.u32(static_cast<uint32_t>(a.decode_params.size()));
  out.u64(a.data.size());
  if (compressed || bounded) {
    out.u32(bounded ? kAnimCompressionBounded : static_cast<uint32_t>(PackCompression::kZstd));
    out.u32(0);
  }
  out.array(a.decode_params);
  out.zero_pad(kAlignment);
  if (!compressed && !bounded) {
    out.array(a.data);
    return;
  }
  const std::vector<uint8_t> frame = bounded ? *bounded_frame : compress_animation_texels(a);
  out.u64(frame.size());
  out.array(frame);
}

bool decode_animation(ByteReader& in, uint32_t version, AnimationTexture& out) {
  uint32_t encoding = 0, params = 0, compression = 0, reserved = 0;
  uint64_t data_bytes = 0;
  in.u32(encoding, "encoding");
  in.u32(out.joints, "joints");
  in.u32(out.texels_per_joint, "texels per joint");
  in.u32(out.bytes_per_texel, "bytes per texel");
  in.u32(out.rows, "rows");
  in.u32(params, "decode parameter count");
  in.u64(data_bytes, "data size");
  if (version >= 2) {
    in.u32(compression, "compression");
    in.u32(reserved, "reserved");
  }
  if (!in.ok()) return false;
  if (encoding > 2) return in.fail("unknown encoding " + std::to_string(encoding));
  out.encoding = static_cast<AnimationEncoding>(encoding);
  // note: before any size is computed from it (a row's width is joints x texels per joint).
  if (out.joints > kMaxJoints)
    return in.fail("joint count " + std::to_string(out.joints) + " exceeds the limit of " +
                   std::to_string(kMaxJoints));
  if (params > kMaxDecodeParams)
    return in.fail("decode parameter count " + std::to_string(params) + " exceeds the limit");
  if (compression >
      (version >= 3 ? kAnimCompressionBounded : static_cast<uint32_t>(PackCompression::kZstd)))
    return in.fail("unknown compression " + std::to_string(compression) + " for version " +
                   std::to_string(version));
  if (reserved != 0) return in.fail("reserved field is " + std::to_string(reserved));
  in.read_f32_array(out.decode_params, params, "decode parameters");
  in.zero_pad(kAlignment, "padding before the texture data");
  if (compression == static_cast<uint32_t>(PackCompression::kNone)) {
    in.read_array(out.data, data_bytes, "texture data");
    return in.expect_end() && checked(in, check_animation(out));
  }
  // note: the layout is checked before the size it implies is allocated.
  const AnimationTextureFormat format = animation_texture_format(out.encoding);
  if (out.texels_per_joint != format.texels_per_joint ||
      out.bytes_per_texel != format.bytes_per_texel)
    return in.fail(std::string(animation_encoding_name(out.encoding)) + " needs " +
                   std::to_string(format.texels_per_joint) + " texels of " +
                   std::to_string(format.bytes_per_texel) + " bytes per joint");
  const uint64_t expected = uint64_t{out.rows} * out.joints * out.texels_per_joint *
                            out.bytes_per_texel;  // note: < 2^32 · 2^16 · 48, no overflow
  if (data_bytes != expected)
    return in.fail("data size " + std::to_string(data_bytes) + " is not rows x joints x " +
                   std::to_string(out.texels_per_joint * out.bytes_per_texel) + " = " +
                   std::to_string(expected));
  if (data_bytes > kMaxAnimationBytes)
    return in.fail("data size " + std::to_string(data_bytes) + " exceeds the limit of " +
                   std::to_string(kMaxAnimationBytes) + " bytes");
  uint64_t frame_bytes = 0;
  if (!in.u64(frame_bytes, "compressed size")) return false;
  if (frame_bytes > in.remaining())
    return in.fail("compressed texels: needs " + std::to_string(frame_bytes) + " bytes, " +
                   std::to_string(in.remaining()) + " left");
  std::string why;
  if (compression == kAnimCompressionBounded) {
    if (out.encoding != AnimationEncoding::kQuantized)
      return in.fail("the error-bounded coding needs the quantized encoding");
    std::vector<uint8_t> stream;
    const uint64_t size = bounded_stream_limit(out.joints, out.rows);
    if (!expand_zstd_frame(in.cursor(), static_cast<size_t>(frame_bytes), size, stream, &why) ||
        !decode_bounded_animation(stream.data(), stream.size(), out, &why))
      return in.fail("error-bounded texels: " + why);
  } else if (!decompress_animation_texels(in.cursor(), static_cast<size_t>(frame_bytes), out,
                                          &why)) {
    return in.fail("compressed texels: " + why);
  }
  in.skip(static_cast<size_t>(frame_bytes), "compressed texels");
  return in.expect_end() && checked(in, check_animation(out));
}

// --- PART ------------------------------------------------------------------------------
// Texels raw, or run-length coded as (run length - 1, region) byte pairs, whichever is
// smaller. Runs are at most 256 texels, so the mask is at most 128x the coded bytes.

void encode_partition(const PartitionMask& p, ByteWriter& out) {
  out.u32(p.width);
  out.u32(p.height);
  out.f32(p.neck_height);
  out.f32(p.waist_height);
  put_floats(out, p.up_axis);
  std::vector<uint8_t> runs;
  for (size_t i = 0; i < p.texels.size();) {
    size_t n = 1;
    while (n < 256 && i + n < p.texels.size() && p.texels[i + n] == p.texels[i]) ++n;
    runs.push_back(static_cast<uint8_t>(n - 1));
    runs.push_back(p.texels[i]);
    i += n;
  }
  const bool rle = runs.size() < p.texels.size();
  out.u32(rle ? kMaskRunLength : kMaskRaw);
  const std::vector<uint8_t>& bytes = rle ? runs : p.texels;
  out.u32(static_cast<uint32_t>(bytes.size()));
  out.array(bytes);
}

bool decode_partition(ByteReader& in, PartitionMask& out) {
  uint32_t encoding = 0, size = 0;
  in.u32(out.width, "width");
  in.u32(out.height, "height");
  in.f32(out.neck_height, "neck height");
  in.f32(out.waist_height, "waist height");
  get_floats(in, out.up_axis, "up axis");
  in.u32(encoding, "encoding");
  in.u32(size, "encoded size");
  if (!in.ok()) return false;
  if (out.width > kMaxTextureSide || out.height > kMaxTextureSide)
    return in.fail("mask " + std::to_string(out.width) + "x" + std::to_string(out.height) +
                   " exceeds the limit");
  const uint64_t texels = uint64_t{out.width} * out.height;
  if (encoding == kMaskRaw) {
    if (size != texels)
      return in.fail(std::to_string(size) + " raw bytes for " + std::to_string(texels) + " texels");
    in.read_array(out.texels, size, "texels");
  } else if (encoding == kMaskRunLength) {
    if (size % 2 != 0) return in.fail("run-length data has an odd size");
    if (!in.count_fits(size, 1, "run-length data")) return false;
    // note: allocate only what the runs can cover (each pair covers at most 256 texels).
    if (texels > uint64_t{size} / 2 * 256)
      return in.fail(std::to_string(size / 2) + " runs cannot cover " + std::to_string(texels) +
                     " texels");
    out.texels.assign(static_cast<size_t>(texels), 0);
    const uint8_t* runs = in.cursor();
    uint64_t at = 0;
    for (uint32_t i = 0; i < size; i += 2) {
      const uint64_t n = uint64_t{runs[i]} + 1;
      if (n > texels - at)
        return in.fail("runs cover more than " + std::to_string(texels) + " texels");
      std::fill_n(out.texels.begin() + static_cast<ptrdiff_t>(at), n, runs[i + 1]);
      at += n;
    }
    if (at != texels)
      return in.fail("runs cover " + std::to_string(at) + " of " + std::to_string(texels) +
                     " texels");
    in.skip(size, "run-length data");
  } else {
    return in.fail("unknown mask encoding " + std::to_string(encoding));
  }
  return in.expect_end() && checked(in, check_partition(out));
}

}  // namespace crowdbake::pack_io
