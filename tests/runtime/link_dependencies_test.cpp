// The runtime links no importer and nothing from the pipeline (docs/design.md §2):
//   1. CMake's view: every target crowdbake_runtime reaches through its link libraries
//      (written at configure time by tests/runtime/CMakeLists.txt);
//   2. the linker's view: this test binary links crowdbake_runtime (and formats, GTest), so
//      its ELF dynamic section must not need libassimp, libOpenMesh or libtinygltf, and its
//      symbol table must hold no Assimp, OpenMesh, tinygltf or pipeline code.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <string>
#include <vector>

#include "runtime/runtime_test_support.h"

namespace crowdbake::test {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

const char* const kForbiddenLibraries[] = {"assimp", "openmesh", "tinygltf", "crowdbake_pipeline",
                                           "crowdbake_spectator"};

TEST(LinkDependencies, CMakeLinkClosureOfTheRuntime) {
  std::ifstream in(RUNTIME_LINK_CLOSURE);
  ASSERT_TRUE(in) << "missing " << RUNTIME_LINK_CLOSURE << " (written when CMake configures)";
  std::vector<std::string> targets;
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) targets.push_back(line);
  ASSERT_FALSE(targets.empty());
  EXPECT_EQ(targets.front(), "crowdbake_runtime");
  EXPECT_NE(std::find(targets.begin(), targets.end(), "crowdbake_formats"), targets.end());
  for (const std::string& t : targets)
    for (const char* bad : kForbiddenLibraries)
      EXPECT_EQ(lower(t).find(bad), std::string::npos) << "crowdbake_runtime links " << t;
}

TEST(LinkDependencies, DynamicSectionOfARuntimeBinary) {
  std::string out;
  ASSERT_EQ(run_command("readelf -d /proc/" + std::to_string(::getpid()) + "/exe", &out), 0) << out;
  ASSERT_NE(out.find("(NEEDED)"), std::string::npos) << out;
  for (const char* bad : {"assimp", "openmesh", "tinygltf"})
    EXPECT_EQ(lower(out).find(bad), std::string::npos)
        << "the runtime test binary needs " << bad << ":\n"
        << out;
}

TEST(LinkDependencies, NoImporterOrPipelineSymbols) {
  std::string out;
  ASSERT_EQ(run_command("nm -C /proc/" + std::to_string(::getpid()) + "/exe", &out), 0)
      << out.substr(0, 2000);
  // The binary does hold the runtime (so the check looks at the right thing).
  ASSERT_NE(out.find("crowdbake::runtime::Pack::open"), std::string::npos);
  for (const char* bad :
       {"Assimp::", "aiScene", "OpenMesh::", "tinygltf::", "crowdbake_tinygltf",
        "crowdbake::ProgressiveMesh", "crowdbake::build_progressive_mesh", "crowdbake::build_pack",
        "crowdbake::bake_animation", "crowdbake::ai::"}) {
    const size_t at = out.find(bad);
    EXPECT_EQ(at, std::string::npos)
        << "found " << bad
        << " in: " << (at == std::string::npos ? "" : out.substr(out.rfind('\n', at) + 1, 200));
  }
}

}  // namespace
}  // namespace crowdbake::test
