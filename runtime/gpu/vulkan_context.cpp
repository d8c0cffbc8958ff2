#include "crowdbake/runtime/gpu/vulkan_context.h"

#include <cstdlib>
#include <cstring>

#include "crowdbake/runtime/gpu/shader_library.h"

namespace crowdbake::runtime::gpu {

const char* const kNoVulkanDeviceMessage =
    "no Vulkan device found: install a Vulkan driver; on Debian/Ubuntu the CPU driver "
    "lavapipe is in the package mesa-vulkan-drivers (apt-get install mesa-vulkan-drivers)";

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

VKAPI_ATTR VkBool32 VKAPI_CALL debug_callback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data,
                                              void* user) {
  static_cast<VulkanContext*>(user)->report_validation(
      severity, data && data->pMessage ? data->pMessage : "(no message)");
  return VK_FALSE;  // note: the spec requires applications to return false
}

bool env_flag(const char* name) {
  const char* v = std::getenv(name);
  return v != nullptr && std::strcmp(v, "1") == 0;
}

bool has_layer(const char* name) {
  uint32_t count = 0;
  if (vkEnumerateInstanceLayerProperties(&count, nullptr) != VK_SUCCESS) return false;
  std::vector<VkLayerProperties> layers(count);
  if (vkEnumerateInstanceLayerProperties(&count, layers.data()) != VK_SUCCESS) return false;
  for (const VkLayerProperties& l : layers)
    if (std::strcmp(l.layerName, name) == 0) return true;
  return false;
}

int device_rank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return 3;
    default:
      return 4;
  }
}

bool find_queue_family(VkPhysicalDevice device, uint32_t* family) {
  uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
  for (uint32_t i = 0; i < count; ++i) {
    if ((families[i].queueFlags & need) == need && families[i].queueCount > 0 &&
        families[i].timestampValidBits > 0) {
      *family = i;
      return true;
    }
  }
  for (uint32_t i = 0; i < count; ++i) {
    if ((families[i].queueFlags & need) == need && families[i].queueCount > 0) {
      *family = i;
      return true;
    }
  }
  return false;
}

DeviceFeatures features_from(const VkPhysicalDeviceFeatures& f) {
  DeviceFeatures d;
  d.float64 = f.shaderFloat64 == VK_TRUE;
  d.int64 = f.shaderInt64 == VK_TRUE;
  d.multi_draw_indirect = f.multiDrawIndirect == VK_TRUE;
  d.fill_mode_non_solid = f.fillModeNonSolid == VK_TRUE;
  return d;
}

}  // namespace

const char* vk_result_name(VkResult r) {
  switch (r) {
    case VK_SUCCESS:
      return "VK_SUCCESS";
    case VK_NOT_READY:
      return "VK_NOT_READY";
    case VK_TIMEOUT:
      return "VK_TIMEOUT";
    case VK_INCOMPLETE:
      return "VK_INCOMPLETE";
    case VK_ERROR_OUT_OF_HOST_MEMORY:
      return "VK_ERROR_OUT_OF_HOST_MEMORY";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY:
      return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
    case VK_ERROR_INITIALIZATION_FAILED:
      return "VK_ERROR_INITIALIZATION_FAILED";
    case VK_ERROR_DEVICE_LOST:
      return "VK_ERROR_DEVICE_LOST";
    case VK_ERROR_MEMORY_MAP_FAILED:
      return "VK_ERROR_MEMORY_MAP_FAILED";
    case VK_ERROR_LAYER_NOT_PRESENT:
      return "VK_ERROR_LAYER_NOT_PRESENT";
    case VK_ERROR_EXTENSION_NOT_PRESENT:
      return "VK_ERROR_EXTENSION_NOT_PRESENT";
    case VK_ERROR_FEATURE_NOT_PRESENT:
      return "VK_ERROR_FEATURE_NOT_PRESENT";
    case VK_ERROR_INCOMPATIBLE_DRIVER:
      return "VK_ERROR_INCOMPATIBLE_DRIVER";
    case VK_ERROR_TOO_MANY_OBJECTS:
      return "VK_ERROR_TOO_MANY_OBJECTS";
    case VK_ERROR_FORMAT_NOT_SUPPORTED:
      return "VK_ERROR_FORMAT_NOT_SUPPORTED";
    default:
      return "VkResult error";
  }
}

Status vulkan_error(const char* what, VkResult result) {
  return Status(StatusCode::kInvalidArgument,
                std::string("Vulkan: ") + what + " failed: " + vk_result_name(result));
}

Status VulkanContext::create(const ContextOptions& options, std::unique_ptr<VulkanContext>& out) {
  std::unique_ptr<VulkanContext> context(new VulkanContext());
  context->owns_ = true;
  Status s = context->init_headless(options);
  if (!s.ok()) return s;
  out = std::move(context);
  return Status();
}

Status VulkanContext::wrap(const HostDevice& host, std::unique_ptr<VulkanContext>& out) {
  if (host.instance == VK_NULL_HANDLE || host.physical_device == VK_NULL_HANDLE ||
      host.device == VK_NULL_HANDLE || host.queue == VK_NULL_HANDLE)
    return Status(StatusCode::kInvalidArgument,
                  "VulkanContext::wrap: the host's instance, physical device, device and queue "
                  "must all be set");
  std::unique_ptr<VulkanContext> context(new VulkanContext());
  context->owns_ = false;
  context->instance_ = host.instance;
  context->physical_device_ = host.physical_device;
  context->device_ = host.device;
  context->queue_ = host.queue;
  context->queue_family_ = host.queue_family;
  context->features_ = features_from(host.enabled_features);
  vkGetPhysicalDeviceProperties(host.physical_device, &context->properties_);
  vkGetPhysicalDeviceMemoryProperties(host.physical_device, &context->memory_);
  Status s = context->init_device();
  if (!s.ok()) return s;
  out = std::move(context);
  return Status();
}

Status VulkanContext::init_headless(const ContextOptions& options) {
  const bool validation = options.validation || env_flag("CROWDBAKE_VULKAN_VALIDATION");
  if (validation && !has_layer(kValidationLayer))
    return Status(StatusCode::kNotLoaded,
                  "Vulkan validation was asked for but VK_LAYER_KHRONOS_validation is not "
                  "installed (Debian/Ubuntu: apt-get install vulkan-validationlayers)");
  if (Status s = create_instance(options, validation); !s.ok()) return s;
  if (Status s = pick_physical_device(); !s.ok()) return s;
  return create_device();
}

Status VulkanContext::create_instance(const ContextOptions& options, bool validation) {
  VkApplicationInfo app{};

  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = options.application_name.c_str();
  app.pEngineName = "crowdbake";
  app.apiVersion = VK_API_VERSION_1_2;

  std::vector<const char*> layers, extensions;
  if (validation) {
    layers.push_back(kValidationLayer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }
  VkDebugUtilsMessengerCreateInfoEXT messenger_info{};
  messenger_info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
  messenger_info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                   VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger_info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messenger_info.pfnUserCallback = debug_callback;
  messenger_info.pUserData = this;

  VkInstanceCreateInfo info{};

  info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  info.pApplicationInfo = &app;
  info.enabledLayerCount = static_cast<uint32_t>(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  // note: chained, the messenger also reports errors of vkCreateInstance itself.
  if (validation) info.pNext = &messenger_info;
  VkResult r = vkCreateInstance(&info, nullptr, &instance_);
  if (r == VK_ERROR_INCOMPATIBLE_DRIVER || r == VK_ERROR_INITIALIZATION_FAILED) {
    instance_ = VK_NULL_HANDLE;
    return Status(StatusCode::kNotLoaded, std::string(kNoVulkanDeviceMessage) +
                                              " (vkCreateInstance: " + vk_result_name(r) + ")");
  }
  if (r != VK_SUCCESS) {
    instance_ = VK_NULL_HANDLE;
    return vulkan_error("vkCreateInstance", r);
  }
  if (validation) {
    auto create_messenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    if (create_messenger == nullptr) return vulkan_error("vkCreateDebugUtilsMessengerEXT", r);
    r = create_messenger(instance_, &messenger_info, nullptr, &messenger_);
    if (r != VK_SUCCESS) return vulkan_error("vkCreateDebugUtilsMessengerEXT", r);
  }
  return Status();
}

Status VulkanContext::pick_physical_device() {
  uint32_t count = 0;
  const VkResult r = vkEnumeratePhysicalDevices(instance_, &count, nullptr);
  if (r != VK_SUCCESS && r != VK_INCOMPLETE) return vulkan_error("vkEnumeratePhysicalDevices", r);
  std::vector<VkPhysicalDevice> devices(count);
  if (count > 0) vkEnumeratePhysicalDevices(instance_, &count, devices.data());
  int best_rank = 1000;
  for (VkPhysicalDevice d : devices) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(d, &p);
    uint32_t family = 0;
    if (p.apiVersion < VK_API_VERSION_1_2 || !find_queue_family(d, &family)) continue;
    const int rank = device_rank(p.deviceType);
    if (rank < best_rank) {
      best_rank = rank;
      physical_device_ = d;
      queue_family_ = family;
    }
  }
  if (physical_device_ == VK_NULL_HANDLE)
    return Status(StatusCode::kNotLoaded,
                  std::string(kNoVulkanDeviceMessage) + " (" + std::to_string(count) +
                      " device(s) enumerated, none with Vulkan 1.2 and a graphics+compute queue)");
  vkGetPhysicalDeviceProperties(physical_device_, &properties_);
  vkGetPhysicalDeviceMemoryProperties(physical_device_, &memory_);
  return Status();
}

Status VulkanContext::create_device() {
  VkPhysicalDeviceFeatures supported{};
  vkGetPhysicalDeviceFeatures(physical_device_, &supported);
  VkPhysicalDeviceFeatures enabled{};
  enabled.shaderFloat64 = supported.shaderFloat64;
  enabled.shaderInt64 = supported.shaderInt64;
  enabled.multiDrawIndirect = supported.multiDrawIndirect;
  enabled.drawIndirectFirstInstance = supported.drawIndirectFirstInstance;
  enabled.fillModeNonSolid = supported.fillModeNonSolid;
  enabled.vertexPipelineStoresAndAtomics = supported.vertexPipelineStoresAndAtomics;
  enabled.fragmentStoresAndAtomics = supported.fragmentStoresAndAtomics;
  enabled.shaderStorageImageWriteWithoutFormat = supported.shaderStorageImageWriteWithoutFormat;
  features_ = features_from(enabled);

  VkPhysicalDeviceVulkan11Features supported11{};

  supported11.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES;
  VkPhysicalDeviceVulkan12Features supported12{};
  supported12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
  supported11.pNext = &supported12;
  VkPhysicalDeviceFeatures2 supported2{};
  supported2.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
  supported2.pNext = &supported11;
  vkGetPhysicalDeviceFeatures2(physical_device_, &supported2);
  VkPhysicalDeviceVulkan11Features enabled11{};
  enabled11.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES;
  VkPhysicalDeviceVulkan12Features enabled12{};
  enabled12.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES;
  enabled11.pNext = &enabled12;
  enabled11.shaderDrawParameters = supported11.shaderDrawParameters;
  enabled11.storageBuffer16BitAccess = supported11.storageBuffer16BitAccess;
  enabled12.storageBuffer8BitAccess = supported12.storageBuffer8BitAccess;
  enabled12.shaderInt8 = supported12.shaderInt8;
  enabled12.scalarBlockLayout = supported12.scalarBlockLayout;
  enabled12.hostQueryReset = supported12.hostQueryReset;
  enabled12.drawIndirectCount = supported12.drawIndirectCount;
  VkPhysicalDeviceFeatures2 enabled2{};
  enabled2.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
  enabled2.features = enabled;
  enabled2.pNext = &enabled11;

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue_info{};
  queue_info.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
  queue_info.queueFamilyIndex = queue_family_;
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;
  VkDeviceCreateInfo device_info{};
  device_info.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
  device_info.pNext = &enabled2;
  device_info.queueCreateInfoCount = 1;
  device_info.pQueueCreateInfos = &queue_info;
  const VkResult r = vkCreateDevice(physical_device_, &device_info, nullptr, &device_);
  if (r != VK_SUCCESS) {
    device_ = VK_NULL_HANDLE;
    return vulkan_error("vkCreateDevice", r);
  }
  vkGetDeviceQueue(device_, queue_family_, 0, &queue_);
  return init_device();
}

Status VulkanContext::init_device() {
  VkCommandPoolCreateInfo pool_info{};
  pool_info.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  pool_info.flags =
      VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT | VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  pool_info.queueFamilyIndex = queue_family_;
  VkResult r = vkCreateCommandPool(device_, &pool_info, nullptr, &pool_);
  if (r != VK_SUCCESS) return vulkan_error("vkCreateCommandPool", r);
  VkFenceCreateInfo fence_info{};
  fence_info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
  r = vkCreateFence(device_, &fence_info, nullptr, &fence_);
  if (r != VK_SUCCESS) return vulkan_error("vkCreateFence", r);
  return Status();
}

VulkanContext::~VulkanContext() {
  if (device_ != VK_NULL_HANDLE) {
    vkDeviceWaitIdle(device_);
    if (fence_ != VK_NULL_HANDLE) vkDestroyFence(device_, fence_, nullptr);
    if (pool_ != VK_NULL_HANDLE) vkDestroyCommandPool(device_, pool_, nullptr);
  }
  if (!owns_) return;
  if (device_ != VK_NULL_HANDLE) vkDestroyDevice(device_, nullptr);
  if (messenger_ != VK_NULL_HANDLE) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance_, messenger_, nullptr);
  }
  if (instance_ != VK_NULL_HANDLE) vkDestroyInstance(instance_, nullptr);
}

void VulkanContext::report_validation(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                      const char* message) {
  std::lock_guard<std::mutex> lock(messages_mutex_);
  if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
    ++errors_;
    messages_.push_back(std::string("error: ") + message);
  } else {
    messages_.push_back(std::string("warning: ") + message);
  }
}

uint32_t VulkanContext::validation_errors() const {
  std::lock_guard<std::mutex> lock(messages_mutex_);
  return errors_;
}

std::vector<std::string> VulkanContext::validation_messages() const {
  std::lock_guard<std::mutex> lock(messages_mutex_);
  return messages_;
}

std::string VulkanContext::validation_report() const {
  std::lock_guard<std::mutex> lock(messages_mutex_);
  std::string out;
  for (const std::string& m : messages_) out += m + "\n";
  return out;
}

void VulkanContext::clear_validation_messages() {
  std::lock_guard<std::mutex> lock(messages_mutex_);
  errors_ = 0;
  messages_.clear();
}

uint32_t VulkanContext::find_memory_type(uint32_t type_bits, VkMemoryPropertyFlags required) const {
  for (uint32_t i = 0; i < memory_.memoryTypeCount; ++i)
    if ((type_bits & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & required) == required)
      return i;
  return UINT32_MAX;
}

Status VulkanContext::submit_and_wait(const std::function<void(VkCommandBuffer)>& record) {
  VkCommandBufferAllocateInfo alloc{};
  alloc.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  alloc.commandPool = pool_;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VkResult r = vkAllocateCommandBuffers(device_, &alloc, &cmd);
  if (r != VK_SUCCESS) return vulkan_error("vkAllocateCommandBuffers", r);
  VkCommandBufferBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  r = vkBeginCommandBuffer(cmd, &begin);
  if (r == VK_SUCCESS) {
    record(cmd);
    r = vkEndCommandBuffer(cmd);
  }
  Status status;
  if (r != VK_SUCCESS) {
    status = vulkan_error("recording a command buffer", r);
  } else {
    VkSubmitInfo submit{};
    submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    vkResetFences(device_, 1, &fence_);
    r = vkQueueSubmit(queue_, 1, &submit, fence_);
    if (r != VK_SUCCESS) {
      status = vulkan_error("vkQueueSubmit", r);
    } else {
      r = vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX);
      if (r != VK_SUCCESS) status = vulkan_error("vkWaitForFences", r);
    }
  }
  vkFreeCommandBuffers(device_, pool_, 1, &cmd);
  return status;
}

Status VulkanContext::create_shader_module(const char* name, VkShaderModule& out) const {
  const Span<const uint32_t> words = find_spirv(name);
  if (words.empty())
    return Status(StatusCode::kInvalidArgument,
                  std::string("no embedded shader named ") + (name ? name : "(null)"));
  VkShaderModuleCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
  info.codeSize = words.size() * sizeof(uint32_t);
  info.pCode = words.data();
  const VkResult r = vkCreateShaderModule(device_, &info, nullptr, &out);
  if (r != VK_SUCCESS) return vulkan_error(name, r);
  return Status();
}

}  // namespace crowdbake::runtime::gpu
