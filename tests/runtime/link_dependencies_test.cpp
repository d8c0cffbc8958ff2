// The runtime links no importer and nothing from the pipeline (docs/design.md §2):
//   1. CMake's view: every target each runtime library reaches through its link libraries
//      (written at configure time by tests/runtime/CMakeLists.txt), which also keeps the
//      layers apart (core, crowd, effects, scene effects, GPU);
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

// Every target `library` reaches through its link libraries (written when CMake configures);
// empty when the library is not part of this build (e.g. no GPU library without Vulkan).
std::vector<std::string> link_closure(const std::string& library) {
  std::ifstream in(std::string(LINK_CLOSURE_DIR) + "/link_closure_" + library + ".txt");
  std::vector<std::string> targets;
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) targets.push_back(line);
  return targets;
}

bool reaches(const std::vector<std::string>& closure, const std::string& target) {
  return std::find(closure.begin(), closure.end(), target) != closure.end();
}

TEST(LinkDependencies, CMakeLinkClosureOfTheRuntime) {
  const std::vector<std::string> targets = link_closure("crowdbake_runtime");
  ASSERT_FALSE(targets.empty()) << "missing " << LINK_CLOSURE_DIR
                                << "/link_closure_crowdbake_runtime.txt (written by CMake)";
  EXPECT_EQ(targets.front(), "crowdbake_runtime");
  EXPECT_TRUE(reaches(targets, "crowdbake_formats"));
}

// Each runtime library reaches no importer and nothing of the pipeline, and only the layers
// below it: the core knows no crowd, effect or GPU code; crowd and effects are independent of
// the core and of each other; the GPU library builds on the core only; scene effects tie the
// core, crowd and effects together.
TEST(LinkDependencies, EveryRuntimeLibraryKeepsToItsLayer) {
  struct Rule {
    const char* library;
    std::vector<const char*> must_not_reach;
  };
  const Rule rules[] = {
      {"crowdbake_runtime",
       {"crowdbake_crowd", "crowdbake_effects", "crowdbake_scene_effects", "crowdbake_gpu",
        "Vulkan::Vulkan"}},
      {"crowdbake_crowd",
       {"crowdbake_runtime", "crowdbake_effects", "crowdbake_scene_effects", "crowdbake_gpu",
        "Vulkan::Vulkan"}},
      {"crowdbake_effects",
       {"crowdbake_runtime", "crowdbake_crowd", "crowdbake_scene_effects", "crowdbake_gpu",
        "Vulkan::Vulkan"}},
      {"crowdbake_scene_effects", {"crowdbake_gpu", "Vulkan::Vulkan"}},
      {"crowdbake_gpu", {"crowdbake_crowd", "crowdbake_effects", "crowdbake_scene_effects"}},
  };
  int checked = 0;
  for (const Rule& rule : rules) {
    const std::vector<std::string> targets = link_closure(rule.library);
    if (targets.empty()) continue;  // note: not in this build
    ++checked;
    EXPECT_EQ(targets.front(), rule.library);
    for (const std::string& t : targets)
      for (const char* bad : kForbiddenLibraries)
        EXPECT_EQ(lower(t).find(bad), std::string::npos) << rule.library << " links " << t;
    for (const char* below : rule.must_not_reach)
      EXPECT_FALSE(reaches(targets, below)) << rule.library << " reaches " << below;
  }
  EXPECT_GE(checked, 4) << "the core, crowd, effects and scene effects are always built";
  EXPECT_TRUE(reaches(link_closure("crowdbake_scene_effects"), "crowdbake_crowd"));
}

// The include folders a library's users get (its own and those of what it links).
std::vector<std::string> include_roots(const std::string& library) {
  std::ifstream in(std::string(LINK_CLOSURE_DIR) + "/include_roots_" + library + ".txt");
  std::vector<std::string> roots;
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) roots.push_back(line);
  return roots;
}

// Each runtime library has its own include root, and sees only the roots of what it links: the
// crowd and effects libraries cannot include the core's pack.h, nor the core an effect.
TEST(LinkDependencies, EachRuntimeLibraryHasItsOwnIncludeRoot) {
  const std::string runtime = RUNTIME_SOURCE_DIR;
  const std::string core = runtime + "/include", crowd = runtime + "/crowd/include",
                    effects = runtime + "/effects/include",
                    scene = runtime + "/scene_effects/include", gpu = runtime + "/gpu/include";
  struct Rule {
    const char* library;
    std::string own;
    std::vector<std::string> must_not_see;
  };
  const Rule rules[] = {
      {"crowdbake_runtime", core, {crowd, effects, scene, gpu}},
      {"crowdbake_crowd", crowd, {core, effects, scene, gpu}},
      {"crowdbake_effects", effects, {core, crowd, scene, gpu}},
      {"crowdbake_scene_effects", scene, {gpu}},
      {"crowdbake_gpu", gpu, {crowd, effects, scene}},
  };
  int checked = 0;
  for (const Rule& rule : rules) {
    const std::vector<std::string> roots = include_roots(rule.library);
    if (roots.empty()) continue;  // note: not in this build
    ++checked;
    EXPECT_TRUE(reaches(roots, rule.own)) << rule.library << " lacks its root " << rule.own;
    for (const std::string& other : rule.must_not_see)
      EXPECT_FALSE(reaches(roots, other)) << rule.library << " sees " << other;
  }
  EXPECT_GE(checked, 4);
  EXPECT_TRUE(reaches(include_roots("crowdbake_scene_effects"), core));
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
