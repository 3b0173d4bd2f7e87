#pragma once
// Isotropic remeshing (Botsch & Kobbelt 2004) to a target edge length, optionally keeping the
// vertices on a target surface. METHOD.md section 1: the paper's authors remeshed the VIPSS output
// to a uniform mesh (proxy_resolution 0.007 of the diagonal).

#include <Eigen/Core>
#include <functional>
#include <string>

#include "surfacing/mesh.h"
#include "surfacing/progress.h"

namespace sketchsurf {

/// Moves every row of `points` (#P x 3) onto the target surface, in place. Deterministic.
using SurfaceProjector = std::function<void(Eigen::MatrixX3d& points)>;

/// Options for remesh().
struct RemeshOptions {
  double target_edge = 0.007;  ///< target edge length, absolute (make_proxy passes the fraction of
                               ///< the bbox diagonal times the diagonal)
  int iterations = 5;          ///< rounds of split / collapse / flip / smooth + project

  /// True when the options can be used; otherwise `why` (if given) says which field is wrong.
  bool valid(std::string* why = nullptr) const;
};

/// What remesh() did.
struct RemeshSummary {
  std::size_t splits = 0, collapses = 0, flips = 0;
  double mean_edge = 0.0;  ///< mean edge length at the end
};

/// Remeshes in place: each round splits edges longer than 4/3 L, collapses edges shorter than
/// 4/5 L (never creating an edge longer than 4/3 L, a fold or a non-manifold configuration),
/// flips edges towards valence 6 (4 on the border), moves each vertex towards the centroid of its
/// neighbours in its tangent plane, then projects the vertices with `project` (when given).
/// Border vertices stay where they are. The topology (genus, components, borders) is kept.
/// @throws Error (Usage) for invalid options; Error (Cancelled).
void remesh(TriMesh& mesh, const RemeshOptions& options, const SurfaceProjector& project = {},
            const Progress& progress = {}, RemeshSummary* summary = nullptr);

}  // namespace sketchsurf
