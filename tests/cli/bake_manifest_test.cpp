// Bakes of every shared character are byte-identical for --jobs 1, 2 and 4 and across
// repeated runs. Iterates the manifest, so new assets are covered automatically.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

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
  for (const nlohmann::json& asset : m["assets"]) {
    const std::string path = (test::shared_assets() / asset["path"].get<std::string>()).string();
    SCOPED_TRACE(path);
    std::string first;
    for (const char* jobs : {"1", "2", "4", "2"}) {
      const auto output = dir / (std::string("out") + jobs + ".crowdpack");
      const test::CommandResult r =
          test::run_crowdbake({"bake", path, "-o", output.string(), "--jobs", jobs, "--quiet"});
      ASSERT_EQ(r.exit_code, 0) << r.err;
      const std::string bytes = test::slurp(output);
      ASSERT_FALSE(bytes.empty());
      if (first.empty())
        first = bytes;
      else
        EXPECT_TRUE(bytes == first) << "--jobs " << jobs << " gave different bytes";
    }
  }
}

}  // namespace
}  // namespace crowdbake
