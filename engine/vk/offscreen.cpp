#include "engine/vk/offscreen.h"

#include <cstring>

#include "engine/vk/check.h"

namespace sketchsurf::vk {

namespace {

constexpr VkFormat kColorFormat = VK_FORMAT_R8G8B8A8_UNORM;

VkFormat choose_depth_format(const Context& context) {
  for (VkFormat f : {VK_FORMAT_D32_SFLOAT, VK_FORMAT_D24_UNORM_S8_UINT, VK_FORMAT_D16_UNORM}) {
    VkFormatProperties props;
    vkGetPhysicalDeviceFormatProperties(context.physical_device(), f, &props);
    if (props.optimalTilingFeatures & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT) return f;
  }
  throw Error::processing("'" + context.device_info().name + "' supports no depth format");
}

}  // namespace

OffscreenTarget::OffscreenTarget(const Context& context, VkExtent2D extent,
                                 VkSampleCountFlagBits samples)
    : context_(&context),
      extent_(extent),
      samples_(context.supported_samples(samples)),
      depth_format_(choose_depth_format(context)) {
  if (extent.width == 0 || extent.height == 0 ||
      extent.width > context.limits().maxFramebufferWidth ||
      extent.height > context.limits().maxFramebufferHeight)
    throw Error::usage("image size " + std::to_string(extent.width) + "x" +
                       std::to_string(extent.height) + " is not supported by '" +
                       context.device_info().name + "' (at most " +
                       std::to_string(context.limits().maxFramebufferWidth) + "x" +
                       std::to_string(context.limits().maxFramebufferHeight) + ")");
  const bool msaa = samples_ != VK_SAMPLE_COUNT_1_BIT;
  if (msaa)
    color_msaa_ = Image(context,
                        {extent, kColorFormat,
                         VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT,
                         samples_, VK_IMAGE_TILING_OPTIMAL, VK_IMAGE_ASPECT_COLOR_BIT, false},
                        "offscreen colour (msaa)");
  depth_ = Image(context,
                 {extent, depth_format_,
                  VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT,
                  samples_, VK_IMAGE_TILING_OPTIMAL, VK_IMAGE_ASPECT_DEPTH_BIT, false},
                 "offscreen depth");
  resolved_ = Image(context,
                    {extent, kColorFormat,
                     VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                     VK_SAMPLE_COUNT_1_BIT, VK_IMAGE_TILING_OPTIMAL, VK_IMAGE_ASPECT_COLOR_BIT, false},
                    "offscreen colour");
  readback_ = Image(context,
                    {extent, kColorFormat, VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_SAMPLE_COUNT_1_BIT,
                     VK_IMAGE_TILING_LINEAR, 0, true},
                    "offscreen readback");

  // Attachments: 0 colour (multisampled, or the single-sample image itself), 1 depth,
  // 2 resolve target (only with MSAA).
  std::vector<VkAttachmentDescription> attachments;
  VkAttachmentDescription color{};
  color.format = kColorFormat;
  color.samples = samples_;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  color.storeOp = msaa ? VK_ATTACHMENT_STORE_OP_DONT_CARE : VK_ATTACHMENT_STORE_OP_STORE;
  color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  color.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  color.finalLayout = msaa ? VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL
                           : VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  attachments.push_back(color);
  VkAttachmentDescription depth = color;
  depth.format = depth_format_;
  depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  depth.finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
  attachments.push_back(depth);
  if (msaa) {
    VkAttachmentDescription resolve = color;
    resolve.samples = VK_SAMPLE_COUNT_1_BIT;
    resolve.loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    resolve.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    resolve.finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
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
  std::array<VkSubpassDependency, 2> deps{};
  deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  deps[0].dstSubpass = 0;
  deps[0].srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  deps[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                         VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT;
  deps[0].srcAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  deps[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                          VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  deps[1].srcSubpass = 0;
  deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  deps[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  deps[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  deps[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  deps[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  VkRenderPassCreateInfo pass_info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  pass_info.attachmentCount = static_cast<std::uint32_t>(attachments.size());
  pass_info.pAttachments = attachments.data();
  pass_info.subpassCount = 1;
  pass_info.pSubpasses = &subpass;
  pass_info.dependencyCount = static_cast<std::uint32_t>(deps.size());
  pass_info.pDependencies = deps.data();
  VkRenderPass pass = VK_NULL_HANDLE;
  VK_CHECK(vkCreateRenderPass(context.device(), &pass_info, nullptr, &pass));
  render_pass_ = UniqueRenderPass(context.device(), pass);

  std::vector<VkImageView> views;
  views.push_back(msaa ? color_msaa_.view() : resolved_.view());
  views.push_back(depth_.view());
  if (msaa) views.push_back(resolved_.view());
  VkFramebufferCreateInfo fb_info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  fb_info.renderPass = pass;
  fb_info.attachmentCount = static_cast<std::uint32_t>(views.size());
  fb_info.pAttachments = views.data();
  fb_info.width = extent.width;
  fb_info.height = extent.height;
  fb_info.layers = 1;
  VkFramebuffer fb = VK_NULL_HANDLE;
  VK_CHECK(vkCreateFramebuffer(context.device(), &fb_info, nullptr, &fb));
  framebuffer_ = UniqueFramebuffer(context.device(), fb);
}

void OffscreenTarget::begin(VkCommandBuffer cmd, const std::array<float, 4>& background) const {
  std::array<VkClearValue, 3> clear{};
  clear[0].color = {{background[0], background[1], background[2], background[3]}};
  clear[1].depthStencil = {1.0f, 0};
  clear[2].color = clear[0].color;
  VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  begin.renderPass = render_pass_.get();
  begin.framebuffer = framebuffer_.get();
  begin.renderArea = {{0, 0}, extent_};
  begin.clearValueCount = samples_ != VK_SAMPLE_COUNT_1_BIT ? 3u : 2u;
  begin.pClearValues = clear.data();
  vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  const VkViewport viewport{0.f, 0.f, float(extent_.width), float(extent_.height), 0.f, 1.f};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  const VkRect2D scissor{{0, 0}, extent_};
  vkCmdSetScissor(cmd, 0, 1, &scissor);
}

void OffscreenTarget::end_and_copy(VkCommandBuffer cmd) const {
  vkCmdEndRenderPass(cmd);
  transition(cmd, readback_.get(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
             0, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
             VK_PIPELINE_STAGE_TRANSFER_BIT);
  VkImageCopy region{};
  region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.dstSubresource = region.srcSubresource;
  region.extent = {extent_.width, extent_.height, 1};
  vkCmdCopyImage(cmd, resolved_.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_.get(),
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
  transition(cmd, readback_.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL,
             VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_HOST_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
             VK_PIPELINE_STAGE_HOST_BIT);
}

std::vector<std::uint8_t> OffscreenTarget::read_pixels() const {
  VkImageSubresource sub{VK_IMAGE_ASPECT_COLOR_BIT, 0, 0};
  VkSubresourceLayout layout;
  vkGetImageSubresourceLayout(context_->device(), readback_.get(), &sub, &layout);
  const std::size_t row_bytes = std::size_t(extent_.width) * 4;
  std::vector<std::uint8_t> pixels(row_bytes * extent_.height);
  const std::byte* src = readback_.mapped() + layout.offset;
  for (std::uint32_t y = 0; y < extent_.height; ++y)
    std::memcpy(pixels.data() + y * row_bytes, src + y * layout.rowPitch, row_bytes);
  return pixels;
}

}  // namespace sketchsurf::vk
