// `crowdbake lod`: writes a valid skinned LoD, and bad options give one clear error with
// nothing written.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "asset_paths.h"
#include "cli/cli_runner.h"
#include "gltf_test_builder.h"

namespace crowdbake {
namespace {

// A bumpy grid skinned to the two-bone chain: enough faces to simplify.
std::filesystem::path write_grid_character(const test::TempDir& dir) {
  test::GltfBuilder b = test::two_bone_character();
  std::vector<float> pos;
  std::vector<uint16_t> joints, idx;
  std::vector<float> weights;
  const int n = 12;
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) {
      const float fy = 2.0f * y / n;
      pos.insert(pos.end(),
                 {static_cast<float>(x) / n, fy, 0.02f * static_cast<float>((x * 7 + y * 3) % 5)});
      joints.insert(joints.end(), {0, 1, 0, 0});
      weights.insert(weights.end(), {1.0f - fy / 2.0f, fy / 2.0f, 0.0f, 0.0f});
    }
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const uint16_t a = static_cast<uint16_t>(y * (n + 1) + x),
                     c = static_cast<uint16_t>(a + n + 1);
      idx.insert(idx.end(), {a, static_cast<uint16_t>(a + 1), static_cast<uint16_t>(c + 1), a,
                             static_cast<uint16_t>(c + 1), c});
    }
  nlohmann::json& prim = b.doc["meshes"][0]["primitives"][0];
  prim["attributes"]["POSITION"] = b.floats(pos, "VEC3");
  prim["attributes"]["JOINTS_0"] = b.u16(joints, "VEC4");
  prim["attributes"]["WEIGHTS_0"] = b.floats(weights, "VEC4");
  prim["indices"] = b.u16(idx, "SCALAR");
  return b.write(dir / "grid.gltf");
}

// A limb chain made by samples/limb_chain with `args` (its size, its joints), in dir.
std::filesystem::path write_limb_chain(const test::TempDir& dir, const std::string& args) {
  const auto chain = dir / "chain.glb";
  const std::string command = test::shell_quote(MAKE_LIMB_CHAIN_EXE) + " " + args + " -o " +
                              test::shell_quote(chain.string()) + " >/dev/null";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  return chain;
}

void expect_usage_error(const std::vector<std::string>& args, const std::string& fragment,
                        const std::filesystem::path& output, int code = 2) {
  const test::CommandResult r = test::run_crowdbake(args);
  EXPECT_EQ(r.exit_code, code) << r.err;
  EXPECT_EQ(test::count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(output));
  for (const auto& entry : std::filesystem::directory_iterator(output.parent_path()))
    EXPECT_EQ(entry.path().filename().string().rfind(output.filename().string(), 0),
              std::string::npos)
        << "left behind: " << entry.path();
}

TEST(LodCommand, WritesTheRequestedLevel) {
  test::TempDir dir;
  const auto input = write_grid_character(dir);
  const auto output = dir / "lod.glb";
  const test::CommandResult r =
      test::run_crowdbake({"lod", input.string(), "--ratio", "0.25", "-o", output.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("vertices   42 of 169"), std::string::npos) << r.out;
  const test::CommandResult info = test::run_crowdbake({"inspect", output.string(), "--json"});
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const nlohmann::json j = nlohmann::json::parse(info.out);
  EXPECT_EQ(j["vertices"], 42);
  EXPECT_EQ(j["joints"], 2);
  EXPECT_EQ(j["clips"].size(), 1u);
  EXPECT_LT(j["triangles"].get<int>(), 288);
}

// The full level is the character as imported: the simplifier's settings (which reorder the
// progressive mesh's vertices) do not change a byte of it.
// A hero mesh (a generated chain of about 105,000 positions, over split_positions) is simplified
// in two halves side by side first, and `lod` says so; a small character is not.
TEST(LodCommand, SaysWhenAHeroMeshWasSimplifiedInTwoHalves) {
  test::TempDir dir;
  const auto chain = write_limb_chain(dir, "--triangles 210000");
  const test::CommandResult hero = test::run_crowdbake(
      {"lod", chain.string(), "--ratio", "0.01", "-o", (dir / "x.glb").string()});
  EXPECT_EQ(hero.exit_code, 0) << hero.err;
  EXPECT_NE(hero.out.find("were made in two halves side by side"), std::string::npos) << hero.out;
  const test::CommandResult small =
      test::run_crowdbake({"lod", write_grid_character(dir).string(), "--ratio", "0.5", "-o",
                           (dir / "y.glb").string()});
  EXPECT_EQ(small.exit_code, 0) << small.err;
  EXPECT_EQ(small.out.find("two halves"), std::string::npos) << small.out;
}

// `--measure` lists the joints a level has no vertex of, and of those the ones no joint below
// them has one of either (parts the level lost). An eight-joint chain's coarsest level keeps
// its tip, so its inner joints without a vertex are all reached through it.
TEST(LodCommand, MeasureSaysWhichJointsNoJointBelowReaches) {
  test::TempDir dir;
  const auto chain = write_limb_chain(dir, "--triangles 4000 --joints 8");
  const test::CommandResult r = test::run_crowdbake(
      {"lod", chain.string(), "--vertices", "1", "--measure", "1", "-o", (dir / "x.glb").string()});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("no vertex  of"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("unreached"), std::string::npos) << r.out;
  // The pack's coarsest level, read back by `inspect` through the pack's own joint parents.
  const auto pack = dir / "chain.crowdpack";
  const test::CommandResult bake =
      test::run_crowdbake({"bake", chain.string(), "-o", pack.string(), "--quiet"});
  ASSERT_EQ(bake.exit_code, 0) << bake.err;
  const test::CommandResult inspect = test::run_crowdbake({"inspect", pack.string(), "--json"});
  ASSERT_EQ(inspect.exit_code, 0) << inspect.err;
  const nlohmann::json lod = nlohmann::json::parse(inspect.out)["lod"];
  EXPECT_FALSE(lod["joints_missing_at_min"].empty()) << lod;
  EXPECT_TRUE(lod["joints_unreached_at_min"].empty()) << lod;
}

// Joint ends (the default): the KnightCharacter's feet hang from the root, outside the legs'
// chains, and with --no-keep-joint-ends (the limb floor alone) its left foot is unreached at
// the coarsest level (docs/accuracy.md); by default, and with --keep-joint-ends, every joint is
// reached there.
TEST(LodCommand, KeepJointEndsKeepsTheFeet) {
  CROWDBAKE_REQUIRE_SHARED_ASSETS();
  test::TempDir dir;
  const std::string knight =
      (test::shared_assets() / "Quaternius_Knight/KnightCharacter.fbx").string();
  const auto level = [&](const std::vector<std::string>& extra) {
    std::vector<std::string> args{"lod",       knight, "--vertices", "1",
                                  "--measure", "1",    "-o",         (dir / "x.glb").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const test::CommandResult r = test::run_crowdbake(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.out;
  };
  const std::string limbs = level({"--no-keep-joint-ends"});
  const size_t line = limbs.find("unreached");
  ASSERT_NE(line, std::string::npos) << limbs;
  EXPECT_NE(limbs.substr(line, limbs.find('\n', line) - line).find("'Foot.L'"), std::string::npos)
      << limbs;
  const std::string plain = level({});
  EXPECT_EQ(plain.find("unreached"), std::string::npos) << plain;
  // note: the same level (its counts and error); only the timings may differ.
  const auto without_times = [](const std::string& out) {
    std::string kept;
    std::istringstream lines(out);
    for (std::string l; std::getline(lines, l);)
      if (l.find(" s (") == std::string::npos) kept += l + "\n";
    return kept;
  };
  EXPECT_EQ(without_times(level({"--keep-joint-ends"})), without_times(plain));
}

// --max-collapse-cost ends the sequence; the note on the coarsest level says why it ends there.
// Without a ceiling (0) the grid, an open sheet, collapses to no triangle at all: the
// coarsest level that keeps one is written, and the note says so.
TEST(LodCommand, CollapseCeilingSetsTheCoarsestLevel) {
  test::TempDir dir;
  const auto input = write_grid_character(dir);
  const auto coarsest = [&](const std::string& ceiling) {
    const test::CommandResult r =
        test::run_crowdbake({"lod", input.string(), "--vertices", "1", "--max-collapse-cost",
                             ceiling, "-o", (dir / "x.glb").string()});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("costs more than --max-collapse-cost"), std::string::npos) << r.out;
    return nlohmann::json::parse(
               test::run_crowdbake({"inspect", (dir / "x.glb").string(), "--json"}).out)["vertices"]
        .get<int>();
  };
  EXPECT_GT(coarsest("1e-5"), coarsest("0.005"));
  EXPECT_GT(coarsest("1e-7"), coarsest("1e-5"));
  const test::CommandResult r =
      test::run_crowdbake({"lod", input.string(), "--vertices", "1", "--max-collapse-cost", "0",
                           "-o", (dir / "x.glb").string()});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("have no triangle left"), std::string::npos) << r.out;
}

// --measure prints the level's animated error and where its max is.
TEST(LodCommand, MeasureSaysTheErrorAndWhereItsMaxIs) {
  test::TempDir dir;
  const auto input = write_grid_character(dir);
  const test::CommandResult r = test::run_crowdbake(
      {"lod", input.string(), "--ratio", "0.1", "--measure", "5", "-o", (dir / "x.glb").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("of the bind-pose diagonal ("), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("max at     joint '"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("at 5 fps"), std::string::npos) << r.out;
  // note: a missing part is traced to the vertex nearest it and what stands for it.
  EXPECT_EQ(r.out.find("part of the original is missing") != std::string::npos,
            r.out.find("  lost       vertex ") != std::string::npos)
      << r.out;
  const test::CommandResult quiet = test::run_crowdbake(
      {"lod", input.string(), "--ratio", "0.1", "-o", (dir / "y.glb").string()});
  EXPECT_EQ(quiet.out.find("max at"), std::string::npos) << "measured only when asked";
}

// On the shared characters at 2%, a max where part of the original is missing is traced to
// the vertex nearest it, whose joint is the one the max names.
TEST(LodCommand, MeasureTracesTheMaxOnTheSharedCharacters) {
  CROWDBAKE_REQUIRE_SHARED_ASSETS();
  const nlohmann::json m =
      nlohmann::json::parse(test::slurp(test::shared_assets() / "MANIFEST.json"));
  test::TempDir dir;
  int traced = 0, listed = 0, strayed = 0;
  for (const nlohmann::json& asset : m["assets"]) {
    const std::string path = (test::shared_assets() / asset["path"].get<std::string>()).string();
    const test::CommandResult r = test::run_crowdbake(
        {"lod", path, "--ratio", "0.02", "--measure", "2", "-o", (dir / "x.glb").string()});
    ASSERT_EQ(r.exit_code, 0) << path << "\n" << r.err;
    // note: "no vertex  of N joints here ...: 'a' (L), 'b' (L)": N names follow.
    const size_t none = r.out.find("  no vertex  of ");
    if (none != std::string::npos) {
      ++listed;
      const std::string line = r.out.substr(none, r.out.find('\n', none) - none);
      const size_t names = std::count(line.begin(), line.end(), '\'') / 2;
      EXPECT_EQ(line.find("of " + std::to_string(names) + " joint"), size_t{13}) << line;
    }
    const size_t at = r.out.find("max at     joint '");
    if (at == std::string::npos) continue;
    const size_t name = at + std::string("max at     joint ").size();
    const std::string joint = r.out.substr(name, r.out.find('\'', name + 1) - name + 1);
    if (r.out.find("the level strays from the original's surface") != std::string::npos) {
      // note: the max's joint is the heaviest of the level's vertex nearest the point.
      ++strayed;
      EXPECT_NE(r.out.find("  near       vertex "), std::string::npos) << path << "\n" << r.out;
      EXPECT_NE(r.out.find("(joint " + joint + "), standing for "), std::string::npos)
          << path << "\n"
          << r.out;
      continue;
    }
    ASSERT_NE(r.out.find("part of the original is missing"), std::string::npos) << r.out;
    ++traced;
    EXPECT_NE(r.out.find("  lost       vertex "), std::string::npos) << path << "\n" << r.out;
    EXPECT_NE(r.out.find("(joint " + joint + "), in the levels down to "), std::string::npos)
        << path << "\n"
        << r.out;
  }
  EXPECT_GT(traced, 0) << "no shared character lost a part at 2%";
  EXPECT_GT(strayed, 0) << "no shared character's level strayed from its surface at 2%";
  EXPECT_GT(listed, 0) << "every joint of every shared character kept a vertex at 2%";
}

TEST(LodCommand, FullResolutionIsTheImportedCharacterWhateverTheSimplifierSettings) {
  test::TempDir dir;
  const auto input = write_grid_character(dir);
  const std::vector<std::vector<std::string>> settings = {
      {"--ratio", "1"}, {"--vertices", "169", "--samples", "1"}, {"--ratio", "1", "--seed", "9"}};
  std::vector<std::string> files;
  for (size_t i = 0; i < settings.size(); ++i) {
    const auto output = dir / ("full" + std::to_string(i) + ".glb");
    std::vector<std::string> args = {"lod", input.string(), "-o", output.string()};
    args.insert(args.end(), settings[i].begin(), settings[i].end());
    const test::CommandResult r = test::run_crowdbake(args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("169 of 169: full resolution"), std::string::npos) << r.out;
    files.push_back(test::slurp(output));
  }
  EXPECT_EQ(files[0], files[1]);
  EXPECT_EQ(files[0], files[2]);
  const test::CommandResult info =
      test::run_crowdbake({"inspect", (dir / "full0.glb").string(), "--json"});
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const nlohmann::json j = nlohmann::json::parse(info.out);
  EXPECT_EQ(j["vertices"], 169);
  EXPECT_EQ(j["triangles"], 288);
}

TEST(LodCommand, SameOptionsGiveByteIdenticalFiles) {
  test::TempDir dir;
  const auto input = write_grid_character(dir);
  for (const char* name : {"a.glb", "b.glb"})
    ASSERT_EQ(test::run_crowdbake({"lod", input.string(), "--vertices", "60", "--samples", "32",
                                   "--seed", "7", "-o", (dir / name).string(), "--quiet"})
                  .exit_code,
              0);
  EXPECT_EQ(test::slurp(dir / "a.glb"), test::slurp(dir / "b.glb"));
}

TEST(LodCommandErrors, RatioOutOfRange) {
  test::TempDir dir;
  const auto input = write_grid_character(dir);
  expect_usage_error({"lod", input.string(), "--ratio", "1.5", "-o", (dir / "x.glb").string()},
                     "--ratio must be in (0, 1]", dir / "x.glb");
  expect_usage_error({"lod", input.string(), "--ratio", "0", "-o", (dir / "x.glb").string()},
                     "--ratio", dir / "x.glb");
}

TEST(LodCommandErrors, VerticesOutOfRange) {
  test::TempDir dir;
  const auto input = write_grid_character(dir);
  expect_usage_error({"lod", input.string(), "--vertices", "5000", "-o", (dir / "x.glb").string()},
                     "more than the character's 169 vertices", dir / "x.glb");
  expect_usage_error({"lod", input.string(), "--vertices", "-3", "-o", (dir / "x.glb").string()},
                     "--vertices must be at least 1", dir / "x.glb");
}

// Simplifier and measurement options out of range: a usage error naming the option.
TEST(LodCommandErrors, OptionsOutOfRange) {
  test::TempDir dir;
  const auto input = write_grid_character(dir);
  const std::vector<std::array<std::string, 3>> cases = {
      {"--samples", "0", "--samples must be at least 1"},
      {"--max-collapse-cost", "-1", "--max-collapse-cost must be a finite number >= 0"},
      {"--small-area-floor", "-0.5", "--small-area-floor must be in [0, 10]"},
      {"--small-area-floor", "11", "--small-area-floor must be in [0, 10]"},
      {"--measure", "500", "--measure must be a frame rate"}};
  for (const auto& [option, value, message] : cases)
    expect_usage_error(
        {"lod", input.string(), "--ratio", "0.5", option, value, "-o", (dir / "x.glb").string()},
        message, dir / "x.glb");
}

TEST(LodCommandErrors, UnreadableRangesFile) {
  test::TempDir dir;
  const auto input = write_grid_character(dir);
  expect_usage_error({"lod", input.string(), "--ratio", "0.5", "--ranges",
                      (dir / "none.json").string(), "-o", (dir / "x.glb").string()},
                     "none.json: pose ranges: file not found", dir / "x.glb", 1);
}

TEST(LodCommandErrors, RangesNamingUnknownJoints) {
  test::TempDir dir;
  const auto input = write_grid_character(dir);
  std::ofstream(dir / "ranges.json") << R"({"joints": {"tail": {"roll": [0, 10]}}})";
  expect_usage_error({"lod", input.string(), "--ratio", "0.5", "--ranges",
                      (dir / "ranges.json").string(), "-o", (dir / "x.glb").string()},
                     "unknown joint 'tail'", dir / "x.glb", 1);
}

TEST(LodCommandErrors, RatioAndVerticesTogether) {
  test::TempDir dir;
  const auto input = write_grid_character(dir);
  const test::CommandResult r =
      test::run_crowdbake({"lod", input.string(), "--ratio", "0.5", "--vertices", "10", "-o",
                           (dir / "x.glb").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(dir / "x.glb"));
}

}  // namespace
}  // namespace crowdbake
