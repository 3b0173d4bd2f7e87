#include "engine/render/renderer.h"

#include <glm/gtc/type_ptr.hpp>
#include <span>

#include "engine/vk/check.h"
#include "shaders/mesh_frag.spv.h"
#include "shaders/mesh_vert.spv.h"
#include "shaders/ribbon_frag.spv.h"
#include "shaders/ribbon_vert.spv.h"

namespace sketchsurf::render {

namespace {

template <class T>
std::span<const std::byte> bytes_of(const std::vector<T>& v) {
  return std::as_bytes(std::span<const T>(v));
}

vk::UniqueShaderModule shader(VkDevice device, std::span<const std::uint32_t> code) {
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = code.size_bytes();
  info.pCode = code.data();
  VkShaderModule module = VK_NULL_HANDLE;
  VK_CHECK(vkCreateShaderModule(device, &info, nullptr, &module));
  return {device, module};
}

enum class Blend { Opaque, Alpha };

struct PipelineDesc {
  std::span<const std::uint32_t> vert, frag;
  std::uint32_t stride = 0;
  std::vector<VkVertexInputAttributeDescription> attributes;
  VkCompareOp depth_compare = VK_COMPARE_OP_LESS;
  bool depth_write = true;
  Blend blend = Blend::Opaque;
  VkCullModeFlags cull = VK_CULL_MODE_NONE;  // open surfaces are seen from both sides
};

vk::UniquePipeline make_pipeline(const vk::Context& context, VkRenderPass pass,
                                 VkSampleCountFlagBits samples, VkPipelineLayout layout,
                                 const PipelineDesc& desc) {
  const VkDevice device = context.device();
  const auto vert = shader(device, desc.vert);
  const auto frag = shader(device, desc.frag);
  std::array<VkPipelineShaderStageCreateInfo, 2> stages{};
  stages[0] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0,
               VK_SHADER_STAGE_VERTEX_BIT, vert.get(), "main", nullptr};
  stages[1] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0,
               VK_SHADER_STAGE_FRAGMENT_BIT, frag.get(), "main", nullptr};

  const VkVertexInputBindingDescription binding{0, desc.stride, VK_VERTEX_INPUT_RATE_VERTEX};
  VkPipelineVertexInputStateCreateInfo input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  input.vertexBindingDescriptionCount = 1;
  input.pVertexBindingDescriptions = &binding;
  input.vertexAttributeDescriptionCount = static_cast<std::uint32_t>(desc.attributes.size());
  input.pVertexAttributeDescriptions = desc.attributes.data();
  VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = desc.cull;
  raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = samples;
  VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  depth.depthTestEnable = VK_TRUE;
  depth.depthWriteEnable = desc.depth_write ? VK_TRUE : VK_FALSE;
  depth.depthCompareOp = desc.depth_compare;
  VkPipelineColorBlendAttachmentState blend{};
  blend.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                         VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  if (desc.blend == Blend::Alpha) {
    blend.blendEnable = VK_TRUE;
    blend.srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
    blend.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    blend.colorBlendOp = VK_BLEND_OP_ADD;
    blend.srcAlphaBlendFactor = VK_BLEND_FACTOR_ZERO;  // keep the target's alpha (opaque picture)
    blend.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
    blend.alphaBlendOp = VK_BLEND_OP_ADD;
  }
  VkPipelineColorBlendStateCreateInfo blending{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  blending.attachmentCount = 1;
  blending.pAttachments = &blend;
  const std::array<VkDynamicState, 2> dynamic_states{VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamic.dynamicStateCount = static_cast<std::uint32_t>(dynamic_states.size());
  dynamic.pDynamicStates = dynamic_states.data();

  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  info.stageCount = static_cast<std::uint32_t>(stages.size());
  info.pStages = stages.data();
  info.pVertexInputState = &input;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &blending;
  info.pDynamicState = &dynamic;
  info.layout = layout;
  info.renderPass = pass;
  info.subpass = 0;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VK_CHECK(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
  return {device, pipeline};
}

glm::mat4 to_glm_matrix(const Eigen::Matrix4d& m) {
  glm::mat4 out;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) out[c][r] = static_cast<float>(m(r, c));
  return out;
}

glm::vec4 to_glm_vector(const Eigen::Vector3d& v) { return {float(v.x()), float(v.y()), float(v.z()), 0.0f}; }

// How far ribbons are lifted towards the eye, in half widths: enough that a stroke lying on the
// surface is not half buried, little enough that strokes behind a thin part stay behind it.
constexpr float kStrokeLift = 1.0f;
constexpr float kEdgeLift = 1.5f;

}  // namespace

GpuScene::GpuScene(const vk::Context& context, const SceneGeometry& geometry)
    : origin_(geometry.origin),
      bounds_(geometry.bounds),
      ribbon_vertices_(vk::upload_buffer(context, bytes_of(geometry.ribbon_vertices),
                                         VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "ribbon vertices")),
      ribbon_indices_(vk::upload_buffer(context, bytes_of(geometry.ribbon_indices),
                                        VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "ribbon indices")),
      mesh_vertices_(vk::upload_buffer(context, bytes_of(geometry.mesh_vertices),
                                       VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "mesh vertices")),
      mesh_indices_(vk::upload_buffer(context, bytes_of(geometry.mesh_indices),
                                      VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "mesh indices")),
      stroke_indices_(geometry.stroke_index_count),
      edge_indices_(static_cast<std::uint32_t>(geometry.ribbon_indices.size()) -
                    geometry.stroke_index_count),
      mesh_index_count_(static_cast<std::uint32_t>(geometry.mesh_indices.size())),
      mesh_closed_(geometry.mesh_closed) {}

Renderer::Renderer(const vk::Context& context, VkRenderPass render_pass,
                   VkSampleCountFlagBits samples)
    : context_(&context) {
  const VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                                 sizeof(FrameConstants)};
  VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layout_info.pushConstantRangeCount = 1;
  layout_info.pPushConstantRanges = &push;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VK_CHECK(vkCreatePipelineLayout(context.device(), &layout_info, nullptr, &layout));
  layout_ = vk::UniquePipelineLayout(context.device(), layout);

  PipelineDesc mesh_desc{mesh_vert_spv, mesh_frag_spv, sizeof(MeshVertex),
                         {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(MeshVertex, position)},
                          {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(MeshVertex, normal)},
                          {2, 0, VK_FORMAT_R8G8B8A8_UNORM, offsetof(MeshVertex, color)}}};
  mesh_ = make_pipeline(context, render_pass, samples, layout, mesh_desc);
  mesh_desc.cull = VK_CULL_MODE_BACK_BIT;
  mesh_culled_ = make_pipeline(context, render_pass, samples, layout, mesh_desc);

  PipelineDesc ribbon_desc{ribbon_vert_spv, ribbon_frag_spv, sizeof(RibbonVertex),
                           {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(RibbonVertex, position)},
                            {1, 0, VK_FORMAT_R32_SFLOAT, offsetof(RibbonVertex, side)},
                            {2, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(RibbonVertex, tangent)},
                            {3, 0, VK_FORMAT_R32_SFLOAT, offsetof(RibbonVertex, half_width)},
                            {4, 0, VK_FORMAT_R8G8B8A8_UNORM, offsetof(RibbonVertex, color)}}};
  ribbon_desc.depth_compare = VK_COMPARE_OP_LESS_OR_EQUAL;
  ribbon_ = make_pipeline(context, render_pass, samples, layout, ribbon_desc);
  // Translucent strokes (the drawing plane's grid): blended by their colours' alpha, hiding
  // nothing drawn after them.
  ribbon_desc.depth_write = false;
  ribbon_desc.blend = Blend::Alpha;
  ribbon_translucent_ = make_pipeline(context, render_pass, samples, layout, ribbon_desc);
  ribbon_desc.depth_write = true;
  ribbon_desc.blend = Blend::Opaque;
  // Hidden strokes: only where something (the surface) is in front, never writing depth.
  ribbon_desc.depth_compare = VK_COMPARE_OP_GREATER;
  ribbon_desc.depth_write = false;
  ribbon_desc.blend = Blend::Alpha;
  ribbon_hidden_ = make_pipeline(context, render_pass, samples, layout, ribbon_desc);
}

void Renderer::record(VkCommandBuffer cmd, const GpuScene& scene, const Camera& camera,
                      double aspect, const DrawOptions& options) const {
  // Everything is drawn relative to the scene origin: move the camera there in double precision.
  Camera local = camera;
  local.eye -= scene.origin_;
  local.target -= scene.origin_;
  FrameConstants frame;
  frame.view_proj = to_glm_matrix(local.projection_matrix(aspect) * local.view_matrix());
  frame.eye = to_glm_vector(local.eye);
  // Key light from the upper left behind the viewer.
  const Eigen::Vector3d forward = (local.target - local.eye).normalized();
  const Eigen::Vector3d right = forward.cross(local.up).normalized();
  const Eigen::Vector3d up = right.cross(forward);
  frame.light = to_glm_vector((-forward + 0.8 * up - 0.6 * right).normalized());

  auto push = [&](float alpha, float lift) {
    frame.params = glm::vec4(alpha, lift, 0.0f, 0.0f);
    vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                       0, sizeof(frame), &frame);
  };
  const VkDeviceSize zero = 0;
  if (options.mesh && scene.mesh_index_count_ > 0) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                      scene.mesh_closed_ ? mesh_culled_.get() : mesh_.get());
    push(1.0f, 0.0f);
    const VkBuffer vb = scene.mesh_vertices_.get();
    vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &zero);
    vkCmdBindIndexBuffer(cmd, scene.mesh_indices_.get(), 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(cmd, scene.mesh_index_count_, 1, 0, 0, 0);
  }
  const bool edges = options.mesh && scene.edge_indices_ > 0;
  const bool strokes = options.strokes && scene.stroke_indices_ > 0;
  if (!edges && !strokes) return;
  const VkBuffer vb = scene.ribbon_vertices_.get();
  vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &zero);
  vkCmdBindIndexBuffer(cmd, scene.ribbon_indices_.get(), 0, VK_INDEX_TYPE_UINT32);
  if (edges) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, ribbon_.get());
    push(1.0f, kEdgeLift);
    vkCmdDrawIndexed(cmd, scene.edge_indices_, 1, scene.stroke_indices_, 0, 0);
  }
  const bool occluded = (options.mesh && scene.mesh_index_count_ > 0) || options.occluders_drawn;
  if (strokes && options.hidden_strokes && occluded) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, ribbon_hidden_.get());
    push(options.hidden_alpha, kStrokeLift);
    vkCmdDrawIndexed(cmd, scene.stroke_indices_, 1, 0, 0, 0);
  }
  if (strokes) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                      options.translucent_strokes ? ribbon_translucent_.get() : ribbon_.get());
    push(1.0f, kStrokeLift);
    vkCmdDrawIndexed(cmd, scene.stroke_indices_, 1, 0, 0, 0);
  }
}

}  // namespace sketchsurf::render
