// `crowdbake bench scale FILE...`: simplification time and peak memory of the default DQEM
// settings against meshoptimizer on big characters (docs/accuracy.md, "At scale"); the
// characters come from samples/limb_chain (make_limb_chain --triangles N).
#include <chrono>
#include <cstdio>

#include "commands/child.h"
#include "commands/openmesh_peer.h"
#include "commands/peers.h"
#include "crowdbake/bench/bench.h"
#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/import.h"
#include "crowdbake/pipeline/simplify.h"

namespace crowdbake::bench {

int run_bench_scale(const BenchScaleSettings& settings) {
  std::printf("%-28s %9s %9s | %-9s %9s %9s %9s | %9s | %9s %9s %9s | %11s %9s %9s %9s\n",
              "character", "triangles", "positions", "form", "DQEM s", "peak MB", "min tris",
              "S=1 s", "meshopt s", "peak MB", "tris", "OpenMesh s", "build s", "peak MB", "tris");
  for (const std::string& file : settings.files) {
    const auto start = std::chrono::steady_clock::now();
    SkinnedAsset asset;
    throw_if_failed(import_asset(file, {}, asset));
    const double import_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // note: the child's results come back as text, parsed below.
    const ChildResult dqem = run_in_child([&] {
      SimplifyReport report;
      SimplifyOptions options;
      options.threads = settings.threads;
      ProgressiveMesh pm;
      throw_if_failed(simplify(asset, options, pm, &report));
      return std::to_string(report.positions) + " " +
             (report.form == DqemForm::kExact ? "exact" : "pullback") + " " +
             std::to_string(pm.triangle_count[pm.min_vertices]);
    });
    // note: classic QEM through the same loop, for the connectivity's share of the time.
    const ChildResult qem = run_in_child([&] {
      SimplifyOptions options;
      options.samples = 1;
      options.threads = settings.threads;
      ProgressiveMesh pm;
      throw_if_failed(simplify(asset, options, pm));
      return std::string("1");
    });
    const ChildResult meshopt = run_in_child([&] {
      return std::to_string(meshopt_simplify_all(asset, settings.meshopt_ratio).triangle_count());
    });
    const ChildResult openmesh = run_in_child([&] {
      const OpenMeshRun run = openmesh_decimate_all(asset, settings.meshopt_ratio);
      return std::to_string(run.build_seconds) + " " + std::to_string(run.triangles) + " " +
             std::to_string(run.refused_faces);
    });
    for (const ChildResult* r : {&dqem, &qem, &meshopt, &openmesh})
      if (!r->ok) throw Error(Error::Kind::kInput, file, "a benchmark run failed: " + r->error);
    double openmesh_build = 0.0;
    unsigned long openmesh_triangles = 0, refused = 0;
    std::sscanf(openmesh.payload.c_str(), "%lf %lu %lu", &openmesh_build, &openmesh_triangles,
                &refused);
    unsigned positions = 0, min_triangles = 0;
    char form[16] = {};
    std::sscanf(dqem.payload.c_str(), "%u %15s %u", &positions, form, &min_triangles);
    std::printf(
        "%-28s %9zu %9u | %-9s %9.2f %9.0f %9u | %9.2f | %9.2f %9.0f %9s | %11.2f %9.2f %9.0f "
        "%9lu   (import %.2f s)\n",
        file.substr(file.find_last_of('/') + 1).c_str(), asset.triangle_count(), positions, form,
        dqem.seconds, dqem.peak_rss_mb, min_triangles, qem.seconds, meshopt.seconds,
        meshopt.peak_rss_mb, meshopt.payload.c_str(), openmesh.seconds, openmesh_build,
        openmesh.peak_rss_mb, openmesh_triangles, import_seconds);
    if (refused > 0)
      std::printf("  OpenMesh refused %lu non-manifold faces of %s\n", refused, file.c_str());
    std::fflush(stdout);
  }
  std::printf(
      "\nDQEM: simplify() with the default options, every level at once (S poses, quadrics, "
      "collapses, arrays);\nS=1: the same with one pose (classic QEM through the same "
      "collapse loop), every level;\nmeshopt: one meshopt_simplify per primitive to %.0f%% of "
      "its indices on a position-welded copy;\nOpenMesh: its half-edge mesh and DecimaterT "
      "with ModQuadricT per primitive on the same copy, to %.0f%% of its faces (build: the "
      "mesh and the decimater's initialisation).\nPeak MB: how far the forked child's "
      "resident set rose above its start.\n",
      100.0 * settings.meshopt_ratio, 100.0 * settings.meshopt_ratio);
  return 0;
}

}  // namespace crowdbake::bench
