#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <array>
#include <chrono>
#include <csignal>
#include <cstdlib>

#include "engine/render/image.h"
#include "engine/session/actions.h"
#include "engine/session/drawing_plane.h"
#include "engine/vk/check.h"
#include "engine/vk/swapchain.h"
#include "tools/sketchsurf-studio/run.h"
#include "tools/sketchsurf-studio/ui.h"

namespace sketchsurf::studio {

namespace {

constexpr std::size_t kFramesInFlight = 2;

/// Set by SIGINT / SIGTERM: the loop ends as if the window were closed (the sketch is saved,
/// the recording written, like a normal exit).
volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }

std::string& glfw_error() {
  static std::string last;  // GLFW reports errors through a C callback without user data
  return last;
}

/// Owns GLFW's initialisation and the window (declared before the Vulkan context: the window
/// outlives the surface made on it, the surface is gone before the instance).
struct WindowSystem {
  GLFWwindow* window = nullptr;
  bool initialised = false;
  WindowSystem() = default;
  WindowSystem(const WindowSystem&) = delete;
  WindowSystem& operator=(const WindowSystem&) = delete;
  ~WindowSystem() {
    if (window) glfwDestroyWindow(window);
    if (initialised) glfwTerminate();
  }
};

/// Owns the window's Vulkan surface (declared after the context, before the swapchain).
struct Surface {
  VkInstance instance = VK_NULL_HANDLE;
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  Surface() = default;
  Surface(const Surface&) = delete;
  Surface& operator=(const Surface&) = delete;
  ~Surface() {
    if (surface != VK_NULL_HANDLE) vkDestroySurfaceKHR(instance, surface, nullptr);
  }
};

/// What the GLFW callbacks reach (through the window's user pointer).
struct Handler {
  Studio* studio = nullptr;
  ImGuiLayer* ui = nullptr;
  double t0 = 0.0;
  bool resized = false;
  double now() const { return glfwGetTime() - t0; }
};

Handler& handler_of(GLFWwindow* window) { return *static_cast<Handler*>(glfwGetWindowUserPointer(window)); }

input::Modifiers modifiers(int mods) {
  return {(mods & GLFW_MOD_SHIFT) != 0, (mods & GLFW_MOD_CONTROL) != 0, (mods & GLFW_MOD_ALT) != 0};
}

input::Modifiers held_modifiers(GLFWwindow* w) {
  const auto down = [w](int a, int b) {
    return glfwGetKey(w, a) == GLFW_PRESS || glfwGetKey(w, b) == GLFW_PRESS;
  };
  return {down(GLFW_KEY_LEFT_SHIFT, GLFW_KEY_RIGHT_SHIFT), down(GLFW_KEY_LEFT_CONTROL, GLFW_KEY_RIGHT_CONTROL),
          down(GLFW_KEY_LEFT_ALT, GLFW_KEY_RIGHT_ALT)};
}

void on_cursor(GLFWwindow* window, double x, double y) {
  Handler& h = handler_of(window);
  if (h.studio) h.studio->mouse().move(x, y, h.now());
}

void on_button(GLFWwindow* window, int button, int action, int mods) {
  Handler& h = handler_of(window);
  if (!h.studio) return;
  if (action == GLFW_PRESS && h.ui && h.ui->wants_mouse()) return;  // a click on the panel
  const input::MouseButton b = button == GLFW_MOUSE_BUTTON_RIGHT    ? input::MouseButton::Right
                               : button == GLFW_MOUSE_BUTTON_MIDDLE ? input::MouseButton::Middle
                                                                    : input::MouseButton::Left;
  if (button > GLFW_MOUSE_BUTTON_MIDDLE) return;
  h.studio->mouse().button(b, action == GLFW_PRESS, modifiers(mods), h.now());
}

void on_scroll(GLFWwindow* window, double, double dy) {
  Handler& h = handler_of(window);
  if (!h.studio || (h.ui && h.ui->wants_mouse())) return;
  h.studio->mouse().scroll(dy, held_modifiers(window), h.now());
}

/// The drawing aids' keys: G plane guide, P plane through three clicks, V plane facing the view,
/// A next axis plane, N snap, O over-sketch, L straight, K smoothing (0 / 3 rounds), R rotation.
void toggle_aid(Studio& s, int key) {
  const session::DrawingOptions& d = s.session().drawing();
  switch (key) {
    case GLFW_KEY_G: s.act(session::aid_action("plane_guide", !d.plane_guide)); break;
    case GLFW_KEY_P: s.act(session::tool_action(session::Tool::PlacePlane)); break;
    case GLFW_KEY_V: s.act(plane_facing_view(s)); break;
    case GLFW_KEY_A: {
      // z -> x -> y: XY, YZ, XZ through the origin.
      const Eigen::Vector3d& n = d.plane.normal;
      const int axis = std::abs(n.z()) > 0.999 ? 0 : std::abs(n.x()) > 0.999 ? 1 : 2;
      s.act(session::plane_action(session::axis_plane(axis, Eigen::Vector3d::Zero())));
      break;
    }
    case GLFW_KEY_N: s.act(session::aid_action("snap", !d.snap)); break;
    case GLFW_KEY_O: s.act(session::aid_action("oversketch", !d.oversketch)); break;
    case GLFW_KEY_L: s.act(session::aid_action("straight", !d.straight)); break;
    case GLFW_KEY_K: s.act(session::aid_action("smoothing", d.smoothing > 0 ? 0 : 3)); break;
    case GLFW_KEY_R:
      s.act(s.session().sketch().rotation ? session::simple_action("clear_rotation")
                                          : session::rotation_action(default_rotation(6)));
      break;
    default: break;
  }
}

void on_key(GLFWwindow* window, int key, int, int action, int mods) {
  Handler& h = handler_of(window);
  if (!h.studio || action != GLFW_PRESS || (h.ui && h.ui->wants_keyboard())) return;
  Studio& s = *h.studio;
  const bool ctrl = (mods & GLFW_MOD_CONTROL) != 0, shift = (mods & GLFW_MOD_SHIFT) != 0;
  int w = 0, ht = 0;
  glfwGetWindowSize(window, &w, &ht);
  switch (key) {
    case GLFW_KEY_Z:
      if (ctrl) s.act(session::simple_action(shift ? "redo" : "undo"));
      break;
    case GLFW_KEY_Y:
      if (ctrl) s.act(session::simple_action("redo"));
      break;
    case GLFW_KEY_Q:
      if (ctrl) glfwSetWindowShouldClose(window, GLFW_TRUE);
      break;
    case GLFW_KEY_ESCAPE: s.act(session::simple_action("cancel")); break;
    case GLFW_KEY_S:
      if (!ctrl) s.act(session::simple_action("surface"));
      break;
    case GLFW_KEY_D: s.act(session::tool_action(session::Tool::Draw)); break;
    case GLFW_KEY_E: s.act(session::tool_action(session::Tool::Erase)); break;
    case GLFW_KEY_B: s.act(session::tool_action(session::Tool::MarkBoundary)); break;
    case GLFW_KEY_I: s.act(session::tool_action(session::Tool::MarkIgnored)); break;
    case GLFW_KEY_M:
      s.act(s.session().sketch().mirror ? session::simple_action("clear_mirror")
                                        : session::mirror_action({Eigen::Vector3d::UnitX(), 0.0}));
      break;
    case GLFW_KEY_F: s.frame_all(w, ht); break;
    default: toggle_aid(s, key); break;
    case GLFW_KEY_TAB: s.panel_visible = !s.panel_visible; break;
    case GLFW_KEY_1: s.mouse().view().look_from(render::View::Front); break;
    case GLFW_KEY_3: s.mouse().view().look_from(render::View::Right); break;
    case GLFW_KEY_7: s.mouse().view().look_from(render::View::Top); break;
    case GLFW_KEY_5: s.mouse().view().look_from(render::View::Iso); break;
  }
}

void on_framebuffer(GLFWwindow* window, int, int) { handler_of(window).resized = true; }

void on_window_size(GLFWwindow* window, int w, int h) {
  Handler& hd = handler_of(window);
  if (hd.studio) hd.studio->mouse().resize(w, h);
}

/// Per frame in flight: its command buffer, the fence of its submission, the semaphore of its
/// acquired image, and the scenes its commands use (released once the fence is passed).
struct FrameSlot {
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  vk::UniqueFence fence;
  vk::UniqueSemaphore acquired;
  std::vector<std::shared_ptr<const void>> in_use;
};

vk::UniqueSemaphore make_semaphore(VkDevice device) {
  VkSemaphoreCreateInfo info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  VkSemaphore s = VK_NULL_HANDLE;
  VK_CHECK(vkCreateSemaphore(device, &info, nullptr, &s));
  return {device, s};
}

}  // namespace

void catch_stop_signals() {
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
}

bool stop_requested() { return g_stop != 0; }

std::string no_display_message(const std::string& detail) {
  return "no display to open a window on (" + detail +
         "); run with --headless for offscreen rendering, or under a virtual display: "
         "xvfb-run -a sketchsurf-studio ... (Debian package xvfb)";
}

int run_window(const StudioOptions& options, const Log& log) {
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((!display || !*display) && (!wayland || !*wayland))
    throw Error::processing(no_display_message("DISPLAY is not set"));
  WindowSystem ws;
  glfwSetErrorCallback([](int, const char* text) { glfw_error() = text ? text : "unknown GLFW error"; });
  if (!glfwInit()) throw Error::processing(no_display_message(glfw_error()));
  ws.initialised = true;
  if (!glfwVulkanSupported())
    throw Error::processing("GLFW finds no Vulkan loader; install the Debian packages libvulkan1 and "
                            "mesa-vulkan-drivers, or run with --headless");
  std::uint32_t count = 0;
  const char** extensions = glfwGetRequiredInstanceExtensions(&count);
  vk::ContextOptions co = context_options(options, log);
  for (std::uint32_t i = 0; i < count; ++i) co.instance_extensions.emplace_back(extensions[i]);
  co.presentation = true;
  const vk::Context context(co);

  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  ws.window = glfwCreateWindow(options.width, options.height, "sketchsurf studio", nullptr, nullptr);
  if (!ws.window) throw Error::processing(no_display_message(glfw_error()));
  Surface surface;
  surface.instance = context.instance();
  VK_CHECK(glfwCreateWindowSurface(context.instance(), ws.window, nullptr, &surface.surface));
  int fb_w = 0, fb_h = 0;
  glfwGetFramebufferSize(ws.window, &fb_w, &fb_h);
  vk::Swapchain swapchain(context, surface.surface,
                          {std::uint32_t(std::max(fb_w, 1)), std::uint32_t(std::max(fb_h, 1))},
                          options.vsync, sample_count(options.msaa, context));
  const auto describe = [&] {
    return std::to_string(swapchain.extent().width) + "x" + std::to_string(swapchain.extent().height) +
           ", " + std::to_string(swapchain.image_count()) + " images";
  };
  log.info("window on '" + context.device_info().name + "': swapchain " + describe() + ", MSAA " +
           std::to_string(int(swapchain.samples())));
  const render::Renderer renderer(context, swapchain.render_pass(), swapchain.samples());
  Studio studio(options, context, log);
  int win_w = 0, win_h = 0;
  glfwGetWindowSize(ws.window, &win_w, &win_h);
  studio.mouse().resize(win_w, win_h);

  Handler handler;
  handler.studio = &studio;
  handler.t0 = glfwGetTime();
  glfwSetWindowUserPointer(ws.window, &handler);
  glfwSetCursorPosCallback(ws.window, on_cursor);
  glfwSetMouseButtonCallback(ws.window, on_button);
  glfwSetScrollCallback(ws.window, on_scroll);
  glfwSetKeyCallback(ws.window, on_key);
  glfwSetFramebufferSizeCallback(ws.window, on_framebuffer);
  glfwSetWindowSizeCallback(ws.window, on_window_size);
  // ImGui's GLFW backend chains the callbacks above: they run first, and ask wants_mouse().
  ImGuiLayer ui(context, swapchain.render_pass(), swapchain.samples(), swapchain.image_count(), ws.window);
  handler.ui = &ui;

  const VkDevice device = context.device();
  VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pool_info.queueFamilyIndex = context.queue_family();
  VkCommandPool pool_handle = VK_NULL_HANDLE;
  VK_CHECK(vkCreateCommandPool(device, &pool_info, nullptr, &pool_handle));
  const vk::UniqueCommandPool pool(device, pool_handle);
  std::array<FrameSlot, kFramesInFlight> slots;
  for (auto& slot : slots) {
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = pool.get();
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VK_CHECK(vkAllocateCommandBuffers(device, &alloc, &slot.cmd));
    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    fence_info.flags = VK_FENCE_CREATE_SIGNALED_BIT;
    VkFence fence = VK_NULL_HANDLE;
    VK_CHECK(vkCreateFence(device, &fence_info, nullptr, &fence));
    slot.fence = vk::UniqueFence(device, fence);
    slot.acquired = make_semaphore(device);
  }
  // One "rendering done" semaphore per swapchain image: presentation holds it until the image
  // is shown, which the fences of the frames in flight do not cover.
  std::vector<vk::UniqueSemaphore> rendered;
  const auto make_rendered = [&] {
    rendered.clear();
    for (std::uint32_t i = 0; i < swapchain.image_count(); ++i) rendered.push_back(make_semaphore(device));
  };
  make_rendered();
  const auto recreate = [&] {
    int w = 0, h = 0;
    glfwGetFramebufferSize(ws.window, &w, &h);
    swapchain.recreate({std::uint32_t(std::max(w, 1)), std::uint32_t(std::max(h, 1))});
    make_rendered();
    handler.resized = false;
    log.info("swapchain recreated: " + describe());
  };

  vk::Buffer shot;
  PanelState panel;
  std::size_t frame = 0, presented = 0;
  double previous = 0.0;
  bool screenshot_written = false;
  catch_stop_signals();
  while (!glfwWindowShouldClose(ws.window) && !g_stop) {
    glfwPollEvents();
    int w = 0, h = 0;
    glfwGetFramebufferSize(ws.window, &w, &h);
    if (w == 0 || h == 0) {  // minimised: nothing to present until it comes back
      glfwWaitEventsTimeout(0.05);
      continue;
    }
    if (handler.resized || std::uint32_t(w) != swapchain.extent().width ||
        std::uint32_t(h) != swapchain.extent().height)
      recreate();
    const auto start = std::chrono::steady_clock::now();
    FrameSlot& slot = slots[frame % kFramesInFlight];
    const VkFence fence = slot.fence.get();
    VK_CHECK(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX));
    slot.in_use.clear();
    std::uint32_t image = 0;
    const VkResult acquired =
        vkAcquireNextImageKHR(device, swapchain.get(), UINT64_MAX, slot.acquired.get(), VK_NULL_HANDLE, &image);
    if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
      recreate();
      continue;
    }
    if (acquired != VK_SUCCESS && acquired != VK_SUBOPTIMAL_KHR) VK_CHECK(acquired);

    const double now = options.frames ? studio.simulated_time(frame) : handler.now();
    studio.input(now);
    const int width = int(swapchain.extent().width), height = int(swapchain.extent().height);
    ui.new_frame(width, height, now - previous);
    previous = now;
    draw_panel(studio, panel, log);
    studio.update();
    const bool last = options.frames && studio.done(frame + 1);
    const bool take_shot = last && !options.screenshot.empty() && swapchain.readable();
    if (take_shot)
      shot = vk::Buffer(context, VkDeviceSize(width) * height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                        vk::MemoryUse::HostVisible, "screenshot");

    VK_CHECK(vkResetFences(device, 1, &fence));
    VK_CHECK(vkResetCommandBuffer(slot.cmd, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(slot.cmd, &begin));
    swapchain.begin(slot.cmd, image, studio.view_options().background);
    studio.record(slot.cmd, renderer, width, height, &slot.in_use);
    ui.render(slot.cmd);
    vkCmdEndRenderPass(slot.cmd);
    if (take_shot) swapchain.record_copy(slot.cmd, image, shot);
    VK_CHECK(vkEndCommandBuffer(slot.cmd));

    const VkSemaphore wait = slot.acquired.get(), signal = rendered[image].get();
    const VkPipelineStageFlags stage = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.waitSemaphoreCount = 1;
    submit.pWaitSemaphores = &wait;
    submit.pWaitDstStageMask = &stage;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &slot.cmd;
    submit.signalSemaphoreCount = 1;
    submit.pSignalSemaphores = &signal;
    VK_CHECK(vkQueueSubmit(context.queue(), 1, &submit, fence));
    VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    present.waitSemaphoreCount = 1;
    present.pWaitSemaphores = &signal;
    const VkSwapchainKHR chain = swapchain.get();
    present.swapchainCount = 1;
    present.pSwapchains = &chain;
    present.pImageIndices = &image;
    const VkResult shown = vkQueuePresentKHR(context.queue(), &present);
    if (shown == VK_ERROR_OUT_OF_DATE_KHR || shown == VK_SUBOPTIMAL_KHR)
      handler.resized = true;
    else
      VK_CHECK(shown);
    ++presented;
    ++frame;
    studio.frame_finished(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (last) {
      if (take_shot) {
        VK_CHECK(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX));
        render::write_png({width, height, swapchain.pixels(shot)}, options.screenshot);
        log.info("wrote " + options.screenshot.string());
        screenshot_written = true;
      }
      break;
    }
  }
  VK_CHECK(vkDeviceWaitIdle(device));
  if (!options.screenshot.empty() && !screenshot_written)
    log.info(swapchain.readable() ? "no screenshot: the window was closed before the last frame"
                                  : "no screenshot: this surface's images cannot be read back");
  studio.finish();
  log.info("presented " + std::to_string(presented) + " frames; " + summary(studio.stats()));
  if (context.validation_enabled())
    log.info("validation: " + std::to_string(context.validation_messages().size()) + " messages");
  return 0;
}

}  // namespace sketchsurf::studio
