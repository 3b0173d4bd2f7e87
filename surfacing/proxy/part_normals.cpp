#include "surfacing/proxy/part_normals.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "surfacing/parallel.h"
#include "surfacing/portable_math.h"

namespace sketchsurf {

PartNormals part_normals(const HermiteRbf& f, double scale, const Eigen::MatrixX3d& samples,
                         const Eigen::MatrixX3d& stroke_points, const PointGrid& strokes,
                         const PartSearch& search) {
  const Eigen::Index n = samples.rows();
  PartNormals out;
  out.normals = Eigen::MatrixX3d::Zero(n, 3);
  out.known.assign(static_cast<std::size_t>(n), 0);
  out.web.assign(static_cast<std::size_t>(n), 0);
  out.between.assign(static_cast<std::size_t>(n), 0);
  const double most_gap = search.gap * M_PI / 180.0;
  const double cone = std::cos(search.cone * M_PI / 180.0);
  parallel_for(0, out.known.size(), search.threads, [&](std::size_t ii) {
    const auto i = static_cast<Eigen::Index>(ii);
    const Eigen::Vector3d p = samples.row(i).transpose();
    std::vector<int> near;
    strokes.for_each_within(p, search.reach, [&](int k, double) { near.push_back(k); });
    if (static_cast<int>(near.size()) < search.least) return;
    std::sort(near.begin(), near.end());  // the sums below in one order
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const int k : near) centroid += stroke_points.row(k).transpose();
    centroid /= static_cast<double>(near.size());
    if (scale * f.value(centroid) >= 0.0) return;
    Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
    for (const int k : near) {
      const Eigen::Vector3d d = stroke_points.row(k).transpose() - centroid;
      spread += d * d.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(spread);
    if (eig.eigenvalues()[1] > search.round * eig.eigenvalues()[0]) return;
    const Eigen::Vector3d axis = eig.eigenvectors().col(2);
    const Eigen::Vector3d u = eig.eigenvectors().col(1), v = eig.eigenvectors().col(0);
    std::vector<double> angles, radii;
    for (const int k : near) {
      const Eigen::Vector3d d = stroke_points.row(k).transpose() - centroid;
      angles.push_back(portable::atan2(d.dot(v), d.dot(u)));
      radii.push_back(std::hypot(d.dot(u), d.dot(v)));
    }
    std::sort(angles.begin(), angles.end());
    double gap = angles.front() + 2.0 * M_PI - angles.back();
    for (std::size_t k = 1; k < angles.size(); ++k) gap = std::max(gap, angles[k] - angles[k - 1]);
    if (gap >= most_gap) return;
    const auto mid = radii.begin() + static_cast<std::ptrdiff_t>(radii.size() / 2);
    std::nth_element(radii.begin(), mid, radii.end());
    Eigen::Vector3d normal = p - centroid;
    normal -= normal.dot(axis) * axis;
    if (!(normal.norm() > 0.0) || normal.norm() < search.rim * *mid) return;
    normal.normalize();
    out.normals.row(i) = normal.transpose();
    out.known[ii] = 1;
    const Eigen::Vector3d front = p + search.ahead * normal;
    const double clear = search.clear * search.ahead;
    const auto [nearest, d2] = strokes.nearest(front);
    out.web[ii] = nearest >= 0 && d2 >= clear * clear && scale * f.value(front) < 0.0;
    if (!out.web[ii]) return;
    // Another part ahead: strokes in the cone round the normal beyond the web's point (none below
    // a foot or a belly that the surface bulges past).
    strokes.for_each_within(p, search.between, [&](int k, double) {
      const Eigen::Vector3d d = stroke_points.row(k).transpose() - p;
      if (d.dot(normal) > search.ahead && d.dot(normal) >= cone * d.norm()) out.between[ii] = 1;
    });
  });
  return out;
}

}  // namespace sketchsurf
