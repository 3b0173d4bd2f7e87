#pragma once
// Nearest-point queries among a fixed set of points (mesh vertices, stroke samples): the
// Least-Squares Mesh's vertex assignment and the proxy's distance to the strokes.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

namespace sketchsurf {

// Nearest-vertex queries on a uniform grid of cells about as wide as the mean vertex spacing:
// rings of cells are searched outwards until no closer vertex can exist. Ties go to the lower
// vertex index, as a brute-force scan would give.
class PointGrid {
 public:
  /// Keeps a reference to V (#n x 3, n >= 1): it must outlive the grid.
  explicit PointGrid(const Eigen::MatrixX3d& V) : V_(V) {
    lo_ = V.colwise().minCoeff().transpose();
    const Eigen::Vector3d extent = (V.colwise().maxCoeff().transpose() - lo_).cwiseMax(1e-12);
    // A few vertices per occupied cell on a surface of area ~ extent^2 (spacing extent / sqrt(n)).
    const double n = static_cast<double>(std::max<Eigen::Index>(V.rows(), 1));
    cell_ = std::max(extent.maxCoeff() / 1024.0, 2.0 * extent.norm() / std::sqrt(n));
    for (int c = 0; c < 3; ++c) dims_[c] = std::max(1, static_cast<int>(extent[c] / cell_) + 1);
    start_.assign(static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2] + 1, 0);
    std::vector<std::size_t> cell_of(static_cast<std::size_t>(V.rows()));
    for (Eigen::Index i = 0; i < V.rows(); ++i) ++start_[cell_of[i] = index(coords(V.row(i)))];
    std::size_t sum = 0;
    for (auto& s : start_) sum += std::exchange(s, sum);
    vertices_.resize(cell_of.size());
    std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < cell_of.size(); ++i) vertices_[fill[cell_of[i]]++] = static_cast<int>(i);
  }

  /// (index, squared distance) of the point nearest to p; with a finite `limit`, the search may
  /// stop once no point within `limit` of p can remain: (-1, inf) when none is that near.
  std::pair<int, double> nearest(const Eigen::Vector3d& p,
                                 double limit = std::numeric_limits<double>::infinity()) const {
    const std::array<int, 3> c = coords(p.transpose());
    std::pair<int, double> best{-1, std::numeric_limits<double>::infinity()};
    const int rings = std::max({dims_[0], dims_[1], dims_[2]});
    for (int r = 0; r <= rings; ++r) {
      for (int x = c[0] - r; x <= c[0] + r; ++x)
        for (int y = c[1] - r; y <= c[1] + r; ++y)
          for (int z = c[2] - r; z <= c[2] + r; ++z) {
            if (std::max({std::abs(x - c[0]), std::abs(y - c[1]), std::abs(z - c[2])}) != r) continue;
            if (x < 0 || y < 0 || z < 0 || x >= dims_[0] || y >= dims_[1] || z >= dims_[2]) continue;
            const std::size_t cell = index({x, y, z});
            for (std::size_t k = start_[cell]; k < start_[cell + 1]; ++k) {
              const int v = vertices_[k];
              const double d2 = (V_.row(v).transpose() - p).squaredNorm();
              if (d2 < best.second || (d2 == best.second && v < best.first)) best = {v, d2};
            }
          }
      // Every cell of ring r + 1 is at least r cells away from p's cell.
      if (best.first >= 0 && std::sqrt(best.second) < r * cell_) break;
      if (limit < r * cell_) break;
    }
    return best;
  }

 private:
  std::array<int, 3> coords(const Eigen::RowVector3d& p) const {
    std::array<int, 3> c{};
    for (int k = 0; k < 3; ++k)
      c[k] = std::clamp(static_cast<int>(std::floor((p[k] - lo_[k]) / cell_)), 0, dims_[k] - 1);
    return c;
  }
  std::size_t index(const std::array<int, 3>& c) const {
    return (static_cast<std::size_t>(c[2]) * dims_[1] + c[1]) * dims_[0] + c[0];
  }

  const Eigen::MatrixX3d& V_;
  Eigen::Vector3d lo_;
  double cell_ = 1.0;
  std::array<int, 3> dims_{1, 1, 1};
  std::vector<std::size_t> start_;
  std::vector<int> vertices_;
};

}  // namespace sketchsurf
