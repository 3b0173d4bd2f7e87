#pragma once
// The ground-truth suite: meshes of the kinds of objects people sketch, each with its known
// topology, made by the project (no third-party meshes). With synthesize_sketch() they give
// sketches whose true surface is known, for eval and quality_bench.

#include <optional>
#include <string>
#include <vector>

#include "surfacing/mesh.h"
#include "surfacing/sketch/sketch.h"

namespace sketchsurf::testing {

/// One ground-truth shape: about 1 unit across, +y up, its bounding box centred at the origin,
/// 2k-20k triangles, manifold and consistently oriented outward (for an open one: the outside of
/// a cup).
struct TruthShape {
  std::string name;         ///< identifier, usable as a file name
  std::string description;  ///< what it is and what it tests, one line
  TriMesh mesh;
  int genus = 0;            ///< total genus (handles, through-holes)
  int components = 1;       ///< connected parts
  bool sharp = false;       ///< CAD-like: creases whose dihedral angle is well above 30 degrees
  bool open = false;        ///< has borders (a cup's mouth); closed otherwise
  std::optional<Plane> mirror;  ///< a symmetry plane, for the shapes meant for mirrored sketching
};

/// Names of every shape, in suite order: box, l_bracket, wedge, chamfered_box, filleted_box,
/// cylinder, thin_plate, curved_shell, plate_two_holes, bar_three_holes, two_boxes, cup,
/// wineglass, vase, bottle, sphere, torus, two_spheres, bean, metaballs, mug, chair, car.
std::vector<std::string> truth_shape_names();

/// One shape by name (deterministic; a few hundred milliseconds at most).
/// @throws Error (Usage) for an unknown name, listing the known ones.
TruthShape truth_shape(const std::string& name);

/// Every shape, in the order of truth_shape_names().
std::vector<TruthShape> truth_suite();

}  // namespace sketchsurf::testing
