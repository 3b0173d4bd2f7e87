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
  /// Copies V (#n x 3, n >= 1) in cell order.
  explicit PointGrid(const Eigen::MatrixX3d& V) {
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
    points_.resize(vertices_.size());
    for (std::size_t k = 0; k < vertices_.size(); ++k) points_[k] = V.row(vertices_[k]).transpose();
  }

  /// (index, squared distance) of the point nearest to p; with a finite `limit`, the search may
  /// stop once no point within `limit` of p can remain: (-1, inf) when none is that near.
  std::pair<int, double> nearest(const Eigen::Vector3d& p,
                                 double limit = std::numeric_limits<double>::infinity()) const {
    const std::array<int, 3> c = coords(p.transpose());
    std::pair<int, double> best{-1, std::numeric_limits<double>::infinity()};
    // The points of cells (x0..x1, y, z) are contiguous in vertices_: a run of cells along x is
    // scanned as one range.
    auto scan = [&](int x0, int x1, int y, int z) {
      x0 = std::max(x0, 0);
      x1 = std::min(x1, dims_[0] - 1);
      if (x0 > x1) return;
      const std::size_t end = start_[index({x1, y, z}) + 1];
      for (std::size_t k = start_[index({x0, y, z})]; k < end; ++k) {
        const int v = vertices_[k];
        const double d2 = squared_distance(points_[k], p);
        if (d2 < best.second || (d2 == best.second && v < best.first)) best = {v, d2};
      }
    };
    // Distance from p to the slab of cells `i` along `axis` (0 for p's own cell), slightly
    // under-estimated: points are binned with a rounded division.
    auto gap = [&](int axis, int i) {
      double g = 0.0;
      if (i < c[axis]) g = p[axis] - (lo_[axis] + (i + 1) * cell_);
      if (i > c[axis]) g = lo_[axis] + i * cell_ - p[axis];
      return std::max(0.0, g - 1e-9 * cell_);
    };
    const int rings = std::max({dims_[0], dims_[1], dims_[2]});
    for (int r = 0; r <= rings; ++r) {
      // Ring r: the cells at Chebyshev distance r from p's cell, row by row along x; rows that
      // cannot hold a point as near as the best one so far are skipped.
      for (int z = std::max(c[2] - r, 0); z <= std::min(c[2] + r, dims_[2] - 1); ++z) {
        const double gz = gap(2, z);
        for (int y = std::max(c[1] - r, 0); y <= std::min(c[1] + r, dims_[1] - 1); ++y) {
          const double gy = gap(1, y);
          if (gy * gy + gz * gz > best.second) continue;
          if (std::abs(z - c[2]) == r || std::abs(y - c[1]) == r) {
            scan(c[0] - r, c[0] + r, y, z);
          } else {
            scan(c[0] - r, c[0] - r, y, z);  // r > 0 here
            scan(c[0] + r, c[0] + r, y, z);
          }
        }
      }
      // Every cell of ring r + 1 is at least r cells away from p's cell.
      if (best.first >= 0 && std::sqrt(best.second) < r * cell_) break;
      if (limit < r * cell_) break;
    }
    return best;
  }

  /// Whether nearest(p, limit) finds a point (index >= 0): whether any point lies in the block of
  /// cells that search scans before it gives up, the rings round p's cell out to the first one
  /// farther than `limit`. Every point within `limit` of p is in that block, and some a little
  /// farther. Answered from the cells' counts alone, without looking at a point.
  bool finds_within(const Eigen::Vector3d& p, double limit) const {
    const std::array<int, 3> c = coords(p.transpose());
    const int rings = std::max({dims_[0], dims_[1], dims_[2]});
    int reach = 0;
    while (reach < rings && !(limit < reach * cell_)) ++reach;
    const int x0 = std::max(c[0] - reach, 0), x1 = std::min(c[0] + reach, dims_[0] - 1);
    for (int z = std::max(c[2] - reach, 0); z <= std::min(c[2] + reach, dims_[2] - 1); ++z)
      for (int y = std::max(c[1] - reach, 0); y <= std::min(c[1] + reach, dims_[1] - 1); ++y)
        if (start_[index({x1, y, z}) + 1] > start_[index({x0, y, z})]) return true;
    return false;
  }

  /// Whether some point lies within `radius` of p: the answer of nearest(p, radius).second <=
  /// radius^2, found without looking for the nearest one (the first point near enough ends it).
  bool any_within(const Eigen::Vector3d& p, double radius) const {
    const double r2 = radius * radius;
    const double pad = radius + 1e-9 * cell_;  // binning rounds: never miss a cell
    const std::array<int, 3> lo = coords((p.array() - pad).matrix().transpose());
    const std::array<int, 3> hi = coords((p.array() + pad).matrix().transpose());
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y) {
        const std::size_t end = start_[index({hi[0], y, z}) + 1];
        for (std::size_t k = start_[index({lo[0], y, z})]; k < end; ++k)
          if (squared_distance(points_[k], p) <= r2) return true;
      }
    return false;
  }

  /// Calls fn(index, squared distance) for every point within `radius` of p.
  template <class Fn>
  void for_each_within(const Eigen::Vector3d& p, double radius, Fn&& fn) const {
    const std::array<int, 3> lo = coords((p.array() - radius).matrix().transpose());
    const std::array<int, 3> hi = coords((p.array() + radius).matrix().transpose());
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y) {
        const std::size_t end = start_[index({hi[0], y, z}) + 1];
        for (std::size_t k = start_[index({lo[0], y, z})]; k < end; ++k) {
          const int v = vertices_[k];
          const double d2 = squared_distance(points_[k], p);
          if (d2 <= radius * radius) fn(v, d2);
        }
      }
  }

 private:
  // |q - p|^2 summed as x^2 + (y^2 + z^2), the order of Eigen's squaredNorm() on a matrix row:
  // the same bits as the distances the callers compute from the rows they gave.
  static double squared_distance(const Eigen::Vector3d& q, const Eigen::Vector3d& p) {
    const double x = q[0] - p[0], y = q[1] - p[1], z = q[2] - p[2];
    return x * x + (y * y + z * z);
  }

  std::array<int, 3> coords(const Eigen::RowVector3d& p) const {
    std::array<int, 3> c{};
    for (int k = 0; k < 3; ++k)
      c[k] = std::clamp(static_cast<int>(std::floor((p[k] - lo_[k]) / cell_)), 0, dims_[k] - 1);
    return c;
  }
  std::size_t index(const std::array<int, 3>& c) const {
    return (static_cast<std::size_t>(c[2]) * dims_[1] + c[1]) * dims_[0] + c[0];
  }

  Eigen::Vector3d lo_;
  double cell_ = 1.0;
  std::array<int, 3> dims_{1, 1, 1};
  std::vector<std::size_t> start_;
  std::vector<int> vertices_;           // point indices, grouped by cell
  std::vector<Eigen::Vector3d> points_;  // their positions, in the same order: scans read memory in order
};

}  // namespace sketchsurf
