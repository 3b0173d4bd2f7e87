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
/// intersect: a uniform grid over the triangles' boxes, then exact segment-triangle tests on
/// `threads` threads (0 = all; the result does not depend on them).
std::vector<std::array<int, 2>> crossing_face_pairs(const TriMesh& mesh, unsigned threads = 0);

/// The same for the triangles F (one row of vertex indices each) over the positions V, only the
/// pairs with at least one triangle flagged in `among` (one flag per row of F; empty: all): after
/// a few vertices move, the pairs that can have changed.
std::vector<std::array<int, 2>> crossing_face_pairs(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F,
                                                    const std::vector<char>& among = {}, unsigned threads = 0);

/// How many such pairs there are.
std::size_t count_self_intersections(const TriMesh& mesh, unsigned threads = 0);

}  // namespace sketchsurf
