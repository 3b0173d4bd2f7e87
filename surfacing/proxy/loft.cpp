#include "surfacing/proxy/loft.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "surfacing/closest_face.h"
#include "surfacing/portable_math.h"
#include "surfacing/sketch/openings.h"

namespace sketchsurf {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Bounds the smoothing passes of a section much shorter than the longest (its directions are
// dense along it, so many passes make the same spread).
constexpr double kMaxSmoothingPasses = 200.0;

struct Section {
  std::size_t stroke = 0;
  StrokeLoop loop;
  double height = 0.0;  // along the family's normal
};

// The largest family of loops whose planes are parallel within `cos_parallel` (ties: the larger
// sum of radii, then the earlier seed), its normal oriented as the seed's.
std::vector<Section> parallel_family(const std::vector<Section>& loops, double cos_parallel,
                                     Eigen::Vector3d& normal) {
  std::vector<Section> best;
  double best_radii = 0.0;
  for (const Section& seed : loops) {
    std::vector<Section> family;
    double radii = 0.0;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const Section& s : loops) {
      const double c = seed.loop.plane.normal.dot(s.loop.plane.normal);
      if (std::abs(c) < cos_parallel) continue;
      family.push_back(s);
      radii += s.loop.radius;
      sum += c < 0.0 ? -s.loop.plane.normal : s.loop.plane.normal;
    }
    if (family.size() > best.size() || (family.size() == best.size() && radii > best_radii)) {
      best = std::move(family);
      best_radii = radii;
      normal = sum.normalized();
    }
  }
  return best;
}

// Where the ray from the loop's centre along the in-plane direction (cos a, sin a) of (e1, e2)
// leaves the stroke for the last time: the stroke's own point there. False when the ray misses.
bool farthest_crossing(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& centre,
                       const Eigen::Vector3d& e1, const Eigen::Vector3d& e2, double angle,
                       Eigen::Vector3d& crossing) {
  const Eigen::Vector2d dir(portable::cos(angle), portable::sin(angle));
  double farthest = -1.0;
  const std::size_t n = points.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d& pa = points[i];
    const Eigen::Vector3d& pb = points[(i + 1) % n];  // the closing segment too
    const Eigen::Vector2d a((pa - centre).dot(e1), (pa - centre).dot(e2));
    const Eigen::Vector2d b((pb - centre).dot(e1), (pb - centre).dot(e2));
    const Eigen::Vector2d ab = b - a;
    const double den = dir.x() * ab.y() - dir.y() * ab.x();
    if (std::abs(den) < 1e-15) continue;
    // a + s ab = t dir
    const double s = (a.x() * dir.y() - a.y() * dir.x()) / den;
    const double t = (a.x() * ab.y() - a.y() * ab.x()) / den;
    // A ray through a vertex must hit one of its two segments despite round-off.
    constexpr double kSlack = 1e-9;
    if (s < -kSlack || s > 1.0 + kSlack || t <= 0.0 || t <= farthest) continue;
    farthest = t;
    crossing = pa + std::clamp(s, 0.0, 1.0) * (pb - pa);
  }
  return farthest > 0.0;
}

// Closed rings of vertices (indices into the mesh) joined by triangles: the shorter step in
// parameter (k / ring size) is taken first, so rings of different sizes zip evenly.
void stitch(const std::vector<int>& a, const std::vector<int>& b, std::vector<Eigen::Vector3i>& faces) {
  const std::size_t na = a.size(), nb = b.size();
  std::size_t i = 0, j = 0;
  while (i < na || j < nb) {
    const double next_a = static_cast<double>(i + 1) / static_cast<double>(na);
    const double next_b = static_cast<double>(j + 1) / static_cast<double>(nb);
    if (j >= nb || (i < na && next_a <= next_b)) {
      faces.emplace_back(a[i % na], a[(i + 1) % na], b[j % nb]);
      ++i;
    } else {
      faces.emplace_back(a[i % na], b[(j + 1) % nb], b[j % nb]);
      ++j;
    }
  }
}

// Cubic Hermite through values y_s at parameters h_s (tangents: central differences, one-sided at
// the ends; with two values, the straight line between them), at h in [h_s, h_s+1].
Eigen::Vector3d hermite(const std::vector<Eigen::Vector3d>& y, const std::vector<double>& h,
                        std::size_t s, double t) {
  const std::size_t last = y.size() - 1;
  const auto tangent = [&](std::size_t i) -> Eigen::Vector3d {
    const std::size_t lo = i == 0 ? 0 : i - 1, hi = i == last ? last : i + 1;
    return (y[hi] - y[lo]) / (h[hi] - h[lo]);
  };
  const double span = h[s + 1] - h[s];
  const double t2 = t * t, t3 = t2 * t;
  return (2 * t3 - 3 * t2 + 1) * y[s] + (t3 - 2 * t2 + t) * span * tangent(s) +
         (-2 * t3 + 3 * t2) * y[s + 1] + (t3 - t2) * span * tangent(s + 1);
}

}  // namespace

std::optional<Loft> loft_sections(const Sketch& sketch, const LoftOptions& options) {
  std::vector<Section> loops;
  for (std::size_t i = 0; i < sketch.strokes.size(); ++i) {
    const Stroke& stroke = sketch.strokes[i];
    if (stroke.ignored) continue;
    std::optional<StrokeLoop> loop = stroke_loop(stroke.points);
    if (loop && loop->radius >= options.min_radius) loops.push_back({i, std::move(*loop), 0.0});
  }
  if (loops.size() < 2) return std::nullopt;
  Eigen::Vector3d n;
  std::vector<Section> sections =
      parallel_family(loops, portable::cos(options.parallel_degrees * kPi / 180.0), n);
  if (sections.size() < 2) return std::nullopt;
  for (Section& s : sections) s.height = n.dot(s.loop.center);
  std::stable_sort(sections.begin(), sections.end(),
                   [](const Section& a, const Section& b) { return a.height < b.height; });
  for (std::size_t s = 1; s < sections.size(); ++s)
    if (sections[s].height - sections[s - 1].height < options.min_spacing) return std::nullopt;

  // Directions round the axis: enough that the longest section's ring has about edge-long edges.
  const Eigen::Vector3d e1 = (sections.front().loop.u - n.dot(sections.front().loop.u) * n).normalized();
  const Eigen::Vector3d e2 = n.cross(e1);
  double longest = 0.0;
  for (const Section& s : sections) longest = std::max(longest, sketch.strokes[s.stroke].length());
  const auto count = static_cast<std::size_t>(
      std::clamp(std::ceil(longest / options.edge), 24.0, 4096.0));
  // rings[s][k] = columns[k][s]: section s's stroke point in direction k.
  std::vector<std::vector<Eigen::Vector3d>> rings(sections.size(), std::vector<Eigen::Vector3d>(count));
  std::vector<std::vector<Eigen::Vector3d>> columns(count, std::vector<Eigen::Vector3d>(sections.size()));
  for (std::size_t s = 0; s < sections.size(); ++s) {
    const Stroke& stroke = sketch.strokes[sections[s].stroke];
    for (std::size_t k = 0; k < count; ++k) {
      const double angle = 2.0 * kPi * static_cast<double>(k) / static_cast<double>(count);
      if (!farthest_crossing(stroke.points, sections[s].loop.center, e1, e2, angle, rings[s][k]))
        return std::nullopt;
    }
    // A hand-drawn section's jitter, crossing after crossing, would corrugate the loft along its
    // rulings: each ring is smoothed by passes of the binomial filter (1, 2, 1) / 4 round it, whose
    // spread after n passes is sqrt(n / 2) directions, to about options.smoothing.
    const double spacing = stroke.length() / static_cast<double>(count);
    const int passes = static_cast<int>(
        std::min(std::ceil(2.0 * (options.smoothing / spacing) * (options.smoothing / spacing)),
                 kMaxSmoothingPasses));
    std::vector<Eigen::Vector3d>& ring = rings[s];
    for (int pass = 0; pass < passes; ++pass) {
      const std::vector<Eigen::Vector3d> before = ring;
      for (std::size_t k = 0; k < count; ++k)
        ring[k] = 0.25 * before[(k + count - 1) % count] + 0.5 * before[k] + 0.25 * before[(k + 1) % count];
    }
    for (std::size_t k = 0; k < count; ++k) columns[k][s] = ring[k];
  }

  Loft loft;
  loft.sections = sections.size();
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> faces;
  const auto add_ring = [&](const std::vector<Eigen::Vector3d>& ring) {
    std::vector<int> ids(ring.size());
    for (std::size_t k = 0; k < ring.size(); ++k) {
      ids[k] = static_cast<int>(vertices.size());
      vertices.push_back(ring[k]);
    }
    return ids;
  };
  // A flat cap inside an end ring: rings shrinking towards its centroid, with fewer vertices
  // as they shrink, and a pole. Returned from the pole outwards, the end ring not included.
  const auto cap = [&](const std::vector<Eigen::Vector3d>& ring) {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    double radius = 0.0;
    for (const Eigen::Vector3d& p : ring) centre += p;
    centre /= static_cast<double>(ring.size());
    for (const Eigen::Vector3d& p : ring) radius = std::max(radius, (p - centre).norm());
    const int levels = std::max(1, static_cast<int>(std::ceil(radius / options.edge)));
    std::vector<std::vector<Eigen::Vector3d>> inner;
    inner.push_back({centre});
    for (int j = 1; j < levels; ++j) {
      const double f = static_cast<double>(j) / levels;
      const auto m = std::max<std::size_t>(6, static_cast<std::size_t>(std::lround(f * count)));
      std::vector<Eigen::Vector3d> r(m);
      for (std::size_t k = 0; k < m; ++k) {
        // The end ring's point at the same fraction of the way round, pulled towards the centre.
        const double at = static_cast<double>(k) * static_cast<double>(count) / static_cast<double>(m);
        const auto k0 = static_cast<std::size_t>(at);
        const double w = at - static_cast<double>(k0);
        const Eigen::Vector3d p = (1.0 - w) * ring[k0 % count] + w * ring[(k0 + 1) % count];
        r[k] = centre + f * (p - centre);
      }
      inner.push_back(std::move(r));
    }
    return inner;
  };

  // The rings from one pole to the other: the first cap, the sections and the rings between them
  // (about edge apart), the last cap reversed.
  std::vector<std::vector<int>> chain;
  for (auto& r : cap(rings.front())) chain.push_back(add_ring(r));
  std::vector<double> heights;
  for (const Section& s : sections) heights.push_back(s.height);
  for (std::size_t s = 0; s + 1 < sections.size(); ++s) {
    double span = 0.0;
    for (std::size_t k = 0; k < count; ++k) span = std::max(span, (rings[s + 1][k] - rings[s][k]).norm());
    const int steps = std::max(1, static_cast<int>(std::ceil(span / options.edge)));
    for (int i = 0; i < steps; ++i) {
      const double t = static_cast<double>(i) / steps;
      std::vector<Eigen::Vector3d> ring(count);
      for (std::size_t k = 0; k < count; ++k) ring[k] = hermite(columns[k], heights, s, t);
      chain.push_back(add_ring(ring));
    }
  }
  chain.push_back(add_ring(rings.back()));
  std::vector<std::vector<Eigen::Vector3d>> last = cap(rings.back());
  for (auto it = last.rbegin(); it != last.rend(); ++it) chain.push_back(add_ring(*it));

  // Poles (one-vertex rings) fan out; every other pair of rings is stitched.
  for (std::size_t c = 0; c + 1 < chain.size(); ++c) {
    const std::vector<int>& a = chain[c];
    const std::vector<int>& b = chain[c + 1];
    if (a.size() == 1) {
      for (std::size_t k = 0; k < b.size(); ++k) faces.emplace_back(a[0], b[(k + 1) % b.size()], b[k]);
    } else if (b.size() == 1) {
      for (std::size_t k = 0; k < a.size(); ++k) faces.emplace_back(a[k], a[(k + 1) % a.size()], b[0]);
    } else {
      stitch(a, b, faces);
    }
  }
  loft.mesh.V.resize(static_cast<Eigen::Index>(vertices.size()), 3);
  for (std::size_t i = 0; i < vertices.size(); ++i) loft.mesh.V.row(static_cast<Eigen::Index>(i)) = vertices[i];
  loft.mesh.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t i = 0; i < faces.size(); ++i) loft.mesh.F.row(static_cast<Eigen::Index>(i)) = faces[i];
  // Outward: a positive enclosed volume.
  double volume = 0.0;
  for (Eigen::Index f = 0; f < loft.mesh.F.rows(); ++f)
    volume += loft.mesh.V.row(loft.mesh.F(f, 0))
                  .dot(loft.mesh.V.row(loft.mesh.F(f, 1)).cross(loft.mesh.V.row(loft.mesh.F(f, 2))));
  if (volume < 0.0) loft.mesh.F.col(1).swap(loft.mesh.F.col(2));

  // The other strokes must lie on it too (a profile on its side, a section's diameter on a cap).
  const ClosestFaceTree tree(loft.mesh.V, loft.mesh.F);
  std::vector<double> distances;
  for (const Stroke& stroke : sketch.strokes) {
    if (stroke.ignored) continue;
    for (const Eigen::Vector3d& p : stroke.points) {
      Eigen::Vector3d q;
      tree.closest_face(p, &q);
      distances.push_back((p - q).norm());
    }
  }
  if (distances.empty()) return std::nullopt;
  const auto at = distances.begin() + static_cast<std::ptrdiff_t>(0.95 * static_cast<double>(distances.size() - 1));
  std::nth_element(distances.begin(), at, distances.end());
  if (*at > options.fit) return std::nullopt;
  return loft;
}

}  // namespace sketchsurf
