// Every shared asset (iterating MANIFEST.json, so new ones are covered automatically):
// imports, and its skinned surface at every frame (30 fps) of every clip is finite and
// keeps a sane shape (within a multiple of the bind-pose bounds about its own centre).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "asset_paths.h"
#include "crowdbake/pipeline/import.h"
#include "crowdbake/pipeline/pose_evaluator.h"
#include "pipeline_calls.h"

namespace crowdbake {
namespace {

TEST(ManifestAssets, SkinnedPositionsAreFiniteAndBoundedAtEveryFrame) {
  CROWDBAKE_REQUIRE_SHARED_ASSETS();
  const nlohmann::json manifest =
      nlohmann::json::parse(std::ifstream(test::shared_assets() / "MANIFEST.json"));
  for (const nlohmann::json& entry : manifest["assets"]) {
    const std::string path = (test::shared_assets() / entry["path"].get<std::string>()).string();
    SCOPED_TRACE(path);
    const SkinnedAsset asset = test::import_or_throw(path);
    std::vector<glm::dvec3> bind;
    for (const Primitive& p : asset.primitives)
      for (const glm::vec3& v : p.positions) bind.emplace_back(v);
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const glm::dvec3& v : bind) lo = glm::min(lo, v), hi = glm::max(hi, v);
    const double diag = glm::length(hi - lo);
    ASSERT_GT(diag, 0.0);

    // Each frame is measured about its own centre, so clips whose root motion carries the
    // body away (the bird's armature flies it 3.8 diagonals) are judged by their shape only.
    double farthest = 0.0, smallest = 1e300;
    int frames = 0;
    for (const Clip& clip : asset.clips) {
      const int count = static_cast<int>(std::floor(clip.duration * 30.0)) + 1;
      for (int f = 0; f <= count; ++f) {
        const double t = std::min(f / 30.0, clip.duration);
        const std::vector<glm::dvec3> posed = skin_asset(asset, &clip, t);
        glm::dvec3 plo(1e300), phi(-1e300);
        for (const glm::dvec3& p : posed) {
          ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))
              << "clip '" << clip.name << "' t = " << t;
          plo = glm::min(plo, p), phi = glm::max(phi, p);
        }
        const glm::dvec3 posed_centre = 0.5 * (plo + phi);
        for (const glm::dvec3& p : posed)
          farthest = std::max(farthest, glm::length(p - posed_centre) / diag);
        smallest = std::min(smallest, glm::length(phi - plo) / diag);
        ++frames;
      }
    }
    // note: a wrong inverse bind typically flings vertices by the joint's distance from the
    // origin (far beyond 3 diagonals) or shrinks everything to a point.
    EXPECT_LT(farthest, 3.0);
    EXPECT_GT(smallest, 0.05);
    std::printf(
        "[ frames ] %s: %d frames, farthest vertex %.2f bbox diagonals from the frame's centre, "
        "smallest frame %.2f diagonals\n",
        path.c_str(), frames, farthest, smallest);
  }
}

}  // namespace
}  // namespace crowdbake
