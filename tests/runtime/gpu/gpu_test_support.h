// The rule every GPU test follows (docs: /work/gpu-brief.md, tests section):
//   - no Vulkan device → the test SKIPS, saying lavapipe / mesa-vulkan-drivers is missing;
//   - with CROWDBAKE_REQUIRE_VULKAN=1 in the environment (CI) it FAILS instead;
//   - the context runs with VK_LAYER_KHRONOS_validation, and any validation error fails the
//     test (checked in TearDown, messages printed).
// Use the fixture (class FooTest : public crowdbake::test::GpuTest) and context() in tests.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>

#include "crowdbake/runtime/gpu/vulkan_context.h"

namespace crowdbake::test {

inline bool vulkan_required() {
  const char* v = std::getenv("CROWDBAKE_REQUIRE_VULKAN");
  return v != nullptr && std::strcmp(v, "1") == 0;
}

// Creates a validating context into `out`, or leaves it null after GTEST_SKIP (no device, not
// required) or a fatal failure (required, or any other error). In SetUp either one stops the
// test before its body; elsewhere the caller returns when `out` is null.
inline void make_test_context(std::unique_ptr<runtime::gpu::VulkanContext>& out) {
  out.reset();
  runtime::gpu::ContextOptions options;
  options.validation = true;
  options.application_name = "crowdbake-gpu-tests";
  const runtime::Status s = runtime::gpu::VulkanContext::create(options, out);
  if (s.ok()) return;
  out.reset();
  if (s.code() == runtime::StatusCode::kNotLoaded && !vulkan_required())
    GTEST_SKIP() << "Vulkan unavailable (set CROWDBAKE_REQUIRE_VULKAN=1 to fail instead): "
                 << s.message();
  FAIL() << "Vulkan context creation failed"
         << (vulkan_required() ? " (CROWDBAKE_REQUIRE_VULKAN=1)" : "") << ": " << s.message();
}

class GpuTest : public ::testing::Test {
 protected:
  void SetUp() override { make_test_context(context_); }
  void TearDown() override {
    if (context_) {
      EXPECT_EQ(context_->validation_errors(), 0u) << "validation layer reported errors:\n"
                                                   << context_->validation_report();
    }
  }
  runtime::gpu::VulkanContext& context() { return *context_; }

  std::unique_ptr<runtime::gpu::VulkanContext> context_;
};

}  // namespace crowdbake::test
