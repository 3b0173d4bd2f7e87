#include "surfacing/quality/sampling.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <numeric>
#include <random>

namespace sketchsurf {

namespace {

// A uniform double in [0, 1) from the top 53 bits of a 64-bit draw: unlike the standard
// distributions, the same on every standard library.
double uniform(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// splitmix64's finaliser: a well-mixed 64-bit value of `x`.
std::uint64_t mix(std::uint64_t x) {
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// The corners of face f in a canonical order: the cycle (orientation kept) that starts at the
// lexicographically smallest position, so that the face's samples do not depend on which corner
// the mesh lists first.
std::array<Eigen::Vector3d, 3> canonical_corners(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F,
                                                 Eigen::Index f) {
  std::array<Eigen::Vector3d, 3> c{V.row(F(f, 0)).transpose(), V.row(F(f, 1)).transpose(),
                                   V.row(F(f, 2)).transpose()};
  const auto less = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  const auto first = std::min_element(c.begin(), c.end(), less) - c.begin();
  std::rotate(c.begin(), c.begin() + first, c.end());
  return c;
}

// A seed made of the bits of a face's canonical corners and the caller's seed.
std::uint64_t face_seed(const std::array<Eigen::Vector3d, 3>& corners, std::uint64_t seed) {
  std::uint64_t h = mix(seed + 0x9e3779b97f4a7c15ULL);
  for (const auto& p : corners)
    for (int k = 0; k < 3; ++k) {
      std::uint64_t bits = 0;
      const double x = p[k] == 0.0 ? 0.0 : p[k];  // -0 and +0 alike
      std::memcpy(&bits, &x, sizeof bits);
      h = mix(h ^ bits);
    }
  return h;
}

}  // namespace

SurfaceSamples sample_surface(const TriMesh& mesh, std::size_t count, std::uint64_t seed) {
  SurfaceSamples out;
  const Eigen::MatrixX3d V = vertex_matrix(mesh);
  const Eigen::MatrixX3i F = face_matrix(mesh);
  std::vector<double> areas(static_cast<std::size_t>(F.rows()));
  double total = 0.0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) total += areas[static_cast<std::size_t>(f)] = triangle_area(V, F, f);
  out.area = total;
  if (!(total > 0.0) || count == 0) {
    out.points.resize(0, 3);
    return out;
  }
  // Each face takes its share of `count` by area, rounded up or down at random; its points are
  // drawn from a generator seeded by the face's own corners.
  std::vector<Eigen::Vector3d> points;
  points.reserve(count + static_cast<std::size_t>(F.rows()));
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const auto corners = canonical_corners(V, F, f);
    std::mt19937_64 rng(face_seed(corners, seed));
    const double share = static_cast<double>(count) * areas[static_cast<std::size_t>(f)] / total;
    const auto n = static_cast<std::size_t>(std::floor(share + uniform(rng)));
    for (std::size_t i = 0; i < n; ++i) {
      // Uniform point in a triangle: (1 - sqrt(r1), sqrt(r1) (1 - r2), sqrt(r1) r2).
      const double r1 = std::sqrt(uniform(rng)), r2 = uniform(rng);
      points.push_back((1 - r1) * corners[0] + r1 * (1 - r2) * corners[1] + r1 * r2 * corners[2]);
      out.faces.push_back(static_cast<int>(f));
    }
  }
  out.points.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i)
    out.points.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  return out;
}

double sorted_quantile(const std::vector<double>& sorted, double q) {
  const auto last = sorted.size() - 1;
  return sorted[std::min(last, static_cast<std::size_t>(std::floor(q * static_cast<double>(last) + 0.5)))];
}

DistanceStats distance_stats(std::vector<double> values) {
  DistanceStats s;
  s.count = values.size();
  if (values.empty()) return s;
  std::sort(values.begin(), values.end());
  s.mean = std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
  s.median = sorted_quantile(values, 0.5);
  s.p95 = sorted_quantile(values, 0.95);
  s.p99 = sorted_quantile(values, 0.99);
  s.max = values.back();
  return s;
}

}  // namespace sketchsurf
