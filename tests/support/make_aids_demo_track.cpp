// make_aids_demo_track: writes tools/sketchsurf-studio/demo/aids_demo.track.json, the studio
// track of the drawing aids' demo: a pear-shaped closed object drawn with a 6-fold rotation about
// the vertical axis. One wobbly profile from the bottom pole to the top pole (smoothing on: the
// wobble goes) becomes six; an over-sketch bulges part of it (all six follow); then, with the
// plane guide on a horizontal plane and end snapping on, one 60-degree arc at each of three
// heights, drawn a little off the plane and ending near the profiles, becomes a closed ring.
//
//   make_aids_demo_track OUT.track.json
//
// Every number is exact or correctly rounded (rational circle parametrisation and sqrt, no other
// libm), so the file is the same on every machine (CTest studio.aids_demo_track_up_to_date).

#include <cmath>
#include <cstdio>
#include <exception>
#include <functional>

#include "engine/input/track.h"
#include "engine/session/actions.h"

namespace {

using namespace sketchsurf;

constexpr double kSampleRate = 60.0;  // samples per second
constexpr int kHoverSamples = 6;      // samples moving between strokes, trigger up

/// The profile at height s in [-1, 1]: its distance from the axis (a pear, wider below).
double radius_at(double s) { return 0.8 * std::sqrt(1.0 - s * s) * (1.0 - 0.25 * s); }

/// The point of the unit circle at t = tan(angle / 2) (rational: no libm).
std::pair<double, double> circle(double t) { return {(1.0 - t * t) / (1.0 + t * t), 2.0 * t / (1.0 + t * t)}; }

struct Writer {
  input::Track track;
  std::size_t sample = 0;
  Eigen::Vector3d at{1.2, 1.2, 0.8};
  Eigen::Quaterniond orientation = Eigen::Quaterniond(0.92, -0.2, 0.3, 0.05).normalized();

  double now() const { return double(sample) / kSampleRate; }
  void add(const Eigen::Vector3d& p, bool draw) {
    input::ControllerState s;
    s.time_s = double(sample++) / kSampleRate;
    s.pose.position = p;
    s.pose.orientation = orientation;
    s.set(input::Button::Draw, draw);
    s.trigger = draw ? 1.0f : 0.0f;
    track.events.push_back({s.time_s, s, std::nullopt});
    at = p;
  }
  void action(const input::TrackAction& a) { track.events.push_back({now(), std::nullopt, a}); }
  /// Moves to f(0), draws through f(i / (n - 1)), releases.
  void stroke(const std::function<Eigen::Vector3d(double)>& f, int n) {
    const Eigen::Vector3d from = at, to = f(0.0);
    for (int i = 1; i <= kHoverSamples; ++i) add(from + (to - from) * (double(i) / (kHoverSamples + 1)), false);
    for (int i = 0; i < n; ++i) add(f(double(i) / double(n - 1)), true);
    add(at, false);
  }
};

input::Track demo_track() {
  Writer w;
  RotationPattern six;
  six.axis = Eigen::Vector3d::UnitY();
  six.count = 6;
  w.action(session::rotation_action(six));
  w.action(session::aid_action("smoothing", 4));
  w.action(session::aid_action("snap_radius", 0.04));
  // The profile in the plane z = 0, x >= 0, from (0, -1, 0) to (0, 1, 0), a zig-zag of 0.008
  // across it that the smoothing removes.
  int index = 0;
  w.stroke([&](double u) {
    const auto [c, s] = circle(2.0 * u - 1.0);  // angle -90 .. 90 degrees
    const double zig = u == 0.0 || u == 1.0 ? 0.0 : ((index++ % 2) ? 0.008 : -0.008);
    return Eigen::Vector3d(0.8 * c * (1.0 - 0.25 * s), s, zig);
  }, 61);
  // Over-sketch: the part from s = -0.3 to 0.6 pushed out by up to 0.025.
  w.action(session::aid_action("oversketch", 1));
  w.stroke([&](double u) {
    const double s = -0.3 + 0.9 * u;
    const double bulge = 0.1 * u * (1.0 - u);  // 0 at the ends, 0.025 in the middle
    return Eigen::Vector3d(radius_at(s) + 0.004 + bulge, s, 0.0);
  }, 40);
  w.action(session::aid_action("oversketch", 0));
  // Rings: arcs from the profile at angle 0 to the one at -60 degrees, on horizontal planes.
  w.action(session::aid_action("snap", 1));
  w.action(session::aid_action("plane_guide", 1));
  const double tan30 = 1.0 / std::sqrt(3.0);
  for (const double s : {-0.6, 0.0, 0.7}) {
    w.action(session::plane_action({Eigen::Vector3d::UnitY(), -s}));
    int k = 0;
    w.stroke([&](double u) {
      const auto [c, sn] = circle(-tan30 * u);
      const double r = radius_at(s) + 0.012 + 0.01 * u * (1.0 - u);  // a little outside
      const double wobble = (k++ % 3 - 1) * 0.01;                       // off the plane
      return Eigen::Vector3d(r * c, s + wobble, r * sn);
    }, 30);
  }
  w.add(w.at + Eigen::Vector3d(0.2, 0.2, 0.2), false);
  return w.track;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_aids_demo_track OUT.track.json\n");
    return 2;
  }
  try {
    input::write_track(demo_track(), argv[1]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_aids_demo_track: %s\n", e.what());
    return 1;
  }
  return 0;
}
