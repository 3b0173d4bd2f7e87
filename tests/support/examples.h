#pragma once
// The bundled example sketches (tests/data/NAME.json), each made by a generator of shapes.h.

#include <string>
#include <utility>
#include <vector>

#include "tests/support/shapes.h"

namespace sketchsurf::testing {

/// (name, sketch) for every bundled example: cube, cylinder, sheet (open, with boundary strokes),
/// torus, and a mirrored cube (mirror plane x = 0).
inline std::vector<std::pair<std::string, Sketch>> bundled_examples() {
  Sketch mirrored = cube_sketch();
  mirrored.provenance = "generated cube with mirror plane x = 0";
  mirrored.mirror = Plane{Eigen::Vector3d::UnitX(), 0.0};
  return {{"cube", cube_sketch()},
          {"cylinder", cylinder_sketch()},
          {"sheet", sheet_sketch()},
          {"torus", torus_sketch()},
          {"cube_mirrored", mirrored}};
}

/// (name, mesh) for every bundled example proxy: a coarse rounded box around the cube sketch, the
/// kind of rough proxy a user makes (`sketchsurf surface cube.json --proxy cube_proxy.obj`).
inline std::vector<std::pair<std::string, TriMesh>> bundled_example_proxies() {
  return {{"cube_proxy", rounded_box_mesh(2, Eigen::Vector3d::Constant(0.56), 0.12)}};
}

}  // namespace sketchsurf::testing
