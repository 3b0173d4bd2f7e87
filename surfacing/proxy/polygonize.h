#pragma once
// Polygonisation of an implicit surface: every connected component of the zero set that passes
// near a seed point, as a closed manifold triangle mesh (METHOD.md section 1).

#include <Eigen/Core>
#include <functional>
#include <string>

#include "surfacing/mesh.h"
#include "surfacing/progress.h"
#include "surfacing/sketch/sketch.h"

namespace sketchsurf {

/// Evaluates a scalar field at every row of `points` (#P x 3) into `values` (#P); may run in
/// parallel but must be deterministic.
using FieldBatch = std::function<void(const Eigen::MatrixX3d& points, Eigen::VectorXd& values)>;

/// Options for polygonize().
struct PolygonizeOptions {
  double cell_size = 0.01;  ///< grid spacing, in the units of the field (make_proxy: fraction of
                            ///< the bbox diagonal, as it works on a unit-diagonal sketch)

  /// True when the options can be used; otherwise `why` (if given) says which field is wrong.
  bool valid(std::string* why = nullptr) const;
};

/// What polygonize() did.
struct PolygonizeSummary {
  std::size_t evaluations = 0;   ///< field values computed
  std::size_t active_cells = 0;  ///< grid cells the surface crosses
};

/// Marching tetrahedra (6 tetrahedra per cube, Kuhn subdivision, so faces match between cells) on
/// a sparse narrow band: starting from the cells that hold the seeds (and their face neighbours),
/// the band grows through every cube face the zero set crosses, so each component through a seed
/// is found whole, however many there are. The grid covers `box`; grid vertices on its border
/// take the sign the field has at the box corners (outside), so a surface leaving the box is
/// closed by it. Triangles face outward, from the inside sign towards the outside sign.
/// @param seeds #S x 3 points on or near the zero set (e.g. the VIPSS samples).
/// @return a closed, manifold, consistently oriented mesh (empty when no surface is found).
/// @throws Error (Usage) for invalid options or an empty box; Error (Cancelled).
TriMesh polygonize(const FieldBatch& field, const Eigen::MatrixX3d& seeds, const BoundingBox& box,
                   const PolygonizeOptions& options, const Progress& progress = {},
                   PolygonizeSummary* summary = nullptr);

/// A polygonisation's vertex positions (#V x 3) and triangles (#F x 3, indices into V).
struct TriangleArrays {
  Eigen::MatrixX3d V;
  Eigen::MatrixX3i F;
};

/// polygonize() without building the mesh (the same vertices and triangles, in the same order):
/// for callers that only measure the surface, or discard most of the surfaces they make.
TriangleArrays polygonize_arrays(const FieldBatch& field, const Eigen::MatrixX3d& seeds,
                                 const BoundingBox& box, const PolygonizeOptions& options,
                                 const Progress& progress = {}, PolygonizeSummary* summary = nullptr);

}  // namespace sketchsurf
