#include "surfacing/extract/tubes.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "surfacing/error.h"
#include "surfacing/extract/mirror.h"
#include "surfacing/portable_math.h"

namespace sketchsurf {

bool TubeOptions::valid(std::string* why) const {
  if (!(radius > 0.0 && radius < 0.1)) {
    if (why) *why = "prepare tube_radius must be in (0, 0.1)";
    return false;
  }
  if (!(max_radius > 0.0 && max_radius < 0.1)) {
    if (why) *why = "prepare tube_max_radius must be in (0, 0.1)";
    return false;
  }
  if (sides < 3 || sides > 64) {
    if (why) *why = "prepare tube_sides must be in [3, 64]";
    return false;
  }
  return true;
}

namespace {

// The stroke's points without those closer than `min_gap` to the previous kept one.
std::vector<Eigen::Vector3d> distinct_points(const std::vector<Eigen::Vector3d>& points, double min_gap) {
  std::vector<Eigen::Vector3d> out;
  for (const auto& p : points) {
    if (!p.allFinite()) continue;
    if (out.empty() || (p - out.back()).norm() > min_gap) out.push_back(p);
  }
  return out;
}

// A unit vector perpendicular to the unit vector t.
Eigen::Vector3d perpendicular(const Eigen::Vector3d& t) {
  Eigen::Index axis = 0;
  t.cwiseAbs().minCoeff(&axis);
  return t.cross(Eigen::Vector3d::Unit(axis)).normalized();
}

// Appends the tube round `x` (at least two distinct points) to `mesh`.
void append_tube(TriMesh& mesh, const std::vector<Eigen::Vector3d>& x, double radius, int sides) {
  const std::size_t n = x.size();
  std::vector<Eigen::Vector3d> t(n);
  for (std::size_t i = 0; i < n; ++i)
    t[i] = (x[std::min(i + 1, n - 1)] - x[i == 0 ? 0 : i - 1]).normalized();
  // Rotation-minimising frames by double reflection (Wang, Juettler, Zheng, Liu 2008).
  std::vector<Eigen::Vector3d> r(n);
  r[0] = perpendicular(t[0]);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const Eigen::Vector3d v1 = x[i + 1] - x[i];
    const double c1 = v1.squaredNorm();
    const Eigen::Vector3d rl = r[i] - (2.0 / c1) * v1.dot(r[i]) * v1;
    const Eigen::Vector3d tl = t[i] - (2.0 / c1) * v1.dot(t[i]) * v1;
    const Eigen::Vector3d v2 = t[i + 1] - tl;
    const double c2 = v2.squaredNorm();
    const Eigen::Vector3d next = c2 > 1e-24 ? Eigen::Vector3d(rl - (2.0 / c2) * v2.dot(rl) * v2) : rl;
    // Keep it exactly perpendicular to the tangent (round-off, and the ends' one-sided tangents).
    const Eigen::Vector3d projected = next - next.dot(t[i + 1]) * t[i + 1];
    r[i + 1] = projected.norm() > 1e-12 ? Eigen::Vector3d(projected.normalized()) : perpendicular(t[i + 1]);
  }
  // Rings: (r, t x r, t) is right-handed, so rings counter-clockwise about t; the side triangles
  // (a_k, a_k+1, b_k+1) and (a_k, b_k+1, b_k) then face outwards.
  std::vector<TriMesh::VertexHandle> ring(n * static_cast<std::size_t>(sides));
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d s = t[i].cross(r[i]);
    for (int k = 0; k < sides; ++k) {
      const double angle = 2.0 * M_PI * k / sides;
      ring[i * sides + k] =
          mesh.add_vertex(
              to_openmesh(x[i] + radius * (portable::cos(angle) * r[i] + portable::sin(angle) * s)));
    }
  }
  const auto at = [&](std::size_t i, int k) { return ring[i * sides + (k % sides)]; };
  for (std::size_t i = 0; i + 1 < n; ++i)
    for (int k = 0; k < sides; ++k) {
      mesh.add_face(at(i, k), at(i, k + 1), at(i + 1, k + 1));
      mesh.add_face(at(i, k), at(i + 1, k + 1), at(i + 1, k));
    }
  const auto first = mesh.add_vertex(to_openmesh(x.front() - radius * t.front()));
  const auto last = mesh.add_vertex(to_openmesh(x.back() + radius * t.back()));
  for (int k = 0; k < sides; ++k) {
    mesh.add_face(first, at(0, k + 1), at(0, k));
    mesh.add_face(last, at(n - 1, k), at(n - 1, k + 1));
  }
}

}  // namespace

StrokeTubes stroke_tubes(const Sketch& strokes, double diagonal, const TubeOptions& options) {
  std::string why;
  if (!options.valid(&why)) throw Error::usage(why);
  if (!(diagonal > 0.0 && std::isfinite(diagonal)))
    throw Error::usage("the tubes' diagonal must be positive and finite");
  const Sketch half = strokes.mirror ? half_sketch(strokes, *strokes.mirror) : strokes;
  StrokeTubes out;
  for (const Stroke& stroke : half.strokes) {
    const double radius = stroke.width > 0.0 && std::isfinite(stroke.width)
                              ? std::min(0.5 * stroke.width, options.max_radius * diagonal)
                              : options.radius * diagonal;
    std::vector<Eigen::Vector3d> x = distinct_points(stroke.points, 0.01 * radius);
    if (x.size() < 2) continue;
    append_tube(out.mesh, x, radius, options.sides);
    ++out.count;
    if (!strokes.mirror) continue;
    for (auto& p : x) p = strokes.mirror->reflect(p);
    append_tube(out.mesh, x, radius, options.sides);
    ++out.count;
  }
  return out;
}

}  // namespace sketchsurf
