// CrowdDraw: the graphics side of the GPU crowd path. Per character type it keeps the pack's
// bind-pose vertices, its animation texture (the raw bytes, decoded by shaders/skin.glsl
// exactly as formats/animation_codec.h), its partition mask, its materials and their images
// (gpu_materials.cpp) and a pose buffer; per frame it
// records the directional shadow-map pass and the colour pass, each ONE vkCmdDrawIndirect per
// character type over the corner buffer that CrowdCompute wrote (never one draw per instance:
// software Vulkan pays per draw), plus one draw for the ground under the crowd.
//
// Descriptor sets (shaders/crowd_frame.glsl, shaders/skin.glsl): set 0 = the frame (instances,
// corners, FrameConstants, shadow map, swatches), set 1 = the type (TypeConstants, vertices,
// animation words, pose buffer, partition mask, geomorph table, materials, material images).
#pragma once

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "crowdbake/runtime/cpu_reference.h"
#include "crowdbake/runtime/effect_frame.h"
#include "crowdbake/runtime/gpu/gpu_buffer.h"
#include "crowdbake/runtime/gpu/vulkan_context.h"
#include "crowdbake/runtime/scene.h"
#include "crowdbake/runtime/span.h"
#include "crowdbake/runtime/status.h"

namespace crowdbake::runtime::gpu {

class CrowdCompute;

// Light, shadow and ground settings of the colour pass.
struct DrawSettings {
  bool shadows = true;
  uint32_t shadow_map_size = 2048;                            // square, D32
  bool ground = true;                                         // a quad under the crowd
  std::array<float, 3> light_direction{-0.45f, 1.0f, 0.35f};  // towards the light; normalised
  std::array<float, 3> light_color{0.85f, 0.82f, 0.75f};
  std::array<float, 3> ambient{0.32f, 0.34f, 0.38f};
  std::array<float, 3> ground_color{0.42f, 0.45f, 0.40f};
  std::array<float, 4> clear_color{0.62f, 0.72f, 0.84f, 1.0f};  // RGBA in [0, 1]
  // Decode each drawn instance's joint matrices once (palette pass) rather than per vertex
  // influence; off only to compare the two (they draw the same).
  bool joint_palette = true;
  // Skinned-vertex slots (16 bytes each) shared by the drawn instances; instances finding no
  // room are skinned in the vertex shader on instanced paths, and not drawn on the corner
  // path. 0: the corner buffer's corners on the corner path, otherwise as many as one storage
  // buffer holds (maxStorageBufferRange / 16).
  uint32_t skin_slots = 0;
};

// A colour + depth target the colour pass renders into: the Renderer's own offscreen image or
// one the host application owns (Renderer::record_draw).
struct HostTarget {
  VkImageView color_view = VK_NULL_HANDLE;
  VkFormat color_format = VK_FORMAT_R8G8B8A8_UNORM;
  VkImageView depth_view = VK_NULL_HANDLE;
  VkFormat depth_format = VK_FORMAT_D32_SFLOAT;
  uint32_t width = 0, height = 0;
  // The colour image's layout after the pass.
  VkImageLayout color_final_layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  // true: both images are cleared (colour to DrawSettings::clear_color, depth to 1) and their
  // old contents dropped. false: the crowd is drawn over what the host drew, depth-tested
  // against the host's depth (Vulkan depth 0 near, 1 far, the camera of scene.camera); the
  // colour image must then be in COLOR_ATTACHMENT_OPTIMAL and the depth image in
  // DEPTH_STENCIL_ATTACHMENT_OPTIMAL, and the depth is kept.
  bool clear = true;
  // Multisampling: color_view and depth_view are images of this many samples, resolved at the
  // end of the pass into resolve_view (single-sampled, color_format, ending in
  // color_final_layout). Needs clear = true and a count the device supports for colour and
  // depth (lavapipe: 1 and 4).
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
  VkImageView resolve_view = VK_NULL_HANDLE;
};

// How one character type is drawn (CrowdCompute's outputs): through the corner buffer with one
// VkDrawIndirectCommand, or, with instanced static levels, from a static index buffer with
// `indexed_count` VkDrawIndexedIndirectCommands (instances from the instance list).
struct TypeDraw {
  VkBuffer args = VK_NULL_HANDLE;  // holds a VkDrawIndirectCommand at args_offset
  VkDeviceSize args_offset = 0;
  uint32_t corner_base = 0;  // added to gl_VertexIndex (0 when firstVertex carries it)
  bool instanced = false;
  VkBuffer index_buffer = VK_NULL_HANDLE;  // uint32 indices
  VkBuffer indexed_args = VK_NULL_HANDLE;  // VkDrawIndexedIndirectCommand[indexed_count]
  VkDeviceSize indexed_offset = 0;
  uint32_t indexed_count = 0;
};

// std140 blocks and the vertex record the shaders read (layouts asserted in gpu_vertices.cpp).
struct FrameConstants {
  float view_proj[16];        // column-major
  float light_view_proj[16];  // column-major
  float light_dir[4];         // towards the light, w = shadows on
  float light_color[4];       // w = shadow depth bias
  float ambient[4];           // w = swatch tiling
  float ground_min[4];        // w = 1: draw the ground
  float ground_max[4];
  float ground_color[4];
  float eye[4];
  uint32_t skin[4];  // x: skinned-vertex slots
};

struct TypeConstants {
  uint32_t anim_layout[4];  // encoding, joints, texels per joint, bytes per texel
  float decode_center[4];
  float decode_half[4];
  float up_neck[4];      // up axis, pack neck height
  float waist_mask[4];   // pack waist height, mask width, mask height, 1 = material shading
  uint32_t variants[4];  // head, upper body, trousers, swatch layers per region
  // Per region (head, upper body, trousers): the pack's variant images (PackVariantImages) as
  // first layer | count << 16; variant k >= 1 of an instance draws layer first + k - 1.
  uint32_t variant_images[4];
};

struct GpuVertex {
  float position_height[4];
  float normal_u[4];
  float weights[4];
  // j0 | j1 << 16, j2 | j3 << 16, bits of v, (1 = unskinned) | material << 16
  uint32_t joints_v[4];
};

// The bind-pose vertex records of a pack (geometry must be loaded). A vertex's material is
// that of the first triangle using it (a vertex is a wedge of one primitive).
std::vector<GpuVertex> make_gpu_vertices(const PackContents& pack);

// One pack material as crowd.frag reads it (std430, 48 bytes). Colours are in the display space
// the renderer shades in (sRGB values: the colour target is UNORM and lighting is not gamma
// correct), so the glTF factor, which is linear, is converted.
struct GpuMaterial {
  float color[4];  // base colour factor (sRGB rgb, alpha)
  float uv_u[4];   // u' = a·u + b·v + c; w: image layer (-1: untextured)
  float uv_v[4];   // v' = d·u + e·v + f; w: alpha cutoff (-1: opaque)
};

// A type's materials and their images: image i of the pack is layer i of one RGBA8 array, each
// resampled to the array's size (the largest image's, at most kMaxMaterialImageSide a side),
// with a full mip chain (far characters are a few pixels tall). A pack without images gets one
// white 1x1 layer, which no material samples.
struct GpuMaterials {
  std::vector<GpuMaterial> materials;  // at least one
  uint32_t width = 1, height = 1, layers = 1;
  std::vector<uint8_t> rgba;                // level 0 (all layers), level 1, ...
  std::vector<VkDeviceSize> level_offsets;  // where each level starts in rgba
};

constexpr uint32_t kMaxMaterialImageSide = 1024;

// Fails (kInvalidPack) when an image of the pack does not decode.
Status make_gpu_materials(const PackContents& pack, GpuMaterials& out);

// The orthographic light transform (column-major, Vulkan depth 0..1) whose box covers the
// given world spheres (4 floats each: centre, radius), seen along -light_direction.
void fit_light_view_proj(const std::array<float, 3>& light_direction, Span<const float> spheres,
                         float out[16]);

// Swatch layers per region in the generated texture array (variants beyond wrap around).
constexpr uint32_t kMaxSwatchesPerRegion = 32;
constexpr uint32_t kSwatchSize = 32;

class CrowdDraw {
 public:
  // Uploads every type's vertices, animation texture and partition mask, builds the swatch
  // array, the shadow map, the descriptor sets and the shadow pipeline.
  // Returns kNotLoaded when a type's geometry or animation is not loaded, kInvalidArgument on
  // Vulkan failures.
  static Status create(VulkanContext& context, const Scene& scene, const DrawSettings& settings,
                       std::unique_ptr<CrowdDraw>& out);
  ~CrowdDraw();
  CrowdDraw(const CrowdDraw&) = delete;
  CrowdDraw& operator=(const CrowdDraw&) = delete;

  // Per frame, before recording: the frame constants (camera of `state`, the light box over the
  // visible instances, the ground under every instance), the pose buffers of `effects` (null or
  // empty: none) and the descriptor sets pointed at the compute passes' instance, LoD and corner
  // buffers. The previous frame's commands must have completed (sets and constants are
  // rewritten in place).
  Status update(const Scene& scene, const FrameState& state, const EffectFrame* effects,
                const CrowdCompute& compute);

  // The skinning pass, after the compute passes and before the shadow and colour passes
  // (outside any render pass): each selected vertex of each drawn instance skinned once
  // (shaders/skin_common.glsl), with the barriers around it.
  void record_skinning(VkCommandBuffer cmd);
  // After the skinning pass ran: slots used and drawn instances that found no room (not drawn).
  Status read_skin_stats(uint32_t& slots_used, uint32_t& no_room) const;
  // After the skinning pass ran (for tests): the world positions the pass wrote for instance i's
  // first `count` vertices (3 floats each; empty when it has no slots).
  Status read_skinned_positions(uint32_t instance, uint32_t count,
                                std::vector<float>& positions) const;

  // GPU memory of the drawing side in bytes, as allocated now: per type (vertices, animation,
  // pose buffer, constants, partition mask), the skinning buffers (skinned-vertex slots,
  // palette, per-instance lists) and the rest (frame constants, swatches, shadow map).
  struct Memory {
    std::vector<uint64_t> per_type;
    uint64_t skinning = 0, frame = 0;
    uint64_t static_geometry = 0;  // the scene's stands and pitch (Scene::static_geometry)
  };
  Memory memory() const;

  // The pose buffers alone (update() calls it): uploads each type's EffectFrame::pose_buffers
  // entry, growing the buffer when needed; types without poses keep what they had.
  Status upload_poses(const EffectFrame* effects);

  // The shadow-map pass (outside any render pass); records nothing when shadows are off.
  // draws: one per character type, in type order
  void record_shadow(VkCommandBuffer cmd, Span<const TypeDraw> draws);
  // Builds the colour pipelines for targets of these formats ahead of the first record_color
  // (which otherwise builds them, a compile that lands in the first frame).
  Status prepare_target(const HostTarget& target);
  // The colour pass into `target`: clear, ground, one indirect draw per type.
  // Returns kInvalidArgument when the target is incomplete or a Vulkan object cannot be made.
  Status record_color(VkCommandBuffer cmd, const HostTarget& target, Span<const TypeDraw> draws);

  uint32_t type_count() const;
  VkDescriptorSetLayout type_set_layout() const;
  VkDescriptorSet type_set(uint32_t type) const;
  uint32_t type_vertices(uint32_t type) const;  // the pack's vertex count
  uint32_t type_joints(uint32_t type) const;    // joints per animation-texture row
  AnimationEncoding type_encoding(uint32_t type) const;
  const FrameConstants& frame_constants() const;
  const DrawSettings& settings() const;

 private:
  struct Impl;
  explicit CrowdDraw(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace crowdbake::runtime::gpu
