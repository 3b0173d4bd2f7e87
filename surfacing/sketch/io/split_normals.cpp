#include "surfacing/sketch/io/split_normals.h"

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

#include "surfacing/error.h"
#include "surfacing/portable_math.h"

namespace sketchsurf::io_detail {

namespace {

/// Union-find over the face corners: the corners of one vertex that share a smooth side.
class CornerSets {
 public:
  explicit CornerSets(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  std::size_t find(std::size_t c) {
    while (parent_[c] != c) c = parent_[c] = parent_[parent_[c]];
    return c;
  }
  /// The smaller root wins, so the sets do not depend on the order of the unions.
  void join(std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<std::size_t> parent_;
};

/// The triangles of the mesh with their vertices, unit normals and corner angles.
struct Triangles {
  std::vector<int> slot;                      // per mesh face index: its triangle, -1 if none
  std::vector<std::array<int, 3>> vertices;   // mesh vertex indices
  std::vector<Eigen::Vector3d> normals;       // zero for a degenerate triangle
  std::vector<std::array<double, 3>> angles;  // at each corner (rad)
};

Triangles triangles(const TriMesh& mesh) {
  Triangles t;
  t.slot.assign(mesh.n_faces(), -1);
  for (auto f : mesh.faces()) {
    std::array<int, 3> v{};
    int k = 0;
    for (auto u : f.vertices()) {
      if (k == 3) throw Error::processing("mesh output: a face with more than three vertices");
      v[k++] = u.idx();
    }
    if (k != 3) throw Error::processing("mesh output: a face with fewer than three vertices");
    std::array<Eigen::Vector3d, 3> p;
    for (int i = 0; i < 3; ++i) p[i] = to_eigen(mesh.point(TriMesh::VertexHandle(v[i])));
    Eigen::Vector3d n = (p[1] - p[0]).cross(p[2] - p[0]);
    n = n.norm() > 0.0 && n.allFinite() ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::Zero();
    std::array<double, 3> angle{};
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d a = p[(i + 1) % 3] - p[i], b = p[(i + 2) % 3] - p[i];
      const double value = portable::atan2(a.cross(b).norm(), a.dot(b));
      angle[i] = std::isfinite(value) ? value : 0.0;
    }
    t.slot[f.idx()] = static_cast<int>(t.vertices.size());
    t.vertices.push_back(v);
    t.normals.push_back(n);
    t.angles.push_back(angle);
  }
  return t;
}

/// Corner index (3 triangle + k) of mesh vertex v in triangle i.
std::size_t corner(const Triangles& t, int i, int v) {
  for (int k = 0; k < 3; ++k)
    if (t.vertices[i][k] == v) return 3 * static_cast<std::size_t>(i) + k;
  throw Error::processing("mesh output: inconsistent mesh connectivity");
}

/// Whether edge `e` (not a border, between triangles f0 and f1) is a crease.
bool is_crease(const Triangles& t, int f0, int f1, bool both_sharp) {
  static const double crease = portable::cos(kCreaseAngle * M_PI / 180.0);
  static const double sharp_crease = portable::cos(kSharpCreaseAngle * M_PI / 180.0);
  const bool degenerate = t.normals[f0].isZero(0.0) || t.normals[f1].isZero(0.0);
  return !degenerate && t.normals[f0].dot(t.normals[f1]) < (both_sharp ? sharp_crease : crease);
}

/// Calls `visit(edge, f0, f1, crease)` for every inner edge between two triangles.
template <typename Visit>
void inner_edges(const TriMesh& mesh, const Triangles& t, const std::vector<std::uint8_t>& sharp,
                 Visit&& visit) {
  for (auto e : mesh.edges()) {
    if (e.is_boundary()) continue;
    const int f0 = t.slot[e.h0().face().idx()], f1 = t.slot[e.h1().face().idx()];
    if (f0 < 0 || f1 < 0) continue;
    const bool both_sharp = !sharp.empty() && sharp[e.v0().idx()] && sharp[e.v1().idx()];
    visit(e, f0, f1, is_crease(t, f0, f1, both_sharp));
  }
}

}  // namespace

std::vector<std::uint8_t> crease_edges(const TriMesh& mesh, const std::vector<std::uint8_t>& sharp) {
  const Triangles t = triangles(mesh);
  std::vector<std::uint8_t> crease(mesh.n_edges(), 0);
  inner_edges(mesh, t, sharp, [&](auto e, int, int, bool is) { crease[e.idx()] = is; });
  return crease;
}

SplitNormals split_normals(const TriMesh& mesh, const std::vector<std::uint8_t>& sharp) {
  const Triangles t = triangles(mesh);
  const std::size_t corners = 3 * t.vertices.size();

  // The corners of a vertex on the two sides of an edge share an output vertex unless the edge
  // is a crease (or a border: then they are not on two sides of it).
  CornerSets sets(corners);
  inner_edges(mesh, t, sharp, [&](auto e, int f0, int f1, bool is) {
    if (is) return;
    for (int w : {e.v0().idx(), e.v1().idx()}) sets.join(corner(t, f0, w), corner(t, f1, w));
  });

  // One output vertex per set, numbered in corner order.
  SplitNormals split;
  split.corner_vertex.resize(corners);
  std::vector<std::size_t> output(corners, std::numeric_limits<std::size_t>::max());
  std::vector<Eigen::Vector3d> fallback;  // a face normal, for a sum that cancels out
  for (std::size_t c = 0; c < corners; ++c) {
    const std::size_t root = sets.find(c);
    if (output[root] == std::numeric_limits<std::size_t>::max()) {
      output[root] = split.source.size();
      split.source.push_back(t.vertices[c / 3][c % 3]);
      split.normals.emplace_back(Eigen::Vector3d::Zero());
      fallback.emplace_back(Eigen::Vector3d::UnitZ());
    }
    const std::size_t o = output[root];
    split.corner_vertex[c] = static_cast<std::uint32_t>(o);
    split.normals[o] += t.angles[c / 3][c % 3] * t.normals[c / 3];
    if (!t.normals[c / 3].isZero(0.0)) fallback[o] = t.normals[c / 3];
  }
  for (std::size_t o = 0; o < split.normals.size(); ++o)
    split.normals[o] = split.normals[o].norm() > 0.0 ? Eigen::Vector3d(split.normals[o].normalized())
                                                     : fallback[o];
  return split;
}

}  // namespace sketchsurf::io_detail
