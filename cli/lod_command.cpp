#include <cmath>
#include <cstdio>
#include <string>

#include "cli/commands.h"
#include "cli/missing_joints.h"
#include "crowdbake/pipeline/animated_error.h"
#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/gltf_export.h"
#include "crowdbake/pipeline/import.h"
#include "crowdbake/pipeline/progressive_mesh.h"
#include "crowdbake/pipeline/simplify.h"

namespace crowdbake::cli {

namespace {

std::string joint_name(const SkinnedAsset& asset, int joint) {
  return joint >= 0 && static_cast<size_t>(joint) < asset.skeleton.joints.size()
             ? "'" + asset.skeleton.joints[static_cast<size_t>(joint)].name + "'"
             : "(none)";
}

// Where the part a level lacks went: the original vertex nearest the farthest point, the
// vertex standing for it in the level, and the collapse on the way that took it off its joint.
void print_loss(const SkinnedAsset& original, const ProgressiveMesh& pm, uint32_t used,
                const AnimatedError& e) {
  const VertexFate fate = vertex_fate(pm, e.max_vertex, used);
  const auto source = [&](size_t k) { return pm.vertex_source[fate.chain[k]]; };
  const auto joint = [&](size_t k) { return original.dominant_joint(source(k)); };
  const size_t last = fate.chain.size() - 1;
  const double away = glm::length(glm::dvec3(original.position(source(0))) -
                                  glm::dvec3(original.position(source(last))));
  std::printf(
      "  lost       vertex %u (joint %s), in the levels down to %u vertices; here vertex %u "
      "(joint %s) stands for it, %.1f%% of the diagonal away in the bind pose\n",
      e.max_vertex, joint_name(original, joint(0)).c_str(), fate.coarsest_level[0], source(last),
      joint_name(original, joint(last)).c_str(),
      e.diagonal > 0.0 ? 100.0 * away / e.diagonal : 0.0);
  for (size_t k = 0; k < last; ++k)
    if (joint(k + 1) != joint(0)) {
      std::printf(
          "  moved off  below %u vertices: vertex %u (joint %s) collapses onto vertex %u (joint "
          "%s)\n",
          fate.coarsest_level[k], source(k), joint_name(original, joint(k)).c_str(), source(k + 1),
          joint_name(original, joint(k + 1)).c_str());
      return;
    }
}

// Where a level that strays got its shape: the level's vertex nearest the farthest point, how
// many original vertices it stands for, and the farthest of them in the bind pose with the
// level below which it got there. A vertex standing for another joint's vertices far away is
// a face stretched across the two (a web).
void print_stray(const SkinnedAsset& original, const ProgressiveMesh& pm, uint32_t used,
                 const std::vector<uint32_t>& progressive_index, const AnimatedError& e) {
  if (e.max_vertex >= progressive_index.size()) return;
  const uint32_t near = progressive_index[e.max_vertex];
  const std::vector<uint32_t> stand_in = level_stand_ins(pm, used);
  const glm::dvec3 at(original.position(pm.vertex_source[near]));
  uint32_t count = 0, farthest = near;
  double away = 0.0;
  for (uint32_t i = 0; i < pm.vertex_count(); ++i) {
    if (stand_in[i] != near) continue;
    ++count;
    const double d = glm::length(glm::dvec3(original.position(pm.vertex_source[i])) - at);
    if (d > away) away = d, farthest = i;
  }
  const uint32_t source = pm.vertex_source[near];
  std::printf("  near       vertex %u (joint %s), standing for %u original vert%s here\n", source,
              joint_name(original, original.dominant_joint(source)).c_str(), count,
              count == 1 ? "ex" : "ices");
  if (farthest == near) return;
  const VertexFate fate = vertex_fate(pm, pm.vertex_source[farthest], used);
  std::printf(
      "  farthest   of them: vertex %u (joint %s), %.1f%% of the diagonal away in the bind pose, "
      "reached it below %u vertices\n",
      pm.vertex_source[farthest],
      joint_name(original, original.dominant_joint(pm.vertex_source[farthest])).c_str(),
      e.diagonal > 0.0 ? 100.0 * away / e.diagonal : 0.0,
      fate.coarsest_level[fate.chain.size() - 2]);
}

// The joints with vertices of their own (largest weight) in the original and none in the level,
// each with the coarsest level that still has one: the parts a level no longer draws with
// their own joint.
void print_joints_without_vertices(const SkinnedAsset& original, const ProgressiveMesh& pm,
                                   uint32_t used) {
  std::vector<uint16_t> heaviest(pm.vertex_count(), UINT16_MAX);
  for (uint32_t i = 0; i < pm.vertex_count(); ++i) {
    const int j = original.dominant_joint(pm.vertex_source[i]);
    if (j >= 0) heaviest[i] = static_cast<uint16_t>(j);
  }
  std::vector<std::string> names;
  std::vector<int> parents;
  for (const Joint& j : original.skeleton.joints)
    names.push_back(j.name), parents.push_back(j.parent);
  const std::vector<uint32_t> levels = coarsest_levels_by_joint(pm.view(), heaviest, names.size());
  const auto list = [](const std::vector<MissingJoint>& joints) {
    std::string out;
    for (const MissingJoint& m : joints)
      out += (out.empty() ? "'" : ", '") + m.name + "' (" + std::to_string(m.coarsest_level) + ")";
    return out;
  };
  const std::vector<MissingJoint> missing = joints_missing_below(levels, names, used);
  if (!missing.empty())
    std::printf("  no vertex  of %zu joint%s here (the coarsest level with one): %s\n",
                missing.size(), missing.size() == 1 ? "" : "s", list(missing).c_str());
  // note: a joint whose own vertices are gone is still drawn when a joint below it keeps one
  // (a foot by its toe); the ones that are not are parts the level has lost.
  const std::vector<MissingJoint> unreached = joints_unreached_below(levels, parents, names, used);
  if (!unreached.empty())
    std::printf(
        "  unreached  %zu of them, no joint below with a vertex either (the coarsest level "
        "reaching one): %s\n",
        unreached.size(), list(unreached).c_str());
}

// The level's animated error (docs/accuracy.md, "What is measured") and where its max is.
void print_error(const SkinnedAsset& original, const SkinnedAsset& lod, const ProgressiveMesh& pm,
                 uint32_t used, const std::vector<uint32_t>& progressive_index, double fps) {
  AnimatedErrorOptions options;
  options.fps = fps;
  options.bind_pose = false;
  const AnimatedError e = animated_error(original, lod, options);
  std::printf(
      "  error      rms %.3f%%, max %.3f%% of the bind-pose diagonal (%d frames at %g fps)\n",
      100.0 * e.mean_rms, 100.0 * e.max, e.frames, fps);
  if (e.max_joint < 0) return;
  const std::string joint = original.skeleton.joints[static_cast<size_t>(e.max_joint)].name;
  char when[256] = "the bind pose";
  if (e.max_clip >= 0)
    std::snprintf(when, sizeof when, "clip '%s' at %.2f s",
                  original.clips[static_cast<size_t>(e.max_clip)].name.c_str(), e.max_time);
  std::printf("  max at     joint '%s', %s: %s\n", joint.c_str(), when,
              e.max_on_lod ? "the level strays from the original's surface"
                           : "part of the original is missing from the level");
  if (e.max_on_lod)
    print_stray(original, pm, used, progressive_index, e);
  else
    print_loss(original, pm, used, e);
  print_joints_without_vertices(original, pm, used);
}

}  // namespace

int run_lod(const LodSettings& settings) {
  const auto usage = [&](const std::string& why) {
    return Error(Error::Kind::kUsage, settings.input, why);
  };
  if (settings.ratio == 0.0 && settings.vertices == 0)
    throw usage(
        "give the level of detail with --ratio R (kept fraction of vertices) or --vertices N");
  if (settings.vertices == 0 && !(settings.ratio > 0.0 && settings.ratio <= 1.0))
    throw usage("--ratio must be in (0, 1], the fraction of vertices to keep");
  if (settings.ratio == 0.0 && settings.vertices < 1) throw usage("--vertices must be at least 1");
  if (settings.simplify.samples < 1)
    throw usage("--samples must be at least 1 (1 = classic QEM on the bind pose)");
  if (!(settings.measure_fps >= 0.0 && settings.measure_fps <= 240.0))
    throw usage("--measure must be a frame rate in (0, 240] frames a second");
  if (!(settings.simplify.max_collapse_cost >= 0.0 &&
        std::isfinite(settings.simplify.max_collapse_cost)))
    throw usage("--max-collapse-cost must be a finite number >= 0 (0 = no ceiling)");
  if (!(settings.simplify.small_area_floor >= 0.0 && settings.simplify.small_area_floor <= 10.0))
    throw usage("--small-area-floor must be in [0, 10] (0 = off)");

  SkinnedAsset asset;
  throw_if_failed(import_asset(settings.input, settings.import, asset));
  const uint32_t total = static_cast<uint32_t>(asset.vertex_count());
  if (settings.vertices > static_cast<int64_t>(total))
    throw usage("--vertices " + std::to_string(settings.vertices) +
                " is more than the character's " + std::to_string(total) + " vertices");
  const uint32_t wanted = settings.vertices > 0
                              ? static_cast<uint32_t>(settings.vertices)
                              : static_cast<uint32_t>(std::lround(settings.ratio * total));

  if (wanted >= total) {
    // note: the full level is the character as imported, in its own vertex order; the
    // progressive mesh's order made every tool reading this file (an index optimiser, a
    // peer simplifier) give results that changed with the simplifier's settings.
    throw_if_failed(export_glb(asset, settings.output));
    if (!settings.quiet)
      std::printf("%s -> %s\n  vertices   %u of %u: full resolution, as imported\n",
                  settings.input.c_str(), settings.output.c_str(), total, total);
    return 0;
  }

  SimplifyReport report;
  ProgressiveMesh pm;
  throw_if_failed(simplify(asset, settings.simplify, pm, &report));
  uint32_t used = pm.usable_vertices(wanted);
  // note: without a cost ceiling an open sheet collapses to no triangle at all; the coarsest
  // level that keeps one is written instead of an empty file.
  const bool empty = pm.triangle_count[used] == 0;
  while (pm.triangle_count[used] == 0 && used < total) {
    uint32_t n = used + 1;
    while (pm.usable_vertices(n) != n) ++n;
    used = n;
  }
  std::vector<uint32_t> progressive_index;
  const SkinnedAsset lod = extract_lod(asset, pm, used, &progressive_index);
  throw_if_failed(export_glb(lod, settings.output));

  if (!settings.quiet) {
    std::printf("%s -> %s\n", settings.input.c_str(), settings.output.c_str());
    std::printf("  vertices   %u of %u (asked %u)\n", used, total, wanted);
    std::printf("  triangles  %zu of %u\n", lod.triangle_count(), pm.max_triangles());
    std::printf("  poses      %d, %s, %.2f s (poses %.2f, quadrics %.2f, collapses %.2f)\n",
                report.poses, report.form == DqemForm::kExact ? "exact DQEM" : "pull-back DQEM",
                report.seconds_poses + report.seconds_quadrics + report.seconds_collapse,
                report.seconds_poses, report.seconds_quadrics, report.seconds_collapse);
    std::printf("  densities  %s\n", report.pose_estimator.c_str());
    if (used < report.seamless_min_vertices)
      std::printf("  note       levels below %u vertices cross UV seams or material borders\n",
                  report.seamless_min_vertices);
    if (report.split_collapses > 0)
      std::printf(
          "  note       a hero mesh: its first %u collapses were made in two halves side by side; "
          "the levels they make keep the positions where the halves meet\n",
          report.split_collapses);
    if (empty)
      std::printf("  note       levels below %u vertices have no triangle left\n", used);
    else if (wanted < pm.min_vertices)
      std::printf("  note       %u vertices is the coarsest level this mesh reaches%s\n",
                  pm.min_vertices,
                  report.stopped_at_cost_ceiling
                      ? " (the next collapse costs more than --max-collapse-cost)"
                      : "");
    if (settings.measure_fps > 0.0)
      print_error(asset, lod, pm, used, progressive_index, settings.measure_fps);
    for (const std::string& w : report.warnings) std::printf("  warning    %s\n", w.c_str());
  }
  return 0;
}

}  // namespace crowdbake::cli
