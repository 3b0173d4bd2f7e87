#include "tests/support/truth_suite.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>

#include "surfacing/error.h"
#include "surfacing/portable_math.h"
#include "surfacing/proxy/polygonize.h"
#include "surfacing/proxy/remesh.h"
#include "tests/support/shapes.h"

namespace sketchsurf::testing {

namespace {

using V2 = Eigen::Vector2d;
using V3 = Eigen::Vector3d;

/// Triangles as index triples over a growing vertex list; welding by exact position where asked.
struct Builder {
  std::vector<V3> points;
  std::vector<std::array<int, 3>> faces;

  int add(const V3& p) {
    points.push_back(p);
    return static_cast<int>(points.size()) - 1;
  }
  TriMesh mesh() const {
    Eigen::MatrixX3d V(points.size(), 3);
    Eigen::MatrixX3i F(faces.size(), 3);
    for (std::size_t i = 0; i < points.size(); ++i) V.row(i) = points[i].transpose();
    for (std::size_t i = 0; i < faces.size(); ++i) F.row(i) << faces[i][0], faces[i][1], faces[i][2];
    return mesh_from_matrices(V, F);
  }
};

int segments_for(double length, double edge) {
  return std::max(1, static_cast<int>(std::lround(length / edge)));
}

/// A planar region triangulated counter-clockwise, built from tiles that share their sides:
/// points at the same position (to 1e-9) are one vertex, so tiles sampled alike weld.
struct Region {
  std::vector<V2> points;
  std::vector<std::array<int, 3>> triangles;
  std::map<std::pair<long long, long long>, int> index;

  int add(const V2& p) {
    const auto key = std::make_pair(std::llround(p.x() * 1e9), std::llround(p.y() * 1e9));
    const auto [it, inserted] = index.emplace(key, static_cast<int>(points.size()));
    if (inserted) points.push_back(p);
    return it->second;
  }
  /// Rings between `inner` and `outer` (same count, both counter-clockwise, point k of one
  /// facing point k of the other); an inner ring of one point is a fan centre.
  void add_rings(const std::vector<V2>& inner, const std::vector<V2>& outer, int rings) {
    const std::size_t n = outer.size();
    std::vector<std::vector<int>> ring(rings + 1);
    for (int j = 0; j <= rings; ++j)
      for (std::size_t k = 0; k < n; ++k) {
        const V2 in = inner.size() == 1 ? inner[0] : inner[k];
        ring[j].push_back(add(in + (outer[k] - in) * j / rings));
      }
    for (int j = 0; j < rings; ++j)
      for (std::size_t k = 0; k < n; ++k) {
        const std::size_t k1 = (k + 1) % n;
        if (inner.size() == 1 && j == 0) {
          triangles.push_back({ring[0][0], ring[1][k], ring[1][k1]});
          continue;
        }
        triangles.push_back({ring[j][k], ring[j + 1][k], ring[j + 1][k1]});
        triangles.push_back({ring[j][k], ring[j + 1][k1], ring[j][k1]});
      }
  }
  /// A rectangle as a grid of squares split by a diagonal.
  void add_rectangle(const V2& lo, const V2& hi, double edge) {
    const int nx = segments_for(hi.x() - lo.x(), edge), ny = segments_for(hi.y() - lo.y(), edge);
    auto at = [&](int i, int j) {
      return add({lo.x() + (hi.x() - lo.x()) * i / nx, lo.y() + (hi.y() - lo.y()) * j / ny});
    };
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
        triangles.push_back({a, b, c});
        triangles.push_back({a, c, d});
      }
  }
  /// A square of half side h at c with a round hole of radius r in its middle.
  void add_holed_square(const V2& c, double h, double r, double edge) {
    const std::vector<V2> outer = square_outline(c, h, edge);
    std::vector<V2> inner;
    for (const V2& p : outer) inner.push_back(c + r * (p - c).normalized());
    add_rings(inner, outer, segments_for(h - r, edge));
  }
  static std::vector<V2> square_outline(const V2& c, double h, double edge) {
    const std::array<V2, 4> corners{c + V2(h, -h), c + V2(h, h), c + V2(-h, h), c + V2(-h, -h)};
    std::vector<V2> out;
    const int n = segments_for(2 * h, edge);
    for (int s = 0; s < 4; ++s)
      for (int i = 0; i < n; ++i) out.push_back(corners[s] + (corners[(s + 1) % 4] - corners[s]) * i / n);
    return out;
  }
};

/// A closed counter-clockwise polygon resampled to about `edge`, keeping its corners.
std::vector<V2> outline(const std::vector<V2>& corners, double edge) {
  std::vector<V2> out;
  for (std::size_t s = 0; s < corners.size(); ++s) {
    const V2 a = corners[s], b = corners[(s + 1) % corners.size()];
    const int n = segments_for((b - a).norm(), edge);
    for (int i = 0; i < n; ++i) out.push_back(a + (b - a) * i / n);
  }
  return out;
}

/// The region extruded between z0 and z1 into a closed solid: region on top facing +z, its
/// mirror image at the bottom facing -z, walls along its borders in rows about `edge` high.
TriMesh extrude(const Region& region, double z0, double z1, double edge) {
  Builder b;
  const int n = static_cast<int>(region.points.size());
  for (const V2& p : region.points) b.add({p.x(), p.y(), z1});
  for (const V2& p : region.points) b.add({p.x(), p.y(), z0});
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : region.triangles) {
    b.faces.push_back({t[0], t[1], t[2]});
    b.faces.push_back({n + t[0], n + t[2], n + t[1]});
    for (int i = 0; i < 3; ++i) ++directed[{t[i], t[(i + 1) % 3]}];
  }
  const int rows = segments_for(z1 - z0, edge);
  std::map<int, std::vector<int>> column;  // border vertex -> its vertices from bottom to top
  auto at = [&](int v) -> const std::vector<int>& {
    auto& c = column[v];
    if (c.empty()) {
      c.push_back(n + v);
      for (int k = 1; k < rows; ++k) {
        const V2& p = region.points[v];
        c.push_back(b.add({p.x(), p.y(), z0 + (z1 - z0) * k / rows}));
      }
      c.push_back(v);
    }
    return c;
  };
  for (const auto& [e, count] : directed) {
    if (directed.count({e.second, e.first})) continue;  // interior edge
    const auto &a = at(e.first), &c = at(e.second);
    for (int k = 0; k < rows; ++k) {
      b.faces.push_back({a[k], c[k], c[k + 1]});
      b.faces.push_back({a[k], c[k + 1], a[k + 1]});
    }
  }
  return b.mesh();
}

/// A surface of revolution around +z of a profile (r, z) drawn from bottom to top: a profile end
/// on the axis (r = 0) is a pole, another end is a border.
TriMesh revolve(const std::vector<V2>& profile, double edge) {
  double r_max = 0;
  for (const V2& p : profile) r_max = std::max(r_max, p.x());
  const int m = std::max(12, segments_for(2 * M_PI * r_max, edge));
  Builder b;
  std::vector<std::vector<int>> ring;
  for (const V2& p : profile) {
    std::vector<int> r;
    if (p.x() <= 0) {
      r.assign(m, b.add({0, 0, p.y()}));
    } else {
      for (int j = 0; j < m; ++j) {
        const double phi = 2 * M_PI * j / m;
        r.push_back(b.add({p.x() * portable::cos(phi), p.x() * portable::sin(phi), p.y()}));
      }
    }
    ring.push_back(r);
  }
  for (std::size_t i = 0; i + 1 < ring.size(); ++i)
    for (int j = 0; j < m; ++j) {
      const int j1 = (j + 1) % m;
      const int a = ring[i][j], bb = ring[i][j1], c = ring[i + 1][j1], d = ring[i + 1][j];
      if (a != bb) b.faces.push_back({a, bb, c});
      if (c != d) b.faces.push_back({a, c, d});
    }
  return b.mesh();
}

/// Pieces of a profile, each a curve on [0, 1]; the joints are kept exactly (creases).
using Piece = std::function<V2(double)>;

Piece line(V2 a, V2 b) {
  return [a, b](double t) { return V2(a + (b - a) * t); };
}

std::vector<V2> sample_profile(const std::vector<Piece>& pieces, double edge) {
  std::vector<V2> out;
  for (const auto& piece : pieces) {
    double length = 0;
    for (int i = 1; i <= 200; ++i) length += (piece(i / 200.0) - piece((i - 1) / 200.0)).norm();
    const int n = segments_for(length, edge);
    for (int i = out.empty() ? 0 : 1; i <= n; ++i) out.push_back(piece(static_cast<double>(i) / n));
  }
  return out;
}

// Signed distances (negative inside) and the smooth union of Quilez.
double sd_round_box(const V3& p, const V3& half, double r) {
  const V3 q = p.cwiseAbs() - (half - V3::Constant(r));
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0) - r;
}
double sd_capped_cylinder(const V2& radial_axial, double radius, double half_height, double r) {
  const V2 d(std::abs(radial_axial.x()) - (radius - r), std::abs(radial_axial.y()) - (half_height - r));
  return d.cwiseMax(0.0).norm() + std::min(d.maxCoeff(), 0.0) - r;
}
double smooth_min(double a, double b, double k) {
  const double h = std::clamp(0.5 + 0.5 * (b - a) / k, 0.0, 1.0);
  return b + (a - b) * h - k * h * (1.0 - h);
}
double smooth_max(double a, double b, double k) { return -smooth_min(-a, -b, k); }

using Sdf = std::function<double(const V3&)>;

/// The zero set of `sdf` through the components containing `inside` points: polygonised on a grid
/// of `cell` over [-extent, extent]^3, then remeshed to `edge` with every vertex projected back
/// onto the zero set (Newton steps along the numerical gradient).
TriMesh implicit_mesh(const Sdf& sdf, const std::vector<V3>& inside, double extent, double cell,
                      double edge) {
  Eigen::MatrixX3d seeds(inside.size(), 3);
  for (std::size_t i = 0; i < inside.size(); ++i) {
    // From an inside point along +x to the surface, by bisection.
    double lo = 0, hi = 0.01;
    while (sdf(inside[i] + hi * V3::UnitX()) < 0) hi *= 2;
    for (int k = 0; k < 60; ++k) {
      const double mid = 0.5 * (lo + hi);
      (sdf(inside[i] + mid * V3::UnitX()) < 0 ? lo : hi) = mid;
    }
    seeds.row(i) = (inside[i] + hi * V3::UnitX()).transpose();
  }
  const FieldBatch field = [&](const Eigen::MatrixX3d& p, Eigen::VectorXd& values) {
    values.resize(p.rows());
    for (Eigen::Index i = 0; i < p.rows(); ++i) values[i] = sdf(p.row(i).transpose());
  };
  BoundingBox box;
  box.extend(V3::Constant(-extent));
  box.extend(V3::Constant(extent));
  PolygonizeOptions poly;
  poly.cell_size = cell;
  TriMesh mesh = polygonize(field, seeds, box, poly);
  const SurfaceProjector project = [&](Eigen::MatrixX3d& points) {
    const double h = 1e-6;
    for (Eigen::Index i = 0; i < points.rows(); ++i) {
      V3 p = points.row(i).transpose();
      for (int it = 0; it < 6; ++it) {
        const double f = sdf(p);
        V3 g;
        for (int a = 0; a < 3; ++a)
          g[a] = (sdf(p + h * V3::Unit(a)) - sdf(p - h * V3::Unit(a))) / (2 * h);
        if (g.squaredNorm() < 1e-12) break;
        p -= f * g / g.squaredNorm();
        if (std::abs(f) < 1e-12) break;
      }
      points.row(i) = p.transpose();
    }
  };
  RemeshOptions options;
  options.target_edge = edge;
  remesh(mesh, options, project);
  return mesh;
}

/// The shapes are designed with +z up; sketches (Open Brush, the renderer's views) have +y up.
V3 y_up(const V3& p) { return {p.x(), p.z(), -p.y()}; }

/// Turns the mesh +y up and moves it so that its bounding box is centred at the origin.
TriMesh centred_y_up(TriMesh mesh) {
  BoundingBox box;
  for (const auto v : mesh.vertices()) box.extend(y_up(to_eigen(mesh.point(v))));
  const V3 c = 0.5 * (box.min + box.max);
  for (const auto v : mesh.vertices()) mesh.set_point(v, to_openmesh(y_up(to_eigen(mesh.point(v))) - c));
  mesh.update_normals();
  return mesh;
}

TriMesh merged(const TriMesh& a, const TriMesh& b) {
  TriMesh out = a;
  std::vector<OpenMesh::VertexHandle> map;
  for (const auto v : b.vertices()) map.push_back(out.add_vertex(b.point(v)));
  for (const auto f : b.faces()) {
    std::vector<OpenMesh::VertexHandle> vs;
    for (const auto v : b.fv_range(f)) vs.push_back(map[v.idx()]);
    out.add_face(vs);
  }
  return out;
}

TriMesh box_mesh(const V3& half, double edge) {
  Region r;
  r.add_rectangle({-half.x(), -half.y()}, {half.x(), half.y()}, edge);
  return extrude(r, -half.z(), half.z(), edge);
}

void translate(TriMesh& mesh, const V3& t) {
  for (const auto v : mesh.vertices()) mesh.set_point(v, mesh.point(v) + to_openmesh(t));
}

constexpr double kEdge = 0.03;  // target edge of the exact constructions, units

struct Entry {
  const char* name;
  std::function<TruthShape()> make;
};

/// A shape designed +z up (see y_up); `mirror_normal`, when not zero, is the normal of a symmetry
/// plane through the origin in the design's frame.
TruthShape shape(const char* name, const char* description, TriMesh mesh, int genus,
                 int components, bool sharp, bool open, const V3& mirror_normal = V3::Zero()) {
  TruthShape s;
  s.name = name;
  s.description = description;
  s.mesh = centred_y_up(std::move(mesh));
  if (mirror_normal.squaredNorm() > 0) s.mirror = Plane{y_up(mirror_normal).normalized(), 0.0};
  s.genus = genus;
  s.components = components;
  s.sharp = sharp;
  s.open = open;
  return s;
}

const std::vector<Entry>& entries() {
  static const std::vector<Entry> list = {
      {"box", [] {
         return shape("box", "unit cube: 12 creases, 8 corners", box_mesh(V3::Constant(0.5), kEdge),
                      0, 1, true, false);
       }},
      {"l_bracket", [] {
         Region r;
         const double t = 0.2, l = 0.9, e = 0.025;
         r.add_rectangle({0, 0}, {t, t}, e);
         r.add_rectangle({t, 0}, {l, t}, e);
         r.add_rectangle({0, t}, {t, l}, e);
         return shape("l_bracket", "L-shaped profile extruded: a concave crease",
                      extrude(r, -0.25, 0.25, e), 0, 1, true, false);
       }},
      {"wedge", [] {
         Region r;
         r.add_rings({V2(0.3, 0.2)}, outline({{-0.1, 0}, {0.9, 0}, {-0.1, 0.6}}, kEdge), 12);
         return shape("wedge", "triangular prism: acute and right-angled creases",
                      extrude(r, -0.3, 0.3, kEdge), 0, 1, true, false);
       }},
      {"chamfered_box", [] {
         const double h = 0.4, c = 0.12;
         Region r;
         r.add_rings({V2(0, 0)},
                     outline({{h, -h + c}, {h, h - c}, {h - c, h}, {-h + c, h}, {-h, h - c},
                              {-h, -h + c}, {-h + c, -h}, {h - c, -h}}, kEdge),
                     14);
         return shape("chamfered_box", "box with its four vertical edges chamfered (135 degree creases)",
                      extrude(r, -0.4, 0.4, kEdge), 0, 1, true, false);
       }},
      {"filleted_box", [] {
         const double h = 0.4, f = 0.15;
         std::vector<V2> corners;
         const std::array<V2, 4> centres{V2(h - f, h - f), V2(-h + f, h - f), V2(-h + f, -h + f),
                                         V2(h - f, -h + f)};
         for (int q = 0; q < 4; ++q)
           for (int i = 0; i <= 8; ++i) {
             const double a = M_PI / 2 * (q + i / 8.0);
             corners.push_back(centres[q] + f * V2(portable::cos(a), portable::sin(a)));
           }
         Region r;
         r.add_rings({V2(0, 0)}, outline(corners, kEdge), 14);
         return shape("filleted_box", "box with its four vertical edges filleted (radius 0.15)",
                      extrude(r, -0.4, 0.4, kEdge), 0, 1, true, false);
       }},
      {"cylinder", [] {
         const auto p = sample_profile({line({0, -0.45}, {0.35, -0.45}), line({0.35, -0.45}, {0.35, 0.45}),
                                        line({0.35, 0.45}, {0, 0.45})}, kEdge);
         return shape("cylinder", "closed cylinder: two circular creases", revolve(p, kEdge), 0, 1,
                      true, false);
       }},
      {"thin_plate", [] {
         return shape("thin_plate", "plate 1 x 0.7, 0.03 thick", box_mesh({0.5, 0.35, 0.015}, 0.025),
                      0, 1, true, false);
       }},
      {"curved_shell", [] {
         TriMesh m = box_mesh({0.55, 0.35, 0.015}, 0.025);
         const double radius = 0.7;  // bent around the y axis: a shell 0.03 thick
         for (const auto v : m.vertices()) {
           const V3 p = to_eigen(m.point(v));
           const double a = p.x() / radius, rr = radius + p.z();
           m.set_point(v, to_openmesh(V3(rr * portable::sin(a), p.y(), rr * portable::cos(a) - radius)));
         }
         return shape("curved_shell", "thin plate bent to a cylindrical shell, 0.03 thick", m, 0, 1,
                      true, false);
       }},
      {"plate_two_holes", [] {
         Region r;
         r.add_holed_square({-0.25, 0}, 0.25, 0.11, 0.025);
         r.add_holed_square({0.25, 0}, 0.25, 0.11, 0.025);
         return shape("plate_two_holes", "plate 1 x 0.5 x 0.1 with two round through-holes",
                      extrude(r, -0.05, 0.05, 0.025), 2, 1, true, false);
       }},
      {"bar_three_holes", [] {
         Region r;
         for (int i = -1; i <= 1; ++i) r.add_holed_square({0.34 * i, 0}, 0.17, 0.08, 0.02);
         return shape("bar_three_holes", "bar 1.02 x 0.34 x 0.2 with three round through-holes",
                      extrude(r, -0.1, 0.1, 0.02), 3, 1, true, false);
       }},
      {"two_boxes", [] {
         TriMesh a = box_mesh({0.22, 0.3, 0.3}, kEdge), b = box_mesh({0.22, 0.25, 0.2}, kEdge);
         translate(a, {-0.27, 0, 0});
         translate(b, {0.27, 0, -0.1});
         return shape("two_boxes", "two separate boxes 0.08 apart", merged(a, b), 0, 2, true, false);
       }},
      {"cup", [] {
         const auto p = sample_profile({line({0, -0.4}, {0.28, -0.4}), line({0.28, -0.4}, {0.36, 0.4})},
                                       0.025);
         return shape("cup", "open cup (a single sheet): its mouth is a border", revolve(p, 0.025), 0,
                      1, true, true);
       }},
      {"wineglass", [] {
         const auto bowl = [](double t) {
           return V2(0.03 + 0.29 * portable::sin(0.55 * M_PI * t) / portable::sin(0.55 * M_PI),
                     -0.05 + 0.55 * t);
         };
         const auto foot = [](double t) {
           return V2(0.26 - 0.23 * t, -0.49 + 0.04 * portable::sin(0.5 * M_PI * t));
         };
         const auto p = sample_profile({line({0, -0.5}, {0.26, -0.5}), line({0.26, -0.5}, {0.26, -0.49}),
                                        foot, line({0.03, -0.45}, {0.03, -0.05}), bowl}, 0.02);
         return shape("wineglass", "wineglass with a thin stem and an open mouth", revolve(p, 0.02), 0,
                      1, false, true);
       }},
      {"vase", [] {
         const auto wall = [](double t) {
           const double z = -0.45 + 0.9 * t;
           return V2(0.22 + 0.12 * portable::sin(M_PI * (1.1 * t + 0.1)) - 0.05 * t, z);
         };
         const auto p = sample_profile({line({0, -0.45}, wall(0)), wall}, 0.025);
         return shape("vase", "open vase with a bulging wall", revolve(p, 0.025), 0, 1, false, true);
       }},
      {"bottle", [] {
         const auto shoulder = [](double t) {
           return V2(0.07 + 0.13 * (0.5 + 0.5 * portable::cos(M_PI * t)), 0.1 + 0.2 * t);
         };
         const auto p = sample_profile({line({0, -0.5}, {0.2, -0.5}), line({0.2, -0.5}, {0.2, 0.1}),
                                        shoulder, line({0.07, 0.3}, {0.07, 0.45}), line({0.07, 0.45}, {0, 0.45})},
                                       0.02);
         return shape("bottle", "closed bottle: body, smooth shoulder, neck", revolve(p, 0.02), 0, 1,
                      true, false);
       }},
      {"sphere", [] {
         return shape("sphere", "sphere of radius 0.5", icosphere(4, 0.5), 0, 1, false, false);
       }},
      {"torus", [] {
         return shape("torus", "torus, radii 0.35 and 0.13", torus_mesh(80, 32, 0.35, 0.13), 1, 1,
                      false, false);
       }},
      {"two_spheres", [] {
         return shape("two_spheres", "two separate spheres 0.1 apart",
                      merged(icosphere(4, 0.25, {-0.3, 0, 0}), icosphere(4, 0.2, {0.25, 0, 0})), 0, 2,
                      false, false);
       }},
      {"bean", [] {
         TriMesh m = icosphere(4, 1.0);
         for (const auto v : m.vertices()) {
           const V3 p = to_eigen(m.point(v));
           V3 q(0.5 * p.x(), 0.27 * p.y(), 0.25 * p.z());
           q.z() += 0.6 * q.x() * q.x() - 0.08;  // bent like a bean
           m.set_point(v, to_openmesh(q));
         }
         return shape("bean", "smooth bent ellipsoid", m, 0, 1, false, false);
       }},
      {"metaballs", [] {
         const std::array<std::pair<V3, double>, 4> balls{{{V3(-0.25, 0, 0), 0.22}, {V3(0.15, 0.05, 0), 0.25},
                                                            {V3(0.05, -0.05, 0.25), 0.17}, {V3(0.3, 0.2, -0.1), 0.14}}};
         const Sdf sdf = [balls](const V3& p) {
           double d = 1e9;
           for (const auto& [c, r] : balls) d = smooth_min(d, (p - c).norm() - r, 0.1);
           return d;
         };
         return shape("metaballs", "four spheres blended smoothly",
                      implicit_mesh(sdf, {balls[0].first}, 0.7, 0.02, 0.022), 0, 1, false, false);
       }},
      {"mug", [] {
         const Sdf sdf = [](const V3& p) {
           const double outer = sd_capped_cylinder({std::hypot(p.x(), p.y()), p.z()}, 0.3, 0.35, 0.02);
           const double cavity = std::max(std::hypot(p.x(), p.y()) - 0.255, -0.3 - p.z());
           const double body = smooth_max(outer, -cavity, 0.01);
           // The handle: a ring in the xz plane with its part inside the body cut away, so that
           // it meets the wall in two places and leaves the cavity alone.
           const double ring = std::hypot(std::hypot(p.x() - 0.36, p.z()) - 0.13, p.y()) - 0.03;
           return smooth_min(body, std::max(ring, -outer), 0.02);
         };
         return shape("mug", "thick-walled mug with a handle: genus 1",
                      implicit_mesh(sdf, {V3(0.275, 0, 0)}, 0.7, 0.01, 0.02), 1, 1, false, false,
                      V3::UnitY());
       }},
      {"chair", [] {
         const Sdf sdf = [](const V3& p) {
           double d = sd_round_box(p, {0.3, 0.3, 0.03}, 0.01);
           const V3 leg(0.025, 0.025, 0.26);
           for (const double x : {-0.26, 0.26})
             for (const double y : {-0.26, 0.26})
               d = smooth_min(d, sd_round_box(p - V3(x, y, -0.27), leg, 0.01), 0.015);
           d = smooth_min(d, sd_round_box(p - V3(0, -0.275, 0.32), {0.3, 0.025, 0.3}, 0.01), 0.015);
           return d;
         };
         return shape("chair", "chair: seat, back and four thin legs (0.05 thick)",
                      implicit_mesh(sdf, {V3(0, 0, 0)}, 0.7, 0.01, 0.02), 0, 1, false, false);
       }},
      {"car", [] {
         const Sdf sdf = [](const V3& p) {
           const double body = sd_round_box(p - V3(0, 0, -0.05), {0.5, 0.2, 0.1}, 0.05);
           const double cabin = sd_round_box(p - V3(-0.05, 0, 0.1), {0.25, 0.16, 0.1}, 0.06);
           double d = smooth_min(body, cabin, 0.05);
           for (const double x : {-0.3, 0.3})
             d = smooth_min(d, sd_capped_cylinder({std::hypot(p.x() - x, p.z() + 0.15), p.y()}, 0.1, 0.21, 0.02),
                            0.02);
           return d;
         };
         return shape("car", "simple car body, mirror-symmetric left to right",
                      implicit_mesh(sdf, {V3(0, 0, 0)}, 0.7, 0.015, 0.02), 0, 1, false, false,
                      V3::UnitY());
       }},
  };
  return list;
}

}  // namespace

std::vector<std::string> truth_shape_names() {
  std::vector<std::string> names;
  for (const auto& e : entries()) names.push_back(e.name);
  return names;
}

TruthShape truth_shape(const std::string& name) {
  for (const auto& e : entries())
    if (name == e.name) return e.make();
  std::string known;
  for (const auto& e : entries()) known += (known.empty() ? "" : ", ") + std::string(e.name);
  throw Error::usage("unknown truth shape '" + name + "' (known: " + known + ")");
}

std::vector<TruthShape> truth_suite() {
  std::vector<TruthShape> suite;
  for (const auto& e : entries()) suite.push_back(e.make());
  return suite;
}

}  // namespace sketchsurf::testing
