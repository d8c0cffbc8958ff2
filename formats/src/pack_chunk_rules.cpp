// The rules between a chunk and the rest of the pack (check_pack_chunk in pack.h): a streaming
// reader applies them chunk by chunk against HEAD's counts; read_pack and the writer apply
// them to a whole pack, with the counts of its own contents.
#include <string>

#include "crowdbake/formats/pack_format.h"
#include "pack_chunks.h"

namespace crowdbake {
namespace pack_io {
namespace {

using pack_format::kTagAnim;
using pack_format::kTagClip;
using pack_format::kTagGeom;
using pack_format::kTagLerr;
using pack_format::kTagMatl;
using pack_format::kTagProg;
using pack_format::kTagSkel;

std::string count_mismatch(const char* chunk, const char* what, uint64_t head, uint64_t actual) {
  return std::string(chunk) + ": holds " + std::to_string(actual) + " " + what + ", HEAD says " +
         std::to_string(head);
}

std::string geometry_rules(const PackGeometry& g, const HeadCounts& counts) {
  if (g.vertex_count() != counts.vertices)
    return count_mismatch("GEOM", "vertices", counts.vertices, g.vertex_count());
  if (g.triangle_count() != counts.triangles)
    return count_mismatch("GEOM", "triangles", counts.triangles, g.triangle_count());
  if (!g.joints.empty() && counts.joints == 0)
    return "GEOM: vertices are skinned but the skeleton is empty";
  for (size_t i = 0; i < g.joints.size(); ++i)
    if (g.joints[i] >= counts.joints)
      return "GEOM: vertex " + std::to_string(i / 4) + " uses joint " +
             std::to_string(g.joints[i]) + ", the skeleton has " + std::to_string(counts.joints);
  for (size_t t = 0; t < g.triangle_material.size(); ++t)
    if (g.triangle_material[t] >= counts.materials)
      return "GEOM: triangle " + std::to_string(t) + " uses material " +
             std::to_string(g.triangle_material[t]) + ", there are " +
             std::to_string(counts.materials);
  return "";
}

std::string clip_rules(const std::vector<PackClip>& clips, const HeadCounts& counts) {
  if (clips.size() != counts.clips)
    return count_mismatch("CLIP", "clips", counts.clips, clips.size());
  for (size_t i = 0; i < clips.size(); ++i) {
    const PackClip& clip = clips[i];
    if (uint64_t{clip.first_row} + clip.frame_count > counts.animation_rows)
      return "CLIP: clip " + std::to_string(i) + " '" + clip.name + "' uses rows " +
             std::to_string(clip.first_row) + ".." +
             std::to_string(uint64_t{clip.first_row} + clip.frame_count - 1) +
             ", the animation texture has " + std::to_string(counts.animation_rows);
  }
  return "";
}

std::string material_rules(const PackContents& c, const HeadCounts& counts) {
  if (c.materials.size() != counts.materials)
    return count_mismatch("MATL", "materials", counts.materials, c.materials.size());
  for (size_t i = 0; i < c.materials.size(); ++i)
    if (c.materials[i].base_color_image >= static_cast<int64_t>(c.images.size()))
      return "MATL: material " + std::to_string(i) + " uses image " +
             std::to_string(c.materials[i].base_color_image) + ", there are " +
             std::to_string(c.images.size());
  const PackVariantImages& v = c.variant_images;
  for (int r = 0; r < 3; ++r)
    if (v.count[r] > 0 && uint64_t{v.first[r]} + v.count[r] > c.images.size())
      return "VARS: region " + std::to_string(r) + " uses images " + std::to_string(v.first[r]) +
             ".." + std::to_string(uint64_t{v.first[r]} + v.count[r] - 1) + ", there are " +
             std::to_string(c.images.size());
  return "";
}

std::string progressive_rules(const PackProgressive& p, const HeadCounts& counts) {
  if (p.collapse_to.empty()) return "";
  if (p.collapse_to.size() != counts.vertices)
    return count_mismatch("PROG", "vertices", counts.vertices, p.collapse_to.size());
  if (p.triangle_count.back() != counts.triangles)
    return "PROG: triangle_count[" + std::to_string(counts.vertices) +
           "] = " + std::to_string(p.triangle_count.back()) + ", HEAD says " +
           std::to_string(counts.triangles) + " triangles";
  return "";
}

// The impostor's rows are the animation's, its materials MATL's.
std::string impostor_rules(const PackImpostor& m, const HeadCounts& counts) {
  if (m.empty()) return "";
  if (m.frame_of_row.size() != counts.animation_rows)
    return count_mismatch("IMPS", "animation rows", counts.animation_rows, m.frame_of_row.size());
  for (size_t i = 1; i < m.texels.size(); i += 2) {
    const uint32_t material = (m.texels[i] >> 16) & 0xFFu;
    if (material != PackImpostor::kEmptyTexel && material >= counts.materials)
      return "IMPS: texel " + std::to_string(i / 2) + " has material " + std::to_string(material) +
             ", HEAD says " + std::to_string(counts.materials) + " materials";
  }
  return "";
}

}  // namespace

std::string chunk_rule_problem(uint32_t tag, const PackContents& c, const HeadCounts& counts) {
  switch (tag) {
    case kTagSkel:
      return c.joints.size() == counts.joints
                 ? ""
                 : count_mismatch("SKEL", "joints", counts.joints, c.joints.size());
    case kTagClip:
      return clip_rules(c.clips, counts);
    case kTagMatl:
      return material_rules(c, counts);
    case kTagProg:
      return progressive_rules(c.progressive, counts);
    case kTagLerr:
      if (!c.level_errors.vertices.empty() && c.level_errors.vertices.back() > counts.vertices)
        return "LERR: a sample has " + std::to_string(c.level_errors.vertices.back()) +
               " vertices, HEAD says " + std::to_string(counts.vertices);
      return "";
    case kTagGeom:
      if (!c.vertex_colors.empty() && c.vertex_colors.size() != counts.vertices)
        return count_mismatch("VCOL", "vertices", counts.vertices, c.vertex_colors.size());
      return geometry_rules(c.geometry, counts);
    case kTagAnim:
      if (c.animation.rows != counts.animation_rows)
        return count_mismatch("ANIM", "rows", counts.animation_rows, c.animation.rows);
      if (c.animation.rows > 0 && c.animation.joints != counts.joints)
        return "ANIM: " + std::to_string(c.animation.joints) +
               " joints per row, the skeleton has " + std::to_string(counts.joints);
      return "";
    case pack_format::kTagImps:
      return impostor_rules(c.impostor, counts);
    default:
      return "";
  }
}

}  // namespace pack_io

Status check_pack_chunk(uint32_t tag, const PackContents& contents, const PackCounts& counts) {
  const std::string problem = pack_io::chunk_rule_problem(tag, contents, counts);
  if (problem.empty()) return {};
  return {StatusCode::kInvalidPack, "chunk " + problem};
}

}  // namespace crowdbake
