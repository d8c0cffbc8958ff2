// The colour pass: the graphics pipelines (crowd, ground, instanced levels; the shadow pass's
// depth-only ones too), the render passes and framebuffers per host target, and the recording
// of one draw per character type plus the ground.
#include <string>
#include <tuple>

#include "crowd_draw_impl.h"
#include "vk_helpers.h"

namespace crowdbake::runtime::gpu {
namespace {

std::string sample_counts(VkSampleCountFlags flags) {
  std::string out;
  for (uint32_t n = 1; n <= 64; n *= 2)
    if (flags & n) out += (out.empty() ? "" : ", ") + std::to_string(n);
  return out.empty() ? "none" : out;
}

}  // namespace

Status CrowdDraw::Impl::create_pipelines(VkRenderPass pass, bool shadow,
                                         VkPipeline (&pipelines)[kEncodings], uint32_t mode,
                                         VkSampleCountFlagBits samples) {
  for (const TypeResources& t : types)
    if (pipelines[t.encoding] == VK_NULL_HANDLE)
      if (Status s = create_graphics_pipeline(pass, shadow, t.encoding, pipelines[t.encoding], mode,
                                              samples);
          !s)
        return s;
  return {};
}

Status CrowdDraw::Impl::create_graphics_pipeline(VkRenderPass pass, bool shadow, uint32_t encoding,
                                                 VkPipeline& out, uint32_t mode,
                                                 VkSampleCountFlagBits samples) {
  // Specialization constants: 0 = the animation encoding, 1 = what is drawn (kMode*), 2 = the
  // target's samples per pixel (impostors write their own sample masks).
  const Specialization specialization({0, 1, 2}, {encoding, mode, static_cast<uint32_t>(samples)});
  VkPipelineShaderStageCreateInfo stages[2] = {};
  stages[0].sType = stages[1].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = shadow ? shadow_vert : crowd_vert;
  stages[0].pName = stages[1].pName = "main";
  stages[0].pSpecializationInfo = stages[1].pSpecializationInfo = specialization.info();
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
  multisample.rasterizationSamples = samples;
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

Status CrowdDraw::Impl::color_pipeline(const HostTarget& target, ColorPipeline*& out) {
  const auto key = std::make_tuple(target.color_format, target.depth_format,
                                   target.color_final_layout, target.clear, target.samples);
  auto found = color_pipelines.find(key);
  if (found != color_pipelines.end()) {
    out = &found->second;
    return {};
  }
  const bool msaa = target.samples != VK_SAMPLE_COUNT_1_BIT;
  if (msaa) {
    const VkPhysicalDeviceLimits& limits = context->limits();
    const VkSampleCountFlags supported =
        limits.framebufferColorSampleCounts & limits.framebufferDepthSampleCounts;
    if ((supported & target.samples) == 0)
      return {StatusCode::kInvalidArgument,
              "render target: " + std::to_string(target.samples) +
                  " samples per pixel (MSAA) are not supported by the device (it supports " +
                  sample_counts(supported) + ")"};
    if (!target.clear)
      return {StatusCode::kInvalidArgument,
              "render target: a multisampled target is cleared (HostTarget::clear)"};
  }
  // note: with MSAA, attachments 0 and 1 are the multisampled colour and depth, and 2 the
  // single-sampled image they resolve into, which takes the colour's final layout.
  VkAttachmentDescription attachments[3] = {};
  attachments[0].format = target.color_format;
  attachments[0].samples = target.samples;
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
  if (msaa) {
    attachments[2] = attachments[0];
    attachments[2].samples = VK_SAMPLE_COUNT_1_BIT;
    attachments[2].loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    attachments[0].storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    attachments[0].finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  }
  const VkAttachmentReference color_ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  const VkAttachmentReference depth_ref{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  const VkAttachmentReference resolve_ref{2, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &color_ref;
  subpass.pResolveAttachments = msaa ? &resolve_ref : nullptr;
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
  ColorPipeline p;
  p.samples = target.samples;
  if (Status s = create_render_pass(context->device(),
                                    Span<const VkAttachmentDescription>(attachments, msaa ? 3 : 2),
                                    subpass, deps, p.render_pass);
      !s)
    return s;
  Status s = create_pipelines(p.render_pass, false, p.pipelines, kModeCrowd, p.samples);
  if (s.ok() && settings.ground && !types.empty())
    s = create_graphics_pipeline(p.render_pass, false, types[0].encoding, p.ground, kModeGround,
                                 p.samples);
  if (s.ok() && static_vertex_count > 0 && !types.empty())
    s = create_graphics_pipeline(p.render_pass, false, types[0].encoding, p.static_geometry,
                                 kModeStatic, p.samples);
  if (s.ok() && any_impostor)
    s = create_graphics_pipeline(p.render_pass, false, types[0].encoding, p.impostor, kModeImpostor,
                                 p.samples);
  if (!s) {
    destroy_pipelines(context->device(), p.pipelines);
    vkDestroyPipeline(context->device(), p.ground, nullptr);
    vkDestroyPipeline(context->device(), p.static_geometry, nullptr);
    vkDestroyPipeline(context->device(), p.impostor, nullptr);
    vkDestroyRenderPass(context->device(), p.render_pass, nullptr);
    return s;
  }
  out = &color_pipelines.emplace(key, p).first->second;
  return {};
}

Status CrowdDraw::Impl::framebuffer(const HostTarget& target, VkRenderPass pass,
                                    VkFramebuffer& out) {
  const auto key = std::make_tuple(pass, target.color_view, target.depth_view, target.resolve_view,
                                   target.width, target.height);
  if (auto found = framebuffers.find(key); found != framebuffers.end()) {
    out = found->second;
    return {};
  }
  const VkImageView views[3] = {target.color_view, target.depth_view, target.resolve_view};
  const size_t view_count = target.samples != VK_SAMPLE_COUNT_1_BIT ? 3 : 2;
  if (Status s =
          create_framebuffer(context->device(), pass, Span<const VkImageView>(views, view_count),
                             target.width, target.height, out);
      !s)
    return s;
  framebuffers.emplace(key, out);
  return {};
}

void CrowdDraw::Impl::record_type_draw(VkCommandBuffer cmd, const TypeDraw& draw) const {
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
    vkCmdDrawIndexedIndirect(cmd, draw.indexed_args, draw.indexed_offset + VkDeviceSize{k} * stride,
                             1, stride);
}

Status CrowdDraw::Impl::record_type_draws(VkCommandBuffer cmd, Span<const TypeDraw> draws,
                                          VkRenderPass pass, VkPipeline (&pipelines)[kEncodings],
                                          VkPipeline (&instanced)[kEncodings],
                                          VkSampleCountFlagBits samples) {
  VkPipeline bound = VK_NULL_HANDLE;
  for (size_t t = 0; t < draws.size() && t < types.size(); ++t) {
    const uint32_t e = types[t].encoding;
    VkPipeline& chosen = draws[t].instanced ? instanced[e] : pipelines[e];
    if (chosen == VK_NULL_HANDLE) {
      if (pass == VK_NULL_HANDLE) continue;
      if (Status s = create_graphics_pipeline(pass, false, e, chosen,
                                              skin_fallback ? kModeInstanced : kModeInstancedSlots,
                                              samples);
          !s)
        return s;
    }
    if (chosen != bound) {
      bound = chosen;
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, bound);
    }
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_layout, 1, 1,
                            &types[t].set, 0, nullptr);
    record_type_draw(cmd, draws[t]);
  }
  return {};
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
  if (target.samples != VK_SAMPLE_COUNT_1_BIT && target.resolve_view == VK_NULL_HANDLE)
    return {StatusCode::kInvalidArgument,
            "render target: a multisampled target needs a resolve view"};
  ColorPipeline* pipeline = nullptr;
  if (Status s = m.color_pipeline(target, pipeline); !s) return s;
  VkFramebuffer framebuffer = VK_NULL_HANDLE;
  if (Status s = m.framebuffer(target, pipeline->render_pass, framebuffer); !s) return s;
  VkClearValue clears[2] = {};
  for (int c = 0; c < 4; ++c) clears[0].color.float32[c] = m.settings.clear_color[c];
  clears[1].depthStencil = {1.0f, 0};
  begin_render_pass(cmd, pipeline->render_pass, framebuffer, target.width, target.height, clears);
  if (!m.types.empty()) {
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m.pipeline_layout, 0, 1,
                            &m.frame_set, 0, nullptr);
    const VkShaderStageFlags stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    if (Status s = m.record_type_draws(cmd, draws, pipeline->render_pass, pipeline->pipelines,
                                       pipeline->instanced[m.skin_fallback], pipeline->samples);
        !s)
      return s;
    m.record_impostors(cmd, pipeline->impostor);
    if (m.constants.ground_min[3] != 0.0f && pipeline->ground != VK_NULL_HANDLE) {
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline->ground);
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m.pipeline_layout, 1, 1,
                              &m.types[0].set, 0, nullptr);
      const DrawPush push{0, 0};
      vkCmdPushConstants(cmd, m.pipeline_layout, stages, 0, sizeof(push), &push);
      vkCmdDraw(cmd, 6, 1, 0, 0);
    }
    m.record_static(cmd, pipeline->static_geometry);
  }
  vkCmdEndRenderPass(cmd);
  return {};
}

}  // namespace crowdbake::runtime::gpu
