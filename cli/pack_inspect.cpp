// `crowdbake inspect PACK [--json]`: what a .crowdpack holds and where its bytes go.
#include <array>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/commands.h"
#include "cli/material_listing.h"
#include "cli/missing_joints.h"
#include "cli/pack_file.h"
#include "crowdbake/formats/animation_codec.h"
#include "crowdbake/formats/pack_format.h"

namespace crowdbake::cli {
namespace {

using nlohmann::ordered_json;

struct LodRange {
  uint32_t min_vertices = 0, max_vertices = 0;
  uint32_t min_triangles = 0, max_triangles = 0;
};

LodRange lod_range(const PackContents& c) {
  LodRange r;
  r.max_vertices = c.geometry.vertex_count();
  r.max_triangles = c.geometry.triangle_count();
  const PackProgressive& p = c.progressive;
  // note: a pack without progressive arrays has one level; the reader guarantees
  // triangle_count has vertex_count + 1 entries when it is present.
  const bool progressive = p.triangle_count.size() == size_t{r.max_vertices} + 1;
  r.min_vertices = progressive ? p.min_vertices : r.max_vertices;
  r.min_triangles = progressive && r.min_vertices <= r.max_vertices
                        ? p.triangle_count[r.min_vertices]
                        : r.max_triangles;
  return r;
}

const PackChunk* find_chunk(const PackFile& pack, uint32_t tag) {
  for (const PackChunk& c : pack.chunks)
    if (c.tag == tag) return &c;
  return nullptr;
}

uint64_t chunk_size(const PackFile& pack, uint32_t tag) {
  const PackChunk* c = find_chunk(pack, tag);
  return c ? c->size : 0;
}

double per(uint64_t bytes, uint64_t count) {
  return count ? static_cast<double>(bytes) / count : 0.0;
}

// How the pack stores the animation texels (docs/pack-format.md 3.8): crowdbake writes ANIM v3
// only for the coding within the bake's animation.max_error, earlier versions losslessly.
const char* animation_storage(const PackFile& pack) {
  const PackChunk* anim = find_chunk(pack, pack_format::kTagAnim);
  return anim && anim->version >= pack_format::kAnimVersion ? "error-bounded" : "lossless";
}

std::string hex32(uint32_t v) {
  char s[16];
  std::snprintf(s, sizeof s, "0x%08x", v);
  return s;
}

ordered_json settings_json(const std::string& text) {
  ordered_json j = ordered_json::parse(text, nullptr, false);
  return j.is_discarded() ? ordered_json(text) : j;
}

std::array<uint64_t, 4> region_texels(const PartitionMask& mask) {
  std::array<uint64_t, 4> n{};  // head, upper body, trousers, unused
  for (uint8_t t : mask.texels) ++n[t < 3 ? t : 3];
  return n;
}

ordered_json to_json(const PackFile& pack) {
  const PackContents& c = pack.contents;
  ordered_json j;
  j["file"] = pack.path;
  j["kind"] = "pack";
  j["bytes"] = pack.bytes;
  j["name"] = c.name;
  j["format_version"] = {{"major", pack.version_major}, {"minor", pack.version_minor}};
  j["chunks"] = ordered_json::array();
  for (const PackChunk& ch : pack.chunks)
    j["chunks"].push_back({{"tag", pack_format::tag_name(ch.tag)},
                           {"version", ch.version},
                           {"offset", ch.offset},
                           {"size", ch.size},
                           {"checksum", ch.checksum}});
  j["counts"] = {{"joints", c.joints.size()},
                 {"vertices", c.geometry.vertex_count()},
                 {"triangles", c.geometry.triangle_count()},
                 {"clips", c.clips.size()},
                 {"materials", c.materials.size()}};
  const LodRange lod = lod_range(c);
  j["lod"] = {{"min_vertices", lod.min_vertices},
              {"max_vertices", lod.max_vertices},
              {"min_triangles", lod.min_triangles},
              {"max_triangles", lod.max_triangles},
              {"joints_missing_at_min", joints_missing_at_min_json(c, c.geometry.weights)},
              {"joints_unreached_at_min", joints_unreached_at_min_json(c, c.geometry.weights)}};
  const PackLevelErrors& e = c.level_errors;
  j["level_errors"] = ordered_json::array();
  for (size_t k = 0; k < e.vertices.size(); ++k)
    j["level_errors"].push_back(
        {{"vertices", e.vertices[k]}, {"max", e.max_error[k]}, {"rms", e.rms_error[k]}});
  j["clips"] = ordered_json::array();
  for (const PackClip& clip : c.clips)
    j["clips"].push_back({{"name", clip.name},
                          {"frames", clip.frame_count},
                          {"fps", clip.fps},
                          {"duration", clip.duration},
                          {"looping", clip.looping},
                          {"root_motion", !clip.root_motion.empty()}});
  const AnimationTexture& a = c.animation;
  j["animation"] = {{"encoding", animation_encoding_name(a.encoding)},
                    {"joints", a.joints},
                    {"rows", a.rows},
                    {"width", a.width()},
                    {"height", a.rows},
                    {"texels_per_joint", a.texels_per_joint},
                    {"bytes_per_texel", a.bytes_per_texel},
                    {"bytes", a.data.size()},
                    {"stored", animation_storage(pack)}};
  const PartitionMask& m = c.partition;
  const auto texels = region_texels(m);
  j["partition"] = {{"width", m.width},
                    {"height", m.height},
                    {"texels",
                     {{"head", texels[0]},
                      {"upper_body", texels[1]},
                      {"trousers", texels[2]},
                      {"unused", texels[3]}}},
                    {"neck_height", m.neck_height},
                    {"waist_height", m.waist_height},
                    {"up_axis", m.up_axis}};
  if (!c.impostor.empty()) {
    const PackImpostor& i = c.impostor;
    j["impostor"] = {{"views", i.views},   {"frames", i.frames},         {"width", i.width},
                     {"height", i.height}, {"half_width", i.half_width}, {"bottom", i.bottom},
                     {"top", i.top}};
  }
  j["bounds"] = {{"min", c.bounds.min},
                 {"max", c.bounds.max},
                 {"diagonal", bbox_diagonal(c)},
                 {"radius", c.bounds.radius}};
  j["materials"] = materials_json(c.materials);
  j["images"] = images_json(c.images);
  j["variant_images"] = variant_images_json(c.variant_images);
  j["vertex_colors"] = c.vertex_colors.size();
  j["settings"] = settings_json(c.settings_json);
  ordered_json sizes = ordered_json::object();
  for (const PackChunk& ch : pack.chunks) sizes[pack_format::tag_name(ch.tag)] = ch.size;
  const uint64_t geom = chunk_size(pack, pack_format::kTagGeom);
  j["bytes_per_component"] = {
      {"chunks", sizes},
      {"geometry_per_vertex", per(geom, lod.max_vertices)},
      {"geometry_per_triangle", per(geom, lod.max_triangles)},
      {"animation_per_joint_frame",
       per(chunk_size(pack, pack_format::kTagAnim), uint64_t{a.rows} * a.joints)},
      {"partition_per_texel",
       per(chunk_size(pack, pack_format::kTagPart), uint64_t{m.width} * m.height)}};
  return j;
}

// "samples=64 seed=1 form=pullback" for one settings section.
std::string settings_line(const ordered_json& section) {
  std::string line;
  for (const auto& [key, value] : section.items())
    line += (line.empty() ? "" : " ") + key + "=" +
            (value.is_string() ? value.get<std::string>() : value.dump());
  return line;
}

void print_text(const PackFile& pack) {
  const PackContents& c = pack.contents;
  std::printf("%s: pack %u.%u, \"%s\", %llu bytes\n", pack.path.c_str(), pack.version_major,
              pack.version_minor, c.name.c_str(), static_cast<unsigned long long>(pack.bytes));
  std::printf("  chunks     %-4s  %7s  %10s  %10s  %-10s  %6s\n", "tag", "version", "offset",
              "size", "checksum", "share");
  for (const PackChunk& ch : pack.chunks)
    std::printf("             %-4s  %7u  %10llu  %10llu  %-10s  %5.1f%%\n",
                pack_format::tag_name(ch.tag).c_str(), ch.version,
                static_cast<unsigned long long>(ch.offset),
                static_cast<unsigned long long>(ch.size), hex32(ch.checksum).c_str(),
                100.0 * per(ch.size, pack.bytes));
  std::printf("  counts     %zu joints, %u vertices, %u triangles, %zu clips, %zu materials\n",
              c.joints.size(), c.geometry.vertex_count(), c.geometry.triangle_count(),
              c.clips.size(), c.materials.size());
  const LodRange lod = lod_range(c);
  std::printf("  lod        %u..%u vertices, %u..%u triangles\n", lod.min_vertices,
              lod.max_vertices, lod.min_triangles, lod.max_triangles);
  // note: the parts the coarsest level no longer draws with their own joint.
  const std::vector<MissingJoint> missing = joints_missing_at_min(c, c.geometry.weights);
  for (size_t k = 0; k < missing.size(); ++k)
    std::printf("  %-10s '%s' has no vertex below %u vertices\n", k == 0 ? "joints" : "",
                missing[k].name.c_str(), missing[k].coarsest_level);
  const std::vector<MissingJoint> unreached = joints_unreached_at_min(c, c.geometry.weights);
  for (size_t k = 0; k < unreached.size(); ++k)
    std::printf("  %-10s '%s' nor a joint below it has a vertex below %u vertices\n",
                k == 0 ? "unreached" : "", unreached[k].name.c_str(), unreached[k].coarsest_level);
  // note: the error table error-driven LoD reads (model units), or why there is none.
  const PackLevelErrors& e = c.level_errors;
  if (e.vertices.empty())
    std::printf("  errors     none (LERR absent: LoD is selected by budget)\n");
  for (size_t k = 0; k < e.vertices.size(); ++k)
    std::printf("  %-10s %8u vertices: max %.4g, rms %.4g model units\n", k == 0 ? "errors" : "",
                e.vertices[k], static_cast<double>(e.max_error[k]),
                static_cast<double>(e.rms_error[k]));
  std::printf("  clips      %-28s  %6s  %6s  %9s  %-7s  %s\n", "name", "frames", "fps", "duration",
              "looping", "root motion");
  for (const PackClip& clip : c.clips)
    std::printf("             %-28s  %6u  %6.2f  %7.3f s  %-7s  %s\n", clip.name.c_str(),
                clip.frame_count, clip.fps, clip.duration, clip.looping ? "yes" : "no",
                clip.root_motion.empty() ? "no" : "yes");
  const AnimationTexture& a = c.animation;
  std::printf(
      "  animation  %s, %u joints x %u rows: %u x %u texels of %u bytes, %zu bytes, stored %s\n",
      animation_encoding_name(a.encoding), a.joints, a.rows, a.width(), a.rows, a.bytes_per_texel,
      a.data.size(), animation_storage(pack));
  const PartitionMask& m = c.partition;
  const auto texels = region_texels(m);
  std::printf(
      "  partition  %u x %u mask: head %llu, upper body %llu, trousers %llu, unused %llu texels; "
      "neck %g, waist %g\n",
      m.width, m.height, static_cast<unsigned long long>(texels[0]),
      static_cast<unsigned long long>(texels[1]), static_cast<unsigned long long>(texels[2]),
      static_cast<unsigned long long>(texels[3]), m.neck_height, m.waist_height);
  if (!c.impostor.empty())
    std::printf(
        "  impostor   %u views x %u frames of %u x %u texels, cell %g wide, %g to %g high\n",
        c.impostor.views, c.impostor.frames, c.impostor.width, c.impostor.height,
        2.0 * c.impostor.half_width, c.impostor.bottom, c.impostor.top);
  std::printf("  bounds     min (%g, %g, %g), max (%g, %g, %g), diagonal %g, radius %g\n",
              c.bounds.min[0], c.bounds.min[1], c.bounds.min[2], c.bounds.max[0], c.bounds.max[1],
              c.bounds.max[2], bbox_diagonal(c), c.bounds.radius);
  print_materials(c.materials, c.images);
  print_variant_images(c.variant_images);
  if (!c.vertex_colors.empty())
    std::printf("  colours    %zu vertex colours (COLOR_0, RGBA8)\n", c.vertex_colors.size());
  const ordered_json settings = settings_json(c.settings_json);
  if (settings.is_object()) {
    bool first = true;
    for (const auto& [section, values] : settings.items()) {
      std::printf("  %-10s %-10s %s\n", first ? "settings" : "", section.c_str(),
                  values.is_object() ? settings_line(values).c_str() : values.dump().c_str());
      first = false;
    }
  } else {
    std::printf("  settings   %s\n", c.settings_json.c_str());
  }
  const uint64_t geom = chunk_size(pack, pack_format::kTagGeom);
  std::printf(
      "  bytes      geometry %.1f per vertex (%.1f per triangle), animation %.1f per joint per "
      "frame, "
      "partition %.3f per texel\n",
      per(geom, lod.max_vertices), per(geom, lod.max_triangles),
      per(chunk_size(pack, pack_format::kTagAnim), uint64_t{a.rows} * a.joints),
      per(chunk_size(pack, pack_format::kTagPart), uint64_t{m.width} * m.height));
}

}  // namespace

int run_inspect_pack(const InspectSettings& settings) {
  const PackFile pack = load_pack_file(settings.input);
  if (settings.json)
    std::cout << to_json(pack).dump(2) << "\n";
  else
    print_text(pack);
  return 0;
}

}  // namespace crowdbake::cli
