#include "surfacing/quality/sampling.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

namespace sketchsurf {

namespace {

// A uniform double in [0, 1) from the top 53 bits of a 64-bit draw: unlike the standard
// distributions, the same on every standard library.
double uniform(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

}  // namespace

SurfaceSamples sample_surface(const TriMesh& mesh, std::size_t count, std::uint64_t seed) {
  SurfaceSamples out;
  const Eigen::MatrixX3d V = vertex_matrix(mesh);
  const Eigen::MatrixX3i F = face_matrix(mesh);
  std::vector<double> cumulative(static_cast<std::size_t>(F.rows()));
  double total = 0.0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    total += triangle_area(V, F, f);
    cumulative[static_cast<std::size_t>(f)] = total;
  }
  out.area = total;
  if (!(total > 0.0) || count == 0) {
    out.points.resize(0, 3);
    return out;
  }
  std::mt19937_64 rng(seed);
  out.points.resize(static_cast<Eigen::Index>(count), 3);
  out.faces.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    const double u = uniform(rng) * total;
    const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), u);
    const int f = static_cast<int>(std::min<std::ptrdiff_t>(it - cumulative.begin(), F.rows() - 1));
    // Uniform point in a triangle: (1 - sqrt(r1), sqrt(r1) (1 - r2), sqrt(r1) r2).
    const double r1 = std::sqrt(uniform(rng)), r2 = uniform(rng);
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    out.points.row(static_cast<Eigen::Index>(i)) = (1 - r1) * a + r1 * (1 - r2) * b + r1 * r2 * c;
    out.faces[i] = f;
  }
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
