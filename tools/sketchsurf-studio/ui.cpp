#include "tools/sketchsurf-studio/ui.h"

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>

#include <algorithm>
#include <cstring>
#include <sstream>

#include "engine/session/actions.h"
#include "engine/session/drawing_plane.h"
#include "engine/vk/check.h"
#include "surfacing/error.h"

namespace sketchsurf::studio {

namespace {

void check_vk(VkResult result) {
  if (result < 0) vk::throw_vk_error(result, "ImGui Vulkan backend", __FILE__, __LINE__);
}

std::string fixed(double v, int digits) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(digits);
  out << v;
  return out.str();
}

}  // namespace

ImGuiLayer::ImGuiLayer(const vk::Context& context, VkRenderPass render_pass,
                       VkSampleCountFlagBits samples, std::uint32_t image_count, GLFWwindow* window)
    : context_(&context) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // the panel's place is fixed; nothing to remember
  ImGui::StyleColorsLight();
  ImGui::GetStyle().WindowRounding = 4.0f;
  if (window) {
    ImGui_ImplGlfw_InitForVulkan(window, true);
    glfw_ = true;
  }
  const std::array<VkDescriptorPoolSize, 1> sizes{{{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 8}}};
  VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pool_info.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  pool_info.maxSets = 8;
  pool_info.poolSizeCount = static_cast<std::uint32_t>(sizes.size());
  pool_info.pPoolSizes = sizes.data();
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VK_CHECK(vkCreateDescriptorPool(context.device(), &pool_info, nullptr, &pool));
  pool_ = vk::UniqueDescriptorPool(context.device(), pool);

  ImGui_ImplVulkan_InitInfo info{};
  info.Instance = context.instance();
  info.PhysicalDevice = context.physical_device();
  info.Device = context.device();
  info.QueueFamily = context.queue_family();
  info.Queue = context.queue();
  info.DescriptorPool = pool;
  info.MinImageCount = std::max(2u, image_count);
  info.ImageCount = std::max(2u, image_count);
  info.MSAASamples = samples;
  info.CheckVkResultFn = &check_vk;
  ImGui_ImplVulkan_Init(&info, render_pass);
  context.submit_and_wait([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();
}

ImGuiLayer::~ImGuiLayer() {
  vkDeviceWaitIdle(context_->device());
  ImGui_ImplVulkan_Shutdown();
  if (glfw_) ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

void ImGuiLayer::new_frame(int width, int height, double dt) {
  ImGui_ImplVulkan_NewFrame();
  ImGuiIO& io = ImGui::GetIO();
  if (glfw_) {
    ImGui_ImplGlfw_NewFrame();
  } else {
    io.DisplaySize = ImVec2(float(width), float(height));
    io.DeltaTime = float(std::max(dt, 1e-4));
  }
  ImGui::NewFrame();
}

void ImGuiLayer::render(VkCommandBuffer cmd) {
  ImGui::Render();
  ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
}

void ImGuiLayer::discard() { ImGui::EndFrame(); }

bool ImGuiLayer::wants_mouse() const { return ImGui::GetIO().WantCaptureMouse; }
bool ImGuiLayer::wants_keyboard() const { return ImGui::GetIO().WantCaptureKeyboard; }

void draw_aids(Studio& studio, PanelState& st) {
  auto& session = studio.session();
  const auto act = [&](const input::TrackAction& a) { studio.act(a); };
  const session::DrawingOptions& d = session.drawing();
  ImGui::Separator();
  // The combo shows the plane however it was set (keys, a track): an axis plane by its normal.
  const Eigen::Vector3d& n = d.plane.normal;
  const int shown = n == Eigen::Vector3d::UnitZ() ? 0 : n == Eigen::Vector3d::UnitX() ? 1 : n == Eigen::Vector3d::UnitY() ? 2 : -1;
  if (shown >= 0) st.plane = shown;
  if (shown < 0 && st.plane < 3) st.plane = 3;
  if (ImGui::Combo("Plane", &st.plane, "XY (z = 0)\0YZ (x = 0)\0XZ (y = 0)\0Facing the view (V)\0Three clicks (P)\0")) {
    if (st.plane < 3) act(session::plane_action(session::axis_plane(st.plane == 0 ? 2 : st.plane == 1 ? 0 : 1,
                                                                     Eigen::Vector3d::Zero())));
    if (st.plane == 3) act(plane_facing_view(studio));
    if (st.plane == 4) act(session::tool_action(session::Tool::PlacePlane));
  }
  bool guide = d.plane_guide, snap = d.snap, over = d.oversketch, straight = d.straight;
  if (ImGui::Checkbox("Plane guide (G)", &guide)) act(session::aid_action("plane_guide", guide));
  ImGui::SameLine();
  if (ImGui::Checkbox("Snap ends (N)", &snap)) act(session::aid_action("snap", snap));
  if (ImGui::Checkbox("Over-sketch (O)", &over)) act(session::aid_action("oversketch", over));
  ImGui::SameLine();
  if (ImGui::Checkbox("Straight (L)", &straight)) act(session::aid_action("straight", straight));
  int smoothing = d.smoothing;
  if (ImGui::SliderInt("Smoothing (K)", &smoothing, 0, 20)) act(session::aid_action("smoothing", smoothing));
  const auto& rotation = session.sketch().rotation;
  bool rotate = rotation.has_value();
  if (ImGui::Checkbox("Rotation (R)", &rotate))
    act(rotate ? session::rotation_action(default_rotation(st.rotation_count))
               : session::simple_action("clear_rotation"));
  ImGui::SameLine();
  ImGui::SetNextItemWidth(90.0f);
  if (ImGui::InputInt("fold", &st.rotation_count)) {
    st.rotation_count = std::clamp(st.rotation_count, 2, 36);
    if (rotation) act(session::rotation_action(default_rotation(st.rotation_count)));
  }
}

input::TrackAction plane_facing_view(const Studio& studio) {
  const render::Camera camera = studio.camera();
  return session::plane_action(session::plane_facing(camera, camera.target));
}

RotationPattern default_rotation(int count) {
  RotationPattern r;
  r.center = Eigen::Vector3d::Zero();
  r.axis = Eigen::Vector3d::UnitY();
  r.count = count;
  return r;
}

void draw_panel(Studio& studio, PanelState& st, const Log& log) {
  auto& session = studio.session();
  auto& mouse = studio.mouse();
  auto& view = studio.view_options();
  if (!st.initialised) {
    st.epsilon = float(session.params().segment.epsilon);
    st.restarts = session.params().segment.restarts;
    st.proxy_points = session.params().proxy.points;
    const std::string file = session.file().empty() ? "sketch.json" : session.file().string();
    std::strncpy(st.path.data(), file.c_str(), st.path.size() - 1);
    st.initialised = true;
  }
  ++st.frame;
  const FrameStats stats = studio.stats();
  if (!studio.panel_visible) {
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_Always);
    ImGui::Begin("##status", nullptr,
                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                     ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoInputs);
    ImGui::Text("%zu strokes | %.1f ms | Tab: panel", session.sketch().strokes.size(), stats.median_ms);
    ImGui::End();
    return;
  }
  std::vector<std::pair<std::string, ImVec2>> where;
  const auto remember = [&](const char* name) {
    const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
    where.push_back({name, ImVec2(0.5f * (a.x + b.x), 0.5f * (a.y + b.y))});
  };
  const auto act = [&](const input::TrackAction& a) { studio.act(a); };
  const auto attempt = [&](const std::string& done, const auto& fn) {
    try {
      fn();
      studio.set_status(done);
    } catch (const Error& e) {
      studio.set_status(e.what());
    }
  };

  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(float(Studio::kPanelWidth), 0), ImGuiCond_Always);
  ImGui::Begin("sketchsurf studio", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoSavedSettings);

  ImGui::TextUnformatted("Tool");
  const std::array<std::pair<session::Tool, const char*>, 4> tools{{{session::Tool::Draw, "Draw"},
                                                                    {session::Tool::Erase, "Erase"},
                                                                    {session::Tool::MarkBoundary, "Boundary"},
                                                                    {session::Tool::MarkIgnored, "Ignore"}}};
  for (std::size_t i = 0; i < tools.size(); ++i) {
    if (i > 0) ImGui::SameLine();
    if (ImGui::RadioButton(tools[i].second, session.tool() == tools[i].first))
      act(session::tool_action(tools[i].first));
  }
  ImGui::BeginDisabled(!session.can_undo());
  if (ImGui::Button("Undo")) act(session::simple_action("undo"));
  ImGui::EndDisabled();
  remember("Undo");
  ImGui::SameLine();
  ImGui::BeginDisabled(!session.can_redo());
  if (ImGui::Button("Redo")) act(session::simple_action("redo"));
  ImGui::EndDisabled();
  remember("Redo");
  ImGui::SameLine();
  if (ImGui::Button("Clear")) act(session::simple_action("clear"));
  ImGui::SameLine();
  bool mirror = session.sketch().mirror.has_value();
  if (ImGui::Checkbox("Mirror x=0", &mirror))
    act(mirror ? session::mirror_action({Eigen::Vector3d::UnitX(), 0.0})
               : session::simple_action("clear_mirror"));
  remember("Mirror");

  if (ImGui::Combo("Depth", &st.depth_mode, "Drawing plane\0Distance\0Snap\0"))
    mouse.set_depth_mode(st.depth_mode == 0   ? input::DepthMode::Plane
                         : st.depth_mode == 1 ? input::DepthMode::Distance
                                              : input::DepthMode::Snap);
  draw_aids(studio, st);

  ImGui::Separator();
  const session::SurfaceStatus job = session.surface_status();
  const bool running = job.state == session::JobState::Running || job.state == session::JobState::Cancelling;
  if (running) {
    const std::string label = job.stage + " " + fixed(100.0 * job.fraction, 0) + "%";
    ImGui::ProgressBar(float(job.fraction), ImVec2(-1.0f, 0.0f), label.c_str());
    if (ImGui::Button("Cancel (Esc)")) act(session::simple_action("cancel"));
    remember("Cancel");
  } else {
    if (ImGui::Button("Surface (S)")) act(session::simple_action("surface"));
    remember("Surface");
  }
  ImGui::SliderFloat("epsilon", &st.epsilon, 0.001f, 0.05f, "%.4f", ImGuiSliderFlags_Logarithmic);
  if (ImGui::IsItemDeactivatedAfterEdit()) act(session::param_action("segment.epsilon", st.epsilon));
  ImGui::InputInt("restarts", &st.restarts);
  if (ImGui::IsItemDeactivatedAfterEdit()) act(session::param_action("segment.restarts", st.restarts));
  ImGui::InputInt("proxy points", &st.proxy_points, 50, 200);
  if (ImGui::IsItemDeactivatedAfterEdit()) act(session::param_action("proxy.points", st.proxy_points));

  ImGui::Separator();
  ImGui::Checkbox("Strokes", &view.strokes);
  ImGui::SameLine();
  ImGui::Checkbox("Surface", &view.surface);
  ImGui::SameLine();
  ImGui::Checkbox("Regions", &view.regions);
  ImGui::SameLine();
  ImGui::Checkbox("Grid", &view.grid);

  ImGui::Separator();
  ImGui::SetNextItemWidth(-1.0f);
  ImGui::InputText("##file", st.path.data(), st.path.size());
  const std::string path(st.path.data());
  if (ImGui::Button("Open")) act(session::open_action(path));
  ImGui::SameLine();
  if (ImGui::Button("Save")) attempt("saved " + path, [&] { session.save(path); });
  ImGui::SameLine();
  if (ImGui::Button("Save surface")) attempt("wrote the surface to " + path, [&] { session.save_surface(path); });
  ImGui::SameLine();
  if (ImGui::Button("Proxy")) attempt("proxy " + path, [&] { session.open_proxy(path); });

  ImGui::Separator();
  ImGui::Text("%zu strokes, %zu points, %zu triangles", session.sketch().strokes.size(),
              session.sketch().point_count(),
              std::size_t(session.result() ? session.result()->mesh.n_faces() : 0));
  ImGui::Text("frame %.1f ms%s%s", stats.median_ms, session.modified() ? " | unsaved" : "",
              session.has_proxy() ? " | proxy" : "");
  ImGui::TextWrapped("%s", studio.status().c_str());
  ImGui::End();

  if (st.frame == 3)
    for (const auto& [name, at] : where)
      log.detail("panel: '" + name + "' at " + std::to_string(int(at.x)) + " " + std::to_string(int(at.y)));
}

}  // namespace sketchsurf::studio
