#pragma once
// Area-weighted point samples on triangle meshes and order statistics of distances: the common
// ground of the surface measures (eval against a ground truth, shape checks against the strokes).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "surfacing/mesh.h"

namespace sketchsurf {

/// Points spread over a mesh's area: each face takes its share of the count by area (rounded up or
/// down at random), each a uniform point in it. A face's points depend only on its corners'
/// positions and the seed, not on the order of the faces or of their corners: the same surface
/// gives the same samples however it is listed, and two surfaces that share faces share those
/// faces' samples. Deterministic (the random numbers are made bit for bit the same on every
/// platform).
struct SurfaceSamples {
  Eigen::MatrixX3d points;  ///< #S x 3
  std::vector<int> faces;   ///< the face each sample lies on
  double area = 0.0;        ///< the mesh's total area
};
/// About `count` area-weighted samples of `mesh` (none when it has no area).
SurfaceSamples sample_surface(const TriMesh& mesh, std::size_t count, std::uint64_t seed);

/// Order statistics of a set of distances (any unit the caller chooses).
struct DistanceStats {
  double mean = 0.0, median = 0.0, p95 = 0.0, p99 = 0.0, max = 0.0;
  std::size_t count = 0;
};
/// The statistics of `values` (sorted here; quantiles by nearest rank). Empty gives zeros.
DistanceStats distance_stats(std::vector<double> values);
/// The q-quantile (q in [0, 1]) of `sorted` by nearest rank; `sorted` must not be empty.
double sorted_quantile(const std::vector<double>& sorted, double q);

}  // namespace sketchsurf
