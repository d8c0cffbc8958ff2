// CrowdDraw's private state, shared by the files that make up its passes (private to
// runtime/gpu/): draw_resources.cpp (layouts, samplers, per-type buffers, descriptor sets),
// frame_constants.cpp, skin_pass.cpp, shadow_pass.cpp, color_pass.cpp and crowd_draw.cpp
// (create, per-frame update).
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <map>
#include <tuple>
#include <vector>

#include "crowdbake/runtime/gpu/crowd_compute.h"
#include "crowdbake/runtime/gpu/crowd_draw.h"
#include "crowdbake/runtime/gpu/gpu_buffer.h"
#include "crowdbake/runtime/gpu/vulkan_context.h"
#include "crowdbake/runtime/static_geometry.h"

namespace crowdbake::runtime::gpu {

// Draw push constants (crowd_frame.glsl DrawPush).
struct DrawPush {
  uint32_t corner_base = 0;
  uint32_t unused = 0;
};

// Swatch regions (head, upper body, trousers) of the generated texture array.
constexpr uint32_t kSwatchRegions = 3;

// kSwatchRegions * per_region layers of kSwatchSize² RGBA8 texels (swatches.cpp).
std::vector<uint8_t> make_swatches(uint32_t per_region);

// Small vector maths (frame_constants.cpp).
void normalize3(float v[3]);
// out = a · b, 4x4 column-major.
void multiply4(const float a[16], const float b[16], float out[16]);

struct TypeResources {
  GpuBuffer constants, vertices, animation, poses, morphs, materials;
  GpuBuffer colors;    // the pack's vertex colours (VCOL), or one white
  GpuBuffer impostor;  // GpuImpostorHeader, frames of rows, texels (impostor.glsl); a header
                       // of zeros for a type without one
  uint32_t impostor_first = 0, impostor_count = 0;  // this frame: its run of the impostor list
  GpuImage mask, images;
  VkDescriptorSet set = VK_NULL_HANDLE;
  uint32_t vertex_count = 0, joints = 0;
  uint32_t encoding = 0;  // AnimationEncoding
};

constexpr uint32_t kEncodings = 3;  // AnimationEncoding values: one pipeline each
                                    // (skin.glsl)

struct ColorPipeline {
  VkRenderPass render_pass = VK_NULL_HANDLE;
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
  VkPipeline pipelines[kEncodings] = {};  // only the encodings the scene's types use
  // Instanced static levels, made when a frame first draws them: [0] every instance has
  // skinned slots, [1] the vertex shader skins instances without (slower on lavapipe).
  VkPipeline instanced[2][kEncodings] = {};
  VkPipeline ground = VK_NULL_HANDLE;
  VkPipeline static_geometry = VK_NULL_HANDLE;  // made when the scene has static geometry
  VkPipeline impostor = VK_NULL_HANDLE;         // made when some type has an impostor
};

// Pipeline kinds (crowd_frame.glsl kDrawMode).
constexpr uint32_t kModeCrowd = 0, kModeGround = 1, kModeInstanced = 2, kModeInstancedSlots = 3,
                   kModeStatic = 4, kModeImpostor = 5;

// The head of a type's impostor buffer (shaders/impostor.glsl ImpostorBlock), std430.
struct GpuImpostorHeader {
  uint32_t shape[4];  // views, frames, width, height (views 0: none)
  float rect[4];      // half width, bottom, top, unused
  float up[4], across[4], centre[4];
  // words before the cells' bounds (= animation rows, each row's frame first), before the texels
  uint32_t offsets[4];
};

struct CrowdDraw::Impl {
  VulkanContext* context = nullptr;
  DrawSettings settings;
  FrameConstants constants{};

  VkDescriptorSetLayout frame_layout = VK_NULL_HANDLE, type_layout = VK_NULL_HANDLE;
  VkPipelineLayout pipeline_layout = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VkDescriptorSet frame_set = VK_NULL_HANDLE;
  VkSampler swatch_sampler = VK_NULL_HANDLE, mask_sampler = VK_NULL_HANDLE,
            shadow_sampler = VK_NULL_HANDLE, material_sampler = VK_NULL_HANDLE;
  VkShaderModule crowd_vert = VK_NULL_HANDLE, crowd_frag = VK_NULL_HANDLE,
                 shadow_vert = VK_NULL_HANDLE;

  GpuBuffer frame_buffer;
  GpuImage swatches, shadow_map;
  VkRenderPass shadow_pass = VK_NULL_HANDLE;
  VkFramebuffer shadow_framebuffer = VK_NULL_HANDLE;
  VkPipeline shadow_pipelines[kEncodings] = {};
  VkPipeline shadow_instanced[2][kEncodings] = {};
  VkPipeline shadow_static = VK_NULL_HANDLE;
  GpuBuffer impostor_list;    // impostor_draw.cpp: this frame's impostor instances by type
  bool any_impostor = false;  // some type has an impostor
  GpuBuffer static_vertices;  // static_draw.cpp
  uint32_t static_vertex_count = 0;
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

  std::map<std::tuple<VkFormat, VkFormat, VkImageLayout, bool, VkSampleCountFlagBits>,
           ColorPipeline>
      color_pipelines;
  std::map<std::tuple<VkRenderPass, VkImageView, VkImageView, VkImageView, uint32_t, uint32_t>,
           VkFramebuffer>
      framebuffers;

  ~Impl();

  // frame_constants.cpp: `constants` for this frame, uploaded to frame_buffer.
  Status update_frame_constants(const Scene& scene, const FrameState& state);

  // draw_resources.cpp
  Status create_layouts();
  Status create_samplers();
  // `data`: every layer of level 0, then every layer of level 1, ...; level_offsets[l] is
  // where level l starts (empty: one level at 0).
  Status upload_image(GpuImage& image, const void* data, VkDeviceSize bytes,
                      Span<const VkDeviceSize> level_offsets = {});
  Status create_type(const CharacterType& type, TypeResources& out);
  Status create_swatches();
  void write_frame_set();
  void write_type_set(const TypeResources& t);

  // shadow_pass.cpp
  Status create_shadow();

  // static_draw.cpp: the scene's static geometry, uploaded once; drawn with `pipeline` (the
  // colour or shadow pass's kModeStatic one).
  Status create_static_geometry(const StaticGeometry& geometry);
  void record_static(VkCommandBuffer cmd, VkPipeline pipeline) const;

  // impostor_draw.cpp: a type's impostor buffer; this frame's impostor list (sets_dirty when
  // it was replaced); the impostor draws (pipeline bound, frame set bound).
  Status create_impostor(const PackContents& pack, TypeResources& out);
  Status update_impostors(const Scene& scene, const FrameState& state, bool& sets_dirty);
  void record_impostors(VkCommandBuffer cmd, VkPipeline pipeline) const;

  // color_pass.cpp
  Status create_graphics_pipeline(VkRenderPass pass, bool shadow, uint32_t encoding,
                                  VkPipeline& out, uint32_t mode = kModeCrowd,
                                  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT);
  // Creates `pipelines[e]` for every encoding e a type uses.
  Status create_pipelines(VkRenderPass pass, bool shadow, VkPipeline (&pipelines)[kEncodings],
                          uint32_t mode = kModeCrowd,
                          VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT);
  Status color_pipeline(const HostTarget& target, ColorPipeline*& out);
  Status framebuffer(const HostTarget& target, VkRenderPass pass, VkFramebuffer& out);
  // Binds each type's set and pipeline (from `pipelines`, or `instanced` for instanced draws)
  // and records its draw; the frame set is bound already. A missing instanced pipeline is made
  // for `pass` (kModeInstanced*), or, with pass null, the type is skipped.
  Status record_type_draws(VkCommandBuffer cmd, Span<const TypeDraw> draws, VkRenderPass pass,
                           VkPipeline (&pipelines)[kEncodings], VkPipeline (&instanced)[kEncodings],
                           VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT);
  // One type's draw (pipeline and sets bound): the corner path or the instanced levels.
  void record_type_draw(VkCommandBuffer cmd, const TypeDraw& draw) const;

  // skin_pass.cpp
  Status create_skin_pass();
  // encoding: null for a shader without specialization constants.
  Status create_compute_pipeline(VkShaderModule module, const uint32_t* encoding, VkPipeline& out,
                                 uint32_t use_palette = 0);
  // Per frame: sizes the skinned-vertex slots, instance lists and palette for this scene and
  // uploads the pass's parameters; sets_dirty when a buffer was replaced.
  Status update_skin_pass(const Scene& scene, const FrameState& state, const CrowdCompute& compute,
                          bool& sets_dirty);
  void write_skin_set();
};

}  // namespace crowdbake::runtime::gpu
