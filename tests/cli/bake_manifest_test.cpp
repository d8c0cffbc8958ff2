// Bakes of every shared character are byte-identical for --jobs 1, 2 and 4 and across
// repeated runs, and their reports name the joints the coarsest level has no vertex of. Iterates
// the manifest, so new assets are covered automatically.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "asset_paths.h"
#include "cli/cli_runner.h"

namespace crowdbake {
namespace {

TEST(BakeManifest, SameBytesForAnyJobsAndOnRepeatedRuns) {
  CROWDBAKE_REQUIRE_SHARED_ASSETS();
  const nlohmann::json m =
      nlohmann::json::parse(test::slurp(test::shared_assets() / "MANIFEST.json"));
  ASSERT_FALSE(m["assets"].empty());
  test::TempDir dir;
  size_t missing = 0;
  for (const nlohmann::json& asset : m["assets"]) {
    const std::string path = (test::shared_assets() / asset["path"].get<std::string>()).string();
    SCOPED_TRACE(path);
    std::string first;
    for (const char* jobs : {"1", "2", "4", "2"}) {
      const auto output = dir / (std::string("out") + jobs + ".crowdpack");
      const auto report = dir / "report.json";
      const test::CommandResult r =
          test::run_crowdbake({"bake", path, "-o", output.string(), "--jobs", jobs, "--quiet",
                               "--report", report.string()});
      ASSERT_EQ(r.exit_code, 0) << r.err;
      if (first.empty()) {
        // note: each joint the coarsest level has no vertex of is named once, with a level
        // between the coarsest and the full mesh.
        const nlohmann::json lod = nlohmann::json::parse(test::slurp(report))["lod"];
        // `inspect` of the pack says the same, one line each.
        const test::CommandResult inspect = test::run_crowdbake({"inspect", output.string()});
        ASSERT_EQ(inspect.exit_code, 0) << inspect.err;
        std::set<std::string> names;
        for (const nlohmann::json& joint : lod["joints_missing_at_min"]) {
          const std::string name = joint["joint"].get<std::string>();
          EXPECT_TRUE(names.insert(name).second) << joint;
          EXPECT_GT(joint["coarsest_level"], lod["min_vertices"]) << joint;
          EXPECT_LE(joint["coarsest_level"], lod["max_vertices"]) << joint;
          EXPECT_NE(inspect.out.find("'" + name + "' has no vertex below " +
                                     std::to_string(joint["coarsest_level"].get<uint32_t>()) +
                                     " vertices"),
                    std::string::npos)
              << name << "\n"
              << inspect.out;
        }
        missing += names.size();
        // note: a joint no joint below it reaches is one without a vertex of its own.
        for (const nlohmann::json& joint : lod["joints_unreached_at_min"])
          EXPECT_TRUE(names.count(joint["joint"].get<std::string>())) << joint;
      }
      const std::string bytes = test::slurp(output);
      ASSERT_FALSE(bytes.empty());
      if (first.empty())
        first = bytes;
      else
        EXPECT_TRUE(bytes == first) << "--jobs " << jobs << " gave different bytes";
    }
  }
  EXPECT_GT(missing, 0u) << "every shared character keeps a vertex of every joint to the end";
}

}  // namespace
}  // namespace crowdbake
