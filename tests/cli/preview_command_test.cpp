// `crowdbake preview` and `bake --preview`: the contact sheet's layout (levels × frames of the
// chosen clips), deterministic bytes, levels that look different, and bad input refused with
// one error line and nothing written. GPU cases SKIP without a Vulkan device unless
// CROWDBAKE_REQUIRE_VULKAN=1.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "cli/cli_runner.h"
#include "cli/image_png.h"
#include "runtime/runtime_test_support.h"

namespace crowdbake {
namespace {

namespace fs = std::filesystem;

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

class PreviewCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    const test::BakedPacks& packs = test::BakedPacks::get();
    ASSERT_TRUE(packs.error().empty()) << packs.error();
    pack_ = packs.spectator();
  }
  std::string out(const std::string& name) const { return (dir_.path() / name).string(); }
  // Runs a command that needs a device; false (after GTEST_SKIP or a failure) when there is none.
  bool run(const std::vector<std::string>& args, test::CommandResult& r) {
    r = test::run_crowdbake(args);
    if (r.exit_code != 0 && r.err.find("no Vulkan device") != std::string::npos) {
      if (test::vulkan_required()) {
        ADD_FAILURE() << "no Vulkan device (CROWDBAKE_REQUIRE_VULKAN=1): " << r.err;
        return false;
      }
      [&] { GTEST_SKIP() << "no Vulkan device: " << r.err; }();
      return false;
    }
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.exit_code == 0;
  }
  void expect_error(const std::vector<std::string>& args, int code, const std::string& fragment) {
    const test::CommandResult r = test::run_crowdbake(args);
    EXPECT_EQ(r.exit_code, code) << r.err;
    EXPECT_EQ(test::count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << "want '" << fragment << "' in " << r.err;
    EXPECT_TRUE(fs::is_empty(dir_.path())) << "something was written";
  }
  test::TempDir dir_;
  std::string pack_;
};

TEST_F(PreviewCommand, OneRowPerLevelOneColumnPerFrame) {
  test::CommandResult r;
  const std::string sheet = out("sheet.png");
  if (!run({"preview", pack_, "-o", sheet, "--clip", "idle", "--clip", "cheer", "--frames", "2",
            "--levels", "1", "0.25", "min", "--cell", "64x96", "--quiet"},
           r))
    return;
  EXPECT_TRUE(r.out.empty()) << r.out;
  const cli::RgbaImage image = cli::read_png(sheet);
  // 4 columns (2 clips × 2 frames) and 3 rows of 64 × 96 cells, 4-pixel gutters.
  EXPECT_EQ(image.width, 4u * 64 + 5 * 4);
  EXPECT_EQ(image.height, 3u * 96 + 4 * 4);
  // The finest and the coarsest level of the same frame are different pictures.
  auto cell = [&](uint32_t row, uint32_t column) {
    std::string bytes;
    for (uint32_t y = 4 + row * 100; y < 4 + row * 100 + 96; ++y) {
      const size_t first = (size_t{y} * image.width + 4 + column * 68) * 4;
      bytes.append(reinterpret_cast<const char*>(&image.rgba[first]), 64 * 4);
    }
    return bytes;
  };
  EXPECT_NE(cell(0, 0), cell(2, 0));
  EXPECT_NE(cell(0, 0), cell(0, 2)) << "idle and cheer";
  // Deterministic: the same command gives the same bytes.
  const std::string again = out("again.png");
  if (!run({"preview", pack_, "-o", again, "--clip", "idle", "--clip", "cheer", "--frames", "2",
            "--levels", "1", "0.25", "min", "--cell", "64x96", "--quiet"},
           r))
    return;
  EXPECT_EQ(file_bytes(sheet), file_bytes(again));
}

TEST_F(PreviewCommand, BakeWritesTheSheetToo) {
  const std::string glb = out("spectator.glb");
  std::string log;
  ASSERT_EQ(test::run_command(std::string(MAKE_SPECTATOR_EXE) + " -o " + test::quote(glb), &log), 0)
      << log;
  test::CommandResult r;
  if (!run({"bake", glb, "-o", out("s.crowdpack"), "--preview", out("s.png"), "--quiet"}, r))
    return;
  EXPECT_TRUE(fs::exists(out("s.crowdpack")));
  const cli::RgbaImage image = cli::read_png(out("s.png"));
  EXPECT_EQ(image.height, 5u * 240 + 6 * 4) << "five default levels";
}

TEST_F(PreviewCommand, BadInputIsRefused) {
  expect_error({"preview", pack_, "-o", out("a.jpg")}, 2, "-o");
  expect_error({"preview", pack_, "-o", out("a.png"), "--clip", "moonwalk"}, 2, "moonwalk");
  expect_error({"preview", pack_, "-o", out("a.png"), "--levels", "0"}, 2, "--levels");
  expect_error({"preview", pack_, "-o", out("a.png"), "--levels", "1.5"}, 2, "--levels");
  expect_error({"preview", pack_, "-o", out("a.png"), "--frames", "0"}, 2, "--frames");
  expect_error({"preview", pack_, "-o", out("a.png"), "--cell", "8x8"}, 2, "--cell");
  expect_error({"preview", out("missing.crowdpack"), "-o", out("a.png")}, 1, "missing.crowdpack");
  expect_error({"bake", pack_, "-o", out("b.crowdpack"), "--preview", out("b.jpg")}, 2,
               "--preview");
}

}  // namespace
}  // namespace crowdbake
