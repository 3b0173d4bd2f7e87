// make_cube_track: writes tests/data/cube.track.json, a studio track (engine/input/track.h) that
// draws the 12 edges of the bundled cube (the first 12 strokes of tests/data/cube.json) with a
// controller: for each edge, the controller moves to its start with the trigger up, presses,
// passes through every point of the edge, and releases at its end; 60 samples a second,
// pressure ramping from 0.5 to 1 along each stroke. Replayed, it gives the cube's edges exactly.
//
//   make_cube_track CUBE.json OUT.track.json
//
// Every number is exact or correctly rounded (no libm), so the file is the same on every machine
// (CTest studio.cube_track_up_to_date compares it with tests/data/cube.track.json).

#include <cmath>
#include <cstdio>
#include <exception>

#include "engine/input/track.h"
#include "surfacing/error.h"
#include "surfacing/sketch/io/sketch_io.h"

namespace {

using namespace sketchsurf;

constexpr int kHoverSamples = 8;      // samples moving between strokes, trigger up
constexpr double kSampleRate = 60.0;  // samples per second

input::Track cube_track(const Sketch& cube) {
  if (cube.strokes.size() < 12) throw Error::usage("the cube sketch has fewer than 12 strokes");
  // A controller held in front of the cube, pointing into it from the upper right: a fixed unit
  // quaternion (w, x, y, z) made of exact decimals, normalised by a correctly rounded sqrt.
  Eigen::Quaterniond orientation(0.92, -0.2, 0.3, 0.05);
  orientation.normalize();
  input::Track track;
  std::size_t sample = 0;
  Eigen::Vector3d at = cube.strokes[0].points.front() + Eigen::Vector3d(0.25, 0.25, 0.25);
  const auto add = [&](const Eigen::Vector3d& p, bool draw, float trigger) {
    input::ControllerState s;
    s.time_s = double(sample++) / kSampleRate;
    s.pose.position = p;
    s.pose.orientation = orientation;
    s.set(input::Button::Draw, draw);
    s.trigger = draw ? trigger : 0.0f;
    track.events.push_back({s.time_s, s, std::nullopt});
    at = p;
  };
  for (std::size_t k = 0; k < 12; ++k) {
    const auto& points = cube.strokes[k].points;
    if (points.size() < 2) throw Error::usage("edge stroke " + std::to_string(k) + " has fewer than 2 points");
    const Eigen::Vector3d from = at, to = points.front();
    for (int i = 1; i <= kHoverSamples; ++i) add(from + (to - from) * (double(i) / (kHoverSamples + 1)), false, 0.0f);
    for (std::size_t i = 0; i < points.size(); ++i)
      add(points[i], true, 0.5f + 0.5f * float(i) / float(points.size() - 1));
    add(points.back(), false, 0.0f);
  }
  add(at + Eigen::Vector3d(0.1, 0.1, 0.1), false, 0.0f);
  return track;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: make_cube_track CUBE.json OUT.track.json\n");
    return 2;
  }
  try {
    input::write_track(cube_track(read_sketch(argv[1])), argv[2]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_cube_track: %s\n", e.what());
    return 1;
  }
  return 0;
}
