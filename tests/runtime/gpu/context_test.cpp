// VulkanContext, buffers, kernels and the embedded shaders on the real driver (lavapipe here).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "crowdbake/runtime/gpu/gpu_buffer.h"
#include "crowdbake/runtime/gpu/shader_library.h"
#include "crowdbake/runtime/gpu/vulkan_context.h"
#include "runtime/gpu/gpu_test_support.h"

namespace crowdbake::runtime::gpu {
namespace {

using ContextTest = test::GpuTest;

TEST(ShaderLibraryTest, FindsEmbeddedShadersByFileName) {
  const Span<const uint32_t> words = find_spirv("test_fill.comp");
  ASSERT_GT(words.size(), 5u);
  EXPECT_EQ(words[0], 0x07230203u);  // SPIR-V magic number
  EXPECT_TRUE(find_spirv("no_such_shader.comp").empty());
  EXPECT_TRUE(find_spirv(nullptr).empty());
}

TEST_F(ContextTest, RunsAComputeShaderWithoutValidationErrors) {
  EXPECT_TRUE(context().validation_enabled());
  EXPECT_FALSE(context().device_name().empty());
  constexpr uint32_t kCount = 1000;
  GpuBuffer data;
  ASSERT_TRUE(GpuBuffer::create(context(), kCount * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                MemoryKind::kDeviceLocal, data)
                  .ok());
  ComputeKernel kernel;
  const Status k = ComputeKernel::create(context(), "test_fill.comp", 1, 12, kernel);
  ASSERT_TRUE(k.ok()) << k.message();
  kernel.bind_buffers(0, {&data});
  const uint32_t push[3] = {kCount, 3, 7};
  TimestampQueries queries;
  ASSERT_TRUE(TimestampQueries::create(context(), 2, queries).ok());
  const Status s = context().submit_and_wait([&](VkCommandBuffer cmd) {
    queries.reset(cmd);
    vkCmdFillBuffer(cmd, data.buffer(), 0, VK_WHOLE_SIZE, 0xFFFFFFFFu);
    full_barrier(cmd);
    queries.write(cmd, 0, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT);
    kernel.bind(cmd, 0, push);
    kernel.dispatch(cmd, (kCount + 63) / 64);
    queries.write(cmd, 1);
  });
  ASSERT_TRUE(s.ok()) << s.message();
  std::vector<uint32_t> out;
  ASSERT_TRUE(download_all(data, out).ok());
  ASSERT_EQ(out.size(), kCount);
  for (uint32_t i = 0; i < kCount; ++i) ASSERT_EQ(out[i], i * 3 + 7) << i;
  double ms = -1.0;
  ASSERT_TRUE(queries.elapsed_ms(0, 1, ms).ok());
  EXPECT_GE(ms, 0.0);
  EXPECT_EQ(context().validation_errors(), 0u) << context().validation_report();
}

TEST_F(ContextTest, UploadAndDownloadRoundTrip) {
  GpuBuffer host, device;
  ASSERT_TRUE(GpuBuffer::create(context(), 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                MemoryKind::kHostVisible, host)
                  .ok());
  ASSERT_TRUE(GpuBuffer::create(context(), 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                MemoryKind::kDeviceLocal, device)
                  .ok());
  ASSERT_NE(host.mapped(), nullptr);
  std::vector<uint32_t> in(16);
  for (uint32_t i = 0; i < 16; ++i) in[i] = i * i + 1;
  ASSERT_TRUE(host.upload(in.data(), 64).ok());
  ASSERT_TRUE(context()
                  .submit_and_wait([&](VkCommandBuffer cmd) {
                    const VkBufferCopy copy{0, 0, 64};
                    vkCmdCopyBuffer(cmd, host.buffer(), device.buffer(), 1, &copy);
                  })
                  .ok());
  std::vector<uint32_t> out;
  ASSERT_TRUE(download_all(device, out).ok());
  EXPECT_EQ(out, in);
  EXPECT_FALSE(host.upload(in.data(), 64, 4).ok());  // past the end
}

// The counter must be able to fail: a buffer of size 0 breaks VUID-VkBufferCreateInfo-size-00912.
TEST_F(ContextTest, ValidationCountsADeliberateError) {
  VkBufferCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  info.size = 0;
  info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  VkBuffer buffer = VK_NULL_HANDLE;
  const VkResult r = vkCreateBuffer(context().device(), &info, nullptr, &buffer);
  if (r == VK_SUCCESS && buffer != VK_NULL_HANDLE)
    vkDestroyBuffer(context().device(), buffer, nullptr);
  EXPECT_GE(context().validation_errors(), 1u);
  EXPECT_NE(context().validation_report().find("VUID-VkBufferCreateInfo-size"), std::string::npos)
      << context().validation_report();
  context().clear_validation_messages();  // note: expected; TearDown checks for others
}

TEST(VulkanContextTest, WrapRejectsNullHandles) {
  std::unique_ptr<VulkanContext> context;
  const Status s = VulkanContext::wrap(HostDevice{}, context);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(context, nullptr);
}

TEST_F(ContextTest, WrapAdoptsAHostDeviceWithoutOwningIt) {
  HostDevice host;
  host.instance = context().instance();
  host.physical_device = context().physical_device();
  host.device = context().device();
  host.queue = context().queue();
  host.queue_family = context().queue_family();
  host.enabled_features.shaderFloat64 = context().features().float64 ? VK_TRUE : VK_FALSE;
  {
    std::unique_ptr<VulkanContext> wrapped;
    const Status s = VulkanContext::wrap(host, wrapped);
    ASSERT_TRUE(s.ok()) << s.message();
    EXPECT_FALSE(wrapped->owns_device());
    EXPECT_EQ(wrapped->features().float64, context().features().float64);
    GpuBuffer data;
    ASSERT_TRUE(GpuBuffer::create(*wrapped, 256, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                  MemoryKind::kDeviceLocal, data)
                    .ok());
    ASSERT_TRUE(wrapped
                    ->submit_and_wait([&](VkCommandBuffer cmd) {
                      vkCmdFillBuffer(cmd, data.buffer(), 0, VK_WHOLE_SIZE, 5u);
                    })
                    .ok());
    std::vector<uint32_t> out;
    ASSERT_TRUE(download_all(data, out).ok());
    EXPECT_EQ(out[63], 5u);
  }
  // The device still works after the wrapper is gone (it was not destroyed).
  EXPECT_TRUE(context().submit_and_wait([](VkCommandBuffer) {}).ok());
}

// Without a driver, creation fails with the message telling how to install lavapipe. The
// loader reads VK_DRIVER_FILES at vkCreateInstance, so the test re-runs this binary with it
// pointing at a missing file (a fresh process: no loader or driver state, no threads forked).
TEST(VulkanContextTest, NoDriverNamesMesaVulkanDrivers) {
  const std::string command =
      "CROWDBAKE_NO_DRIVER_CHILD=1 VK_DRIVER_FILES=/nonexistent/crowdbake_no_driver.json "
      "VK_ICD_FILENAMES=/nonexistent/crowdbake_no_driver.json /proc/" +
      std::to_string(::getpid()) + "/exe 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string text;
  char buffer[512];
  for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) text.append(buffer, n);
  const int status = ::pclose(pipe);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << text;
  EXPECT_NE(text.find("code " + std::to_string(static_cast<int>(StatusCode::kNotLoaded)) + "|"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("no Vulkan device found"), std::string::npos) << text;
  EXPECT_NE(text.find("mesa-vulkan-drivers"), std::string::npos) << text;
  EXPECT_NE(text.find("lavapipe"), std::string::npos) << text;
}

// The child side of NoDriverNamesMesaVulkanDrivers: runs before main, prints the status of a
// context creation and exits without running any test.
const bool kNoDriverChild = [] {
  if (std::getenv("CROWDBAKE_NO_DRIVER_CHILD") == nullptr) return false;
  std::unique_ptr<VulkanContext> context;
  const Status s = VulkanContext::create(ContextOptions{}, context);
  std::printf("code %d|%s\n", static_cast<int>(s.code()), s.message().c_str());
  std::fflush(stdout);
  std::_Exit(0);
}();

}  // namespace
}  // namespace crowdbake::runtime::gpu
