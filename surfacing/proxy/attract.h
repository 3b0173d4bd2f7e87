#pragma once
// Attraction of a proxy mesh to the strokes with a Least-Squares Mesh (Sorkine & Cohen-Or 2004),
// paper §5 "Proxy creation".

#include <Eigen/Core>
#include <string>

#include "surfacing/mesh.h"
#include "surfacing/progress.h"

namespace sketchsurf {

/// Options for attract_to_points().
struct AttractOptions {
  double weight = 2.0;  ///< weight of the positional rows against the (uniform) Laplacian rows
  int rounds = 3;       ///< re-assign targets to nearest vertices and solve again this many times
  unsigned threads = 0; ///< worker threads for the nearest-vertex search (0 = all)

  /// True when the options can be used; otherwise `why` (if given) says which field is wrong.
  bool valid(std::string* why = nullptr) const;
};

/// What attract_to_points() did.
struct AttractSummary {
  std::size_t anchors = 0;        ///< vertices pulled towards at least one target (last round)
  double median_before = 0.0;     ///< median target-to-nearest-vertex distance before, mesh units
  double median_after = 0.0;      ///< the same after the last round
};

/// Median over `targets` (#T x 3) of the distance to the nearest vertex of `mesh`.
double median_nearest_vertex_distance(const TriMesh& mesh, const Eigen::MatrixX3d& targets,
                                      unsigned threads = 0);

/// Least-Squares Mesh: each target point picks its nearest vertex; the new positions X minimise
/// |L X|^2 + weight^2 sum_v |X_v - mean of v's targets|^2 with L the uniform graph Laplacian of
/// the mesh's connectivity, so that the mesh passes near the targets and stays smooth between
/// them (L X = 0 rows, as in the paper). Sparse LDL^T per round, METIS fill-reducing ordering.
/// Connectivity is unchanged.
/// @throws Error (Usage) for invalid options; Error (Processing) for an empty mesh or no targets,
///         or when the sparse system cannot be factorised; Error (Cancelled).
void attract_to_points(TriMesh& mesh, const Eigen::MatrixX3d& targets, const AttractOptions& options,
                       const Progress& progress = {}, AttractSummary* summary = nullptr);

}  // namespace sketchsurf
