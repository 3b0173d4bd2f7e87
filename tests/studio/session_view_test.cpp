// SessionView (engine/render/session_view.h): what the studio draws of a session, on the
// offscreen target. A stroke is on screen the frame its trigger is released (and while drawn);
// strokes behind the surface are faint; nothing is uploaded again when nothing changed.

#include "engine/render/session_view.h"
#include "engine/vk/offscreen.h"
#include "tests/render/render_support.h"

namespace sketchsurf::testing {
namespace {

constexpr int kW = 160, kH = 120;

/// The view of a session as the studio draws it, front view.
class Picture {
 public:
  Picture()
      : target_(render_context(), {kW, kH}, VK_SAMPLE_COUNT_1_BIT),
        renderer_(render_context(), target_.render_pass(), target_.samples()),
        view_(render_context()) {
    options_.grid = false;
    options_.cursor = false;
    options_.stroke_width = 0.03;  // about 2 pixels here
    camera_.eye = {0, 0, 3};
    camera_.near_plane = 0.1;
    camera_.far_plane = 10;
  }
  render::RgbaImage draw(const session::SketchSession& s) {
    view_.update(s, {}, options_);
    render_context().submit_and_wait([&](VkCommandBuffer cmd) {
      target_.begin(cmd, options_.background);
      view_.record(cmd, renderer_, camera_, double(kW) / kH, options_);
      target_.end_and_copy(cmd);
    });
    return {kW, kH, target_.read_pixels()};
  }
  render::SessionView& view() { return view_; }
  render::SessionViewOptions& options() { return options_; }
  Eigen::Vector2d pixel(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d q = camera_.project(p, kW, kH);
    return {q.x(), q.y()};
  }

 private:
  vk::OffscreenTarget target_;
  render::Renderer renderer_;
  render::SessionView view_;
  render::SessionViewOptions options_;
  render::Camera camera_;
};

input::ControllerState sample(double t, const Eigen::Vector3d& p, bool draw) {
  input::ControllerState s;
  s.time_s = t;
  s.pose.position = p;
  s.set(input::Button::Draw, draw);
  s.trigger = draw ? 1.0f : 0.0f;
  return s;
}

int darkness(const render::RgbaImage& image, const Eigen::Vector2d& at) {
  const auto c = image.at(int(at.x()), int(at.y()));
  return 255 - (int(c[0]) + int(c[1]) + int(c[2])) / 3;
}

TEST(SessionView, AStrokeIsShownWhileDrawnAndTheFrameItsTriggerIsReleased) {
  session::SketchSession s;
  Picture picture;
  const auto empty = picture.draw(s);
  EXPECT_EQ(non_background_pixels(empty, {255, 255, 255}), 0u);
  double t = 0.0;
  for (int i = 0; i <= 10; ++i) s.apply(sample(t += 0.01, {-0.5 + 0.1 * i, 0.0, 0.0}, true));
  const auto drawing = picture.draw(s);  // the stroke in progress
  EXPECT_GT(darkness(drawing, picture.pixel({0.0, 0.0, 0.0})), 80);
  s.apply(sample(t += 0.01, {0.5, 0.2, 0.0}, false));
  ASSERT_EQ(s.sketch().strokes.size(), 1u);
  const auto released = picture.draw(s);  // the next frame: now in the sketch
  EXPECT_GT(darkness(released, picture.pixel({0.0, 0.0, 0.0})), 80);
  EXPECT_GT(darkness(released, picture.pixel({0.5, 0.1, 0.0})), 40);
  EXPECT_EQ(picture.view().points(), 12u);
  // Nothing changed: nothing uploaded.
  const std::size_t uploads = picture.view().uploads();
  picture.draw(s);
  EXPECT_EQ(picture.view().uploads(), uploads);
  // Undo: gone the next frame.
  s.undo();
  EXPECT_EQ(non_background_pixels(picture.draw(s), {255, 255, 255}), 0u);
}

TEST(SessionView, StrokesBehindTheSurfaceAreFaintAndRegionsToggle) {
  session::SketchSession s;
  Stroke behind;
  behind.points = {{-0.6, -0.3, -0.8}, {0.6, -0.3, -0.8}};
  Stroke front;
  front.points = {{-0.6, 0.3, 0.8}, {0.6, 0.3, 0.8}};
  s.add_stroke(behind);
  s.add_stroke(front);
  SurfaceResult r;
  r.mesh = box_grid_mesh(2, {0.5, 0.5, 0.5});
  r.labels = box_face_labels(r.mesh, {0.5, 0.5, 0.5});
  s.set_result(std::move(r));
  Picture picture;
  const auto image = picture.draw(s);
  const int hidden = darkness(image, picture.pixel({0.0, -0.3, -0.8}));
  const int visible = darkness(image, picture.pixel({0.0, 0.3, 0.8}));
  const int surface = darkness(image, picture.pixel({0.0, 0.0, 0.5}));
  EXPECT_GT(visible, hidden + 40) << "the hidden stroke is faint";
  EXPECT_GT(hidden, surface + 5) << "but there";
  picture.options().surface = false;
  const auto no_surface = picture.draw(s);
  EXPECT_GT(darkness(no_surface, picture.pixel({0.0, -0.3, -0.8})), hidden + 40);
  picture.options().surface = true;
  picture.options().regions = false;
  const auto plain = picture.draw(s);
  const auto a = image.at(int(picture.pixel({0, 0, 0.5}).x()), int(picture.pixel({0, 0, 0.5}).y()));
  const auto b = plain.at(int(picture.pixel({0, 0, 0.5}).x()), int(picture.pixel({0, 0, 0.5}).y()));
  EXPECT_NE(a, b) << "regions coloured, then one colour";
}

}  // namespace
}  // namespace sketchsurf::testing
