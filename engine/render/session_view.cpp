#include "engine/render/session_view.h"

#include <cmath>

#include "engine/render/palette.h"

namespace sketchsurf::render {

namespace {

// Semi-transparent (Kuhn 2009 §3.4): strokes behind the plane show through its grid.
constexpr std::array<float, 4> kGridColor{0.55f, 0.62f, 0.72f, 0.35f};
constexpr std::array<float, 4> kGridAxisColor{0.3f, 0.4f, 0.55f, 0.6f};
constexpr int kGridHalfLines = 5;      // lines each side of the centre
constexpr double kGridSpacing = 0.1;   // of the reference size
constexpr double kCursorLength = 0.06; // axes of the controller, of the reference size

/// Two unit vectors spanning `plane`.
std::pair<Eigen::Vector3d, Eigen::Vector3d> plane_basis(const Plane& plane) {
  const Eigen::Vector3d& n = plane.normal;
  const Eigen::Vector3d helper =
      std::abs(n.y()) < 0.9 ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitX();
  const Eigen::Vector3d u = helper.cross(n).normalized();
  return {u, n.cross(u)};
}

Stroke segment(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const std::array<float, 4>& color) {
  Stroke s;
  s.points = {a, b};
  s.color = color;
  return s;
}

}  // namespace

SessionView::SessionView(const vk::Context& context) : context_(&context) {}

void SessionView::upload(Layer& layer, const SceneGeometry& geometry) {
  layer.scene = std::make_shared<GpuScene>(*context_, geometry);
  layer.bounds = geometry.bounds;
  ++uploads_;
}

void SessionView::update(const session::SketchSession& session, const Overlay& overlay,
                         const SessionViewOptions& options) {
  const double reference = session.reference_size();
  const bool widths_changed = reference != reference_ || options.stroke_width != stroke_width_;
  reference_ = reference;
  stroke_width_ = options.stroke_width;
  SceneOptions scene_options;
  scene_options.reference_diagonal = reference;
  scene_options.stroke_width = options.stroke_width;
  scene_options.edge_width = 0.6 * options.stroke_width;

  if (!have_sketch_ || widths_changed || session.revision() != sketch_revision_) {
    const SceneGeometry g = build_scene(session.sketch(), nullptr, nullptr, scene_options);
    upload(sketch_, g);
    points_ = g.stroke_points;
    sketch_revision_ = session.revision();
    have_sketch_ = true;
  }
  if (!have_live_ || widths_changed || session.live_revision() != live_revision_) {
    Sketch live;
    live.strokes = session.live_strokes();
    upload(live_, build_scene(live, nullptr, nullptr, scene_options));
    live_revision_ = session.live_revision();
    have_live_ = true;
  }
  if (!have_surface_ || widths_changed || session.result_revision() != result_revision_ ||
      options.regions != regions_) {
    const SurfaceResult* r = session.result();
    if (r) {
      MeshAttributes attributes;
      attributes.labels = r->labels;
      SceneOptions mesh_options = scene_options;
      mesh_options.regions = options.regions;
      upload(surface_, build_scene(Sketch{}, &r->mesh, &attributes, mesh_options));
      triangles_ = r->mesh.n_faces();
    } else {
      upload(surface_, SceneGeometry{});
      triangles_ = 0;
    }
    result_revision_ = session.result_revision();
    regions_ = options.regions;
    have_surface_ = true;
  }

  // Grid and controller: rebuilt when the pose, the plane or the grid's centre moves.
  std::array<double, 11> key{};
  key.fill(std::nan(""));
  if (overlay.cursor && options.cursor) {
    const auto& p = overlay.cursor->position;
    const auto& q = overlay.cursor->orientation;
    key = {p.x(), p.y(), p.z(), q.w(), q.x(), q.y(), q.z(), 0, 0, 0, 0};
  }
  Eigen::Vector3d grid_origin = Eigen::Vector3d::Zero();
  if (overlay.drawing_plane && options.grid) {
    const Plane& plane = *overlay.drawing_plane;
    // The grid follows the centre in whole cells, so that it does not swim as the view pans.
    const auto [u, v] = plane_basis(plane);
    const double cell = kGridSpacing * reference;
    const Eigen::Vector3d on_plane =
        overlay.grid_centre - plane.signed_distance(overlay.grid_centre) * plane.normal;
    const Eigen::Vector3d origin = -plane.offset * plane.normal;
    grid_origin = origin + u * std::round((on_plane - origin).dot(u) / cell) * cell +
                  v * std::round((on_plane - origin).dot(v) / cell) * cell;
    key[7] = grid_origin.x(), key[8] = grid_origin.y(), key[9] = grid_origin.z();
    key[10] = plane.normal.x() + 3.0 * plane.normal.y() + 9.0 * plane.normal.z();
  }
  const auto same = [](const std::array<double, 11>& a, const std::array<double, 11>& b) {
    for (std::size_t i = 0; i < a.size(); ++i)
      if (!(a[i] == b[i] || (std::isnan(a[i]) && std::isnan(b[i])))) return false;
    return true;
  };
  if (!overlay_key_ || widths_changed || !same(*overlay_key_, key)) {
    Sketch aids;
    if (overlay.drawing_plane && options.grid) {
      const auto [u, v] = plane_basis(*overlay.drawing_plane);
      const double cell = kGridSpacing * reference, half = kGridHalfLines * cell;
      for (int i = -kGridHalfLines; i <= kGridHalfLines; ++i) {
        const auto& color = i == 0 ? kGridAxisColor : kGridColor;
        aids.strokes.push_back(segment(grid_origin + u * (i * cell) - v * half,
                                       grid_origin + u * (i * cell) + v * half, color));
        aids.strokes.push_back(segment(grid_origin + v * (i * cell) - u * half,
                                       grid_origin + v * (i * cell) + u * half, color));
      }
    }
    if (overlay.cursor && options.cursor) {
      const input::Pose& pose = *overlay.cursor;
      const double length = kCursorLength * reference;
      const Eigen::Matrix3d r = pose.orientation.toRotationMatrix();
      aids.strokes.push_back(segment(pose.position, pose.position + 0.5 * length * r.col(0), {0.85f, 0.2f, 0.2f, 1.0f}));
      aids.strokes.push_back(segment(pose.position, pose.position + 0.5 * length * r.col(1), {0.2f, 0.7f, 0.25f, 1.0f}));
      aids.strokes.push_back(segment(pose.position, pose.position + length * pose.direction(), {0.15f, 0.35f, 0.95f, 1.0f}));
    }
    SceneOptions aid_options = scene_options;
    aid_options.stroke_colors = true;
    aid_options.stroke_alpha = true;
    aid_options.stroke_width = 0.35 * options.stroke_width;
    aid_options.stroke_tolerance = 0.0;
    upload(overlay_, build_scene(aids, nullptr, nullptr, aid_options));
    overlay_key_ = key;
  }
}

void SessionView::record(VkCommandBuffer cmd, const Renderer& renderer, const Camera& camera,
                         double aspect, const SessionViewOptions& options,
                         std::vector<std::shared_ptr<const void>>* in_use) const {
  const auto keep = [&](const Layer& layer) {
    if (in_use && layer.scene) in_use->push_back(layer.scene);
  };
  DrawOptions draw;
  draw.background = options.background;
  draw.hidden_alpha = options.hidden_alpha;
  const bool surface = options.surface && surface_.scene && triangles_ > 0;
  if (surface) {
    DrawOptions mesh = draw;
    mesh.strokes = false;
    renderer.record(cmd, *surface_.scene, camera, aspect, mesh);
    keep(surface_);
  }
  DrawOptions strokes = draw;
  strokes.mesh = false;
  strokes.occluders_drawn = surface;
  if (options.strokes && sketch_.scene) {
    renderer.record(cmd, *sketch_.scene, camera, aspect, strokes);
    keep(sketch_);
  }
  if (live_.scene) {
    renderer.record(cmd, *live_.scene, camera, aspect, strokes);
    keep(live_);
  }
  if (overlay_.scene) {
    DrawOptions aids = strokes;
    aids.hidden_strokes = false;
    aids.translucent_strokes = true;
    renderer.record(cmd, *overlay_.scene, camera, aspect, aids);
    keep(overlay_);
  }
}

BoundingBox SessionView::bounds() const {
  BoundingBox box;
  for (const Layer* layer : {&sketch_, &live_, &surface_, &overlay_})
    if (!layer->bounds.empty()) {
      box.extend(layer->bounds.min);
      box.extend(layer->bounds.max);
    }
  return box;
}

}  // namespace sketchsurf::render
