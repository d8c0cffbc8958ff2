// host_embed: a minimal "game" that owns its Vulkan instance, device, command buffer and render
// target, and lets crowdbake record a crowd into them (runtime/gpu/include/crowdbake/runtime/gpu/
// renderer.h: VulkanContext::wrap, Renderer::prepare, Renderer::record_draw).
//
//   host_embed PACK.crowdpack [OUT.ppm]
//
// Creates its device with plain Vulkan calls (validation layer on when installed), wraps it,
// clears its own colour/depth images to its own background, has crowdbake draw 3x5 instances
// of the pack over them at 320x180 inside its own command buffer, copies the picture to a
// host buffer and checks that something was drawn.
// Exit codes: 0 drawn, 1 failure (including validation errors), 77 no Vulkan device (unless
// CROWDBAKE_REQUIRE_VULKAN=1, then 1).
#include <vulkan/vulkan.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "crowdbake/runtime/gpu/renderer.h"
#include "crowdbake/runtime/gpu/vulkan_context.h"
#include "crowdbake/runtime/scene.h"

namespace {

constexpr uint32_t kWidth = 320, kHeight = 180;
uint32_t g_validation_errors = 0;

VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                          VkDebugUtilsMessageTypeFlagsEXT,
                                          const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
  if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
    ++g_validation_errors;
    std::fprintf(stderr, "validation: %s\n", data->pMessage);
  }
  return VK_FALSE;
}

int no_device(const char* why) {
  const char* required = std::getenv("CROWDBAKE_REQUIRE_VULKAN");
  std::fprintf(
      stderr, "host_embed: %s: no Vulkan device (install mesa-vulkan-drivers for lavapipe)\n", why);
  return required && std::strcmp(required, "1") == 0 ? 1 : 77;
}

int fail(const std::string& what) {
  std::fprintf(stderr, "host_embed: %s\n", what.c_str());
  return 1;
}

bool has_layer(const char* name) {
  uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  vkEnumerateInstanceLayerProperties(&count, layers.data());
  for (const VkLayerProperties& l : layers)
    if (std::strcmp(l.layerName, name) == 0) return true;
  return false;
}

// What the game owns: everything here is created and destroyed by the host, never by
// crowdbake.
struct Host {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t family = 0;
  VkPhysicalDeviceFeatures features{};
  VkCommandPool pool = VK_NULL_HANDLE;
  VkImage images[2] = {};
  VkDeviceMemory memories[3] = {};
  VkImageView views[2] = {};
  VkBuffer readback = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;

  ~Host() {
    if (device) {
      vkDeviceWaitIdle(device);
      vkDestroyFence(device, fence, nullptr);
      vkDestroyBuffer(device, readback, nullptr);
      for (VkImageView v : views) vkDestroyImageView(device, v, nullptr);
      for (VkImage i : images) vkDestroyImage(device, i, nullptr);
      for (VkDeviceMemory m : memories) vkFreeMemory(device, m, nullptr);
      vkDestroyCommandPool(device, pool, nullptr);
      vkDestroyDevice(device, nullptr);
    }
    if (messenger) {
      auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
          vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
      if (destroy) destroy(instance, messenger, nullptr);
    }
    if (instance) vkDestroyInstance(instance, nullptr);
  }

  uint32_t memory_type(uint32_t bits, VkMemoryPropertyFlags flags) const {
    VkPhysicalDeviceMemoryProperties props;
    vkGetPhysicalDeviceMemoryProperties(physical, &props);
    for (uint32_t i = 0; i < props.memoryTypeCount; ++i)
      if ((bits & (1u << i)) && (props.memoryTypes[i].propertyFlags & flags) == flags) return i;
    return UINT32_MAX;
  }
};

// The game's own device: an instance (with validation when installed), the first device with
// a graphics+compute queue and shaderFloat64 (what crowdbake's compute passes need).
int create_device(Host& host) {
  VkApplicationInfo app{};
  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = "host_embed";
  app.apiVersion = VK_API_VERSION_1_2;
  const char* layer = "VK_LAYER_KHRONOS_validation";
  const bool validate = has_layer(layer);
  const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
  VkInstanceCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  info.pApplicationInfo = &app;
  info.enabledLayerCount = validate ? 1 : 0;
  info.ppEnabledLayerNames = &layer;
  info.enabledExtensionCount = validate ? 1 : 0;
  info.ppEnabledExtensionNames = &extension;
  if (vkCreateInstance(&info, nullptr, &host.instance) != VK_SUCCESS)
    return no_device("vkCreateInstance failed");
  if (validate) {
    VkDebugUtilsMessengerCreateInfoEXT m{};
    m.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
    m.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT |
                        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT;
    m.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                    VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT;
    m.pfnUserCallback = on_message;
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(host.instance, "vkCreateDebugUtilsMessengerEXT"));
    if (create) create(host.instance, &m, nullptr, &host.messenger);
  }
  uint32_t count = 0;
  vkEnumeratePhysicalDevices(host.instance, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(host.instance, &count, devices.data());
  for (VkPhysicalDevice d : devices) {
    VkPhysicalDeviceFeatures f;
    vkGetPhysicalDeviceFeatures(d, &f);
    uint32_t families = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(d, &families, nullptr);
    std::vector<VkQueueFamilyProperties> props(families);
    vkGetPhysicalDeviceQueueFamilyProperties(d, &families, props.data());
    for (uint32_t q = 0; q < families && !host.physical; ++q)
      if ((props[q].queueFlags & VK_QUEUE_GRAPHICS_BIT) &&
          (props[q].queueFlags & VK_QUEUE_COMPUTE_BIT) && f.shaderFloat64) {
        host.physical = d;
        host.family = q;
      }
  }
  if (!host.physical) return no_device("no device with graphics, compute and shaderFloat64");
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue{};
  queue.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
  queue.queueFamilyIndex = host.family;
  queue.queueCount = 1;
  queue.pQueuePriorities = &priority;
  host.features.shaderFloat64 = VK_TRUE;
  host.features.shaderInt64 = VK_TRUE;
  VkDeviceCreateInfo device{};
  device.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
  device.queueCreateInfoCount = 1;
  device.pQueueCreateInfos = &queue;
  device.pEnabledFeatures = &host.features;
  VkPhysicalDeviceFeatures supported;
  vkGetPhysicalDeviceFeatures(host.physical, &supported);
  host.features.shaderInt64 = supported.shaderInt64;
  if (vkCreateDevice(host.physical, &device, nullptr, &host.device) != VK_SUCCESS)
    return fail("vkCreateDevice failed");
  vkGetDeviceQueue(host.device, host.family, 0, &host.queue);
  return 0;
}

// The game's render target: colour (RGBA8) and depth images, and a host-visible buffer to read
// the picture back.
bool create_target(Host& host) {
  const VkFormat formats[2] = {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_D32_SFLOAT};
  const VkImageUsageFlags usages[2] = {
      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
          VK_IMAGE_USAGE_TRANSFER_DST_BIT,
      VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT};
  const VkImageAspectFlags aspects[2] = {VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_ASPECT_DEPTH_BIT};
  for (int i = 0; i < 2; ++i) {
    VkImageCreateInfo image{};
    image.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
    image.imageType = VK_IMAGE_TYPE_2D;
    image.format = formats[i];
    image.extent = {kWidth, kHeight, 1};
    image.mipLevels = image.arrayLayers = 1;
    image.samples = VK_SAMPLE_COUNT_1_BIT;
    image.tiling = VK_IMAGE_TILING_OPTIMAL;
    image.usage = usages[i];
    if (vkCreateImage(host.device, &image, nullptr, &host.images[i]) != VK_SUCCESS) return false;
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(host.device, host.images[i], &req);
    VkMemoryAllocateInfo alloc{};
    alloc.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex =
        host.memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (vkAllocateMemory(host.device, &alloc, nullptr, &host.memories[i]) != VK_SUCCESS ||
        vkBindImageMemory(host.device, host.images[i], host.memories[i], 0) != VK_SUCCESS)
      return false;
    VkImageViewCreateInfo view{};
    view.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
    view.image = host.images[i];
    view.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view.format = formats[i];
    view.subresourceRange = {aspects[i], 0, 1, 0, 1};
    if (vkCreateImageView(host.device, &view, nullptr, &host.views[i]) != VK_SUCCESS) return false;
  }
  VkBufferCreateInfo buffer{};
  buffer.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  buffer.size = VkDeviceSize{kWidth} * kHeight * 4;
  buffer.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  if (vkCreateBuffer(host.device, &buffer, nullptr, &host.readback) != VK_SUCCESS) return false;
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(host.device, host.readback, &req);
  VkMemoryAllocateInfo alloc{};
  alloc.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex =
      host.memory_type(req.memoryTypeBits,
                       VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  if (vkAllocateMemory(host.device, &alloc, nullptr, &host.memories[2]) != VK_SUCCESS ||
      vkBindBufferMemory(host.device, host.readback, host.memories[2], 0) != VK_SUCCESS)
    return false;
  VkCommandPoolCreateInfo pool{};
  pool.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  pool.queueFamilyIndex = host.family;
  VkFenceCreateInfo fence{};
  fence.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
  return vkCreateCommandPool(host.device, &pool, nullptr, &host.pool) == VK_SUCCESS &&
         vkCreateFence(host.device, &fence, nullptr, &host.fence) == VK_SUCCESS;
}

// The crowd: 3 rows of 5 instances of the pack, cycling through its clips.
crowdbake::runtime::Status make_crowd(const char* pack_path, crowdbake::runtime::Scene& scene) {
  namespace rt = crowdbake::runtime;
  rt::Pack pack;
  if (rt::Status s = rt::Pack::open_file(pack_path, pack, rt::kPackAll); !s) return s;
  if (rt::Status s = rt::add_character_type(scene, "character", std::move(pack)); !s) return s;
  const uint32_t clips = static_cast<uint32_t>(scene.types[0].pack.contents().clips.size());
  const auto& partition = scene.types[0].pack.contents().partition;
  for (uint32_t i = 0; i < 15; ++i) {
    rt::Instance instance;
    instance.position = {1.2f * static_cast<float>(i % 5) - 2.4f, 0.0f,
                         -1.2f * static_cast<float>(i / 5)};
    instance.clip = i % clips;
    instance.time_offset = 0.3f * static_cast<float>(i);
    instance.color = {15.0f * static_cast<float>(i), 1.0f, 1.0f};
    instance.neck_height = partition.neck_height;
    instance.waist_height = partition.waist_height;
    scene.instances.add(instance);
  }
  scene.camera.position = {0.0f, 3.0f, 6.0f};
  scene.camera.target = {0.0f, 0.9f, -1.2f};
  scene.camera.width = kWidth;
  scene.camera.height = kHeight;
  return {};
}

const VkClearColorValue kBackground{{0.08f, 0.09f, 0.12f, 1.0f}};

// The host's own picture: a background and a depth buffer at the far plane, left ready for
// the crowd's passes.
void record_host_picture(const Host& host, VkCommandBuffer cmd) {
  // The host's own picture first (here just a background and a depth buffer at the far plane).
  const VkImageAspectFlags aspects[2] = {VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_ASPECT_DEPTH_BIT};
  const VkImageLayout ready[2] = {VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                                  VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  for (int i = 0; i < 2; ++i) {
    VkImageMemoryBarrier barrier{};
    barrier.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
    barrier.srcAccessMask = 0;
    barrier.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    barrier.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = host.images[i];
    barrier.subresourceRange = {aspects[i], 0, 1, 0, 1};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
                         0, nullptr, 0, nullptr, 1, &barrier);
  }
  const VkClearDepthStencilValue far{1.0f, 0};
  const VkImageSubresourceRange color_range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  const VkImageSubresourceRange depth_range{VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, 1};
  vkCmdClearColorImage(cmd, host.images[0], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &kBackground, 1,
                       &color_range);
  vkCmdClearDepthStencilImage(cmd, host.images[1], VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &far, 1,
                              &depth_range);
  for (int i = 0; i < 2; ++i) {
    VkImageMemoryBarrier barrier{};
    barrier.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
    barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.dstAccessMask = i == 0 ? VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT
                                   : VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                                         VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    barrier.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    barrier.newLayout = ready[i];
    barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = host.images[i];
    barrier.subresourceRange = {aspects[i], 0, 1, 0, 1};
    vkCmdPipelineBarrier(
        cmd, VK_PIPELINE_STAGE_TRANSFER_BIT,
        VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT,
        0, 0, nullptr, 0, nullptr, 1, &barrier);
  }
}

// Pixels that differ from the background, and the picture as a PPM file when `path` is set.
size_t count_drawn_pixels(const Host& host, const char* path) {
  // Something was drawn over the host's background, and the background is still there.
  void* mapped = nullptr;
  vkMapMemory(host.device, host.memories[2], 0, VK_WHOLE_SIZE, 0, &mapped);
  const uint8_t* rgba = static_cast<const uint8_t*>(mapped);
  size_t drawn = 0;
  for (size_t p = 0; p < size_t{kWidth} * kHeight; ++p)
    for (int c = 0; c < 3; ++c)
      if (std::abs(int(rgba[4 * p + c]) - int(std::lround(kBackground.float32[c] * 255.0f))) > 2) {
        ++drawn;
        break;
      }
  if (path) {
    std::ofstream out(path, std::ios::binary);
    out << "P6\n" << kWidth << " " << kHeight << "\n255\n";
    for (size_t p = 0; p < size_t{kWidth} * kHeight; ++p)
      out.write(reinterpret_cast<const char*>(rgba + 4 * p), 3);
  }
  vkUnmapMemory(host.device, host.memories[2]);
  return drawn;
}

}  // namespace

int main(int argc, char** argv) {
  namespace rt = crowdbake::runtime;
  if (argc < 2) {
    std::fprintf(stderr, "usage: host_embed PACK.crowdpack [OUT.ppm]\n");
    return 2;
  }
  Host host;
  if (int code = create_device(host); code != 0) return code;
  if (!create_target(host)) return fail("could not create the render target");

  rt::Scene scene;
  if (rt::Status s = make_crowd(argv[1], scene); !s) return fail(s.message());

  // crowdbake on the host's device.
  rt::gpu::HostDevice device;
  device.instance = host.instance;
  device.physical_device = host.physical;
  device.device = host.device;
  device.queue = host.queue;
  device.queue_family = host.family;
  device.enabled_features = host.features;
  std::unique_ptr<rt::gpu::VulkanContext> context;
  if (rt::Status s = rt::gpu::VulkanContext::wrap(device, context); !s) return fail(s.message());
  std::unique_ptr<rt::gpu::Renderer> renderer;
  if (rt::Status s = rt::gpu::Renderer::create(*context, scene, {}, renderer); !s)
    return fail(s.message());

  // One frame in the host's own command buffer: crowd compute, shadow and colour passes into
  // the host's target, then the host's own copy to its readback buffer.
  VkCommandBufferAllocateInfo alloc{};
  alloc.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  alloc.commandPool = host.pool;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  if (vkAllocateCommandBuffers(host.device, &alloc, &cmd) != VK_SUCCESS)
    return fail("vkAllocateCommandBuffers failed");
  VkCommandBufferBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkBeginCommandBuffer(cmd, &begin);
  record_host_picture(host, cmd);
  // Then the crowd: compute and skinning passes, shadow and colour passes over the picture.
  if (rt::Status s = renderer->prepare(scene, 1.0f, cmd); !s) return fail(s.message());
  rt::gpu::HostTarget target;
  target.color_view = host.views[0];
  target.depth_view = host.views[1];
  target.width = kWidth;
  target.height = kHeight;
  target.color_final_layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  target.clear = false;  // draw over the host's picture
  if (rt::Status s = renderer->record_draw(cmd, target); !s) return fail(s.message());
  VkBufferImageCopy copy{};
  copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  copy.imageExtent = {kWidth, kHeight, 1};
  vkCmdCopyImageToBuffer(cmd, host.images[0], VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, host.readback,
                         1, &copy);
  vkEndCommandBuffer(cmd);
  VkSubmitInfo submit{};
  submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  if (vkQueueSubmit(host.queue, 1, &submit, host.fence) != VK_SUCCESS ||
      vkWaitForFences(host.device, 1, &host.fence, VK_TRUE, UINT64_MAX) != VK_SUCCESS)
    return fail("submit failed");

  const size_t drawn = count_drawn_pixels(host, argc > 2 ? argv[2] : nullptr);
  renderer.reset();
  context.reset();
  std::printf("host_embed: %zu of %u pixels drawn, %u validation errors\n", drawn, kWidth * kHeight,
              g_validation_errors);
  if (g_validation_errors) return fail("the validation layer reported errors");
  if (drawn < size_t{kWidth} * kHeight / 50) return fail("nothing was drawn");
  if (drawn == size_t{kWidth} * kHeight) return fail("the host's background was not kept");
  return 0;
}
