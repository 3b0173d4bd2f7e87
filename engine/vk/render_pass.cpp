#include "engine/vk/render_pass.h"

#include "engine/vk/check.h"

namespace sketchsurf::vk {

VkFormat choose_depth_format(const Context& context) {
  for (VkFormat f : {VK_FORMAT_D32_SFLOAT, VK_FORMAT_D24_UNORM_S8_UINT, VK_FORMAT_D16_UNORM}) {
    VkFormatProperties props;
    vkGetPhysicalDeviceFormatProperties(context.physical_device(), f, &props);
    if (props.optimalTilingFeatures & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT) return f;
  }
  throw Error::processing("'" + context.device_info().name + "' supports no depth format");
}

UniqueRenderPass create_render_pass(const Context& context, VkFormat color_format, VkFormat depth_format,
                                    VkSampleCountFlagBits samples, VkImageLayout final_layout,
                                    const std::vector<VkSubpassDependency>& dependencies) {
  const bool msaa = samples != VK_SAMPLE_COUNT_1_BIT;
  std::vector<VkAttachmentDescription> attachments;
  VkAttachmentDescription color{};
  color.format = color_format;
  color.samples = samples;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  color.storeOp = msaa ? VK_ATTACHMENT_STORE_OP_DONT_CARE : VK_ATTACHMENT_STORE_OP_STORE;
  color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  color.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  color.finalLayout = msaa ? VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL : final_layout;
  attachments.push_back(color);
  VkAttachmentDescription depth = color;
  depth.format = depth_format;
  depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  depth.finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
  attachments.push_back(depth);
  if (msaa) {
    VkAttachmentDescription resolve = color;
    resolve.samples = VK_SAMPLE_COUNT_1_BIT;
    resolve.loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    resolve.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    resolve.finalLayout = final_layout;
    attachments.push_back(resolve);
  }
  const VkAttachmentReference color_ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  const VkAttachmentReference depth_ref{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  const VkAttachmentReference resolve_ref{2, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &color_ref;
  subpass.pDepthStencilAttachment = &depth_ref;
  subpass.pResolveAttachments = msaa ? &resolve_ref : nullptr;
  VkRenderPassCreateInfo pass_info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  pass_info.attachmentCount = static_cast<std::uint32_t>(attachments.size());
  pass_info.pAttachments = attachments.data();
  pass_info.subpassCount = 1;
  pass_info.pSubpasses = &subpass;
  pass_info.dependencyCount = static_cast<std::uint32_t>(dependencies.size());
  pass_info.pDependencies = dependencies.data();
  VkRenderPass pass = VK_NULL_HANDLE;
  VK_CHECK(vkCreateRenderPass(context.device(), &pass_info, nullptr, &pass));
  return UniqueRenderPass(context.device(), pass);
}

UniqueFramebuffer create_framebuffer(const Context& context, VkRenderPass pass, VkExtent2D extent,
                                     const std::vector<VkImageView>& views) {
  VkFramebufferCreateInfo fb_info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  fb_info.renderPass = pass;
  fb_info.attachmentCount = static_cast<std::uint32_t>(views.size());
  fb_info.pAttachments = views.data();
  fb_info.width = extent.width;
  fb_info.height = extent.height;
  fb_info.layers = 1;
  VkFramebuffer fb = VK_NULL_HANDLE;
  VK_CHECK(vkCreateFramebuffer(context.device(), &fb_info, nullptr, &fb));
  return UniqueFramebuffer(context.device(), fb);
}

void begin_render_pass(VkCommandBuffer cmd, VkRenderPass pass, VkFramebuffer framebuffer,
                       VkExtent2D extent, VkSampleCountFlagBits samples,
                       const std::array<float, 4>& background) {
  std::array<VkClearValue, 3> clear{};
  clear[0].color = {{background[0], background[1], background[2], background[3]}};
  clear[1].depthStencil = {1.0f, 0};
  clear[2].color = clear[0].color;
  VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  begin.renderPass = pass;
  begin.framebuffer = framebuffer;
  begin.renderArea = {{0, 0}, extent};
  begin.clearValueCount = samples != VK_SAMPLE_COUNT_1_BIT ? 3u : 2u;
  begin.pClearValues = clear.data();
  vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  const VkViewport viewport{0.f, 0.f, float(extent.width), float(extent.height), 0.f, 1.f};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  const VkRect2D scissor{{0, 0}, extent};
  vkCmdSetScissor(cmd, 0, 1, &scissor);
}

}  // namespace sketchsurf::vk
