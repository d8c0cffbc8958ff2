// VulkanContext: the Vulkan instance, device and queue the GPU path runs on — either created
// here (headless: no window system, no surface) or adopted from a host application that owns
// them (wrap). Every GPU object of crowdbake_gpu is made through one.
//
// Device choice: a discrete GPU, then an integrated one, then anything else with a queue that
// does graphics and compute — so Mesa's lavapipe (llvmpipe, a CPU device) is accepted when it
// is the only device. The optional features the passes use (shaderFloat64 for the LoD weights,
// shaderInt64, multiDrawIndirect, ...) are enabled when the device has them; features() says
// which.
//
// Validation: with ContextOptions::validation (or CROWDBAKE_VULKAN_VALIDATION=1 in the
// environment) the instance enables VK_LAYER_KHRONOS_validation and a debug messenger that
// counts error messages and keeps their text; tests treat any count above 0 as a failure.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "crowdbake/runtime/span.h"
#include "crowdbake/runtime/status.h"

namespace crowdbake::runtime::gpu {

struct ContextOptions {
  bool validation = false;  // also on when CROWDBAKE_VULKAN_VALIDATION=1
  std::string application_name = "crowdbake";
};

// A device owned by the host application (the embedding case). The context uses these
// handles and never destroys them; the host keeps them alive longer than the context.
struct HostDevice {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;  // must support graphics and compute
  uint32_t queue_family = 0;
  // The features the host enabled at vkCreateDevice (CrowdCompute needs shaderFloat64).
  VkPhysicalDeviceFeatures enabled_features{};
};

// Features of the device that crowdbake_gpu enabled (or, wrapped, that the host enabled).
struct DeviceFeatures {
  bool float64 = false;              // shaderFloat64
  bool int64 = false;                // shaderInt64
  bool multi_draw_indirect = false;  // multiDrawIndirect
  bool fill_mode_non_solid = false;  // fillModeNonSolid
};

class VulkanContext {
 public:
  // Creates a headless instance and device.
  // Returns kNotLoaded when there is no Vulkan driver or no usable device (the message says
  // to install mesa-vulkan-drivers for lavapipe), kNotLoaded too when validation is asked for
  // and VK_LAYER_KHRONOS_validation is missing, kInvalidArgument for other Vulkan failures.
  static Status create(const ContextOptions& options, std::unique_ptr<VulkanContext>& out);
  // Adopts a host-owned device (not owned: never destroyed here). The host's instance decides
  // about validation; validation_errors() stays 0 for a wrapped device.
  // Returns kInvalidArgument for null handles.
  static Status wrap(const HostDevice& host, std::unique_ptr<VulkanContext>& out);

  ~VulkanContext();
  VulkanContext(const VulkanContext&) = delete;
  VulkanContext& operator=(const VulkanContext&) = delete;

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physical_device() const { return physical_device_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  uint32_t queue_family() const { return queue_family_; }
  bool owns_device() const { return owns_; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  const VkPhysicalDeviceLimits& limits() const { return properties_.limits; }
  const DeviceFeatures& features() const { return features_; }
  std::string device_name() const { return properties_.deviceName; }

  // Validation messages of severity ERROR since creation (or the last clear).
  bool validation_enabled() const { return messenger_ != VK_NULL_HANDLE; }
  uint32_t validation_errors() const;
  std::vector<std::string> validation_messages() const;
  // All messages joined with newlines (for test failure output).
  std::string validation_report() const;
  void clear_validation_messages();

  // A memory type index with all of `required` among `type_bits`; UINT32_MAX when none.
  uint32_t find_memory_type(uint32_t type_bits, VkMemoryPropertyFlags required) const;

  // Records `record` into a fresh primary command buffer, submits it to the queue and waits
  // on a fence. For uploads, readbacks and the standalone paths; not for per-frame host work.
  // Returns kInvalidArgument when a Vulkan call fails (the message names it).
  Status submit_and_wait(const std::function<void(VkCommandBuffer)>& record);

  // A shader module of an embedded shader (shader_library.h); the caller destroys it.
  // Returns kInvalidArgument when no shader has that name or creation fails.
  Status create_shader_module(const char* name, VkShaderModule& out) const;

  // Called by the debug messenger.
  void report_validation(VkDebugUtilsMessageSeverityFlagBitsEXT severity, const char* message);

 private:
  VulkanContext() = default;
  Status init_headless(const ContextOptions& options);
  // init_headless' steps: the instance (with the validation messenger when asked), the
  // physical device (the best-ranked with Vulkan 1.2 and a graphics+compute queue), the
  // logical device with the features crowdbake uses where supported.
  Status create_instance(const ContextOptions& options, bool validation);
  Status pick_physical_device();
  Status create_device();
  Status init_device();

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t queue_family_ = 0;
  bool owns_ = false;
  VkPhysicalDeviceProperties properties_{};
  VkPhysicalDeviceMemoryProperties memory_{};
  DeviceFeatures features_;
  VkCommandPool pool_ = VK_NULL_HANDLE;  // for submit_and_wait
  VkFence fence_ = VK_NULL_HANDLE;

  mutable std::mutex messages_mutex_;  // the messenger may be called from driver threads
  uint32_t errors_ = 0;
  std::vector<std::string> messages_;
};

// Status for a failed Vulkan call: "<what>: <VkResult name>".
Status vulkan_error(const char* what, VkResult result);
const char* vk_result_name(VkResult result);

// The message every "no Vulkan" failure carries (names mesa-vulkan-drivers).
extern const char* const kNoVulkanDeviceMessage;

}  // namespace crowdbake::runtime::gpu
