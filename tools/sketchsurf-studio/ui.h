#pragma once
// The panel (Dear ImGui, Debian's libimgui-dev with its GLFW and Vulkan backends): tools, undo /
// redo, mirror, drawing depth, surfacing with progress and parameters, view toggles, files and a
// status line. Drawn into the same render pass as the scene, on either target.

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <string>

#include "engine/vk/context.h"
#include "engine/vk/handle.h"
#include "tools/sketchsurf-studio/studio.h"

struct GLFWwindow;

namespace sketchsurf::studio {

/// ImGui's context and Vulkan backend for one render pass. One per process.
class ImGuiLayer {
 public:
  /// `window` null: headless (display size and time are given to new_frame()).
  ImGuiLayer(const vk::Context& context, VkRenderPass render_pass, VkSampleCountFlagBits samples,
             std::uint32_t image_count, GLFWwindow* window);
  ~ImGuiLayer();
  ImGuiLayer(const ImGuiLayer&) = delete;
  ImGuiLayer& operator=(const ImGuiLayer&) = delete;

  /// Starts a frame of width x height pixels, `dt` seconds after the previous one.
  void new_frame(int width, int height, double dt);
  /// Ends the frame and records its draws into the render pass begun on `cmd`.
  void render(VkCommandBuffer cmd);
  /// Ends the frame without drawing it. ImGui sizes a new window in its first frame and shows
  /// it from the second: a first frame laid out and thrown away puts the panel in a one-frame
  /// picture.
  void discard();
  /// The panel has the mouse (or the keyboard): the 3D view must not take the event.
  bool wants_mouse() const;
  bool wants_keyboard() const;

 private:
  const vk::Context* context_;
  vk::UniqueDescriptorPool pool_;
  bool glfw_ = false;
};

/// What the panel keeps between frames.
struct PanelState {
  std::array<char, 512> path{};  ///< the file field
  int depth_mode = 0;            ///< 0 plane, 1 distance, 2 snap
  int plane = 0;                 ///< 0 XY (z = 0), 1 YZ (x = 0), 2 XZ (y = 0), 3 facing the
                                 ///< view, 4 three clicks
  int rotation_count = 6;        ///< the rotation's fold
  float epsilon = 0.01f;
  int restarts = 10;
  int proxy_points = 400;
  bool initialised = false;
  std::size_t frame = 0;
};

/// The drawing aids' part of the panel: the plane, the guide, snap, over-sketch, straight,
/// smoothing, rotation.
void draw_aids(Studio& studio, PanelState& state);
/// The action that puts the drawing plane through the view's target, facing the view (V).
input::TrackAction plane_facing_view(const Studio& studio);
/// The rotational pattern of the panel and the R key: `count`-fold about the vertical (y) axis
/// through the origin (sketches are y-up).
RotationPattern default_rotation(int count);

/// Draws the panel for this frame and applies what was clicked (through studio.act() for the
/// actions a track records). With --verbose, logs where the main widgets are on the 3rd frame
/// ("panel: 'Mirror' at X Y"), for scripted clicks.
void draw_panel(Studio& studio, PanelState& state, const Log& log);

}  // namespace sketchsurf::studio
