// libdraco.so (loaded through Assimp) exports an embedded copy of tinygltf under the
// same mangled names as libtinygltf.so (docs/toolchain.md §3). crowdbake compiles its own
// tinygltf under a private namespace (pipeline/import/tinygltf.h), so none of its calls
// may ever bind to libdraco's copy. This test runs the real executable with every
// symbol bound at start-up and reads the dynamic loader's binding log.
#include <gtest/gtest.h>

#include <sstream>

#include "cli/cli_runner.h"
#include "gltf_test_builder.h"

namespace crowdbake {
namespace {

TEST(SymbolBinding, NoTinygltfSymbolOfCrowdbakeBindsToAnotherLibrary) {
  test::TempDir dir;
  test::GltfBuilder b = test::two_bone_character();
  const auto file = b.write(dir / "two_bone.gltf");
  const auto log = dir / "bindings";
  const test::CommandResult r =
      test::run_crowdbake({"inspect", file.string(), "--json"},
                          "LD_BIND_NOW=1 LD_DEBUG=bindings LD_DEBUG_OUTPUT=" + log.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;

  std::string text;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
    if (entry.path().filename().string().rfind("bindings", 0) == 0)
      text += test::slurp(entry.path());
  ASSERT_FALSE(text.empty()) << "the dynamic loader wrote no binding log";

  // Without libdraco in the process the check would prove nothing.
  ASSERT_NE(text.find("libdraco"), std::string::npos)
      << "libdraco is not loaded by crowdbake any more; this test no longer guards anything";

  std::istringstream lines(text);
  std::string line;
  int checked = 0;
  while (std::getline(lines, line)) {
    const size_t from = line.find("binding file ");
    const size_t to = line.find(" to ");
    if (from == std::string::npos || to == std::string::npos) continue;
    const std::string binder = line.substr(from + 13, to - from - 13);
    if (binder.find("libdraco") != std::string::npos) continue;  // libdraco's own internal calls
    ++checked;
    EXPECT_EQ(line.find("tinygltf"), std::string::npos)
        << "crowdbake binds a tinygltf symbol dynamically:\n"
        << line;
  }
  EXPECT_GT(checked, 100) << "too few bindings logged to trust the check";
}

}  // namespace
}  // namespace crowdbake
