// `crowdbake render`: bad input gives one clear error line, a non-zero exit and no output;
// without a Vulkan driver the message says how to install lavapipe; with a device (lavapipe)
// it writes the PNGs, sequences, contact sheets and the --profile table.
// GPU cases SKIP when no Vulkan device exists, unless CROWDBAKE_REQUIRE_VULKAN=1 (then FAIL);
// they run with --validate, so a validation error fails them.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <regex>

#include "cli/cli_runner.h"
#include "cli/image_png.h"
#include "crowdbake/formats/pack.h"
#include "pack_bytes.h"
#include "runtime/runtime_test_support.h"

namespace crowdbake {
namespace {

namespace fs = std::filesystem;

// A small scene of the baked spectator: a listed instance and a 4 x 6 seat grid in front of
// the camera. `edit` is spliced into the JSON text (e.g. a different resolution).
std::string scene_json(const std::string& pack, const std::string& camera_extra = "",
                       const std::string& instance_clip = "idle") {
  return R"({
  "camera": {"position": [1.4, 2.2, 7], "target": [1.4, 1.2, -1], "resolution": [96, 64])" +
         camera_extra + R"(},
  "lod": {"budget": 20000},
  "character_types": [{"name": "spectator", "pack": ")" +
         pack + R"(", "texture_variants": {"head": 2, "upper_body": 3, "trousers": 2}}],
  "instances": [{"position": [0, 0, 2], "clip": ")" +
         instance_clip + R"("}],
  "generators": [{"kind": "seat_grid", "rows": 4, "columns": 6, "spacing": [0.55, 0.85],
                  "row_rise": 0.4, "clips": ["idle", "clap", "cheer"], "textures": "random",
                  "time_offset": [0, 2], "seed": 3}]
})";
}

class RenderCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    const test::BakedPacks& packs = test::BakedPacks::get();
    ASSERT_TRUE(packs.error().empty()) << packs.error();
    pack_ = packs.spectator();
    scene_ = (dir_.path() / "scene.json").string();
    test::write_text(scene_, scene_json(pack_));
  }
  std::string out(const std::string& name) const { return (dir_.path() / name).string(); }
  std::string write_scene(const std::string& name, const std::string& text) const {
    test::write_text(dir_.path() / name, text);
    return out(name);
  }

  // A bad-input case: exit code, one error line naming `fragment`, nothing written into the
  // output folder except the scene files.
  void expect_error(const std::vector<std::string>& args, int code, const std::string& fragment) {
    const size_t before = count_files();
    const test::CommandResult r = test::run_crowdbake(args);
    EXPECT_EQ(r.exit_code, code) << r.err;
    EXPECT_EQ(test::count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << "want '" << fragment << "' in " << r.err;
    EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << r.err;
    EXPECT_EQ(count_files(), before) << "something was written";
  }
  size_t count_files() const {
    size_t n = 0;
    for (auto it = fs::recursive_directory_iterator(dir_.path());
         it != fs::recursive_directory_iterator(); ++it)
      ++n;
    return n;
  }

  // Runs a render that needs a device; false (after GTEST_SKIP or a failure) when there is none.
  bool render(const std::vector<std::string>& args, test::CommandResult& r) {
    std::vector<std::string> all = {"render"};
    all.insert(all.end(), args.begin(), args.end());
    all.push_back("--validate");
    r = test::run_crowdbake(all);
    if (r.exit_code != 0 && r.err.find("no Vulkan device") != std::string::npos) {
      if (test::vulkan_required()) {
        ADD_FAILURE() << "no Vulkan device (CROWDBAKE_REQUIRE_VULKAN=1): " << r.err;
        return false;
      }
      [&] {
        GTEST_SKIP() << "no Vulkan device (lavapipe / mesa-vulkan-drivers missing?): " << r.err;
      }();
      return false;
    }
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.exit_code == 0;
  }

  test::TempDir dir_;
  std::string pack_, scene_;
};

TEST_F(RenderCommand, MissingSceneFile) {
  expect_error({"render", out("nope.json"), "-o", out("a.png")}, 1, "nope.json");
}

TEST_F(RenderCommand, SceneNamingAMissingPack) {
  const std::string scene = write_scene("missing_pack.json", scene_json(out("gone.crowdpack")));
  expect_error({"render", scene, "-o", out("a.png")}, 1, "gone.crowdpack");
  expect_error({"render", scene, "-o", out("a.png")}, 1, "character_types[0].pack");
}

TEST_F(RenderCommand, InstanceWithAClipThatDoesNotExist) {
  const std::string scene = write_scene("bad_clip.json", scene_json(pack_, "", "moonwalk"));
  expect_error({"render", scene, "-o", out("a.png")}, 1, "instances[0].clip");
  expect_error({"render", scene, "-o", out("a.png")}, 1, "moonwalk");
}

TEST_F(RenderCommand, BudgetZero) {
  expect_error({"render", scene_, "-o", out("a.png"), "--budget", "0"}, 2, "--budget");
  expect_error({"render", scene_, "-o", out("a.png"), "--budget", "-5"}, 2, "--budget");
  expect_error({"render", scene_, "-o", out("a.png"), "--geomorph", "1"}, 2, "--geomorph");
  expect_error({"render", scene_, "-o", out("a.png"), "--geomorph", "-0.1"}, 2, "--geomorph");
  const std::string scene = write_scene(
      "budget0.json",
      std::regex_replace(scene_json(pack_), std::regex("\"budget\": 20000"), "\"budget\": 0"));
  expect_error({"render", scene, "-o", out("a.png")}, 1, "lod.budget");
}

TEST_F(RenderCommand, ResolutionZeroOrHuge) {
  for (const char* bad : {"0x720", "1280x0", "100000x720", "1280x100000", "1280", "wide"})
    expect_error({"render", scene_, "-o", out("a.png"), "--resolution", bad}, 2, "--resolution");
  for (const char* res : {"[0, 720]", "[100000, 720]"}) {
    const std::string scene = write_scene(
        "res.json", std::regex_replace(scene_json(pack_), std::regex("\\[96, 64\\]"), res));
    expect_error({"render", scene, "-o", out("a.png")}, 1, "camera.resolution");
  }
}

TEST_F(RenderCommand, FramesAndFpsMustBePositive) {
  expect_error({"render", scene_, "-o", out("seq"), "--frames", "0"}, 2, "--frames");
  expect_error({"render", scene_, "-o", out("seq"), "--frames", "3", "--fps", "0"}, 2, "--fps");
  expect_error({"render", scene_, "-o", out("seq"), "--frames", "3", "--fps", "-30"}, 2, "--fps");
  expect_error({"render", scene_, "-o", out("a.png"), "--fps", "30"}, 2, "--fps");
  expect_error({"render", scene_, "-o", out("a.png"), "--time", "-1"}, 2, "--time");
  expect_error({"render", scene_, "-o", out("a.png"), "--lod", "medium"}, 2, "--lod");
}

TEST_F(RenderCommand, OutputProblems) {
  expect_error({"render", scene_, "-o", out("missing/a.png")}, 3, "does not exist");
  expect_error({"render", scene_, "-o", out("a.jpg")}, 2, ".png");
  expect_error({"render", scene_, "-o", out("seq.png"), "--frames", "2"}, 2, "folder");
  expect_error({"render", scene_, "-o", out("missing/seq"), "--frames", "2"}, 3, "does not exist");
  test::write_text(dir_.path() / "file", "x");
  expect_error({"render", scene_, "-o", out("file"), "--frames", "2"}, 3, "not a folder");
  fs::create_directory(dir_.path() / "d.png");
  expect_error({"render", scene_, "-o", out("d.png")}, 3, "is a folder");
  expect_error({"render", scene_, "-o", out("a.png"), "--contact-sheet", out("s.png")}, 2,
               "--contact-sheet");
  expect_error({"render", scene_, "-o", out("a.png"), "--stats", out("d.png")}, 3, "is a folder");
  expect_error({"render", scene_, "-o", out("a.png"), "--msaa", "3"}, 2, "--msaa");
  expect_error({"render", scene_, "-o", out("a.png"), "--stats", out("missing/s.json")}, 3,
               "does not exist");
}

TEST_F(RenderCommand, NoVulkanDriverSaysHowToInstallLavapipe) {
  const test::CommandResult r =
      test::run_crowdbake({"render", scene_, "-o", out("a.png")},
                          "VK_DRIVER_FILES=/nonexistent.json VK_ICD_FILENAMES=");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("mesa-vulkan-drivers"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("no Vulkan device"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out("a.png")));
}

TEST_F(RenderCommand, WritesOnePng) {
  test::CommandResult r;
  if (!render({scene_, "-o", out("a.png"), "--time", "0.5"}, r)) return;
  EXPECT_NE(r.out.find("wrote " + out("a.png")), std::string::npos) << r.out;
  const cli::RgbaImage image = cli::read_png(out("a.png"));
  EXPECT_EQ(image.width, 96u);
  EXPECT_EQ(image.height, 64u);
  // Some pixels differ from the top-left one (the background): the crowd is in the picture.
  size_t different = 0;
  for (size_t i = 0; i < image.rgba.size(); i += 4)
    different += std::memcmp(&image.rgba[i], &image.rgba[0], 3) != 0;
  EXPECT_GT(different, image.rgba.size() / 4 / 20) << "nearly uniform image";
  // --resolution overrides the scene's.
  if (!render({scene_, "-o", out("b.png"), "--resolution", "48x40", "--quiet"}, r)) return;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_EQ(cli::read_png(out("b.png")).width, 48u);
}

TEST_F(RenderCommand, ProfilePrintsPassesAndCounts) {
  test::CommandResult r;
  if (!render({scene_, "-o", out("a.png"), "--profile"}, r)) return;
  for (const char* word : {"pass", "cpu ms", "gpu ms", "total", "instances 25", "visible", "drawn",
                           "vertices", "triangles", "effects"})
    EXPECT_NE(r.out.find(word), std::string::npos) << word << " missing in\n" << r.out;
}

// Full resolution draws more triangles than a tight continuous budget; both render.
TEST_F(RenderCommand, LodModesChangeTrianglesDrawn) {
  auto triangles = [](const std::string& text) -> long long {
    std::smatch m;
    if (!std::regex_search(text, m, std::regex("triangles (\\d+)"))) return -1;
    return std::stoll(m[1]);
  };
  test::CommandResult full, lod, discrete;
  if (!render({scene_, "-o", out("full.png"), "--profile", "--lod", "full"}, full)) return;
  if (!render({scene_, "-o", out("lod.png"), "--profile", "--budget", "3000"}, lod)) return;
  if (!render({scene_, "-o", out("d.png"), "--profile", "--budget", "3000", "--lod", "discrete"},
              discrete))
    return;
  EXPECT_GT(triangles(full.out), triangles(lod.out)) << full.out << lod.out;
  EXPECT_GT(triangles(lod.out), 0) << lod.out;
  EXPECT_GT(triangles(discrete.out), 0) << discrete.out;
}

// --stats: the frame's numbers as JSON for build systems; every visible instance is drawn even
// at a budget far below the crowd's minimum (budget_exceeded says so).
TEST_F(RenderCommand, StatsWritesTheFramesNumbersAsJson) {
  test::CommandResult r;
  if (!render({scene_, "-o", out("seq"), "--stats", out("stats.json"), "--frames", "2", "--budget",
               "100", "--quiet"},
              r))
    return;
  EXPECT_TRUE(r.out.empty()) << r.out;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(out("stats.json")));
  EXPECT_FALSE(j["device"].get<std::string>().empty());
  ASSERT_EQ(j["frames"].size(), 2u);
  for (const nlohmann::json& f : j["frames"]) {
    EXPECT_EQ(f["instances"], 25);
    EXPECT_GT(f["visible"].get<int>(), 0);
    EXPECT_EQ(f["drawn"], f["visible"]);
    EXPECT_EQ(f["budget"], 100);
    EXPECT_EQ(f["budget_exceeded"], true);
    EXPECT_GT(f["vertices"].get<long long>(), 100);
    EXPECT_GT(f["triangles"].get<long long>(), 0);
    EXPECT_GE(f["level_cache"]["levels_drawn"].get<int>(), 1);
    EXPECT_GT(f["gpu_bytes"]["total"].get<long long>(),
              f["gpu_bytes"]["level_cache"].get<long long>());
    EXPECT_EQ(f["gpu_bytes"]["per_type"].size(), 1u);
    EXPECT_GT(f["passes"].size(), 8u);
    EXPECT_GT(f["gpu_ms"].get<double>(), 0.0);
  }
  EXPECT_EQ(j["frames"][1]["level_cache"]["levels_built"], 0) << "the second frame reuses";
}

// A pack without level errors (format 1.0 has none) renders in budget mode, with a note.
TEST_F(RenderCommand, PackWithoutLevelErrorsRendersByBudgetWithANote) {
  PackContents contents;
  {
    std::ifstream in(pack_, std::ios::binary);
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                     std::istreambuf_iterator<char>());
    ASSERT_TRUE(read_pack(bytes.data(), bytes.size(), contents).ok());
  }
  contents.level_errors = {};
  const std::vector<uint8_t> bytes = test::pack_bytes(contents, {});
  const std::string old_pack = out("old.crowdpack");
  std::ofstream(old_pack, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
  const std::string scene = write_scene("old.json", scene_json(old_pack));
  test::CommandResult r;
  if (!render({scene, "-o", out("old.png"), "--stats", out("old.json.stats")}, r)) return;
  EXPECT_NE(r.err.find("note: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("no level errors"), std::string::npos) << r.err;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(out("old.json.stats")));
  EXPECT_EQ(j["frames"][0]["lod_mode"], "budget");
  EXPECT_EQ(j["frames"][0]["drawn"], j["frames"][0]["visible"]);
  // The same scene with the original pack selects by error, quietly.
  if (!render({scene_, "-o", out("new.png"), "--stats", out("new.json.stats")}, r)) return;
  EXPECT_EQ(r.err.find("note: "), std::string::npos) << r.err;
  EXPECT_EQ(nlohmann::json::parse(std::ifstream(out("new.json.stats")))["frames"][0]["lod_mode"],
            "error");
}

TEST_F(RenderCommand, SequenceAndContactSheet) {
  test::CommandResult r;
  if (!render({scene_, "-o", out("seq"), "--frames", "3", "--fps", "10", "--no-shadows",
               "--contact-sheet", out("sheet.png")},
              r))
    return;
  for (const char* f : {"frame_0000.png", "frame_0001.png", "frame_0002.png"})
    EXPECT_TRUE(fs::exists(dir_.path() / "seq" / f)) << f;
  EXPECT_FALSE(fs::exists(dir_.path() / "seq" / "frame_0003.png"));
  const cli::RgbaImage sheet = cli::read_png(out("sheet.png"));
  EXPECT_EQ(sheet.width, 2u * 96 + 3 * 4);  // 2 columns, 2 rows, 4-pixel gutters
  EXPECT_EQ(sheet.height, 2u * 64 + 3 * 4);
  // The clips move: consecutive frames differ.
  EXPECT_NE(cli::read_png(out("seq/frame_0000.png")).rgba,
            cli::read_png(out("seq/frame_0002.png")).rgba);
}

// Issue 6: --profile shows which effects a scene built. The stadium sample declares the
// behaviour FSM and animation sharing; the small scene declares none and builds nothing.
TEST_F(RenderCommand, ProfileShowsOnlyTheDeclaredEffects) {
  std::string stadium = test::slurp(fs::path(CROWDBAKE_SOURCE_DIR) / "samples/stadium/scene.json");
  stadium =
      std::regex_replace(stadium, std::regex("\\.\\./\\.\\./out/spectator\\.crowdpack"), pack_);
  stadium = std::regex_replace(stadium, std::regex("\"resolution\": \\[\\d+, \\d+\\]"),
                               "\"resolution\": [96, 54]");
  const std::string scene = write_scene("stadium.json", stadium);
  test::CommandResult fx, plain;
  if (!render({scene, "-o", out("stadium.png"), "--profile", "--time", "4"}, fx)) return;
  EXPECT_NE(fx.out.find("behaviour FSM yes"), std::string::npos) << fx.out;
  EXPECT_NE(fx.out.find("animation sharing yes"), std::string::npos) << fx.out;
  EXPECT_EQ(fx.out.find("0 systems constructed"), std::string::npos) << fx.out;
  if (!render({scene_, "-o", out("plain.png"), "--profile"}, plain)) return;
  EXPECT_NE(plain.out.find("0 systems constructed"), std::string::npos) << plain.out;
  EXPECT_NE(plain.out.find("0 poses evaluated"), std::string::npos) << plain.out;
}

}  // namespace
}  // namespace crowdbake
