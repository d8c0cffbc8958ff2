// CrowdDraw: creation (every type's resources, the swatches, shadow map and skinning pass),
// the per-frame update (frame constants, light box, ground, pose buffers, descriptor sets) and
// the accessors. The passes live in skin_pass.cpp, shadow_pass.cpp and color_pass.cpp.
#include "crowdbake/runtime/gpu/crowd_draw.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "crowd_draw_impl.h"

namespace crowdbake::runtime::gpu {

namespace {

// note: the shader indexes the pose buffer without bounds checks: refuse what would overrun.
Status check_poses(const Scene& scene, const EffectFrame* effects,
                   const std::vector<TypeResources>& types) {
  const size_t n = scene.instances.size();
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
      const size_t per_pose = 12 * static_cast<size_t>(t < types.size() ? types[t].joints : 0);
      if (per_pose == 0 || pose >= floats / per_pose)
        return {StatusCode::kInvalidArgument,
                "effects: instance " + std::to_string(i) + " takes pose " + std::to_string(pose) +
                    " but its type's pose buffer holds " +
                    std::to_string(per_pose ? floats / per_pose : 0) + " poses"};
    }
  }
  return {};
}

}  // namespace

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

  if (Status s = GpuBuffer::create(context, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                   MemoryKind::kHostVisible, impl->impostor_list);
      !s)
    return s;
  if (Status s = impl->create_swatches(); !s) return s;
  if (Status s = impl->create_static_geometry(scene.static_geometry); !s) return s;
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
  if (Status s = m.update_skin_pass(scene, state, compute, sets_dirty); !s) return s;
  if (Status s = m.update_impostors(scene, state, sets_dirty); !s) return s;
  if (Status s = m.update_frame_constants(scene, state); !s) return s;

  if (Status s = check_poses(scene, effects, m.types); !s) return s;
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
