#include "crowdbake/runtime/gpu/crowd_draw.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <map>
#include <string>
#include <tuple>
#include <utility>

#include "crowdbake/runtime/gpu/crowd_compute.h"

namespace crowdbake::runtime::gpu {

// note: the shaders read these as std140 / std430 blocks; any change must match the GLSL.
static_assert(sizeof(FrameConstants) == 2 * 64 + 8 * 16, "FrameBlock layout");
static_assert(offsetof(FrameConstants, light_dir) == 128, "FrameBlock layout");
static_assert(sizeof(TypeConstants) == 6 * 16, "TypeBlock layout");
static_assert(sizeof(GpuVertex) == 64, "GpuVertex layout");

namespace {

// Draw push constants (crowd_frame.glsl DrawPush).
struct DrawPush {
  uint32_t corner_base = 0;
  uint32_t unused = 0;
};

constexpr uint32_t kRegions = 3;

float clamp01(float v) { return std::min(1.0f, std::max(0.0f, v)); }

void hsv_to_rgb(float h, float s, float v, float rgb[3]) {
  const float k[3] = {5.0f, 3.0f, 1.0f};
  for (int i = 0; i < 3; ++i) {
    const float t = std::fmod(k[i] + h * 6.0f, 6.0f);
    rgb[i] = v - v * s * std::max(0.0f, std::min({t, 4.0f - t, 1.0f}));
  }
}

// Simple, recognisable swatches (the packs carry no images): skin tones for the head, shirts of
// well-spread hues with stripes on odd variants, dark trousers with a faint weave.
std::vector<uint8_t> make_swatches(uint32_t per_region) {
  const uint32_t n = kSwatchSize;
  std::vector<uint8_t> rgba(static_cast<size_t>(kRegions) * per_region * n * n * 4);
  static const float skin[][3] = {{0.96f, 0.80f, 0.69f}, {0.87f, 0.67f, 0.52f},
                                  {0.72f, 0.53f, 0.38f}, {0.55f, 0.38f, 0.26f},
                                  {0.38f, 0.26f, 0.18f}, {0.93f, 0.75f, 0.60f}};
  for (uint32_t region = 0; region < kRegions; ++region) {
    for (uint32_t variant = 0; variant < per_region; ++variant) {
      float base[3];
      if (region == 0) {
        std::memcpy(base, skin[variant % 6], sizeof(base));
      } else {
        // note: golden-ratio hue steps keep neighbouring variants far apart.
        const float hue =
            std::fmod(0.07f + 0.618034f * static_cast<float>(variant + 3 * region), 1.0f);
        if (region == 1)
          hsv_to_rgb(hue, 0.55f + 0.1f * static_cast<float>(variant % 3), 0.85f, base);
        else
          hsv_to_rgb(hue, 0.35f, 0.30f + 0.08f * static_cast<float>(variant % 4), base);
      }
      uint8_t* layer = &rgba[(static_cast<size_t>(region) * per_region + variant) * n * n * 4];
      for (uint32_t y = 0; y < n; ++y) {
        for (uint32_t x = 0; x < n; ++x) {
          float f = 1.0f;
          if (region == 1 && variant % 2 == 1 && (y / 4) % 2 == 1) f = 0.78f;  // stripes
          if (region == 2 && (x + y) % 4 == 0) f = 0.9f;                       // weave
          uint8_t* p = &layer[(static_cast<size_t>(y) * n + x) * 4];
          for (int c = 0; c < 3; ++c)
            p[c] = static_cast<uint8_t>(std::lround(clamp01(base[c] * f) * 255.0f));
          p[3] = 255;
        }
      }
    }
  }
  return rgba;
}

void normalize3(float v[3]) {
  const float len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (len > 0.0f)
    for (int i = 0; i < 3; ++i) v[i] /= len;
}

void cross3(const float a[3], const float b[3], float out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

// out = a · b, 4x4 column-major.
void multiply4(const float a[16], const float b[16], float out[16]) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {
      float s = 0.0f;
      for (int k = 0; k < 4; ++k) s += a[4 * k + r] * b[4 * c + k];
      out[4 * c + r] = s;
    }
}

Status check(VkResult result, const char* what) {
  return result == VK_SUCCESS ? Status() : vulkan_error(what, result);
}

}  // namespace

std::vector<GpuVertex> make_gpu_vertices(const PackContents& pack) {
  const PackGeometry& g = pack.geometry;
  const uint32_t n = g.vertex_count();
  const auto& up = pack.partition.up_axis;
  const bool skinned =
      g.joints.size() == 4 * static_cast<size_t>(n) && g.weights.size() == g.joints.size();
  std::vector<GpuVertex> out(n);
  for (uint32_t i = 0; i < n; ++i) {
    GpuVertex& v = out[i];
    const float* p = &g.positions[3 * static_cast<size_t>(i)];
    v.position_height[0] = p[0];
    v.position_height[1] = p[1];
    v.position_height[2] = p[2];
    v.position_height[3] = p[0] * up[0] + p[1] * up[1] + p[2] * up[2];
    for (int c = 0; c < 3; ++c)
      v.normal_u[c] =
          g.normals.size() == g.positions.size() ? g.normals[3 * static_cast<size_t>(i) + c] : 0.0f;
    const bool has_uv = g.uvs.size() == 2 * static_cast<size_t>(n);
    v.normal_u[3] = has_uv ? g.uvs[2 * static_cast<size_t>(i)] : 0.0f;
    const float uv_v = has_uv ? g.uvs[2 * static_cast<size_t>(i) + 1] : 0.0f;
    std::memcpy(&v.joints_v[2], &uv_v, 4);
    if (skinned) {
      const uint16_t* j = &g.joints[4 * static_cast<size_t>(i)];
      for (int k = 0; k < 4; ++k) v.weights[k] = g.weights[4 * static_cast<size_t>(i) + k];
      v.joints_v[0] = uint32_t{j[0]} | (uint32_t{j[1]} << 16);
      v.joints_v[1] = uint32_t{j[2]} | (uint32_t{j[3]} << 16);
      v.joints_v[3] = 0;
    } else {
      for (float& w : v.weights) w = 0.0f;
      v.joints_v[0] = v.joints_v[1] = 0;
      v.joints_v[3] = 1;
    }
  }
  return out;
}

void fit_light_view_proj(const std::array<float, 3>& light_direction, Span<const float> spheres,
                         float out[16]) {
  float l[3] = {light_direction[0], light_direction[1], light_direction[2]};
  normalize3(l);
  // Light space: x = right, y = up, z = forward (from the light into the scene, = -l).
  const float f[3] = {-l[0], -l[1], -l[2]};
  float helper[3] = {0.0f, 1.0f, 0.0f};
  if (std::abs(f[1]) > 0.99f) helper[0] = 1.0f, helper[1] = 0.0f;
  float r[3], u[3];
  cross3(f, helper, r);
  normalize3(r);
  cross3(r, f, u);
  float lo[3] = {-1.0f, -1.0f, -1.0f}, hi[3] = {1.0f, 1.0f, 1.0f};
  const size_t count = spheres.size() / 4;
  for (size_t i = 0; i < count; ++i) {
    const float* s = &spheres[4 * i];
    const float p[3] = {s[0] * r[0] + s[1] * r[1] + s[2] * r[2],
                        s[0] * u[0] + s[1] * u[1] + s[2] * u[2],
                        s[0] * f[0] + s[1] * f[1] + s[2] * f[2]};
    for (int a = 0; a < 3; ++a) {
      if (i == 0) lo[a] = p[a] - s[3], hi[a] = p[a] + s[3];
      lo[a] = std::min(lo[a], p[a] - s[3]);
      hi[a] = std::max(hi[a], p[a] + s[3]);
    }
  }
  float scale[3], offset[3];
  for (int a = 0; a < 3; ++a) {
    const float extent = std::max(hi[a] - lo[a], 1e-3f);
    // x, y to [-1, 1]; z (depth) to [0, 1].
    scale[a] = a < 2 ? 2.0f / extent : 1.0f / extent;
    offset[a] = a < 2 ? -(hi[a] + lo[a]) / extent : -lo[a] / extent;
  }
  const float* axes[3] = {r, u, f};
  std::fill(out, out + 16, 0.0f);
  for (int a = 0; a < 3; ++a) {
    for (int c = 0; c < 3; ++c) out[4 * c + a] = scale[a] * axes[a][c];
    out[12 + a] = offset[a];
  }
  out[15] = 1.0f;
}

// ---- resources ---------------------------------------------------------------------------

namespace {

struct TypeResources {
  GpuBuffer constants, vertices, animation, poses;
  GpuImage mask;
  VkDescriptorSet set = VK_NULL_HANDLE;
  uint32_t vertex_count = 0, joints = 0;
  uint32_t encoding = 0;  // AnimationEncoding
};

constexpr uint32_t kEncodings = 3;  // AnimationEncoding values: one pipeline each
                                    // (skin.glsl)

struct ColorPipeline {
  VkRenderPass render_pass = VK_NULL_HANDLE;
  VkPipeline pipelines[kEncodings] = {};  // only the encodings the scene's types use
  // Instanced static levels, made when a frame first draws them: [0] every instance has
  // skinned slots, [1] the vertex shader skins instances without (slower on lavapipe).
  VkPipeline instanced[2][kEncodings] = {};
  VkPipeline ground = VK_NULL_HANDLE;
};

// Pipeline kinds (crowd_frame.glsl kDrawMode).
constexpr uint32_t kModeCrowd = 0, kModeGround = 1, kModeInstanced = 2, kModeInstancedSlots = 3;

}  // namespace

struct CrowdDraw::Impl {
  VulkanContext* context = nullptr;
  DrawSettings settings;
  FrameConstants constants{};

  VkDescriptorSetLayout frame_layout = VK_NULL_HANDLE, type_layout = VK_NULL_HANDLE;
  VkPipelineLayout pipeline_layout = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VkDescriptorSet frame_set = VK_NULL_HANDLE;
  VkSampler swatch_sampler = VK_NULL_HANDLE, mask_sampler = VK_NULL_HANDLE,
            shadow_sampler = VK_NULL_HANDLE;
  VkShaderModule crowd_vert = VK_NULL_HANDLE, crowd_frag = VK_NULL_HANDLE,
                 shadow_vert = VK_NULL_HANDLE;

  GpuBuffer frame_buffer;
  GpuImage swatches, shadow_map;
  VkRenderPass shadow_pass = VK_NULL_HANDLE;
  VkFramebuffer shadow_framebuffer = VK_NULL_HANDLE;
  VkPipeline shadow_pipelines[kEncodings] = {};
  VkPipeline shadow_instanced[2][kEncodings] = {};
  bool skin_fallback = false;  // this frame: some instance may find no skinned slots
  uint32_t shadow_size = 1;
  uint32_t swatches_per_region = 1;

  std::vector<TypeResources> types;
  VkBuffer bound_instances = VK_NULL_HANDLE, bound_corners = VK_NULL_HANDLE,
           bound_lods = VK_NULL_HANDLE, bound_instance_list = VK_NULL_HANDLE;

  // The skinning pass (skin_list.comp, skin_pass.comp; see shaders/skin_common.glsl).
  VkDescriptorSetLayout skin_layout = VK_NULL_HANDLE;
  VkPipelineLayout skin_pipeline_layout = VK_NULL_HANDLE;
  VkDescriptorSet skin_set = VK_NULL_HANDLE;
  VkShaderModule skin_list_module = VK_NULL_HANDLE, skin_pass_module = VK_NULL_HANDLE,
                 skin_palette_module = VK_NULL_HANDLE;
  VkPipeline palette_pipelines[kEncodings] = {};
  VkPipeline skin_list_pipeline = VK_NULL_HANDLE;
  // Per encoding; [1]: joint matrices from the palette pass (skin_palette.comp), [0]: decoded
  // per influence (when the palette buffer would exceed the storage buffer range).
  VkPipeline skin_pipelines[kEncodings][2] = {};
  GpuBuffer skin_params, type_args, skin_list, skin_base, skinned, palette;
  bool palette_on = true;
  uint32_t palette_stride = 1;  // joints per instance in the palette (max over types)
  uint32_t list_stride = 0, skin_capacity = 0, instance_count = 0;

  std::map<std::tuple<VkFormat, VkFormat, VkImageLayout, bool>, ColorPipeline> color_pipelines;
  std::map<std::tuple<VkRenderPass, VkImageView, VkImageView, uint32_t, uint32_t>, VkFramebuffer>
      framebuffers;

  ~Impl() {
    if (!context) return;
    VkDevice d = context->device();
    for (auto& [key, fb] : framebuffers) vkDestroyFramebuffer(d, fb, nullptr);
    for (auto& [key, p] : color_pipelines) {
      for (VkPipeline pipeline : p.pipelines) vkDestroyPipeline(d, pipeline, nullptr);
      for (auto& kind : p.instanced)
        for (VkPipeline pipeline : kind) vkDestroyPipeline(d, pipeline, nullptr);
      vkDestroyPipeline(d, p.ground, nullptr);
      vkDestroyRenderPass(d, p.render_pass, nullptr);
    }
    for (VkPipeline pipeline : shadow_pipelines) vkDestroyPipeline(d, pipeline, nullptr);
    for (auto& kind : shadow_instanced)
      for (VkPipeline pipeline : kind) vkDestroyPipeline(d, pipeline, nullptr);
    vkDestroyFramebuffer(d, shadow_framebuffer, nullptr);
    vkDestroyPipeline(d, skin_list_pipeline, nullptr);
    for (auto& pair : skin_pipelines)
      for (VkPipeline pipeline : pair) vkDestroyPipeline(d, pipeline, nullptr);
    vkDestroyShaderModule(d, skin_list_module, nullptr);
    vkDestroyShaderModule(d, skin_pass_module, nullptr);
    vkDestroyShaderModule(d, skin_palette_module, nullptr);
    for (VkPipeline pipeline : palette_pipelines) vkDestroyPipeline(d, pipeline, nullptr);
    vkDestroyPipelineLayout(d, skin_pipeline_layout, nullptr);
    vkDestroyDescriptorSetLayout(d, skin_layout, nullptr);
    vkDestroyRenderPass(d, shadow_pass, nullptr);
    vkDestroyShaderModule(d, crowd_vert, nullptr);
    vkDestroyShaderModule(d, crowd_frag, nullptr);
    vkDestroyShaderModule(d, shadow_vert, nullptr);
    vkDestroySampler(d, swatch_sampler, nullptr);
    vkDestroySampler(d, mask_sampler, nullptr);
    vkDestroySampler(d, shadow_sampler, nullptr);
    vkDestroyDescriptorPool(d, pool, nullptr);
    vkDestroyPipelineLayout(d, pipeline_layout, nullptr);
    vkDestroyDescriptorSetLayout(d, frame_layout, nullptr);
    vkDestroyDescriptorSetLayout(d, type_layout, nullptr);
  }

  Status create_layouts();
  Status create_samplers();
  Status upload_image(GpuImage& image, const void* data, VkDeviceSize bytes);
  Status create_type(const CharacterType& type, TypeResources& out);
  Status create_shadow();
  Status create_graphics_pipeline(VkRenderPass pass, bool shadow, uint32_t encoding,
                                  VkPipeline& out, uint32_t mode = kModeCrowd);
  // Creates `pipelines[e]` for every encoding e a type uses.
  Status create_pipelines(VkRenderPass pass, bool shadow, VkPipeline (&pipelines)[kEncodings],
                          uint32_t mode = kModeCrowd);
  Status color_pipeline(const HostTarget& target, ColorPipeline*& out);
  void write_frame_set();
  // One type's draw (pipeline and sets bound): the corner path or the instanced levels.
  void record_type_draw(VkCommandBuffer cmd, const TypeDraw& draw) const {
    const DrawPush push{draw.corner_base, 0};
    vkCmdPushConstants(cmd, pipeline_layout,
                       VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(push),
                       &push);
    if (!draw.instanced) {
      vkCmdDrawIndirect(cmd, draw.args, draw.args_offset, 1, sizeof(VkDrawIndirectCommand));
      return;
    }
    vkCmdBindIndexBuffer(cmd, draw.index_buffer, 0, VK_INDEX_TYPE_UINT32);
    const uint32_t stride = sizeof(VkDrawIndexedIndirectCommand);
    if (context->features().multi_draw_indirect) {
      vkCmdDrawIndexedIndirect(cmd, draw.indexed_args, draw.indexed_offset, draw.indexed_count,
                               stride);
      return;
    }
    for (uint32_t k = 0; k < draw.indexed_count; ++k)
      vkCmdDrawIndexedIndirect(cmd, draw.indexed_args,
                               draw.indexed_offset + VkDeviceSize{k} * stride, 1, stride);
  }
  Status create_skin_pass();
  // encoding: null for a shader without specialization constants.
  Status create_compute_pipeline(VkShaderModule module, const uint32_t* encoding, VkPipeline& out,
                                 uint32_t use_palette = 0);
  void write_skin_set();
  void write_type_set(const TypeResources& t);
};

Status CrowdDraw::Impl::create_layouts() {
  VkDevice d = context->device();
  const VkShaderStageFlags all = VK_SHADER_STAGE_ALL_GRAPHICS | VK_SHADER_STAGE_COMPUTE_BIT;
  const VkDescriptorSetLayoutBinding frame_bindings[] = {
      {0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
      {4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
      {5, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {7, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
  };
  const VkDescriptorSetLayoutBinding type_bindings[] = {
      {0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
  };
  VkDescriptorSetLayoutCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  info.bindingCount = 8;
  info.pBindings = frame_bindings;
  if (Status s = check(vkCreateDescriptorSetLayout(d, &info, nullptr, &frame_layout),
                       "vkCreateDescriptorSetLayout");
      !s)
    return s;
  info.bindingCount = 5;
  info.pBindings = type_bindings;
  if (Status s = check(vkCreateDescriptorSetLayout(d, &info, nullptr, &type_layout),
                       "vkCreateDescriptorSetLayout");
      !s)
    return s;
  const VkDescriptorSetLayout layouts[] = {frame_layout, type_layout};
  const VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                                 sizeof(DrawPush)};
  VkPipelineLayoutCreateInfo layout_info{};
  layout_info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  layout_info.setLayoutCount = 2;
  layout_info.pSetLayouts = layouts;
  layout_info.pushConstantRangeCount = 1;
  layout_info.pPushConstantRanges = &push;
  if (Status s = check(vkCreatePipelineLayout(d, &layout_info, nullptr, &pipeline_layout),
                       "vkCreatePipelineLayout");
      !s)
    return s;

  const uint32_t type_count = static_cast<uint32_t>(std::max<size_t>(types.size(), 1));
  const VkDescriptorPoolSize sizes[] = {
      {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 6 + 4 * type_count + 8},
      {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2 + type_count},
  };
  VkDescriptorPoolCreateInfo pool_info{};
  pool_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  pool_info.maxSets = 2 + type_count;
  pool_info.poolSizeCount = 2;
  pool_info.pPoolSizes = sizes;
  if (Status s =
          check(vkCreateDescriptorPool(d, &pool_info, nullptr, &pool), "vkCreateDescriptorPool");
      !s)
    return s;
  VkDescriptorSetAllocateInfo alloc{};
  alloc.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  alloc.descriptorPool = pool;
  alloc.descriptorSetCount = 1;
  alloc.pSetLayouts = &frame_layout;
  if (Status s = check(vkAllocateDescriptorSets(d, &alloc, &frame_set), "vkAllocateDescriptorSets");
      !s)
    return s;
  alloc.pSetLayouts = &type_layout;
  for (TypeResources& t : types)
    if (Status s = check(vkAllocateDescriptorSets(d, &alloc, &t.set), "vkAllocateDescriptorSets");
        !s)
      return s;
  return {};
}

Status CrowdDraw::Impl::create_samplers() {
  VkDevice d = context->device();
  VkSamplerCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO;
  info.magFilter = info.minFilter = VK_FILTER_LINEAR;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
  info.maxLod = 0.0f;
  if (Status s = check(vkCreateSampler(d, &info, nullptr, &swatch_sampler), "vkCreateSampler"); !s)
    return s;
  info.magFilter = info.minFilter = VK_FILTER_NEAREST;
  info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  if (Status s = check(vkCreateSampler(d, &info, nullptr, &mask_sampler), "vkCreateSampler"); !s)
    return s;
  // note: linear filtering of a compare sampler gives 2x2 percentage-closer filtering.
  info.magFilter = info.minFilter = VK_FILTER_LINEAR;
  info.addressModeU = info.addressModeV = info.addressModeW =
      VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
  info.borderColor = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
  info.compareEnable = VK_TRUE;
  info.compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
  return check(vkCreateSampler(d, &info, nullptr, &shadow_sampler), "vkCreateSampler");
}

Status CrowdDraw::Impl::upload_image(GpuImage& image, const void* data, VkDeviceSize bytes) {
  GpuBuffer staging;
  if (Status s = GpuBuffer::create(*context, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                   MemoryKind::kHostVisible, staging);
      !s)
    return s;
  if (Status s = staging.upload(data, bytes); !s) return s;
  const ImageDesc& desc = image.desc();
  return context->submit_and_wait([&](VkCommandBuffer cmd) {
    transition_image(cmd, image.image(), desc.aspect, VK_IMAGE_LAYOUT_UNDEFINED,
                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {desc.aspect, 0, 0, desc.layers};
    copy.imageExtent = {desc.width, desc.height, 1};
    vkCmdCopyBufferToImage(cmd, staging.buffer(), image.image(),
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
    transition_image(cmd, image.image(), desc.aspect, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  });
}

Status CrowdDraw::Impl::create_type(const CharacterType& type, TypeResources& out) {
  const Pack& pack = type.pack;
  if (!pack.has(kPackGeometry) || !pack.has(kPackAnimation))
    return {StatusCode::kNotLoaded,
            "character type '" + type.name +
                "': the GPU path needs its pack's geometry and animation loaded"};
  const PackContents& c = pack.contents();
  const AnimationTexture& anim = c.animation;
  std::string why;
  if (!check_animation_texture(anim, &why))
    return {StatusCode::kInvalidPack,
            "character type '" + type.name + "': animation texture: " + why};

  TypeConstants k{};
  k.anim_layout[0] = static_cast<uint32_t>(anim.encoding);
  k.anim_layout[1] = anim.joints;
  k.anim_layout[2] = anim.texels_per_joint;
  k.anim_layout[3] = anim.bytes_per_texel;
  for (size_t i = 0; i < 4 && i < anim.decode_params.size(); ++i)
    k.decode_center[i] = anim.decode_params[i];
  for (size_t i = 4; i < 8 && i < anim.decode_params.size(); ++i)
    k.decode_half[i - 4] = anim.decode_params[i];
  const PartitionMask& mask = c.partition;
  for (int i = 0; i < 3; ++i) k.up_neck[i] = mask.up_axis[i];
  k.up_neck[3] = mask.neck_height;
  k.waist_mask[0] = mask.waist_height;
  const bool has_mask = pack.has(kPackPartition) && mask.width > 0 && mask.height > 0 &&
                        mask.texels.size() == static_cast<size_t>(mask.width) * mask.height;
  k.waist_mask[1] = has_mask ? static_cast<float>(mask.width) : 0.0f;
  k.waist_mask[2] = has_mask ? static_cast<float>(mask.height) : 0.0f;
  k.variants[0] = type.texture_variants.head;
  k.variants[1] = type.texture_variants.upper_body;
  k.variants[2] = type.texture_variants.trousers;
  k.variants[3] = swatches_per_region;

  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  if (Status s = GpuBuffer::create(*context, sizeof(k), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                   MemoryKind::kHostVisible, out.constants);
      !s)
    return s;
  if (Status s = out.constants.upload(&k, sizeof(k)); !s) return s;

  const std::vector<GpuVertex> vertices = make_gpu_vertices(c);
  out.vertex_count = static_cast<uint32_t>(vertices.size());
  out.joints = anim.joints;
  out.encoding = static_cast<uint32_t>(anim.encoding);
  const VkDeviceSize vertex_bytes = std::max<VkDeviceSize>(vertices.size() * sizeof(GpuVertex), 64);
  if (Status s = GpuBuffer::create(*context, vertex_bytes, storage, MemoryKind::kDeviceLocal,
                                   out.vertices);
      !s)
    return s;
  if (!vertices.empty())
    if (Status s = out.vertices.upload(vertices.data(), vertices.size() * sizeof(GpuVertex)); !s)
      return s;

  // note: the texture is uploaded byte for byte; skin.glsl reads it as little-endian words.
  const VkDeviceSize anim_bytes = std::max<VkDeviceSize>((anim.data.size() + 3) / 4 * 4, 16);
  if (anim_bytes > context->limits().maxStorageBufferRange)
    return {StatusCode::kInvalidArgument, "character type '" + type.name +
                                              "': animation texture of " +
                                              std::to_string(anim.data.size()) +
                                              " bytes exceeds the device's storage buffer range"};
  if (Status s =
          GpuBuffer::create(*context, anim_bytes, storage, MemoryKind::kDeviceLocal, out.animation);
      !s)
    return s;
  if (!anim.data.empty())
    if (Status s = out.animation.upload(anim.data.data(), anim.data.size()); !s) return s;

  if (Status s = GpuBuffer::create(*context, 48, storage, MemoryKind::kHostVisible, out.poses); !s)
    return s;

  ImageDesc mask_desc;
  mask_desc.width = has_mask ? mask.width : 1;
  mask_desc.height = has_mask ? mask.height : 1;
  mask_desc.format = VK_FORMAT_R8_UINT;
  if (Status s = GpuImage::create(*context, mask_desc, out.mask); !s) return s;
  const uint8_t unused = 255;
  return has_mask ? upload_image(out.mask, mask.texels.data(), mask.texels.size())
                  : upload_image(out.mask, &unused, 1);
}

Status CrowdDraw::Impl::create_pipelines(VkRenderPass pass, bool shadow,
                                         VkPipeline (&pipelines)[kEncodings], uint32_t mode) {
  for (const TypeResources& t : types)
    if (pipelines[t.encoding] == VK_NULL_HANDLE)
      if (Status s =
              create_graphics_pipeline(pass, shadow, t.encoding, pipelines[t.encoding], mode);
          !s)
        return s;
  return {};
}

Status CrowdDraw::Impl::create_graphics_pipeline(VkRenderPass pass, bool shadow, uint32_t encoding,
                                                 VkPipeline& out, uint32_t mode) {
  // Specialization constants: 0 = the animation encoding, 1 = what is drawn (kMode*).
  const uint32_t spec[2] = {encoding, mode};
  const VkSpecializationMapEntry entries[2] = {{0, 0, sizeof(uint32_t)},
                                               {1, sizeof(uint32_t), sizeof(uint32_t)}};
  VkSpecializationInfo specialization{};
  specialization.mapEntryCount = 2;
  specialization.pMapEntries = entries;
  specialization.dataSize = sizeof(spec);
  specialization.pData = spec;
  VkPipelineShaderStageCreateInfo stages[2] = {};
  stages[0].sType = stages[1].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = shadow ? shadow_vert : crowd_vert;
  stages[0].pName = stages[1].pName = "main";
  stages[0].pSpecializationInfo = stages[1].pSpecializationInfo = &specialization;
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = crowd_frag;

  VkPipelineVertexInputStateCreateInfo vertex_input{};

  vertex_input.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
  VkPipelineInputAssemblyStateCreateInfo assembly{};
  assembly.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo viewport{};
  viewport.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
  viewport.viewportCount = viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{};
  raster.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  // note: packs promise neither a winding nor closed meshes: draw both sides.
  raster.cullMode = VK_CULL_MODE_NONE;
  raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  raster.lineWidth = 1.0f;
  if (shadow) {
    raster.depthBiasEnable = VK_TRUE;
    raster.depthBiasConstantFactor = 1.0f;
    raster.depthBiasSlopeFactor = 1.5f;
  }
  VkPipelineMultisampleStateCreateInfo multisample{};
  multisample.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo depth{};
  depth.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
  depth.depthTestEnable = depth.depthWriteEnable = VK_TRUE;
  depth.depthCompareOp = VK_COMPARE_OP_LESS;
  VkPipelineColorBlendAttachmentState blend_attachment{};
  blend_attachment.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                                    VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  VkPipelineColorBlendStateCreateInfo blend{};
  blend.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
  blend.attachmentCount = shadow ? 0 : 1;
  blend.pAttachments = &blend_attachment;
  const VkDynamicState dynamic_states[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{};
  dynamic.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO;
  dynamic.dynamicStateCount = 2;
  dynamic.pDynamicStates = dynamic_states;

  VkGraphicsPipelineCreateInfo info{};

  info.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
  info.stageCount = shadow ? 1 : 2;  // note: depth-only: no fragment shader at all
  info.pStages = stages;
  info.pVertexInputState = &vertex_input;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &blend;
  info.pDynamicState = &dynamic;
  info.layout = pipeline_layout;
  info.renderPass = pass;
  return check(
      vkCreateGraphicsPipelines(context->device(), VK_NULL_HANDLE, 1, &info, nullptr, &out),
      "vkCreateGraphicsPipelines");
}

Status CrowdDraw::Impl::create_shadow() {
  shadow_size = settings.shadows ? std::max<uint32_t>(settings.shadow_map_size, 1) : 1;
  ImageDesc desc;
  desc.width = desc.height = shadow_size;
  desc.format = VK_FORMAT_D32_SFLOAT;
  desc.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  desc.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
  if (Status s = GpuImage::create(*context, desc, shadow_map); !s) return s;
  if (!settings.shadows) {
    // note: the colour pass still binds the (1x1, never drawn) map; give it a valid layout.
    return context->submit_and_wait([&](VkCommandBuffer cmd) {
      transition_image(cmd, shadow_map.image(), VK_IMAGE_ASPECT_DEPTH_BIT,
                       VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    });
  }
  VkAttachmentDescription attachment{};
  attachment.format = VK_FORMAT_D32_SFLOAT;
  attachment.samples = VK_SAMPLE_COUNT_1_BIT;
  attachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  attachment.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  attachment.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  attachment.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  attachment.finalLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  const VkAttachmentReference depth_ref{0, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.pDepthStencilAttachment = &depth_ref;
  VkSubpassDependency deps[2] = {};
  deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  deps[0].dstSubpass = 0;
  deps[0].srcStageMask = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
  deps[0].dstStageMask =
      VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  deps[0].srcAccessMask = VK_ACCESS_SHADER_READ_BIT;
  deps[0].dstAccessMask =
      VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  deps[1].srcSubpass = 0;
  deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  deps[1].srcStageMask = VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  deps[1].dstStageMask = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
  deps[1].srcAccessMask = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  deps[1].dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
  VkRenderPassCreateInfo pass_info{};
  pass_info.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
  pass_info.attachmentCount = 1;
  pass_info.pAttachments = &attachment;
  pass_info.subpassCount = 1;
  pass_info.pSubpasses = &subpass;
  pass_info.dependencyCount = 2;
  pass_info.pDependencies = deps;
  VkDevice d = context->device();
  if (Status s =
          check(vkCreateRenderPass(d, &pass_info, nullptr, &shadow_pass), "vkCreateRenderPass");
      !s)
    return s;
  const VkImageView view = shadow_map.view();
  VkFramebufferCreateInfo fb{};
  fb.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
  fb.renderPass = shadow_pass;
  fb.attachmentCount = 1;
  fb.pAttachments = &view;
  fb.width = fb.height = shadow_size;
  fb.layers = 1;
  if (Status s =
          check(vkCreateFramebuffer(d, &fb, nullptr, &shadow_framebuffer), "vkCreateFramebuffer");
      !s)
    return s;
  return create_pipelines(shadow_pass, true, shadow_pipelines);
}

Status CrowdDraw::Impl::color_pipeline(const HostTarget& target, ColorPipeline*& out) {
  const auto key = std::make_tuple(target.color_format, target.depth_format,
                                   target.color_final_layout, target.clear);
  auto found = color_pipelines.find(key);
  if (found != color_pipelines.end()) {
    out = &found->second;
    return {};
  }
  VkAttachmentDescription attachments[2] = {};
  attachments[0].format = target.color_format;
  attachments[0].samples = VK_SAMPLE_COUNT_1_BIT;
  attachments[0].loadOp = target.clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
  attachments[0].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  attachments[0].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  attachments[0].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  attachments[0].initialLayout =
      target.clear ? VK_IMAGE_LAYOUT_UNDEFINED : VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  attachments[0].finalLayout = target.color_final_layout;
  attachments[1] = attachments[0];
  attachments[1].format = target.depth_format;
  // note: a host drawing over its own scene may want the crowd's depth afterwards.
  attachments[1].storeOp =
      target.clear ? VK_ATTACHMENT_STORE_OP_DONT_CARE : VK_ATTACHMENT_STORE_OP_STORE;
  attachments[1].initialLayout =
      target.clear ? VK_IMAGE_LAYOUT_UNDEFINED : VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
  attachments[1].finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
  const VkAttachmentReference color_ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  const VkAttachmentReference depth_ref{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &color_ref;
  subpass.pDepthStencilAttachment = &depth_ref;
  VkSubpassDependency deps[2] = {};
  deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  deps[0].dstSubpass = 0;
  deps[0].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                         VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
  deps[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                         VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                         VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  deps[0].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                          VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                          VK_ACCESS_TRANSFER_READ_BIT;
  deps[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                          VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                          VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  deps[1].srcSubpass = 0;
  deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  deps[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  deps[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
  deps[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  deps[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_SHADER_READ_BIT;
  VkRenderPassCreateInfo pass_info{};
  pass_info.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
  pass_info.attachmentCount = 2;
  pass_info.pAttachments = attachments;
  pass_info.subpassCount = 1;
  pass_info.pSubpasses = &subpass;
  pass_info.dependencyCount = 2;
  pass_info.pDependencies = deps;
  ColorPipeline p;
  if (Status s = check(vkCreateRenderPass(context->device(), &pass_info, nullptr, &p.render_pass),
                       "vkCreateRenderPass");
      !s)
    return s;
  Status s = create_pipelines(p.render_pass, false, p.pipelines);
  if (s.ok() && settings.ground && !types.empty())
    s = create_graphics_pipeline(p.render_pass, false, types[0].encoding, p.ground, kModeGround);
  if (!s) {
    for (VkPipeline pipeline : p.pipelines) vkDestroyPipeline(context->device(), pipeline, nullptr);
    vkDestroyPipeline(context->device(), p.ground, nullptr);
    vkDestroyRenderPass(context->device(), p.render_pass, nullptr);
    return s;
  }
  out = &color_pipelines.emplace(key, p).first->second;
  return {};
}

void CrowdDraw::Impl::write_frame_set() {
  const VkDescriptorBufferInfo instances{bound_instances, 0, VK_WHOLE_SIZE};
  const VkDescriptorBufferInfo corners{bound_corners, 0, VK_WHOLE_SIZE};
  const VkDescriptorBufferInfo frame = frame_buffer.descriptor();
  const VkDescriptorImageInfo shadow{shadow_sampler, shadow_map.view(),
                                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  const VkDescriptorImageInfo swatch{swatch_sampler, swatches.view(),
                                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  const VkDescriptorBufferInfo base_info = skin_base.descriptor();
  const VkDescriptorBufferInfo skinned_info = skinned.descriptor();
  const VkDescriptorBufferInfo list_info{bound_instance_list, 0, VK_WHOLE_SIZE};
  VkWriteDescriptorSet writes[8] = {};
  for (uint32_t b = 0; b < 8; ++b) {
    writes[b].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    writes[b].dstSet = frame_set;
    writes[b].dstBinding = b;
    writes[b].descriptorCount = 1;
  }
  writes[0].descriptorType = writes[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  writes[0].pBufferInfo = &instances;
  writes[1].pBufferInfo = &corners;
  writes[2].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  writes[2].pBufferInfo = &frame;
  writes[3].descriptorType = writes[4].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  writes[3].pImageInfo = &shadow;
  writes[4].pImageInfo = &swatch;
  writes[5].descriptorType = writes[6].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  writes[5].pBufferInfo = &base_info;
  writes[6].pBufferInfo = &skinned_info;
  writes[7].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  writes[7].pBufferInfo = &list_info;
  vkUpdateDescriptorSets(context->device(), 8, writes, 0, nullptr);
}

void CrowdDraw::Impl::write_skin_set() {
  const VkDescriptorBufferInfo buffers[8] = {{bound_instances, 0, VK_WHOLE_SIZE},
                                             {bound_lods, 0, VK_WHOLE_SIZE},
                                             type_args.descriptor(),
                                             skin_list.descriptor(),
                                             skin_base.descriptor(),
                                             skin_params.descriptor(),
                                             skinned.descriptor(),
                                             palette.descriptor()};
  VkWriteDescriptorSet writes[8] = {};
  for (uint32_t b = 0; b < 8; ++b) {
    writes[b].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    writes[b].dstSet = skin_set;
    writes[b].dstBinding = b;
    writes[b].descriptorCount = 1;
    writes[b].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[b].pBufferInfo = &buffers[b];
  }
  vkUpdateDescriptorSets(context->device(), 8, writes, 0, nullptr);
}

Status CrowdDraw::Impl::create_compute_pipeline(VkShaderModule module, const uint32_t* encoding,
                                                VkPipeline& out, uint32_t use_palette) {
  // Specialization constants 0 (encoding) and 2 (palette) of skin.glsl / skin_pass.comp.
  const uint32_t spec[2] = {encoding ? *encoding : 0u, use_palette};
  const VkSpecializationMapEntry entries[2] = {{0, 0, sizeof(uint32_t)},
                                               {2, sizeof(uint32_t), sizeof(uint32_t)}};
  VkSpecializationInfo specialization{};
  specialization.mapEntryCount = 2;
  specialization.pMapEntries = entries;
  specialization.dataSize = sizeof(spec);
  specialization.pData = spec;
  VkComputePipelineCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
  info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module;
  info.stage.pName = "main";
  info.stage.pSpecializationInfo = encoding ? &specialization : nullptr;
  info.layout = skin_pipeline_layout;
  return check(vkCreateComputePipelines(context->device(), VK_NULL_HANDLE, 1, &info, nullptr, &out),
               "vkCreateComputePipelines");
}

Status CrowdDraw::Impl::create_skin_pass() {
  VkDevice d = context->device();
  VkDescriptorSetLayoutBinding bindings[8] = {};
  for (uint32_t b = 0; b < 8; ++b)
    bindings[b] = {b, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
  VkDescriptorSetLayoutCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
  info.bindingCount = 8;
  info.pBindings = bindings;
  if (Status s = check(vkCreateDescriptorSetLayout(d, &info, nullptr, &skin_layout),
                       "vkCreateDescriptorSetLayout");
      !s)
    return s;
  const VkDescriptorSetLayout layouts[2] = {skin_layout, type_layout};
  const VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(uint32_t)};
  VkPipelineLayoutCreateInfo layout_info{};
  layout_info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
  layout_info.setLayoutCount = 2;
  layout_info.pSetLayouts = layouts;
  layout_info.pushConstantRangeCount = 1;
  layout_info.pPushConstantRanges = &push;
  if (Status s = check(vkCreatePipelineLayout(d, &layout_info, nullptr, &skin_pipeline_layout),
                       "vkCreatePipelineLayout");
      !s)
    return s;
  VkDescriptorSetAllocateInfo alloc{};
  alloc.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
  alloc.descriptorPool = pool;
  alloc.descriptorSetCount = 1;
  alloc.pSetLayouts = &skin_layout;
  if (Status s = check(vkAllocateDescriptorSets(d, &alloc, &skin_set), "vkAllocateDescriptorSets");
      !s)
    return s;
  if (Status s = context->create_shader_module("skin_list.comp", skin_list_module); !s) return s;
  if (Status s = context->create_shader_module("skin_pass.comp", skin_pass_module); !s) return s;
  if (Status s = context->create_shader_module("skin_palette.comp", skin_palette_module); !s)
    return s;
  if (Status s = create_compute_pipeline(skin_list_module, nullptr, skin_list_pipeline); !s)
    return s;
  for (const TypeResources& t : types) {
    palette_stride = std::max(palette_stride, t.joints);
    if (skin_pipelines[t.encoding][1] == VK_NULL_HANDLE)
      if (Status s = create_compute_pipeline(skin_pass_module, &t.encoding,
                                             skin_pipelines[t.encoding][1], 1);
          !s)
        return s;
    if (palette_pipelines[t.encoding] == VK_NULL_HANDLE)
      if (Status s = create_compute_pipeline(skin_palette_module, &t.encoding,
                                             palette_pipelines[t.encoding]);
          !s)
        return s;
  }
  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  // note: one entry per type plus the totals (skin_list.comp).
  // note: per type, then the totals, then per type the palette pass's dispatch (skin_list.comp).
  const VkDeviceSize type_bytes = 16 * (2 * types.size() + 1);
  if (Status s = GpuBuffer::create(*context, 32 + 4 * types.size(), storage,
                                   MemoryKind::kHostVisible, skin_params);
      !s)
    return s;
  return GpuBuffer::create(*context, type_bytes, storage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                           MemoryKind::kDeviceLocal, type_args);
}

void CrowdDraw::Impl::write_type_set(const TypeResources& t) {
  const VkDescriptorBufferInfo buffers[4] = {t.constants.descriptor(), t.vertices.descriptor(),
                                             t.animation.descriptor(), t.poses.descriptor()};
  const VkDescriptorImageInfo mask{mask_sampler, t.mask.view(),
                                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkWriteDescriptorSet writes[5] = {};
  for (uint32_t b = 0; b < 5; ++b) {
    writes[b].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    writes[b].dstSet = t.set;
    writes[b].dstBinding = b;
    writes[b].descriptorCount = 1;
    writes[b].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    if (b < 4) writes[b].pBufferInfo = &buffers[b];
  }
  writes[4].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  writes[4].pImageInfo = &mask;
  vkUpdateDescriptorSets(context->device(), 5, writes, 0, nullptr);
}

// ---- CrowdDraw ---------------------------------------------------------------------------

CrowdDraw::CrowdDraw(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
CrowdDraw::~CrowdDraw() = default;

Status CrowdDraw::create(VulkanContext& context, const Scene& scene, const DrawSettings& settings,
                         std::unique_ptr<CrowdDraw>& out) {
  auto impl = std::make_unique<Impl>();
  impl->context = &context;
  impl->settings = settings;
  impl->types.resize(scene.types.size());
  uint32_t variants = 1;
  for (const CharacterType& t : scene.types)
    variants = std::max({variants, t.texture_variants.head, t.texture_variants.upper_body,
                         t.texture_variants.trousers});
  impl->swatches_per_region = std::min(variants, kMaxSwatchesPerRegion);

  if (Status s = impl->create_layouts(); !s) return s;
  if (Status s = impl->create_samplers(); !s) return s;
  if (Status s = context.create_shader_module("crowd.vert", impl->crowd_vert); !s) return s;
  if (Status s = context.create_shader_module("crowd.frag", impl->crowd_frag); !s) return s;
  if (Status s = context.create_shader_module("shadow.vert", impl->shadow_vert); !s) return s;
  for (size_t i = 0; i < scene.types.size(); ++i) {
    if (Status s = impl->create_type(scene.types[i], impl->types[i]); !s) return s;
    impl->write_type_set(impl->types[i]);
  }

  ImageDesc swatch_desc;
  swatch_desc.width = swatch_desc.height = kSwatchSize;
  swatch_desc.layers = kRegions * impl->swatches_per_region;
  if (Status s = GpuImage::create(context, swatch_desc, impl->swatches); !s) return s;
  const std::vector<uint8_t> swatches = make_swatches(impl->swatches_per_region);
  if (Status s = impl->upload_image(impl->swatches, swatches.data(), swatches.size()); !s) return s;

  if (Status s = impl->create_shadow(); !s) return s;
  if (Status s = impl->create_skin_pass(); !s) return s;
  if (Status s =
          GpuBuffer::create(context, sizeof(FrameConstants), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                            MemoryKind::kHostVisible, impl->frame_buffer);
      !s)
    return s;
  out.reset(new CrowdDraw(std::move(impl)));
  return {};
}

Status CrowdDraw::update(const Scene& scene, const FrameState& state, const EffectFrame* effects,
                         const CrowdCompute& compute) {
  Impl& m = *impl_;
  if (scene.types.size() != m.types.size())
    return {StatusCode::kInvalidArgument,
            "CrowdDraw::update: the scene has " + std::to_string(scene.types.size()) +
                " character types, the renderer was created for " + std::to_string(m.types.size())};
  const GpuBuffer& instances = compute.instance_buffer();
  const GpuBuffer& corners = compute.corner_buffer();
  const GpuBuffer& lods = compute.instance_lod_buffer();
  bool sets_dirty = false;
  // Skinned-vertex slots (skin_common.glsl): as many as the corner buffer has corners (a LoD
  // has fewer vertices than corners), capped by the device's storage buffer range; instances
  // finding no room are counted and not drawn.
  const uint32_t slots = static_cast<uint32_t>(
      std::max<uint64_t>(1, std::min<uint64_t>(compute.corner_capacity(),
                                               m.context->limits().maxStorageBufferRange / 16)));
  if (!m.skinned.valid() || slots != m.skin_capacity) {
    GpuBuffer buffer;
    if (Status s =
            GpuBuffer::create(*m.context, VkDeviceSize{slots} * 16,
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryKind::kDeviceLocal, buffer);
        !s)
      return s;
    m.skinned = std::move(buffer);
    m.skin_capacity = slots;
    sets_dirty = true;
  }
  m.instance_count = static_cast<uint32_t>(scene.instances.size());
  if (!m.skin_list.valid() || m.instance_count > m.list_stride) {
    const uint32_t stride = std::max<uint32_t>(m.instance_count, 1);
    GpuBuffer list, base;
    if (Status s = GpuBuffer::create(
            *m.context, VkDeviceSize{stride} * 4 * std::max<VkDeviceSize>(m.types.size(), 1),
            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryKind::kDeviceLocal, list);
        !s)
      return s;
    if (Status s =
            GpuBuffer::create(*m.context, VkDeviceSize{stride} * 4,
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryKind::kDeviceLocal, base);
        !s)
      return s;
    m.skin_list = std::move(list);
    m.skin_base = std::move(base);
    m.list_stride = stride;
    sets_dirty = true;
  }
  // The palette: every listed instance's joint matrices (48 bytes each), or, beyond the
  // storage buffer range, none (the skinning pass then decodes per influence).
  const uint64_t palette_bytes =
      uint64_t{m.list_stride} * std::max<size_t>(m.types.size(), 1) * m.palette_stride * 48;
  const bool palette_on =
      m.settings.joint_palette && palette_bytes <= m.context->limits().maxStorageBufferRange;
  const VkDeviceSize wanted = palette_on ? palette_bytes : 48;
  if (!m.palette.valid() || m.palette.size() < wanted || palette_on != m.palette_on) {
    GpuBuffer buffer;
    if (Status s = GpuBuffer::create(*m.context, wanted, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                     MemoryKind::kDeviceLocal, buffer);
        !s)
      return s;
    m.palette = std::move(buffer);
    m.palette_on = palette_on;
    sets_dirty = true;
  }
  if (!palette_on)
    for (const TypeResources& t : m.types)
      if (m.skin_pipelines[t.encoding][0] == VK_NULL_HANDLE)
        if (Status s = m.create_compute_pipeline(m.skin_pass_module, &t.encoding,
                                                 m.skin_pipelines[t.encoding][0], 0);
            !s)
          return s;
  std::vector<uint32_t> params = {m.instance_count,
                                  static_cast<uint32_t>(m.types.size()),
                                  m.list_stride,
                                  m.skin_capacity,
                                  compute.instanced() ? 1u : 0u,
                                  m.palette_stride,
                                  0,
                                  0};
  for (const TypeResources& t : m.types) params.push_back(t.joints);
  {
    // note: Σ n_i (selected) bounds Σ n'_i (slots taken); the GPU selection equals the CPU's.
    uint64_t selected = 0;
    for (uint32_t v : state.vertex_count) selected += v;
    m.skin_fallback = selected > m.skin_capacity;
    if (compute.instanced() && m.shadow_pass != VK_NULL_HANDLE)
      if (Status s = m.create_pipelines(m.shadow_pass, true, m.shadow_instanced[m.skin_fallback],
                                        m.skin_fallback ? kModeInstanced : kModeInstancedSlots);
          !s)
        return s;
  }
  if (Status s = m.skin_params.upload(params.data(), params.size() * 4); !s) return s;
  FrameConstants& k = m.constants;
  const View& view = state.view;
  float view_m[16], proj[16];
  view_matrix(view, view_m);
  projection_matrix(view, proj);
  multiply4(proj, view_m, k.view_proj);

  // The light box covers what the camera sees (the casters drawn are the visible instances).
  const size_t n = scene.instances.size();
  std::vector<float> spheres;
  spheres.reserve(4 * static_cast<size_t>(state.visible_count) + 4);
  for (size_t i = 0; i < n && 4 * i + 3 < state.spheres.size(); ++i)
    if (i < state.visible.size() && state.visible[i])
      spheres.insert(spheres.end(), &state.spheres[4 * i], &state.spheres[4 * i] + 4);
  // Ground: under every instance, at the lowest one's feet.
  float radius = 0.0f;
  for (const CharacterType& t : scene.types) radius = std::max(radius, t.pack.bounds_radius());
  float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (size_t i = 0; i < n; ++i) {
    const float* p = &scene.instances.position[3 * i];
    for (int a = 0; a < 3; ++a) {
      lo[a] = i == 0 ? p[a] : std::min(lo[a], p[a]);
      hi[a] = i == 0 ? p[a] : std::max(hi[a], p[a]);
    }
  }
  const float margin = 2.0f * radius;
  const bool ground = m.settings.ground && n > 0 && !m.types.empty();
  const float ground_min[4] = {lo[0] - margin, lo[1], lo[2] - margin, ground ? 1.0f : 0.0f};
  const float ground_max[4] = {hi[0] + margin, lo[1], hi[2] + margin, 0.0f};
  std::memcpy(k.ground_min, ground_min, sizeof(ground_min));
  std::memcpy(k.ground_max, ground_max, sizeof(ground_max));
  if (ground && spheres.empty()) {
    // note: with nothing visible the ground alone receives light; fit the box to it.
    const float c[3] = {(ground_min[0] + ground_max[0]) / 2, lo[1],
                        (ground_min[2] + ground_max[2]) / 2};
    const float r = std::hypot(ground_max[0] - c[0], ground_max[2] - c[2]);
    spheres = {c[0], c[1], c[2], r};
  }
  fit_light_view_proj(m.settings.light_direction, Span<const float>(spheres.data(), spheres.size()),
                      k.light_view_proj);

  float l[3] = {m.settings.light_direction[0], m.settings.light_direction[1],
                m.settings.light_direction[2]};
  normalize3(l);
  const bool shadows = m.settings.shadows && !spheres.empty();
  const float light_dir[4] = {l[0], l[1], l[2], shadows ? 1.0f : 0.0f};
  std::memcpy(k.light_dir, light_dir, sizeof(light_dir));
  // Depth bias of about two shadow texels of the box, in the map's 0..1 depth units.
  float box_width = 2.0f / std::max(std::hypot(k.light_view_proj[0], k.light_view_proj[4]), 1e-12f);
  float depth_range =
      1.0f / std::max(std::hypot(k.light_view_proj[2], k.light_view_proj[6]), 1e-12f);
  const float bias =
      std::min(0.01f, 2.0f * box_width / static_cast<float>(m.shadow_size) / depth_range);
  const float light_color[4] = {m.settings.light_color[0], m.settings.light_color[1],
                                m.settings.light_color[2], bias};
  std::memcpy(k.light_color, light_color, sizeof(light_color));
  const float ambient[4] = {m.settings.ambient[0], m.settings.ambient[1], m.settings.ambient[2],
                            1.0f};
  std::memcpy(k.ambient, ambient, sizeof(ambient));
  const float ground_color[4] = {m.settings.ground_color[0], m.settings.ground_color[1],
                                 m.settings.ground_color[2], 1.0f};
  std::memcpy(k.ground_color, ground_color, sizeof(ground_color));
  const float eye[4] = {view.eye[0], view.eye[1], view.eye[2], 1.0f};
  std::memcpy(k.eye, eye, sizeof(eye));
  k.skin[0] = m.skin_capacity;
  if (Status s = m.frame_buffer.upload(&k, sizeof(k)); !s) return s;

  // note: the shader indexes the pose buffer without bounds checks: refuse what would overrun.
  if (effects && effects->has_poses()) {
    if (effects->pose.size() != n)
      return {StatusCode::kInvalidArgument, "effects: pose array has " +
                                                std::to_string(effects->pose.size()) +
                                                " entries for " + std::to_string(n) + " instances"};
    for (size_t i = 0; i < n; ++i) {
      const uint32_t pose = effects->pose[i];
      if (pose == kNoPose) continue;
      const uint32_t t = scene.instances.type[i];
      const size_t floats = t < effects->pose_buffers.size() ? effects->pose_buffers[t].size() : 0;
      const size_t per_pose = 12 * static_cast<size_t>(t < m.types.size() ? m.types[t].joints : 0);
      if (per_pose == 0 || pose >= floats / per_pose)
        return {StatusCode::kInvalidArgument,
                "effects: instance " + std::to_string(i) + " takes pose " + std::to_string(pose) +
                    " but its type's pose buffer holds " +
                    std::to_string(per_pose ? floats / per_pose : 0) + " poses"};
    }
  }
  if (Status s = upload_poses(effects); !s) return s;

  const GpuBuffer& instance_list = compute.instance_list_buffer();
  if (sets_dirty || instances.buffer() != m.bound_instances ||
      corners.buffer() != m.bound_corners || lods.buffer() != m.bound_lods ||
      instance_list.buffer() != m.bound_instance_list) {
    m.bound_instances = instances.buffer();
    m.bound_corners = corners.buffer();
    m.bound_lods = lods.buffer();
    m.bound_instance_list = instance_list.valid() ? instance_list.buffer() : lods.buffer();
    m.write_frame_set();
    m.write_skin_set();
  }
  return {};
}

Status CrowdDraw::upload_poses(const EffectFrame* effects) {
  Impl& m = *impl_;
  // Pose buffers: only types some instance takes a pose of get one (a baked-only scene
  // uploads nothing here).
  for (size_t t = 0; t < m.types.size(); ++t) {
    TypeResources& type = m.types[t];
    const std::vector<float>* poses =
        effects && t < effects->pose_buffers.size() ? &effects->pose_buffers[t] : nullptr;
    if (!poses || poses->empty()) continue;
    const VkDeviceSize bytes = poses->size() * sizeof(float);
    if (bytes > type.poses.size()) {
      GpuBuffer grown;
      if (Status s = GpuBuffer::create(*m.context, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                       MemoryKind::kHostVisible, grown);
          !s)
        return s;
      type.poses = std::move(grown);
      m.write_type_set(type);
    }
    if (Status s = type.poses.upload(poses->data(), bytes); !s) return s;
  }

  return {};
}

Status CrowdDraw::read_skin_stats(uint32_t& slots_used, uint32_t& no_room) const {
  const Impl& m = *impl_;
  uint32_t totals[4] = {0, 0, 0, 0};
  if (Status s = m.type_args.download(totals, sizeof(totals), 16 * m.types.size()); !s) return s;
  slots_used = std::min(totals[0], m.skin_capacity);
  no_room = totals[1];
  return {};
}

void CrowdDraw::record_skinning(VkCommandBuffer cmd) {
  Impl& m = *impl_;
  const uint32_t types = static_cast<uint32_t>(m.types.size());
  if (types == 0 || m.skin_set == VK_NULL_HANDLE || m.bound_lods == VK_NULL_HANDLE) return;
  // note: the compute passes' outputs (LoD, corner offsets) feed the list pass.
  full_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
               VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT);
  std::vector<uint32_t> cleared(4 * (2 * static_cast<size_t>(types) + 1));
  for (uint32_t t = 0; t < types; ++t) {
    cleared[4 * t + 1] = cleared[4 * t + 2] = 1;
    cleared[4 * (types + 1 + t) + 1] = cleared[4 * (types + 1 + t) + 2] = 1;
  }
  // note: vkCmdUpdateBuffer takes at most 65536 bytes at a time.
  for (size_t first = 0; first < cleared.size(); first += 16384) {
    const size_t words = std::min<size_t>(16384, cleared.size() - first);
    vkCmdUpdateBuffer(cmd, m.type_args.buffer(), first * 4, words * 4, &cleared[first]);
  }
  full_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m.skin_pipeline_layout, 0, 1,
                          &m.skin_set, 0, nullptr);
  if (m.instance_count > 0) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m.skin_list_pipeline);
    vkCmdDispatch(cmd, std::min<uint32_t>((m.instance_count + 255) / 256, 65535), 1, 1);
  }
  full_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
               VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT);
  if (m.palette_on) {
    // One thread per (listed instance, joint), sized by the list pass.
    for (uint32_t t = 0; t < types; ++t) {
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE,
                        m.palette_pipelines[m.types[t].encoding]);
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m.skin_pipeline_layout, 1, 1,
                              &m.types[t].set, 0, nullptr);
      vkCmdPushConstants(cmd, m.skin_pipeline_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(t),
                         &t);
      vkCmdDispatchIndirect(cmd, m.type_args.buffer(), VkDeviceSize{types + 1 + t} * 16);
    }
    full_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
  }
  VkPipeline bound = VK_NULL_HANDLE;
  for (uint32_t t = 0; t < types; ++t) {
    const TypeResources& type = m.types[t];
    const VkPipeline pipeline = m.skin_pipelines[type.encoding][m.palette_on ? 1 : 0];
    if (pipeline != bound) {
      bound = pipeline;
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, bound);
    }
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m.skin_pipeline_layout, 1, 1,
                            &m.types[t].set, 0, nullptr);
    vkCmdPushConstants(cmd, m.skin_pipeline_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(t), &t);
    vkCmdDispatchIndirect(cmd, m.type_args.buffer(), VkDeviceSize{t} * 16);
  }
  full_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
               VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT);
}

void CrowdDraw::record_shadow(VkCommandBuffer cmd, Span<const TypeDraw> draws) {
  Impl& m = *impl_;
  if (!m.settings.shadows || m.shadow_pass == VK_NULL_HANDLE) return;
  VkClearValue clear{};
  clear.depthStencil = {1.0f, 0};
  VkRenderPassBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
  begin.renderPass = m.shadow_pass;
  begin.framebuffer = m.shadow_framebuffer;
  begin.renderArea.extent = {m.shadow_size, m.shadow_size};
  begin.clearValueCount = 1;
  begin.pClearValues = &clear;
  vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  const VkViewport viewport{0, 0, float(m.shadow_size), float(m.shadow_size), 0, 1};
  const VkRect2D scissor{{0, 0}, {m.shadow_size, m.shadow_size}};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m.pipeline_layout, 0, 1,
                          &m.frame_set, 0, nullptr);
  VkPipeline bound = VK_NULL_HANDLE;
  for (size_t t = 0; t < draws.size() && t < m.types.size(); ++t) {
    const uint32_t e = m.types[t].encoding;
    const VkPipeline pipeline =
        draws[t].instanced ? m.shadow_instanced[m.skin_fallback][e] : m.shadow_pipelines[e];
    if (pipeline == VK_NULL_HANDLE) continue;  // note: update() makes them before such frames
    if (pipeline != bound) {
      bound = pipeline;
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, bound);
    }
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m.pipeline_layout, 1, 1,
                            &m.types[t].set, 0, nullptr);
    m.record_type_draw(cmd, draws[t]);
  }
  vkCmdEndRenderPass(cmd);
}

Status CrowdDraw::prepare_target(const HostTarget& target) {
  ColorPipeline* pipeline = nullptr;
  return impl_->color_pipeline(target, pipeline);
}

Status CrowdDraw::record_color(VkCommandBuffer cmd, const HostTarget& target,
                               Span<const TypeDraw> draws) {
  Impl& m = *impl_;
  if (target.color_view == VK_NULL_HANDLE || target.depth_view == VK_NULL_HANDLE ||
      target.width == 0 || target.height == 0)
    return {StatusCode::kInvalidArgument,
            "render target: colour view, depth view and size are required"};
  ColorPipeline* pipeline = nullptr;
  if (Status s = m.color_pipeline(target, pipeline); !s) return s;
  const auto key = std::make_tuple(pipeline->render_pass, target.color_view, target.depth_view,
                                   target.width, target.height);
  VkFramebuffer framebuffer = VK_NULL_HANDLE;
  if (auto found = m.framebuffers.find(key); found != m.framebuffers.end()) {
    framebuffer = found->second;
  } else {
    const VkImageView views[2] = {target.color_view, target.depth_view};
    VkFramebufferCreateInfo fb{};
    fb.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
    fb.renderPass = pipeline->render_pass;
    fb.attachmentCount = 2;
    fb.pAttachments = views;
    fb.width = target.width;
    fb.height = target.height;
    fb.layers = 1;
    if (Status s = check(vkCreateFramebuffer(m.context->device(), &fb, nullptr, &framebuffer),
                         "vkCreateFramebuffer");
        !s)
      return s;
    m.framebuffers.emplace(key, framebuffer);
  }
  VkClearValue clears[2] = {};
  for (int c = 0; c < 4; ++c) clears[0].color.float32[c] = m.settings.clear_color[c];
  clears[1].depthStencil = {1.0f, 0};
  VkRenderPassBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
  begin.renderPass = pipeline->render_pass;
  begin.framebuffer = framebuffer;
  begin.renderArea.extent = {target.width, target.height};
  begin.clearValueCount = 2;
  begin.pClearValues = clears;
  vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  const VkViewport viewport{0, 0, float(target.width), float(target.height), 0, 1};
  const VkRect2D scissor{{0, 0}, {target.width, target.height}};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
  if (!m.types.empty()) {
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m.pipeline_layout, 0, 1,
                            &m.frame_set, 0, nullptr);
    const VkShaderStageFlags stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    VkPipeline bound = VK_NULL_HANDLE;
    for (size_t t = 0; t < draws.size() && t < m.types.size(); ++t) {
      const uint32_t e = m.types[t].encoding;
      VkPipeline& chosen =
          draws[t].instanced ? pipeline->instanced[m.skin_fallback][e] : pipeline->pipelines[e];
      if (chosen == VK_NULL_HANDLE)
        if (Status s =
                m.create_graphics_pipeline(pipeline->render_pass, false, e, chosen,
                                           m.skin_fallback ? kModeInstanced : kModeInstancedSlots);
            !s)
          return s;
      if (chosen != bound) {
        bound = chosen;
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, bound);
      }
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m.pipeline_layout, 1, 1,
                              &m.types[t].set, 0, nullptr);
      m.record_type_draw(cmd, draws[t]);
    }
    if (m.constants.ground_min[3] != 0.0f && pipeline->ground != VK_NULL_HANDLE) {
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline->ground);
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m.pipeline_layout, 1, 1,
                              &m.types[0].set, 0, nullptr);
      const DrawPush push{0, 0};
      vkCmdPushConstants(cmd, m.pipeline_layout, stages, 0, sizeof(push), &push);
      vkCmdDraw(cmd, 6, 1, 0, 0);
    }
  }
  vkCmdEndRenderPass(cmd);
  return {};
}

uint32_t CrowdDraw::type_count() const { return static_cast<uint32_t>(impl_->types.size()); }
VkDescriptorSetLayout CrowdDraw::type_set_layout() const { return impl_->type_layout; }
VkDescriptorSet CrowdDraw::type_set(uint32_t type) const { return impl_->types.at(type).set; }
uint32_t CrowdDraw::type_vertices(uint32_t type) const {
  return impl_->types.at(type).vertex_count;
}
uint32_t CrowdDraw::type_joints(uint32_t type) const { return impl_->types.at(type).joints; }
AnimationEncoding CrowdDraw::type_encoding(uint32_t type) const {
  return static_cast<AnimationEncoding>(impl_->types.at(type).encoding);
}
const FrameConstants& CrowdDraw::frame_constants() const { return impl_->constants; }
const DrawSettings& CrowdDraw::settings() const { return impl_->settings; }

}  // namespace crowdbake::runtime::gpu
