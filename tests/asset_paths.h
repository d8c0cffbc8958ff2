// Where tests find their inputs. Shared third-party characters live outside the repo
// (../shared/assets); tests that need them call CROWDBAKE_REQUIRE_SHARED_ASSETS() and
// skip, saying why, where the folder is absent.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace crowdbake::test {

inline std::filesystem::path shared_assets() { return CROWDBAKE_SHARED_ASSETS; }
inline std::filesystem::path binary_dir() { return CROWDBAKE_BINARY_DIR; }
inline std::filesystem::path source_dir() { return CROWDBAKE_SOURCE_DIR; }
inline bool have_shared_assets() {
  return std::filesystem::exists(shared_assets() / "MANIFEST.json");
}

}  // namespace crowdbake::test

#define CROWDBAKE_REQUIRE_SHARED_ASSETS()                                                          \
  do {                                                                                             \
    if (!::crowdbake::test::have_shared_assets())                                                  \
      GTEST_SKIP() << "shared test characters not found at " << ::crowdbake::test::shared_assets() \
                   << " (they ship beside the repository in CI; set "                              \
                      "-DCROWDBAKE_SHARED_ASSETS=<dir> to point at a copy)";                       \
  } while (0)
