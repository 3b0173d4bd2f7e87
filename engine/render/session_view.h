#pragma once
// SessionView: what the studio draws of a session, on any target (the offscreen target of
// --headless, the window's swapchain): the strokes, the stroke being drawn (and its mirror image),
// the surface over them (regions on or off; strokes hidden by it drawn faintly), the drawing
// plane's grid and the controller. Built from the session and uploaded only when something
// changed; recorded by the one Renderer into whatever render pass is begun.

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "engine/input/controller.h"
#include "engine/render/renderer.h"
#include "engine/session/session.h"

namespace sketchsurf::render {

/// What to show.
struct SessionViewOptions {
  bool strokes = true;            ///< the sketch's strokes
  bool surface = true;            ///< the last surface computed
  bool regions = true;            ///< the surface coloured by region (else one colour)
  bool grid = true;               ///< the drawing plane's grid
  bool cursor = true;             ///< the controller, as three short axes
  float hidden_alpha = 0.2f;      ///< opacity of the strokes the surface hides
  std::array<float, 4> background{1.0f, 1.0f, 1.0f, 1.0f};
  double stroke_width = 0.008;    ///< ribbon width, fraction of the session's reference size
};

/// The controller and drawing aids of one frame.
struct Overlay {
  std::optional<input::Pose> cursor;   ///< where the controller is (none: not drawn)
  std::optional<Plane> drawing_plane;  ///< its grid is drawn around `grid_centre`
  Eigen::Vector3d grid_centre = Eigen::Vector3d::Zero();
};

class SessionView {
 public:
  /// Borrows the context, which must outlive the view.
  explicit SessionView(const vk::Context& context);

  /// Rebuilds and uploads what changed since the last call. A replaced scene is freed once the
  /// last frame that recorded it (see record()) lets go of it.
  void update(const session::SketchSession& session, const Overlay& overlay,
              const SessionViewOptions& options);

  /// Records the draws into the render pass begun on `cmd` (viewport and scissor set): surface,
  /// strokes (faint where hidden by it), stroke in progress, grid, controller. Adds the scenes
  /// recorded to `in_use`, which the caller keeps until the frame's commands have completed.
  void record(VkCommandBuffer cmd, const Renderer& renderer, const Camera& camera, double aspect,
              const SessionViewOptions& options,
              std::vector<std::shared_ptr<const void>>* in_use = nullptr) const;

  /// Strokes, stroke in progress, surface, grid and controller together.
  BoundingBox bounds() const;
  /// Points and triangles drawn (for the status line).
  std::size_t points() const { return points_; }
  std::size_t triangles() const { return triangles_; }
  /// How many uploads update() did since the view was made (tests: nothing changed, none done).
  std::size_t uploads() const { return uploads_; }

 private:
  struct Layer {
    std::shared_ptr<GpuScene> scene;
    BoundingBox bounds;
  };
  void upload(Layer& layer, const SceneGeometry& geometry);

  const vk::Context* context_;
  Layer sketch_, live_, surface_, overlay_;
  std::uint64_t sketch_revision_ = 0, live_revision_ = 0, result_revision_ = 0;
  bool have_sketch_ = false, have_live_ = false, have_surface_ = false;
  bool regions_ = true;
  double reference_ = 0.0, stroke_width_ = 0.0;
  std::optional<std::array<double, 11>> overlay_key_;
  std::size_t points_ = 0, triangles_ = 0, uploads_ = 0;
};

}  // namespace sketchsurf::render
