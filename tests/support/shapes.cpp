#include "tests/support/shapes.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

namespace sketchsurf::testing {

namespace {

using V3 = Eigen::Vector3d;

void add_stroke(Sketch& sketch, Stroke stroke) {
  stroke.id = static_cast<std::int64_t>(sketch.strokes.size());
  sketch.strokes.push_back(std::move(stroke));
}

Stroke segment(const V3& a, const V3& b, double spacing) {
  return sample_curve([&](double t) -> V3 { return (1 - t) * a + t * b; }, 0.0, 1.0, spacing);
}

// Point on the surface of a box with rounded edges (half extents `half`, radius `r`) along the ray
// from the origin in direction d: bisection on the signed distance of the rounded box.
double rounded_box_sdf(const V3& p, const V3& half, double r) {
  const V3 q = p.cwiseAbs() - (half - V3::Constant(r));
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0) - r;
}

double rounded_cylinder_sdf(const V3& p, double radius, double half_height, double r) {
  const Eigen::Vector2d d(std::hypot(p.x(), p.y()) - (radius - r), std::abs(p.z()) - (half_height - r));
  return d.cwiseMax(0.0).norm() + std::min(d.maxCoeff(), 0.0) - r;
}

template <class Sdf>
TriMesh push_onto(TriMesh mesh, const Sdf& sdf) {
  for (auto v : mesh.vertices()) {
    const V3 dir = to_eigen(mesh.point(v)).normalized();
    double lo = 0.0, hi = 1.0;
    while (sdf(hi * dir) < 0.0) hi *= 2.0;
    for (int i = 0; i < 60; ++i) {
      const double mid = 0.5 * (lo + hi);
      (sdf(mid * dir) < 0.0 ? lo : hi) = mid;
    }
    mesh.set_point(v, to_openmesh(0.5 * (lo + hi) * dir));
  }
  mesh.update_normals();
  return mesh;
}

}  // namespace

Stroke sample_curve(const std::function<Eigen::Vector3d(double)>& c, double t0, double t1,
                    double spacing) {
  // Measure the length on a fine polyline, then sample uniformly in t (curves here are smooth and
  // close to arc-length parameterised), at least 2 points.
  double length = 0.0;
  V3 prev = c(t0);
  for (int i = 1; i <= 1000; ++i) {
    const V3 p = c(t0 + (t1 - t0) * i / 1000.0);
    length += (p - prev).norm();
    prev = p;
  }
  const int n = std::max(1, static_cast<int>(std::ceil(length / spacing)));
  Stroke s;
  for (int i = 0; i <= n; ++i) s.points.push_back(c(t0 + (t1 - t0) * i / n));
  return s;
}

Stroke horizontal_ring(double radius, double z, int points) {
  Stroke ring;
  for (int k = 0; k <= points; ++k) {
    const double angle = 2.0 * k * M_PI / points;
    ring.points.emplace_back(radius * std::cos(angle), radius * std::sin(angle), z);
  }
  return ring;
}

Stroke polyline_stroke(std::vector<V3> corners, bool closed, double step) {
  if (closed) corners.push_back(corners.front());
  Stroke s;
  for (std::size_t i = 1; i < corners.size(); ++i) {
    const int n = std::max(1, static_cast<int>(std::ceil((corners[i] - corners[i - 1]).norm() / step)));
    for (int k = 0; k < n; ++k)
      s.points.push_back(corners[i - 1] + (corners[i] - corners[i - 1]) * (static_cast<double>(k) / n));
  }
  s.points.push_back(corners.back());
  return s;
}

Sketch box_sections_sketch(const V3& half, const std::vector<double>& xs) {
  Sketch sketch;
  for (double x : xs)
    sketch.strokes.push_back(polyline_stroke({V3(x, -half.y(), -half.z()), V3(x, -half.y(), half.z()),
                                              V3(x, half.y(), half.z()), V3(x, half.y(), -half.z())},
                                             true));
  return sketch;
}

Sketch cube_sketch(double side, bool cross_strokes) {
  Sketch sketch;
  sketch.provenance = "generated cube";
  const double h = side / 2, spacing = side / 50;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, w = (axis + 2) % 3;
    for (double su : {-h, h})
      for (double sw : {-h, h}) {
        V3 a, b;
        a[axis] = -h, b[axis] = h;
        a[u] = b[u] = su;
        a[w] = b[w] = sw;
        add_stroke(sketch, segment(a, b, spacing));
      }
  }
  if (cross_strokes) {
    for (int axis = 0; axis < 3; ++axis) {
      const int u = (axis + 1) % 3, w = (axis + 2) % 3;
      for (double s : {-h, h}) {
        V3 a, b;
        a[axis] = b[axis] = s;
        a[u] = -h, b[u] = h;
        a[w] = b[w] = 0.1 * side;  // slightly off-centre, like a hand-drawn hatch
        add_stroke(sketch, segment(a, b, spacing));
      }
    }
  }
  return sketch;
}

Sketch cylinder_sketch(double radius, double height, int side_strokes) {
  Sketch sketch;
  sketch.provenance = "generated cylinder";
  const double h = height / 2, spacing = std::max(radius, h) / 40;
  for (double z : {-h, h}) {
    add_stroke(sketch, sample_curve([&](double t) -> V3 {
      return {radius * std::cos(t), radius * std::sin(t), z};
    }, 0.0, 2 * M_PI, spacing));
    add_stroke(sketch, segment({-radius, 0.2 * radius, z}, {radius, 0.2 * radius, z}, spacing));
  }
  for (int i = 0; i < side_strokes; ++i) {
    const double a = 2 * M_PI * (i + 0.25) / side_strokes;
    const V3 base(radius * std::cos(a), radius * std::sin(a), 0.0);
    add_stroke(sketch, segment(base - V3(0, 0, h), base + V3(0, 0, h), spacing));
  }
  return sketch;
}

Sketch cup_sketch(double rim, double bottom, double height, int sections) {
  Sketch sketch;
  sketch.provenance = "generated cup";
  const double spacing = rim / 40;
  for (const auto& [r, z] : {std::pair{bottom, 0.0}, std::pair{rim, height}})
    add_stroke(sketch, sample_curve([&](double t) -> V3 {
      return {r * std::cos(t), r * std::sin(t), z};
    }, 0.0, 2 * M_PI, spacing));
  for (int i = 0; i < sections; ++i) {
    const double a = M_PI * (i + 0.25) / sections;
    const V3 d(std::cos(a), std::sin(a), 0.0);
    // Arc length parameter: side down (0..1), bottom across (1..2), side up (2..3).
    add_stroke(sketch, sample_curve([&](double t) -> V3 {
      if (t < 1.0) return (rim + (bottom - rim) * t) * d + V3(0, 0, height * (1.0 - t));
      if (t < 2.0) return bottom * (1.0 - 2.0 * (t - 1.0)) * d;
      return -(bottom + (rim - bottom) * (t - 2.0)) * d + V3(0, 0, height * (t - 2.0));
    }, 0.0, 3.0, spacing));
  }
  return sketch;
}

Sketch torus_ring_sketch(int strokes, int points) {
  Sketch sketch;
  for (int s = 0; s < strokes; ++s) {
    Stroke stroke;
    const double u = 2.0 * M_PI * s / strokes;
    for (int i = 0; i < points; ++i) {
      const double v = 2.0 * M_PI * i / (points - 1);
      const double r = 0.5 + 0.21 * std::cos(v);
      stroke.points.emplace_back(r * std::cos(u), r * std::sin(u), 0.21 * std::sin(v));
    }
    sketch.strokes.push_back(std::move(stroke));
  }
  return sketch;
}

Sketch sphere_with_antenna_sketch() {
  Sketch sketch = sphere_sketch(0.5, 4);
  sketch.strokes.push_back(sample_curve([](double t) { return Eigen::Vector3d(0.5 + 0.4 * t, 0, 0); }, 0.0, 1.0, 0.01));
  return sketch;
}

Sketch sphere_sketch(double radius, int meridians) {
  Sketch sketch;
  sketch.provenance = "generated sphere";
  const double spacing = radius / 40;
  for (int i = 0; i < meridians; ++i) {
    const double phi = M_PI * i / meridians;
    add_stroke(sketch, sample_curve([&](double t) -> V3 {
      return radius * V3(std::sin(t) * std::cos(phi), std::sin(t) * std::sin(phi), std::cos(t));
    }, 0.0, 2 * M_PI, spacing));
  }
  add_stroke(sketch, sample_curve([&](double t) -> V3 {
    return radius * V3(std::cos(t), std::sin(t), 0.0);
  }, 0.0, 2 * M_PI, spacing));
  return sketch;
}

Sketch torus_sketch(double major, double minor, int tube_circles) {
  Sketch sketch;
  sketch.provenance = "generated torus";
  const double spacing = minor / 15;
  auto point = [&](double u, double v) -> V3 {
    return {(major + minor * std::cos(v)) * std::cos(u), (major + minor * std::cos(v)) * std::sin(u),
            minor * std::sin(v)};
  };
  for (int i = 0; i < tube_circles; ++i) {
    const double u = 2 * M_PI * i / tube_circles;
    add_stroke(sketch, sample_curve([&](double v) { return point(u, v); }, 0.0, 2 * M_PI, spacing));
  }
  for (double v : {0.0, M_PI, M_PI / 2, -M_PI / 2})
    add_stroke(sketch, sample_curve([&](double u) { return point(u, v); }, 0.0, 2 * M_PI, spacing));
  return sketch;
}

Sketch sheet_sketch(double half, double curvature) {
  Sketch sketch;
  sketch.provenance = "generated sheet";
  const double spacing = half / 40;
  auto z = [&](double x, double y) { return curvature * (x * x - y * y); };
  auto line_x = [&](double y) {
    return sample_curve([&, y](double x) -> V3 { return {x, y, z(x, y)}; }, -half, half, spacing);
  };
  auto line_y = [&](double x) {
    return sample_curve([&, x](double y) -> V3 { return {x, y, z(x, y)}; }, -half, half, spacing);
  };
  for (double s : {-half, half}) {
    Stroke a = line_x(s), b = line_y(s);
    a.boundary = b.boundary = true;
    add_stroke(sketch, a);
    add_stroke(sketch, b);
  }
  for (double f : {-0.5, 0.0, 0.5}) {
    add_stroke(sketch, line_x(f * half));
    add_stroke(sketch, line_y(f * half));
  }
  return sketch;
}

Sketch hatching_sketch(int patches, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  Sketch sketch;
  sketch.provenance = "generated hatching";
  for (int g = 0; g < patches; ++g) {
    const V3 centre(u(rng), u(rng), u(rng));
    const V3 along = V3(u(rng), u(rng), u(rng)).normalized();
    const V3 across = along.cross(V3(u(rng), u(rng), u(rng))).normalized();
    for (int k = 0; k < 6; ++k) {
      const V3 a = centre + 0.03 * k * across - 0.08 * along + 0.02 * V3(u(rng), u(rng), u(rng));
      add_stroke(sketch, segment(a, a + 0.16 * along, 0.005));
    }
  }
  return sketch;
}

Sketch over_sketched(const Sketch& sketch, int passes, double offset, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0.0, offset);
  std::uniform_real_distribution<double> shorter(0.0, 0.15);
  Sketch out = sketch;
  out.strokes.clear();
  for (const Stroke& stroke : sketch.strokes)
    for (int pass = 0; pass < passes; ++pass) {
      Stroke copy = stroke;
      const std::size_t count = stroke.points.size();
      if (pass > 0 && count > 4) {
        const auto cut = [&] { return static_cast<std::size_t>(shorter(rng) * static_cast<double>(count)); };
        const std::size_t a = cut(), b = count - cut();
        copy.points.assign(stroke.points.begin() + static_cast<std::ptrdiff_t>(a),
                           stroke.points.begin() + static_cast<std::ptrdiff_t>(b));
        const V3 from(n(rng), n(rng), n(rng)), to(n(rng), n(rng), n(rng));
        for (std::size_t i = 0; i < copy.points.size(); ++i) {
          const double t = copy.points.size() > 1 ? static_cast<double>(i) / (copy.points.size() - 1) : 0.0;
          copy.points[i] += (1 - t) * from + t * to;
        }
        copy.orientations.clear();
        copy.pressures.clear();
        copy.timestamps_ms.clear();
      }
      add_stroke(out, std::move(copy));
    }
  return out;
}

Sketch prepared_sketch(Sketch sketch) {
  sketch.assign_ids();
  resample(sketch, 0.005 * sketch.bounding_box().diagonal());
  return sketch;
}

void add_noise(Sketch& sketch, double sigma, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0.0, sigma);
  for (auto& s : sketch.strokes)
    for (auto& p : s.points) p += V3(n(rng), n(rng), n(rng));
}

void transform(Sketch& sketch, double s, const Eigen::Vector3d& t) {
  for (auto& stroke : sketch.strokes) {
    for (auto& p : stroke.points) p = s * p + t;
    stroke.width *= s;
  }
  if (sketch.mirror) {
    // n.x + d = 0 for x = (y - t)/s  =>  n.y + (s d - n.t) = 0
    sketch.mirror->offset = s * sketch.mirror->offset - sketch.mirror->normal.dot(t);
  }
}

TriMesh icosphere(int subdivisions, double radius, const Eigen::Vector3d& center) {
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<V3> pts = {{-1, g, 0}, {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                         {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
  std::vector<std::array<int, 3>> tris = {
      {0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (auto& p : pts) p.normalize();
  for (int k = 0; k < subdivisions; ++k) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      pts.push_back((pts[a] + pts[b]).normalized());
      return mid[key] = static_cast<int>(pts.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    next.reserve(tris.size() * 4);
    for (const auto& t : tris) {
      const int ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
      next.push_back({t[0], ab, ca});
      next.push_back({t[1], bc, ab});
      next.push_back({t[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    tris = std::move(next);
  }
  Eigen::MatrixX3d V(pts.size(), 3);
  for (std::size_t i = 0; i < pts.size(); ++i) V.row(i) = (center + radius * pts[i]).transpose();
  Eigen::MatrixX3i F(tris.size(), 3);
  for (std::size_t i = 0; i < tris.size(); ++i) F.row(i) << tris[i][0], tris[i][1], tris[i][2];
  return mesh_from_matrices(V, F);
}

TriMesh rounded_box_mesh(int subdivisions, const Eigen::Vector3d& half, double rounding) {
  return push_onto(icosphere(subdivisions), [&](const V3& p) { return rounded_box_sdf(p, half, rounding); });
}

TriMesh rounded_cylinder_mesh(int subdivisions, double radius, double half_height, double rounding) {
  return push_onto(icosphere(subdivisions), [&](const V3& p) {
    return rounded_cylinder_sdf(p, radius, half_height, rounding);
  });
}

TriMesh torus_mesh(int n_major, int n_minor, double major, double minor) {
  Eigen::MatrixX3d V(n_major * n_minor, 3);
  Eigen::MatrixX3i F(2 * n_major * n_minor, 3);
  auto id = [&](int i, int j) { return (i % n_major) * n_minor + (j % n_minor); };
  for (int i = 0; i < n_major; ++i)
    for (int j = 0; j < n_minor; ++j) {
      const double u = 2 * M_PI * i / n_major, v = 2 * M_PI * j / n_minor;
      V.row(id(i, j)) << (major + minor * std::cos(v)) * std::cos(u),
          (major + minor * std::cos(v)) * std::sin(u), minor * std::sin(v);
      const int k = 2 * id(i, j);
      F.row(k) << id(i, j), id(i + 1, j), id(i + 1, j + 1);
      F.row(k + 1) << id(i, j), id(i + 1, j + 1), id(i, j + 1);
    }
  return mesh_from_matrices(V, F);
}

double box_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& half) {
  const V3 q = p.cwiseAbs() - half;
  const double outside = q.cwiseMax(0.0).norm();
  return outside > 0.0 ? outside : -q.maxCoeff();
}

std::vector<std::array<int, 2>> triangulated_grid_edges(int side) {
  std::vector<std::array<int, 2>> edges;
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const int v = y * side + x;
      if (x + 1 < side) edges.push_back({v, v + 1});
      if (y + 1 < side) edges.push_back({v, v + side});
      if (x + 1 < side && y + 1 < side) edges.push_back({v, v + side + 1});
    }
  return edges;
}

}  // namespace sketchsurf::testing
