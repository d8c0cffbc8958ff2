#include <algorithm>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/material_listing.h"
#include "cli/pack_file.h"
#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/import.h"

namespace crowdbake::cli {
namespace {

int max_influences(const SkinnedAsset& asset) {
  int most = 0;
  for (const Primitive& p : asset.primitives)
    for (const auto& w : p.weights)
      most = std::max<int>(most, static_cast<int>(std::count_if(w.begin(), w.end(),
                                                                [](float x) { return x > 0.0f; })));
  return most;
}

std::string root_name(const Skeleton& skeleton) {
  std::string names;
  for (int r : skeleton.roots()) names += (names.empty() ? "" : ", ") + skeleton.joints[r].name;
  return names;
}

nlohmann::json to_json(const SkinnedAsset& asset) {
  nlohmann::json j;
  j["file"] = asset.source;
  j["joints"] = asset.skeleton.joints.size();
  j["animated_nodes_kept"] = asset.stats.animated_nodes_kept;
  j["skeleton_depth"] = asset.skeleton.depth();
  j["root"] = root_name(asset.skeleton);
  j["vertices"] = asset.vertex_count();
  j["welded_vertices"] = asset.stats.vertices_welded;
  j["triangles"] = asset.triangle_count();
  j["max_influences"] = max_influences(asset);
  j["source_max_influences"] = asset.stats.max_influences;
  j["materials"] = materials_json(asset.materials);
  j["images"] = images_json(asset.images);
  j["primitives"] = nlohmann::json::array();
  for (const Primitive& p : asset.primitives)
    j["primitives"].push_back({{"name", p.name},
                               {"material", p.material},
                               {"vertices", p.vertex_count()},
                               {"triangles", p.triangle_count()},
                               {"has_normals", !p.normals.empty()},
                               {"has_uvs", !p.uvs.empty()},
                               {"has_colors", !p.colors.empty()}});
  j["clips"] = nlohmann::json::array();
  for (const Clip& c : asset.clips)
    j["clips"].push_back(
        {{"name", c.name}, {"duration", c.duration}, {"keyframes", c.keyframes()}});
  j["warnings"] = asset.warnings;
  return j;
}

void print_text(const SkinnedAsset& asset) {
  const Skeleton& s = asset.skeleton;
  std::printf("%s\n", asset.source.c_str());
  std::printf("  skeleton   %zu joints, depth %d, root %s", s.joints.size(), s.depth(),
              root_name(s).c_str());
  if (asset.stats.animated_nodes_kept > 0)
    std::printf(" (%d animated non-bone node(s) kept as joints)", asset.stats.animated_nodes_kept);
  std::printf("\n");
  std::printf(
      "  meshes     %zu primitives, %zu vertices, %zu triangles, max %d influences (source had "
      "%d)\n",
      asset.primitives.size(), asset.vertex_count(), asset.triangle_count(), max_influences(asset),
      asset.stats.max_influences);
  if (asset.stats.vertices_welded > 0)
    std::printf(
        "             %d identical vertices welded (--keep-duplicate-vertices keeps them)\n",
        asset.stats.vertices_welded);
  for (const Primitive& p : asset.primitives)
    std::printf("    %-24s material %2d  %6zu vertices  %6zu triangles%s%s%s\n", p.name.c_str(),
                p.material, p.vertex_count(), p.triangle_count(),
                p.normals.empty() ? "  no normals" : "", p.uvs.empty() ? "  no uvs" : "",
                p.colors.empty() ? "" : "  vertex colours");
  print_materials(asset.materials, asset.images);
  std::printf("  clips      %zu\n", asset.clips.size());
  for (const Clip& c : asset.clips)
    std::printf("    %-32s %8.3f s  %4d keyframes\n", c.name.c_str(), c.duration, c.keyframes());
  std::printf("  warnings   %zu\n", asset.warnings.size());
  for (const std::string& w : asset.warnings) std::printf("    %s\n", w.c_str());
}

}  // namespace

int run_inspect(const InspectSettings& settings) {
  if (looks_like_pack(settings.input)) return run_inspect_pack(settings);
  SkinnedAsset asset;
  throw_if_failed(import_asset(settings.input, settings.import, asset));
  if (settings.json)
    std::cout << to_json(asset).dump(2) << "\n";
  else
    print_text(asset);
  return 0;
}

}  // namespace crowdbake::cli
