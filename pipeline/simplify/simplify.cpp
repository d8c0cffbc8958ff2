// simplify(): poses → welded mesh → DQEM quadrics → collapses → ProgressiveMesh.
#include "crowdbake/pipeline/simplify.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "crowdbake/base/clock.h"
#include "crowdbake/pipeline/error.h"
#include "simplify/collapse.h"
#include "simplify/dqem.h"
#include "simplify/pose_sampler.h"
#include "simplify/simplify_mesh.h"

namespace crowdbake {
static ProgressiveMesh simplify_or_throw(const SkinnedAsset& asset, const SimplifyOptions& options,
                                         SimplifyReport* report) {
  if (options.samples < 1)
    throw Error(Error::Kind::kUsage, asset.source,
                "samples must be at least 1 (S = 1 is classic QEM on the bind pose)");
  if (!(options.max_collapse_cost >= 0.0 && std::isfinite(options.max_collapse_cost)))
    throw Error(Error::Kind::kUsage, asset.source,
                "max_collapse_cost must be a finite number >= 0 (0 = no ceiling)");
  SimplifyReport local;
  SimplifyReport& r = report ? *report : local;

  auto start = std::chrono::steady_clock::now();
  PoseDistribution distribution = estimate_pose_distribution(asset);
  if (!options.ranges_file.empty())
    apply_pose_ranges(distribution, asset.skeleton, options.ranges_file);
  const std::vector<std::vector<glm::dmat4>> poses = sample_poses(asset, distribution, options);
  const SimplifyMesh mesh = build_simplify_mesh(asset);
  const std::vector<glm::dvec3> posed = posed_positions(asset, mesh, poses, options.threads);
  r.poses = static_cast<int>(poses.size());
  r.pose_estimator = distribution.estimator;
  r.positions = mesh.position_count();
  r.degenerate_triangles_dropped = mesh.degenerate_triangles;
  r.seconds_poses = seconds_since(start);

  start = std::chrono::steady_clock::now();
  r.form = options.form;
  const double exact_megabytes =
      static_cast<double>(poses.size()) * mesh.position_count() * sizeof(Quadric) / 1048576.0;
  if (r.form == DqemForm::kExact && options.max_quadric_megabytes > 0.0 &&
      exact_megabytes > options.max_quadric_megabytes) {
    r.form = DqemForm::kPullback;
    char line[200];
    std::snprintf(line, sizeof line,
                  "exact DQEM would keep %.0f MB of quadrics (%zu poses x %u positions), more than "
                  "%.0f MB; used the pull-back form",
                  exact_megabytes, poses.size(), mesh.position_count(),
                  options.max_quadric_megabytes);
    r.warnings.push_back(line);
  }
  DqemCost cost(r.form, asset, mesh, poses, posed, options.threads);
  r.seconds_quadrics = seconds_since(start);

  start = std::chrono::steady_clock::now();
  CollapseStats stats;
  const std::vector<CollapseRecord> records =
      collapse_all(mesh, posed, static_cast<uint32_t>(poses.size()), options, cost, stats);
  ProgressiveMesh pm =
      build_progressive_mesh(mesh.vertex_count, mesh.triangles, mesh.triangle_primitive, records);
  r.seconds_collapse = seconds_since(start);
  uint32_t removed = 0;
  for (size_t i = 0; i < stats.collapses_before_crossing; ++i)
    removed += static_cast<uint32_t>(records[i].wedges.size());
  r.seamless_min_vertices = mesh.vertex_count - removed;
  r.seam_crossings = stats.seam_crossings;
  r.stopped_at_cost_ceiling = stats.stopped_at_ceiling;
  r.priced_flips = stats.priced_flips;
  r.unpriced_collapses = stats.unpriced_collapses;
  r.split_collapses = stats.split_collapses;
  r.collapses_before_stand_off = stats.collapses_before_stand_off;

  r.locked_vertices = stats.locked_positions;
  r.rejected_flips = stats.rejected_flips;
  if (mesh.degenerate_triangles > 0)
    r.warnings.push_back(std::to_string(mesh.degenerate_triangles) +
                         " triangles with two corners at one position were dropped");
  if (stats.locked_positions > 0)
    r.warnings.push_back(std::to_string(stats.locked_positions) +
                         " vertices sit on non-manifold edges or where several borders meet; they "
                         "are kept as they are");
  return pm;
}

SkinnedAsset extract_lod(const SkinnedAsset& asset, const ProgressiveMesh& pm, uint32_t n,
                         std::vector<uint32_t>* progressive_index) {
  const uint32_t used = pm.usable_vertices(n);
  const std::vector<uint32_t> triangles = pm.reconstruct(used);

  // Original vertex id -> (primitive, index in primitive).
  std::vector<std::pair<uint32_t, uint32_t>> origin;
  for (uint32_t p = 0; p < asset.primitives.size(); ++p)
    for (uint32_t v = 0; v < asset.primitives[p].vertex_count(); ++v) origin.push_back({p, v});

  // note: everything but the primitives' arrays is copied; copying those only to clear them
  // cost a hero character's whole vertex data per level.
  SkinnedAsset lod;
  lod.source = asset.source, lod.files = asset.files, lod.skeleton = asset.skeleton;
  lod.materials = asset.materials, lod.images = asset.images, lod.clips = asset.clips;
  lod.stats = asset.stats;
  lod.warnings = asset.warnings;
  for (const Primitive& p : asset.primitives) {
    lod.primitives.emplace_back();
    lod.primitives.back().name = p.name, lod.primitives.back().material = p.material;
  }
  std::vector<uint32_t> local(used);
  std::vector<std::vector<uint32_t>> kept(asset.primitives.size());
  for (uint32_t i = 0; i < used; ++i) {
    const auto [prim, v] = origin[pm.vertex_source[i]];
    Primitive& dst = lod.primitives[prim];
    local[i] = static_cast<uint32_t>(dst.positions.size());
    if (progressive_index) kept[prim].push_back(i);
    dst.append_vertex(asset.primitives[prim], v);
  }
  for (size_t t = 0; t < triangles.size() / 3; ++t) {
    const uint32_t prim = pm.triangle_primitive[t];
    for (int c = 0; c < 3; ++c) {
      const uint32_t i = triangles[3 * t + c];
      // note: collapses map wedges only within shared faces, so a face's corners always
      // stay in the face's own primitive.
      if (origin[pm.vertex_source[i]].first != prim)
        throw std::logic_error("extract_lod: a triangle's corner left its primitive");
      lod.primitives[prim].indices.push_back(local[i]);
    }
  }
  if (progressive_index) {
    progressive_index->clear();
    for (size_t p = 0; p < kept.size(); ++p)
      if (!lod.primitives[p].indices.empty())
        progressive_index->insert(progressive_index->end(), kept[p].begin(), kept[p].end());
  }
  // note: a primitive whose faces all collapsed away is dropped; empty ones are invalid glTF.
  lod.primitives.erase(std::remove_if(lod.primitives.begin(), lod.primitives.end(),
                                      [](const Primitive& p) { return p.indices.empty(); }),
                       lod.primitives.end());
  return lod;
}

Status simplify(const SkinnedAsset& asset, const SimplifyOptions& options, ProgressiveMesh& out,
                SimplifyReport* report) {
  return capture_errors([&] { out = simplify_or_throw(asset, options, report); });
}

}  // namespace crowdbake
