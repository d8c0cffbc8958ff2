#include "pack_validate.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "crowdbake/formats/animation_codec.h"
#include "crowdbake/formats/pack_format.h"
#include "crowdbake/formats/progressive.h"
#include "pack_chunks.h"

namespace crowdbake::pack_io {
namespace {

using namespace pack_format;

template <typename Container>
bool all_finite(const Container& values) {
  for (float v : values)
    if (!std::isfinite(v)) return false;
  return true;
}

bool valid_region(uint8_t r) { return r <= 2 || r == 255; }

std::string too_many(const char* what, size_t count, uint32_t limit) {
  return std::to_string(count) + " " + what + " exceed the limit of " + std::to_string(limit);
}

}  // namespace

std::string check_joints(const std::vector<PackJoint>& joints) {
  if (joints.size() > kMaxJoints) return too_many("joints", joints.size(), kMaxJoints);
  for (size_t i = 0; i < joints.size(); ++i) {
    const PackJoint& j = joints[i];
    std::ostringstream out;
    if (j.name.size() > kMaxStringBytes)
      out << "name is " << j.name.size() << " bytes";
    else if (j.parent < -1 || j.parent >= static_cast<int64_t>(i))
      out << "parent " << j.parent << " is not -1 or below the joint's own index";
    else if (!all_finite(j.inverse_bind) || !all_finite(j.rest_translation) ||
             !all_finite(j.rest_rotation) || !all_finite(j.rest_scale))
      out << "has a non-finite matrix or rest transform";
    if (!out.str().empty()) return "joint " + std::to_string(i) + ": " + out.str();
  }
  return "";
}

std::string check_clips(const std::vector<PackClip>& clips) {
  if (clips.size() > kMaxClips) return too_many("clips", clips.size(), kMaxClips);
  for (size_t i = 0; i < clips.size(); ++i) {
    const PackClip& c = clips[i];
    std::ostringstream out;
    if (c.name.size() > kMaxStringBytes)
      out << "name is " << c.name.size() << " bytes";
    else if (c.frame_count == 0)
      out << "has no frames";
    else if (!std::isfinite(c.fps) || !(c.fps > 0.0f))
      out << "fps " << c.fps << " is not positive";
    else if (!std::isfinite(c.duration) || c.duration < 0.0f)
      out << "duration " << c.duration << " is negative";
    else if (!c.root_motion.empty() && c.root_motion.size() != 3 * size_t{c.frame_count})
      out << "root motion has " << c.root_motion.size() << " floats, expected 0 or "
          << 3 * size_t{c.frame_count};
    else if (!all_finite(c.root_motion))
      out << "root motion is not finite";
    if (!out.str().empty())
      return "clip " + std::to_string(i) + " (" + c.name.substr(0, 64) + "): " + out.str();
  }
  return "";
}

std::string check_materials(const std::vector<PackMaterial>& materials) {
  if (materials.size() > kMaxMaterials)
    return too_many("materials", materials.size(), kMaxMaterials);
  for (size_t i = 0; i < materials.size(); ++i) {
    const PackMaterial& m = materials[i];
    if (m.name.size() > kMaxStringBytes || m.base_color_texture.size() > kMaxStringBytes)
      return "material " + std::to_string(i) + ": name or texture reference exceeds " +
             std::to_string(kMaxStringBytes) + " bytes";
    const std::string what = "material " + std::to_string(i) + ": ";
    if (!all_finite(m.base_color)) return what + "base colour is not finite";
    if (m.base_color_image < -1)
      return what + "image index " + std::to_string(m.base_color_image) + " is negative";
    if (!all_finite(m.uv_transform)) return what + "texture transform is not finite";
    if (static_cast<uint32_t>(m.alpha_mode) > static_cast<uint32_t>(AlphaMode::kBlend))
      return what + "unknown alpha mode " + std::to_string(static_cast<uint32_t>(m.alpha_mode));
    if (!(m.alpha_cutoff >= 0.0f && m.alpha_cutoff <= 1.0f))
      return what + "alpha cutoff is not in [0, 1]";
  }
  return "";
}

std::string image_type(const std::vector<uint8_t>& bytes) {
  static const uint8_t kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (bytes.size() >= 8 && std::equal(kPng, kPng + 8, bytes.begin())) return "image/png";
  if (bytes.size() >= 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff)
    return "image/jpeg";
  return "";
}

std::string check_images(const std::vector<PackImage>& images) {
  if (images.size() > kMaxImages) return too_many("images", images.size(), kMaxImages);
  for (size_t i = 0; i < images.size(); ++i) {
    const PackImage& m = images[i];
    const std::string what = "image " + std::to_string(i) + ": ";
    if (m.name.size() > kMaxStringBytes || m.mime_type.size() > kMaxStringBytes)
      return what + "name or type exceeds " + std::to_string(kMaxStringBytes) + " bytes";
    if (m.data.size() > kMaxImageBytes)
      return what + std::to_string(m.data.size()) + " bytes exceed the limit of " +
             std::to_string(kMaxImageBytes);
    const std::string type = image_type(m.data);
    if (type.empty()) return what + "the bytes are neither PNG nor JPEG";
    if (type != m.mime_type) return what + "says " + m.mime_type + " but the bytes are " + type;
    if (m.width == 0 || m.height == 0 || m.width > kMaxImageSide || m.height > kMaxImageSide)
      return what + std::to_string(m.width) + "x" + std::to_string(m.height) +
             " is empty or larger than " + std::to_string(kMaxImageSide) + " on a side";
  }
  return "";
}

std::string check_bounds(const PackBounds& b) {
  if (!all_finite(b.min) || !all_finite(b.max) || !std::isfinite(b.radius))
    return "bounds are not finite";
  if (b.radius < 0.0f) return "bounding radius " + std::to_string(b.radius) + " is negative";
  return "";
}

std::string check_level_errors(const PackLevelErrors& e) {
  const size_t n = e.vertices.size();
  if (e.max_error.size() != n || e.rms_error.size() != n)
    return "vertex counts and errors differ in length";
  for (size_t k = 0; k < n; ++k) {
    const std::string at = "sample " + std::to_string(k) + ": ";
    if (e.vertices[k] == 0 || e.vertices[k] > kMaxVertices)
      return at + "vertex count " + std::to_string(e.vertices[k]) + " out of range";
    if (k > 0 && !(e.vertices[k] > e.vertices[k - 1]))
      return at + "vertex counts must strictly increase";
    if (!(std::isfinite(e.max_error[k]) && e.max_error[k] >= 0.0f) ||
        !(std::isfinite(e.rms_error[k]) && e.rms_error[k] >= 0.0f))
      return at + "errors must be finite and >= 0";
    if (k > 0 && e.max_error[k] > e.max_error[k - 1])
      return at + "max_error grows with the vertex count";
  }
  return "";
}

std::string check_progressive(const PackProgressive& p) {
  if (p.collapse_to.size() > kMaxVertices)
    return too_many("progressive vertices", p.collapse_to.size(), kMaxVertices);
  ProgressiveView view;
  view.collapse_to = p.collapse_to;
  view.triangle_count = p.triangle_count;
  view.group_start = p.group_start;
  view.min_vertices = p.min_vertices;
  view.vertex_count = static_cast<uint32_t>(p.collapse_to.size());
  return check_progressive(view).message();
}

std::string check_geometry(const PackGeometry& g) {
  std::ostringstream out;
  if (g.positions.size() % 3 != 0) return "positions are not 3 floats per vertex";
  if (g.triangles.size() % 3 != 0) return "triangles are not 3 indices each";
  const size_t v = g.positions.size() / 3, t = g.triangles.size() / 3;
  if (v > kMaxVertices) return too_many("vertices", v, kMaxVertices);
  if (t > kMaxTriangles) return too_many("triangles", t, kMaxTriangles);
  if (!g.normals.empty() && g.normals.size() != 3 * v)
    out << g.normals.size() << " normal floats for " << v << " vertices";
  else if (!g.uvs.empty() && g.uvs.size() != 2 * v)
    out << g.uvs.size() << " uv floats for " << v << " vertices";
  else if (g.joints.size() != g.weights.size() || (!g.joints.empty() && g.joints.size() != 4 * v))
    out << g.joints.size() << " joint indices and " << g.weights.size() << " weights for " << v
        << " vertices (expected 4 each per vertex, or none)";
  else if (!g.regions.empty() && g.regions.size() != v)
    out << g.regions.size() << " regions for " << v << " vertices";
  else if (!g.triangle_material.empty() && g.triangle_material.size() != t)
    out << g.triangle_material.size() << " triangle materials for " << t << " triangles";
  if (!out.str().empty()) return out.str();
  if (!all_finite(g.positions) || !all_finite(g.normals) || !all_finite(g.uvs) ||
      !all_finite(g.weights))
    return "a position, normal, uv or weight is not finite";
  for (size_t i = 0; i < g.weights.size(); ++i)
    if (g.weights[i] < 0.0f) return "vertex " + std::to_string(i / 4) + " has a negative weight";
  for (size_t i = 0; i < g.regions.size(); ++i)
    if (!valid_region(g.regions[i]))
      return "vertex " + std::to_string(i) + " has unknown region " + std::to_string(g.regions[i]);
  for (size_t c = 0; c < g.triangles.size(); ++c)
    if (g.triangles[c] >= v)
      return "triangle " + std::to_string(c / 3) + " uses vertex " +
             std::to_string(g.triangles[c]) + ", vertex count is " + std::to_string(v);
  return "";
}

std::string check_animation(const AnimationTexture& a) {
  std::ostringstream out;
  // note: the format's limits first (they bound every size), then the codec's own rules
  // (animation_codec.h: layout per encoding, data size, finite values).
  if (a.joints > kMaxJoints)
    out << too_many("joints per row", a.joints, kMaxJoints);
  else if (a.decode_params.size() > kMaxDecodeParams)
    out << too_many("decode parameters", a.decode_params.size(), kMaxDecodeParams);
  if (!out.str().empty()) return out.str();
  return check_animation_texture(a).message();
}

std::string check_partition(const PartitionMask& p) {
  std::ostringstream out;
  if (p.width > kMaxTextureSide || p.height > kMaxTextureSide)
    out << "mask " << p.width << "x" << p.height << " exceeds " << kMaxTextureSide
        << " texels a side";
  else if (p.texels.size() != size_t{p.width} * p.height)
    out << p.texels.size() << " texels for a " << p.width << "x" << p.height << " mask";
  else if (!std::isfinite(p.neck_height) || !std::isfinite(p.waist_height) ||
           !all_finite(p.up_axis))
    out << "heights or up axis not finite";
  if (!out.str().empty()) return out.str();
  for (size_t i = 0; i < p.texels.size(); ++i)
    if (!valid_region(p.texels[i]))
      return "texel " + std::to_string(i) + " has unknown region " + std::to_string(p.texels[i]);
  return "";
}

std::string check_impostor(const PackImpostor& m) {
  if (m.empty()) return m.texels.empty() && m.frame_of_row.empty() ? "" : "data without views";
  if (std::string problem = impostor_shape_problem(m); !problem.empty()) return problem;
  if (m.texels.size() != 2 * size_t{m.views} * m.frames * m.cell_texels())
    return std::to_string(m.texels.size()) + " texel words, the shape needs " +
           std::to_string(2 * size_t{m.views} * m.frames * m.cell_texels());
  for (size_t r = 0; r < m.frame_of_row.size(); ++r)
    if (m.frame_of_row[r] >= m.frames)
      return "row " + std::to_string(r) + " shows frame " + std::to_string(m.frame_of_row[r]) +
             " of " + std::to_string(m.frames);
  for (size_t i = 1; i < m.texels.size(); i += 2)
    if (((m.texels[i] >> 16) & 0xFFu) == PackImpostor::kEmptyTexel &&
        (m.texels[i] != PackImpostor::kEmptyWord1 || m.texels[i - 1] != 0))
      return "empty texel " + std::to_string(i / 2) + " has data";
  return "";
}

std::string check_cross_references(const PackContents& c) {
  // note: a whole pack is checked with its own counts, which HEAD records (pack_chunk_rules).
  const HeadCounts counts = head_counts(c);
  for (uint32_t tag :
       {pack_format::kTagGeom, pack_format::kTagMatl, pack_format::kTagLerr, pack_format::kTagProg,
        pack_format::kTagClip, pack_format::kTagAnim, pack_format::kTagImps})
    if (std::string problem = chunk_rule_problem(tag, c, counts); !problem.empty()) return problem;
  return "";
}

}  // namespace crowdbake::pack_io
