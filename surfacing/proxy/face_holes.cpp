#include "surfacing/proxy/face_holes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "surfacing/parallel.h"

namespace sketchsurf {

FaceHoles face_holes(const std::function<double(const Eigen::Vector3d&)>& g, const Plane& face,
                     const BoundingBox& extent, const Sketch& unit, const PointGrid& strokes,
                     const FaceHoleSearch& search, unsigned threads) {
  constexpr int kMostPoints = 1024;  // per direction: a face of the unit sketch at h = 0.001
  FaceHoles out;
  const double h = search.step;
  const Eigen::Vector3d n = face.normal, u = n.unitOrthogonal(), v = n.cross(u);
  const Eigen::Vector3d origin = -face.offset * n;
  // The face's rectangle: the extent's corners seen in the face, a cell round them.
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d c((corner & 1) ? extent.max.x() : extent.min.x(),
                            (corner & 2) ? extent.max.y() : extent.min.y(),
                            (corner & 4) ? extent.max.z() : extent.min.z());
    const Eigen::Vector2d at(c.dot(u), c.dot(v));
    lo = lo.cwiseMin(at);
    hi = hi.cwiseMax(at);
  }
  lo.array() -= h;
  hi.array() += h;
  const int nu = std::min(kMostPoints, static_cast<int>(std::ceil((hi.x() - lo.x()) / h)) + 1);
  const int nv = std::min(kMostPoints, static_cast<int>(std::ceil((hi.y() - lo.y()) / h)) + 1);
  const auto on_face = [&](int i, int j) {
    return Eigen::Vector3d(origin + (lo.x() + i * h) * u + (lo.y() + j * h) * v);
  };
  const auto id = [&](int i, int j) { return static_cast<std::size_t>(j) * nu + i; };
  std::vector<double> value(static_cast<std::size_t>(nu) * nv);
  parallel_for(0, value.size(), threads, [&](std::size_t k) {
    const int i = static_cast<int>(k % nu), j = static_cast<int>(k / nu);
    value[k] = g(on_face(i, j) - 0.5 * h * n);
  });
  // The inside grown by kBridge points (a square), so that a thin rim broken between two grid
  // points still encloses its hole; the other points flooded 4-connected, a flood that reaches the
  // grid's edge being the space round the surface.
  constexpr int kBridge = 2;
  std::vector<char> grown(value.size(), 0);
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i)
      if (value[id(i, j)] < 0.0)
        for (int b = std::max(0, j - kBridge); b <= std::min(nv - 1, j + kBridge); ++b)
          for (int a = std::max(0, i - kBridge); a <= std::min(nu - 1, i + kBridge); ++a) grown[id(a, b)] = 1;
  std::vector<char> seen(value.size(), 0);
  std::vector<int> in_hole(value.size(), 0);  // the last hole (counted from 1) a point was put in
  int hole_count = 0;
  // Floods the points not in `grown` from (i0, j0) into `out`; whether it reached the grid's edge.
  const auto flood = [&](int i0, int j0, std::vector<std::array<int, 2>>& out) {
    bool open = false;
    std::vector<std::array<int, 2>> stack{{i0, j0}};
    seen[id(i0, j0)] = 1;
    while (!stack.empty()) {
      const auto [i, j] = stack.back();
      stack.pop_back();
      out.push_back({i, j});
      open = open || i == 0 || j == 0 || i + 1 == nu || j + 1 == nv;
      for (const auto [di, dj] : {std::array{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
        const int a = i + di, b = j + dj;
        if (a < 0 || b < 0 || a >= nu || b >= nv || seen[id(a, b)] || grown[id(a, b)]) continue;
        seen[id(a, b)] = 1;
        stack.push_back({a, b});
      }
    }
    return open;
  };
  for (int j0 = 0; j0 < nv; ++j0)
    for (int i0 = 0; i0 < nu; ++i0) {
      if (seen[id(i0, j0)] || grown[id(i0, j0)]) continue;
      std::vector<std::array<int, 2>> core;
      if (flood(i0, j0, core)) continue;
      // The hole: the points outside the surface within kBridge of its core.
      ++hole_count;
      std::vector<std::array<int, 2>> hole;
      for (const auto [i, j] : core)
        for (int b = std::max(0, j - kBridge); b <= std::min(nv - 1, j + kBridge); ++b)
          for (int a = std::max(0, i - kBridge); a <= std::min(nu - 1, i + kBridge); ++a)
            if (value[id(a, b)] >= 0.0 && in_hole[id(a, b)] != hole_count) {
              in_hole[id(a, b)] = hole_count;
              hole.push_back({a, b});
            }
      Eigen::Vector3d centre = Eigen::Vector3d::Zero();
      for (const auto [i, j] : hole) centre += on_face(i, j);
      centre /= static_cast<double>(hole.size());
      const double nearest = std::sqrt(strokes.nearest(centre).second);
      if (opening_drawn(centre, n, std::max(2.0 * nearest, 2.0 * h), unit)) continue;
      ++out.holes;
      for (const auto [i, j] : hole) {
        Bump bump;
        bump.centre = on_face(i, j);
        bump.axes.col(0) = u;
        bump.axes.col(1) = v;
        bump.axes.col(2) = n;
        bump.radii = Eigen::Vector3d(1.5 * h, 1.5 * h, search.thickness);
        bump.depth = 2.0 * (value[id(i, j)] + h);
        out.membranes.push_back(bump);
      }
    }
  return out;
}

}  // namespace sketchsurf
