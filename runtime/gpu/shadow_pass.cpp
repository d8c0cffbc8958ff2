// The directional shadow map: its D32 image, depth-only render pass, framebuffer and
// pipelines, and the pass that draws every visible instance into it before the colour pass.
#include <algorithm>

#include "crowd_draw_impl.h"
#include "vk_helpers.h"

namespace crowdbake::runtime::gpu {

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
  VkDevice d = context->device();
  if (Status s = create_render_pass(d, {&attachment, 1}, subpass, deps, shadow_pass); !s) return s;
  const VkImageView view = shadow_map.view();
  if (Status s = create_framebuffer(d, shadow_pass, {&view, 1}, shadow_size, shadow_size,
                                    shadow_framebuffer);
      !s)
    return s;
  if (Status s = create_pipelines(shadow_pass, true, shadow_pipelines); !s) return s;
  if (static_vertex_count == 0 || types.empty()) return {};
  return create_graphics_pipeline(shadow_pass, true, types[0].encoding, shadow_static, kModeStatic);
}

void CrowdDraw::record_shadow(VkCommandBuffer cmd, Span<const TypeDraw> draws) {
  Impl& m = *impl_;
  if (!m.settings.shadows || m.shadow_pass == VK_NULL_HANDLE) return;
  VkClearValue clear{};
  clear.depthStencil = {1.0f, 0};
  begin_render_pass(cmd, m.shadow_pass, m.shadow_framebuffer, m.shadow_size, m.shadow_size,
                    {&clear, 1});
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m.pipeline_layout, 0, 1,
                          &m.frame_set, 0, nullptr);
  // note: update() makes the instanced pipelines before such frames; none is made here.
  (void)m.record_type_draws(cmd, draws, VK_NULL_HANDLE, m.shadow_pipelines,
                            m.shadow_instanced[m.skin_fallback]);
  m.record_static(cmd, m.shadow_static);
  vkCmdEndRenderPass(cmd);
}

}  // namespace crowdbake::runtime::gpu
