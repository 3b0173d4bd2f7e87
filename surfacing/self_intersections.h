#pragma once
// Triangles of a mesh that pass through each other: the shape checks' count of crossing pairs (a
// surface that crosses itself is no surface a person drew), and the final mesh's folds
// (extract/unfold.h).

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <vector>

#include "surfacing/mesh.h"

namespace sketchsurf {

/// Pairs {a, b} (a < b, in increasing order) of triangles of `mesh` that share no vertex and
/// intersect: a uniform grid over the triangles' boxes, then exact segment-triangle tests.
std::vector<std::array<int, 2>> crossing_face_pairs(const TriMesh& mesh);

/// The same for the triangles F (one row of vertex indices each) over the positions V.
std::vector<std::array<int, 2>> crossing_face_pairs(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F);

/// How many such pairs there are.
std::size_t count_self_intersections(const TriMesh& mesh);

}  // namespace sketchsurf
