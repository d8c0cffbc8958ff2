// `crowdbake bake`: atomic, deterministic output; depfile; report; config errors.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "asset_paths.h"
#include "cli/cli_runner.h"
#include "crowdbake/formats/pack.h"
#include "gltf_test_builder.h"

namespace crowdbake {
namespace {

// The spectator written by the sample tests' fixture is not available here, so bake the
// two-bone test character (with an external image reference, for the depfile).
std::filesystem::path write_character(const test::TempDir& dir) {
  test::GltfBuilder b = test::two_bone_character();
  b.doc["images"] = nlohmann::json::array({nlohmann::json{{"uri", "skin tone.png"}}});
  std::ofstream(dir / "skin tone.png") << "not really a png";
  return b.write(dir / "character.gltf");
}

// Bakes the test character into dir/x.crowdpack with `config` (JSON) as dir/config.json.
test::CommandResult bake_with_config(const test::TempDir& dir, const std::string& config,
                                     const std::vector<std::string>& extra = {}) {
  const auto input = write_character(dir);
  std::ofstream(dir / "config.json") << config;
  std::vector<std::string> args = {"bake",     input.string(),
                                   "-o",       (dir / "x.crowdpack").string(),
                                   "--config", (dir / "config.json").string()};
  args.insert(args.end(), extra.begin(), extra.end());
  return test::run_crowdbake(args);
}

// Bakes with `config` as bake_with_config does, keeps the pack as dir/name and returns what
// `crowdbake inspect` prints of it.
std::string bake_and_inspect(const test::TempDir& dir, const std::string& config,
                             const std::string& name) {
  const test::CommandResult r = bake_with_config(dir, config, {"--quiet"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::filesystem::rename(dir / "x.crowdpack", dir / name);
  return test::run_crowdbake({"inspect", (dir / name).string()}).out;
}

TEST(BakeCommand, WritesAPackThatReadsBack) {
  test::TempDir dir;
  const auto input = write_character(dir);
  const auto output = dir / "character.crowdpack";
  const test::CommandResult r =
      test::run_crowdbake({"bake", input.string(), "-o", output.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.out.empty()) << "stdout is not a terminal: nothing should be printed\n" << r.out;
  const std::string bytes = test::slurp(output);
  PackContents pack;
  const Status status =
      read_pack(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), pack);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(pack.joints.size(), 2u);
  EXPECT_EQ(pack.geometry.vertex_count(), 3u);
  ASSERT_EQ(pack.clips.size(), 1u);
  EXPECT_EQ(pack.clips[0].name, "bend");
}

TEST(BakeCommand, SameBytesForAnyJobsAndOnRepeatedRuns) {
  test::TempDir dir;
  const auto input = write_character(dir);
  std::string first;
  for (const char* jobs : {"1", "2", "1", "4"}) {
    const auto output = dir / (std::string("out") + jobs + ".crowdpack");
    ASSERT_EQ(test::run_crowdbake({"bake", input.string(), "-o", output.string(), "--jobs", jobs})
                  .exit_code,
              0);
    const std::string bytes = test::slurp(output);
    if (first.empty())
      first = bytes;
    else
      EXPECT_EQ(bytes, first) << "--jobs " << jobs;
  }
}

TEST(BakeCommand, DepfileListsEveryFileRead) {
  test::TempDir dir;
  const auto input = write_character(dir);
  std::ofstream(dir / "config.json") << R"({"animation": {"encoding": "float16"}})";
  const auto output = dir / "c.crowdpack";
  const test::CommandResult r =
      test::run_crowdbake({"bake", input.string(), "-o", output.string(), "--config",
                           (dir / "config.json").string(), "--depfile", (dir / "c.d").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string dep = test::slurp(dir / "c.d");
  EXPECT_EQ(dep.rfind(output.string() + ":", 0), 0u) << dep;
  EXPECT_NE(dep.find(input.string()), std::string::npos) << dep;
  EXPECT_NE(dep.find((dir / "config.json").string()), std::string::npos) << dep;
  EXPECT_NE(dep.find("skin\\ tone.png"), std::string::npos) << "spaces are escaped for make\n"
                                                            << dep;
}

TEST(BakeCommand, ReportHasStatsTimingsSettingsLodAndChunks) {
  test::TempDir dir;
  const auto input = write_character(dir);
  const auto output = dir / "c.crowdpack";
  ASSERT_EQ(test::run_crowdbake({"bake", input.string(), "-o", output.string(), "--report",
                                 (dir / "r.json").string()})
                .exit_code,
            0);
  const nlohmann::json j = nlohmann::json::parse(test::slurp(dir / "r.json"));
  EXPECT_EQ(j["input"]["vertices"], 3);
  EXPECT_EQ(j["output"]["bytes"], std::filesystem::file_size(output));
  EXPECT_EQ(j["settings"]["simplify"]["samples"], 16);
  EXPECT_EQ(j["settings"]["simplify"]["form"], "exact");
  EXPECT_FALSE(j["stages"].empty());
  EXPECT_EQ(j["lod"]["max_vertices"], 3);
  EXPECT_EQ(j["lod"]["unpriced_collapses"], 0) << "a small character is priced throughout";
  EXPECT_EQ(j["lod"]["collapses_before_stand_off"], 0);
  EXPECT_EQ(j["lod"]["split_collapses"], 0) << "a small character is not split";
  // Collapsing the lone triangle would remove the whole surface: the cost ceiling keeps it.
  EXPECT_EQ(j["lod"]["stopped_at_cost_ceiling"], true);
  EXPECT_EQ(j["lod"]["min_vertices"], 3);
  EXPECT_TRUE(j["lod"]["joints_missing_at_min"].empty()) << "the coarsest level is the mesh";
  bool geometry = false;
  for (const auto& c : j["chunks"]) geometry |= c["tag"] == "GEOM";
  EXPECT_TRUE(geometry);
  EXPECT_LT(j["accuracy"]["animation_max_error"].get<double>(), 1e-3);
  // The animation coding: the default bound and what the coding itself moved a vertex.
  const double bound = j["settings"]["animation"]["max_error"].get<double>();
  EXPECT_GT(bound, 0.0) << "bakes code the animation within a bound by default";
  const std::string coding = j["accuracy"]["animation_coding"].get<std::string>();
  EXPECT_TRUE(coding == "error-bounded" || coding == "lossless") << coding;
  EXPECT_LE(j["accuracy"]["animation_coding_max_error"].get<double>(), bound);
}

// A bound below the quantized texture's own rounding cannot be met: the pack keeps the texels
// losslessly and the report says why (a warning, not an error: the pack is still right).
TEST(BakeCommand, UnreachableAnimationBoundStaysLosslessWithAWarning) {
  test::TempDir dir;
  const test::CommandResult r = bake_with_config(dir, R"({"animation": {"max_error": 1e-12}})",
                                                 {"--report", (dir / "r.json").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(test::slurp(dir / "r.json"));
  EXPECT_EQ(j["accuracy"]["animation_coding"], "lossless");
  EXPECT_EQ(j["accuracy"]["animation_coding_max_error"], 0.0);
  bool warned = false;
  for (const auto& w : j["warnings"])
    warned |= w.get<std::string>().find("stored losslessly, not within animation.max_error") !=
              std::string::npos;
  EXPECT_TRUE(warned) << j["warnings"].dump();
}

TEST(BakeCommandErrors, AnimationErrorOutOfRangeNamesTheKey) {
  test::TempDir dir;
  const test::CommandResult r = bake_with_config(dir, R"({"animation": {"max_error": 0.5}})");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("animation.max_error"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.crowdpack"));
}

TEST(BakeCommandErrors, UnknownConfigKeyNamesTheKey) {
  test::TempDir dir;
  const test::CommandResult r = bake_with_config(dir, R"({"simplify": {"smaples": 4}})");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("bake config: simplify.smaples: unknown key (expected one of: samples"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.crowdpack"));
}

// The two-phase simplifier's switch is gone; an old config says so instead of being ignored.
TEST(BakeCommandErrors, RemovedRelaxWhenStuckKeyIsNamed) {
  test::TempDir dir;
  const test::CommandResult r =
      bake_with_config(dir, R"({"simplify": {"relax_when_stuck": true}})");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(test::count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("simplify.relax_when_stuck: is no longer an option"), std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.crowdpack"));
}

TEST(BakeCommandErrors, BadConfigValue) {
  test::TempDir dir;
  const test::CommandResult r = bake_with_config(dir, R"({"animation": {"encoding": "jpeg"}})");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("animation.encoding: expected one of float32, float16, quantized"),
            std::string::npos)
      << r.err;
}

TEST(BakeCommandErrors, ImpostorOutOfRangeNamesTheKey) {
  test::TempDir dir;
  const test::CommandResult r = bake_with_config(dir, R"({"impostor": {"views": 300}})");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("impostor.views"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.crowdpack"));
}

// An impostor in the config reaches the pack (IMPS) and `inspect` says so; the settings text
// records it.
TEST(BakeCommand, ImpostorConfigGivesAPackWithAnImpostor) {
  test::TempDir dir;
  const test::CommandResult r =
      bake_with_config(dir, R"({"impostor": {"views": 4, "frames_per_clip": 2, "height": 16}})");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const test::CommandResult inspect =
      test::run_crowdbake({"inspect", (dir / "x.crowdpack").string()});
  ASSERT_EQ(inspect.exit_code, 0) << inspect.err;
  EXPECT_NE(inspect.out.find("impostor   4 views x "), std::string::npos) << inspect.out;
  EXPECT_NE(inspect.out.find("views=4 frames_per_clip=2 height=16"), std::string::npos)
      << inspect.out;
}

// The pricing limits are config keys; the settings text names one only when it is not the
// default, so giving the default changes no byte; a bad value names the key.
TEST(BakeCommand, PricingLimitKeysAreRecordedOnlyWhenNotTheDefault) {
  test::TempDir dir;
  const auto input = write_character(dir);
  const auto bake = [&](const std::string& config, const std::string& name) {
    std::vector<std::string> args{"bake", input.string(), "-o", (dir / name).string(), "--quiet"};
    if (!config.empty()) {
      std::ofstream(dir / (name + ".json")) << config;
      args.push_back("--config");
      args.push_back((dir / (name + ".json")).string());
    }
    const test::CommandResult r = test::run_crowdbake(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return test::run_crowdbake({"inspect", (dir / name).string()}).out;
  };
  const std::string plain = bake("", "plain.crowdpack");
  // note: the defaults of SimplifyOptions (docs/bake-config.md).
  for (const auto& [key, default_value] :
       {std::pair<std::string, std::string>{"max_pose_priced_positions", "100000"},
        {"max_stand_off_priced_positions", "5000"},
        {"split_positions", "100000"}}) {
    const auto config = [&](const std::string& value) {
      return R"({"simplify": {")" + key + R"(": )" + value + "}}";
    };
    bake(config(default_value), "same.crowdpack");
    const std::string always = bake(config("0"), "always.crowdpack");
    EXPECT_EQ(plain.find(key), std::string::npos) << plain;
    EXPECT_EQ(test::slurp(dir / "plain.crowdpack"), test::slurp(dir / "same.crowdpack")) << key;
    EXPECT_NE(always.find(key + "=0"), std::string::npos) << always;
    const test::CommandResult bad = bake_with_config(dir, config("-1"));
    EXPECT_EQ(bad.exit_code, 1);
    EXPECT_NE(bad.err.find("simplify." + key), std::string::npos) << bad.err;
  }
}

// The collapse-cost ceiling is a config key, always named in the settings text (packs from
// before it had none); a bad value names the key.
TEST(BakeCommand, CollapseCostCeilingIsAConfigKeyInTheSettings) {
  test::TempDir dir;
  const auto inspect = [&](const std::string& config) {
    const test::CommandResult r = bake_with_config(dir, config, {"--quiet"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return test::run_crowdbake({"inspect", (dir / "x.crowdpack").string()}).out;
  };
  EXPECT_NE(inspect("{}").find("max_collapse_cost=0.005"), std::string::npos);
  EXPECT_NE(inspect(R"({"simplify": {"max_collapse_cost": 0}})").find("max_collapse_cost=0.0 "),
            std::string::npos);
  for (const char* bad : {R"({"simplify": {"max_collapse_cost": -1}})",
                          R"({"simplify": {"max_collapse_cost": "high"}})"}) {
    const test::CommandResult r = bake_with_config(dir, bad);
    EXPECT_EQ(r.exit_code, 1) << bad;
    EXPECT_NE(r.err.find("simplify.max_collapse_cost"), std::string::npos) << r.err;
  }
}

// The small-area floor is a config key, always named in the settings text (packs from before
// it had none); 0 turns it off and changes the levels; a bad value names the key.
TEST(BakeCommand, SmallAreaFloorIsAConfigKeyInTheSettings) {
  test::TempDir dir;
  const auto bake = [&](const std::string& config, const std::string& name) {
    return bake_and_inspect(dir, config, name);
  };
  EXPECT_NE(bake("{}", "plain.crowdpack").find("small_area_floor=0.3"), std::string::npos);
  EXPECT_NE(bake(R"({"simplify": {"small_area_floor": 0}})", "off.crowdpack")
                .find("small_area_floor=0.0 "),
            std::string::npos);
  EXPECT_NE(test::slurp(dir / "plain.crowdpack"), test::slurp(dir / "off.crowdpack"));
  for (const char* bad :
       {R"({"simplify": {"small_area_floor": -1}})", R"({"simplify": {"small_area_floor": 11}})",
        R"({"simplify": {"small_area_floor": "high"}})"}) {
    const test::CommandResult r = bake_with_config(dir, bad);
    EXPECT_EQ(r.exit_code, 1) << bad;
    EXPECT_NE(r.err.find("simplify.small_area_floor"), std::string::npos) << r.err;
  }
}

// keep_joint_ends is a config key, on by default and named in the settings text either way;
// a bad value names the key.
TEST(BakeCommand, KeepJointEndsIsAConfigKeyOnByDefault) {
  test::TempDir dir;
  const auto bake = [&](const std::string& config, const std::string& name) {
    return bake_and_inspect(dir, config, name);
  };
  const std::string plain = bake("{}", "plain.crowdpack");
  const std::string off = bake(R"({"simplify": {"keep_joint_ends": false}})", "off.crowdpack");
  bake(R"({"simplify": {"keep_joint_ends": true}})", "on.crowdpack");
  EXPECT_NE(plain.find("keep_joint_ends=true"), std::string::npos) << plain;
  EXPECT_EQ(test::slurp(dir / "plain.crowdpack"), test::slurp(dir / "on.crowdpack"));
  EXPECT_NE(off.find("keep_joint_ends=false"), std::string::npos) << off;
  EXPECT_NE(test::slurp(dir / "plain.crowdpack"), test::slurp(dir / "off.crowdpack"));
  const test::CommandResult bad = bake_with_config(dir, R"({"simplify": {"keep_joint_ends": 1}})");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("simplify.keep_joint_ends"), std::string::npos) << bad.err;
}

// On a terminal the bake's summary names the parts its coarsest level has lost (by their
// topmost joint) and the setting that would keep them, when a config turned it off; by
// default there is no such line. The summary is for terminals only, so the bake runs under
// script(1), which gives it one.
TEST(BakeCommand, TerminalSummaryNamesTheLostPartsAndTheSetting) {
  CROWDBAKE_REQUIRE_SHARED_ASSETS();
  if (std::system("command -v script >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "script(1) not found (util-linux): no terminal to run the bake on";
  test::TempDir dir;
  const std::string knight =
      (test::shared_assets() / "Quaternius_Knight/KnightCharacter.fbx").string();
  std::ofstream(dir / "no-ends.json") << R"({"simplify": {"keep_joint_ends": false}})";
  const auto summary = [&](const std::string& extra) {
    const std::string bake = test::shell_quote(CROWDBAKE_EXE) + " bake " +
                             test::shell_quote(knight) + " -o " +
                             test::shell_quote((dir / "x.crowdpack").string()) + extra;
    const std::string cmd = "script -qec " + test::shell_quote(bake) + " /dev/null >" +
                            test::shell_quote((dir / "summary.txt").string()) + " 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0);
    return test::slurp(dir / "summary.txt");
  };
  const std::string no_ends =
      summary(" --config " + test::shell_quote((dir / "no-ends.json").string()));
  const size_t at = no_ends.find("  lost ");
  ASSERT_NE(at, std::string::npos) << no_ends;
  const std::string line = no_ends.substr(at, no_ends.find('\n', at) - at);
  EXPECT_NE(line.find("Foot.L"), std::string::npos) << line;
  EXPECT_NE(line.find("Palm.L"), std::string::npos) << line;
  EXPECT_EQ(line.find("Fingers.L"), std::string::npos) << line;  // below Palm.L
  EXPECT_NE(line.find("simplify.keep_joint_ends"), std::string::npos) << line;
  const std::string plain = summary("");
  EXPECT_NE(plain.find("  lod "), std::string::npos) << plain;
  EXPECT_EQ(plain.find("  lost "), std::string::npos) << plain;
}

TEST(BakeCommandErrors, UnwritableOutputLeavesNothing) {
  test::TempDir dir;
  const auto input = write_character(dir);
  const test::CommandResult r = test::run_crowdbake(
      {"bake", input.string(), "-o", (dir / "missing" / "x.crowdpack").string()});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_EQ(test::count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("check that the output folder exists"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "missing"));
}

TEST(BakeCommandErrors, BadInputLeavesNoOutput) {
  test::TempDir dir;
  std::ofstream(dir / "broken.glb") << "nope";
  const auto output = dir / "x.crowdpack";
  const test::CommandResult r =
      test::run_crowdbake({"bake", (dir / "broken.glb").string(), "-o", output.string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()),
                          std::filesystem::directory_iterator{}),
            1);
}

}  // namespace
}  // namespace crowdbake

namespace crowdbake {
namespace {

TEST(BakeCommandErrors, InterruptLeavesNeitherOutputNorTemporaryFile) {
  test::TempDir dir;
  const auto input = write_character(dir);
  const auto output = dir / "x.crowdpack";
  // The bake pauses between writing its temporary file and renaming it; SIGINT arrives then.
  const std::string command = "CROWDBAKE_TEST_WRITE_DELAY_MS=3000 timeout -s INT 1 " +
                              test::shell_quote(CROWDBAKE_EXE) + " bake " +
                              test::shell_quote(input.string()) + " -o " +
                              test::shell_quote(output.string()) + " >/dev/null 2>&1";
  const int status = std::system(command.c_str());
  EXPECT_NE(WEXITSTATUS(status), 0);
  EXPECT_FALSE(std::filesystem::exists(output));
  for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
    EXPECT_EQ(entry.path().filename().string().find("x.crowdpack"), std::string::npos)
        << "left behind: " << entry.path();
}

}  // namespace
}  // namespace crowdbake
