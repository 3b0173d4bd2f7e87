#include "engine/vk/offscreen.h"

#include <cstring>

#include "engine/vk/check.h"
#include "engine/vk/render_pass.h"

namespace sketchsurf::vk {

namespace {

constexpr VkFormat kColorFormat = VK_FORMAT_R8G8B8A8_UNORM;

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

  // Attachments (render_pass.h): the single-sample image is the colour target, or the resolve
  // target with MSAA; it ends ready for the copy to the readback image.
  std::vector<VkSubpassDependency> deps(2);
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
  render_pass_ = create_render_pass(context, kColorFormat, depth_format_, samples_,
                                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, deps);

  std::vector<VkImageView> views;
  views.push_back(msaa ? color_msaa_.view() : resolved_.view());
  views.push_back(depth_.view());
  if (msaa) views.push_back(resolved_.view());
  framebuffer_ = create_framebuffer(context, render_pass_.get(), extent, views);
}

void OffscreenTarget::begin(VkCommandBuffer cmd, const std::array<float, 4>& background) const {
  begin_render_pass(cmd, render_pass_.get(), framebuffer_.get(), extent_, samples_, background);
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
