// Every shared asset imports, and `inspect --json` reports the counts its
// MANIFEST.json records. Iterates the manifest, so new assets are tested automatically.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "asset_paths.h"
#include "cli/cli_runner.h"

namespace crowdbake {
namespace {

nlohmann::json manifest() {
  return nlohmann::json::parse(test::slurp(test::shared_assets() / "MANIFEST.json"));
}

TEST(InspectManifest, CountsMatchForEveryAsset) {
  CROWDBAKE_REQUIRE_SHARED_ASSETS();
  const nlohmann::json m = manifest();
  ASSERT_FALSE(m["assets"].empty());
  for (const nlohmann::json& asset : m["assets"]) {
    const std::string path = (test::shared_assets() / asset["path"].get<std::string>()).string();
    SCOPED_TRACE(path);
    const test::CommandResult r = test::run_crowdbake({"inspect", path, "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    // Bones, plus animated non-bone nodes that move them (docs/importers.md).
    EXPECT_EQ(j["joints"].get<int>(),
              asset["bones"].get<int>() + j["animated_nodes_kept"].get<int>());
    // The file's vertices: those kept plus the identical copies welded away.
    EXPECT_EQ(j["vertices"].get<int>() + j["welded_vertices"].get<int>(),
              asset["vertices"].get<int>());
    EXPECT_EQ(j["triangles"], asset["triangles"]);
    ASSERT_EQ(j["clips"].size(), asset["animations"].size());
    for (size_t c = 0; c < j["clips"].size(); ++c) {
      const nlohmann::json& expected = asset["animations"][c];
      if (expected["name"].is_string()) {
        EXPECT_EQ(j["clips"][c]["name"], expected["name"]);
      }
      // The manifest rounds durations to 4 decimals.
      EXPECT_NEAR(j["clips"][c]["duration"].get<double>(), expected["duration_s"].get<double>(),
                  1e-3);
    }
    EXPECT_EQ(j["source_max_influences"], asset["max_influences"]);
    const bool over_four = asset["max_influences"].get<int>() > 4;
    bool warned = false;
    for (const auto& w : j["warnings"])
      warned |= w.get<std::string>().find("more than 4 influences") != std::string::npos;
    EXPECT_EQ(warned, over_four);
  }
}

}  // namespace
}  // namespace crowdbake
