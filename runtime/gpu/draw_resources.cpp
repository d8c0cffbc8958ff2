// CrowdDraw's long-lived resources: descriptor set layouts, pool and sets, samplers, each
// character type's buffers (constants, vertices, animation words, poses, geomorph table,
// materials), partition mask and material image array, and the swatch array; plus the descriptor
// writes that point the sets at them.
#include <algorithm>
#include <string>

#include "crowd_draw_impl.h"
#include "crowdbake/runtime/geomorph.h"
#include "vk_helpers.h"

namespace crowdbake::runtime::gpu {

CrowdDraw::Impl::~Impl() {
  if (!context) return;
  VkDevice d = context->device();
  for (auto& [key, fb] : framebuffers) vkDestroyFramebuffer(d, fb, nullptr);
  for (auto& [key, p] : color_pipelines) {
    destroy_pipelines(d, p.pipelines);
    destroy_pipelines(d, p.instanced);
    vkDestroyPipeline(d, p.ground, nullptr);
    vkDestroyPipeline(d, p.static_geometry, nullptr);
    vkDestroyPipeline(d, p.impostor, nullptr);
    vkDestroyRenderPass(d, p.render_pass, nullptr);
  }
  destroy_pipelines(d, shadow_pipelines);
  destroy_pipelines(d, shadow_instanced);
  vkDestroyPipeline(d, shadow_static, nullptr);
  vkDestroyFramebuffer(d, shadow_framebuffer, nullptr);
  vkDestroyPipeline(d, skin_list_pipeline, nullptr);
  destroy_pipelines(d, skin_pipelines);
  vkDestroyShaderModule(d, skin_list_module, nullptr);
  vkDestroyShaderModule(d, skin_pass_module, nullptr);
  vkDestroyShaderModule(d, skin_palette_module, nullptr);
  destroy_pipelines(d, palette_pipelines);
  vkDestroyPipelineLayout(d, skin_pipeline_layout, nullptr);
  vkDestroyDescriptorSetLayout(d, skin_layout, nullptr);
  vkDestroyRenderPass(d, shadow_pass, nullptr);
  vkDestroyShaderModule(d, crowd_vert, nullptr);
  vkDestroyShaderModule(d, crowd_frag, nullptr);
  vkDestroyShaderModule(d, shadow_vert, nullptr);
  vkDestroySampler(d, swatch_sampler, nullptr);
  vkDestroySampler(d, material_sampler, nullptr);
  vkDestroySampler(d, mask_sampler, nullptr);
  vkDestroySampler(d, shadow_sampler, nullptr);
  vkDestroyDescriptorPool(d, pool, nullptr);
  vkDestroyPipelineLayout(d, pipeline_layout, nullptr);
  vkDestroyDescriptorSetLayout(d, frame_layout, nullptr);
  vkDestroyDescriptorSetLayout(d, type_layout, nullptr);
}

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
      {8, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {9, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
  };
  const VkDescriptorSetLayoutBinding type_bindings[] = {
      {0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
      {5, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {6, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {7, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
      {8, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
      {9, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, all, nullptr},
  };
  if (Status s = create_set_layout(d, frame_bindings, frame_layout); !s) return s;
  if (Status s = create_set_layout(d, type_bindings, type_layout); !s) return s;
  const VkDescriptorSetLayout layouts[] = {frame_layout, type_layout};
  const VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                                 sizeof(DrawPush)};
  if (Status s = create_pipeline_layout(d, layouts, &push, pipeline_layout); !s) return s;

  const uint32_t type_count = static_cast<uint32_t>(std::max<size_t>(types.size(), 1));
  const VkDescriptorPoolSize sizes[] = {
      {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 8 + 8 * type_count + 8},
      {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2 + 2 * type_count},
  };
  if (Status s = create_descriptor_pool(d, sizes, 2 + type_count, pool); !s) return s;
  if (Status s = allocate_set(d, pool, frame_layout, frame_set); !s) return s;
  for (TypeResources& t : types)
    if (Status s = allocate_set(d, pool, type_layout, t.set); !s) return s;
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
  // note: material images repeat (glTF's default wrap) and are trilinearly filtered.
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  info.maxLod = VK_LOD_CLAMP_NONE;
  if (Status s = check(vkCreateSampler(d, &info, nullptr, &material_sampler), "vkCreateSampler");
      !s)
    return s;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  info.maxLod = 0.0f;
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

Status CrowdDraw::Impl::upload_image(GpuImage& image, const void* data, VkDeviceSize bytes,
                                     Span<const VkDeviceSize> level_offsets) {
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
    // note: level l of every layer starts at level_offsets[l] (level 0 at 0 when none given).
    for (uint32_t level = 0; level < desc.mip_levels; ++level) {
      VkBufferImageCopy copy{};
      copy.bufferOffset = level < level_offsets.size() ? level_offsets[level] : 0;
      copy.imageSubresource = {desc.aspect, level, 0, desc.layers};
      copy.imageExtent = {std::max(desc.width >> level, 1u), std::max(desc.height >> level, 1u), 1};
      vkCmdCopyBufferToImage(cmd, staging.buffer(), image.image(),
                             VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
    }
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
  if (const Status checked = check_animation_texture(anim); !checked)
    return {StatusCode::kInvalidPack,
            "character type '" + type.name + "': animation texture: " + checked.message()};

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
  k.waist_mask[3] = resolved_shading(type) == Shading::kMaterial ? 1.0f : 0.0f;
  k.variants[0] = type.texture_variants.head;
  k.variants[1] = type.texture_variants.upper_body;
  k.variants[2] = type.texture_variants.trousers;
  k.variants[3] = swatches_per_region;
  const PackVariantImages& vi = c.variant_images;
  for (int r = 0; r < 3; ++r) k.variant_images[r] = vi.first[r] | vi.count[r] << 16;
  k.variant_images[3] = 0;

  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  if (Status s = create_filled_buffer(*context, storage, MemoryKind::kHostVisible, &k, sizeof(k),
                                      out.constants);
      !s)
    return s;

  const std::vector<GpuVertex> vertices = make_gpu_vertices(c);
  out.vertex_count = static_cast<uint32_t>(vertices.size());
  out.joints = anim.joints;
  out.encoding = static_cast<uint32_t>(anim.encoding);
  if (Status s = create_filled_buffer(*context, storage, MemoryKind::kDeviceLocal, vertices.data(),
                                      vertices.size() * sizeof(GpuVertex), out.vertices, 64);
      !s)
    return s;

  // Geomorph table (skin.glsl): a type without progressive data never morphs.
  std::vector<GeomorphVertex> morphs = geomorph_table(progressive_view(c));
  if (morphs.empty())
    for (uint32_t v = 0; v < std::max<uint32_t>(out.vertex_count, 1); ++v)
      morphs.push_back({v, kGeomorphNever});
  if (Status s = create_filled_buffer(*context, storage, MemoryKind::kDeviceLocal, morphs.data(),
                                      morphs.size() * sizeof(GeomorphVertex), out.morphs);
      !s)
    return s;

  // note: the texture is uploaded byte for byte; skin.glsl reads it as little-endian words.
  const VkDeviceSize anim_bytes = std::max<VkDeviceSize>((anim.data.size() + 3) / 4 * 4, 16);
  if (anim_bytes > context->limits().maxStorageBufferRange)
    return {StatusCode::kInvalidArgument, "character type '" + type.name +
                                              "': animation texture of " +
                                              std::to_string(anim.data.size()) +
                                              " bytes exceeds the device's storage buffer range"};
  if (Status s = create_filled_buffer(*context, storage, MemoryKind::kDeviceLocal, anim.data.data(),
                                      anim.data.size(), out.animation, anim_bytes);
      !s)
    return s;

  if (Status s = GpuBuffer::create(*context, 48, storage, MemoryKind::kHostVisible, out.poses); !s)
    return s;

  // note: a type without vertex colours (VCOL) gets one white entry, which crowd.vert reads.
  const bool colored =
      !c.vertex_colors.empty() && c.vertex_colors.size() == c.geometry.vertex_count();
  const uint32_t white = 0xFFFFFFFFu;
  if (Status s = create_filled_buffer(
          *context, storage, MemoryKind::kDeviceLocal, colored ? c.vertex_colors.data() : &white,
          colored ? c.vertex_colors.size() * sizeof(uint32_t) : sizeof(white), out.colors);
      !s)
    return s;

  if (Status s = create_impostor(c, out); !s) return s;

  GpuMaterials materials;
  if (Status s = make_gpu_materials(c, materials); !s)
    return {s.code(), "character type '" + type.name + "': " + s.message()};
  if (Status s = create_filled_buffer(
          *context, storage, MemoryKind::kDeviceLocal, materials.materials.data(),
          materials.materials.size() * sizeof(GpuMaterial), out.materials);
      !s)
    return s;
  ImageDesc images_desc;
  images_desc.width = materials.width;
  images_desc.height = materials.height;
  images_desc.layers = materials.layers;
  images_desc.mip_levels = static_cast<uint32_t>(materials.level_offsets.size());
  images_desc.array_view = true;
  if (Status s = GpuImage::create(*context, images_desc, out.images); !s) return s;
  if (Status s = upload_image(out.images, materials.rgba.data(), materials.rgba.size(),
                              materials.level_offsets);
      !s)
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

void CrowdDraw::Impl::write_frame_set() {
  SetWrites(frame_set)
      .buffer(0, {bound_instances, 0, VK_WHOLE_SIZE})
      .buffer(1, {bound_corners, 0, VK_WHOLE_SIZE})
      .buffer(2, frame_buffer.descriptor())
      .image(3, {shadow_sampler, shadow_map.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL})
      .image(4, {swatch_sampler, swatches.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL})
      .buffer(5, skin_base.descriptor())
      .buffer(6, skinned.descriptor())
      .buffer(7, {bound_instance_list, 0, VK_WHOLE_SIZE})
      .buffer(8, static_vertices.descriptor())
      .buffer(9, impostor_list.descriptor())
      .apply(context->device());
}

Status CrowdDraw::Impl::create_swatches() {
  ImageDesc desc;
  desc.width = desc.height = kSwatchSize;
  desc.layers = kSwatchRegions * swatches_per_region;
  if (Status s = GpuImage::create(*context, desc, swatches); !s) return s;
  const std::vector<uint8_t> rgba = make_swatches(swatches_per_region);
  return upload_image(swatches, rgba.data(), rgba.size());
}

void CrowdDraw::Impl::write_type_set(const TypeResources& t) {
  SetWrites(t.set)
      .buffer(0, t.constants.descriptor())
      .buffer(1, t.vertices.descriptor())
      .buffer(2, t.animation.descriptor())
      .buffer(3, t.poses.descriptor())
      .image(4, {mask_sampler, t.mask.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL})
      .buffer(5, t.morphs.descriptor())
      .buffer(6, t.materials.descriptor())
      .image(7, {material_sampler, t.images.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL})
      .buffer(8, t.colors.descriptor())
      .buffer(9, t.impostor.descriptor())
      .apply(context->device());
}

namespace {

uint64_t image_bytes(const GpuImage& image) {
  if (!image.valid()) return 0;
  const ImageDesc& d = image.desc();
  const uint64_t texel = d.format == VK_FORMAT_R8_UINT ? 1 : 4;  // R8 masks; RGBA8 and D32
  uint64_t texels = 0;
  for (uint32_t l = 0; l < d.mip_levels; ++l)
    texels += uint64_t{std::max(d.width >> l, 1u)} * std::max(d.height >> l, 1u);
  return texels * d.layers * texel;
}

}  // namespace

CrowdDraw::Memory CrowdDraw::memory() const {
  const Impl& m = *impl_;
  Memory out;
  for (const TypeResources& t : m.types)
    out.per_type.push_back(t.constants.size() + t.vertices.size() + t.animation.size() +
                           t.poses.size() + t.morphs.size() + t.materials.size() + t.colors.size() +
                           t.impostor.size() + image_bytes(t.mask) + image_bytes(t.images));
  for (const GpuBuffer* b :
       {&m.skin_params, &m.type_args, &m.skin_list, &m.skin_base, &m.skinned, &m.palette})
    out.skinning += b->size();
  out.frame = m.frame_buffer.size() + m.impostor_list.size() + image_bytes(m.swatches) +
              image_bytes(m.shadow_map);
  out.static_geometry = m.static_vertices.size();
  return out;
}

}  // namespace crowdbake::runtime::gpu
