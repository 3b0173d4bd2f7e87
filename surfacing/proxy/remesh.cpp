#include "surfacing/proxy/remesh.h"

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstdlib>
#include <queue>
#include <utility>
#include <vector>

#include "surfacing/error.h"

namespace sketchsurf {

namespace {

using VH = TriMesh::VertexHandle;
using HH = TriMesh::HalfedgeHandle;
using EH = TriMesh::EdgeHandle;

Eigen::Vector3d point(const TriMesh& mesh, VH v) { return to_eigen(mesh.point(v)); }

Eigen::Vector3d triangle_normal(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                const Eigen::Vector3d& c) {
  return (b - a).cross(c - a);
}

class Remesher {
 public:
  Remesher(TriMesh& mesh, const RemeshOptions& options, RemeshSummary& summary)
      : mesh_(mesh), hi_(4.0 / 3.0 * options.target_edge), lo_(0.8 * options.target_edge),
        summary_(summary) {}

  // Longest-edge bisection: always split the longest edge left, so it is the longest edge of
  // both its triangles and the process ends with bounded angles (splitting in index order can
  // refine forever).
  void split_long_edges() {
    const double hi2 = hi_ * hi_;
    using Item = std::pair<double, int>;  // (squared length, edge index); ties by index
    std::priority_queue<Item> queue;
    auto push = [&](EH e) {
      const double l2 = mesh_.calc_edge_sqr_length(e);
      if (l2 > hi2) queue.emplace(l2, e.idx());
    };
    for (const auto e : mesh_.edges()) push(e);
    while (!queue.empty()) {
      const auto [l2, idx] = queue.top();
      queue.pop();
      const EH e(idx);
      if (mesh_.calc_edge_sqr_length(e) != l2) continue;  // stale: the edge was split already
      const HH h = mesh_.halfedge_handle(e, 0);
      const Eigen::Vector3d a = point(mesh_, mesh_.from_vertex_handle(h));
      const Eigen::Vector3d b = point(mesh_, mesh_.to_vertex_handle(h));
      const VH mid = mesh_.split(e, to_openmesh(0.5 * (a + b)));
      ++summary_.splits;
      for (const auto g : mesh_.voh_range(mid)) push(mesh_.edge_handle(g));
    }
  }

  void collapse_short_edges() {
    const double lo2 = lo_ * lo_, hi2 = hi_ * hi_;
    for (std::size_t i = 0; i < mesh_.n_edges(); ++i) {
      const EH e(static_cast<int>(i));
      if (mesh_.status(e).deleted()) continue;
      const HH h0 = mesh_.halfedge_handle(e, 0);
      if ((point(mesh_, mesh_.from_vertex_handle(h0)) - point(mesh_, mesh_.to_vertex_handle(h0)))
              .squaredNorm() >= lo2)
        continue;
      for (const HH h : {h0, mesh_.halfedge_handle(e, 1)})
        if (collapse_ok(h, hi2)) {
          mesh_.collapse(h);
          ++summary_.collapses;
          break;
        }
    }
    mesh_.garbage_collection();
  }

  void flip_edges() {
    // Valences kept up to date across the flips: OpenMesh's valence() walks the 1-ring.
    std::vector<int> valence(mesh_.n_vertices());
    std::vector<char> border(mesh_.n_vertices());
    for (const auto v : mesh_.vertices()) {
      valence[v.idx()] = static_cast<int>(mesh_.valence(v));
      border[v.idx()] = mesh_.is_boundary(v);
    }
    for (std::size_t i = 0; i < mesh_.n_edges(); ++i) {
      const EH e(static_cast<int>(i));
      if (mesh_.status(e).deleted() || mesh_.is_boundary(e)) continue;
      const HH h0 = mesh_.halfedge_handle(e, 0), h1 = mesh_.halfedge_handle(e, 1);
      const VH a = mesh_.from_vertex_handle(h0), b = mesh_.to_vertex_handle(h0);
      const VH c = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h0));
      const VH d = mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h1));
      auto dev = [&](VH v, int change) {
        return std::abs(valence[v.idx()] + change - (border[v.idx()] ? 4 : 6));
      };
      const int before = dev(a, 0) + dev(b, 0) + dev(c, 0) + dev(d, 0);
      const int after = dev(a, -1) + dev(b, -1) + dev(c, 1) + dev(d, 1);
      if (after >= before || !mesh_.is_flip_ok(e)) continue;
      // Faces (a, b, c) and (b, a, d) become (a, d, c) and (d, b, c): refuse folds.
      const Eigen::Vector3d pa = point(mesh_, a), pb = point(mesh_, b), pc = point(mesh_, c),
                            pd = point(mesh_, d);
      const Eigen::Vector3d n = triangle_normal(pa, pb, pc) + triangle_normal(pb, pa, pd);
      if (triangle_normal(pa, pd, pc).dot(n) <= 0.0 || triangle_normal(pd, pb, pc).dot(n) <= 0.0)
        continue;
      mesh_.flip(e);
      --valence[a.idx()];
      --valence[b.idx()];
      ++valence[c.idx()];
      ++valence[d.idx()];
      ++summary_.flips;
    }
  }

  void smooth_and_project(const SurfaceProjector& project) {
    mesh_.update_normals();
    const auto n = static_cast<Eigen::Index>(mesh_.n_vertices());
    Eigen::MatrixX3d p(n, 3);
    for (const auto v : mesh_.vertices()) {
      const Eigen::Vector3d x = point(mesh_, v);
      Eigen::Vector3d moved = x;
      if (!mesh_.is_boundary(v) && mesh_.valence(v) > 0) {
        Eigen::Vector3d c = Eigen::Vector3d::Zero();
        for (const auto w : v.vertices()) c += point(mesh_, w);
        c /= static_cast<double>(mesh_.valence(v));
        const Eigen::Vector3d nv = to_eigen(mesh_.normal(v));
        const Eigen::Vector3d u = c - x;
        moved = x + u - nv * nv.dot(u);
      }
      p.row(v.idx()) = moved.transpose();
    }
    if (project) {
      Eigen::MatrixX3d projected = p;
      project(projected);
      for (const auto v : mesh_.vertices())
        if (!mesh_.is_boundary(v)) p.row(v.idx()) = projected.row(v.idx());
    }
    for (const auto v : mesh_.vertices()) mesh_.set_point(v, to_openmesh(p.row(v.idx())));
  }

 private:
  // Collapsing h moves its from-vertex onto its to-vertex.
  bool collapse_ok(HH h, double hi2) const {
    const VH gone = mesh_.from_vertex_handle(h), kept = mesh_.to_vertex_handle(h);
    if (mesh_.is_boundary(gone)) return false;
    // The length test before OpenMesh's link-condition test: it is cheaper and refuses most
    // candidates when coarsening a user proxy (same answer, the tests are independent).
    const Eigen::Vector3d target = point(mesh_, kept);
    for (const auto w : mesh_.vv_range(gone))
      if ((point(mesh_, w) - target).squaredNorm() > hi2) return false;
    if (!mesh_.is_collapse_ok(h)) return false;
    // No face around `gone` (other than the two that vanish) may flip.
    for (const auto f : mesh_.vf_range(gone)) {
      std::array<Eigen::Vector3d, 3> q;
      int k = 0;
      bool vanishes = false;
      for (const auto v : mesh_.fv_range(f)) {
        if (v == kept) vanishes = true;
        q[k++] = point(mesh_, v);
      }
      if (vanishes) continue;
      const Eigen::Vector3d before = triangle_normal(q[0], q[1], q[2]);
      k = 0;
      for (const auto v : mesh_.fv_range(f)) {
        if (v == gone) q[k] = target;
        ++k;
      }
      if (triangle_normal(q[0], q[1], q[2]).dot(before) <= 0.0) return false;
    }
    return true;
  }

  TriMesh& mesh_;
  double hi_, lo_;
  RemeshSummary& summary_;
};

}  // namespace

bool RemeshOptions::valid(std::string* why) const {
  auto fail = [&](const char* msg) {
    if (why) *why = msg;
    return false;
  };
  if (!(target_edge > 0.0) || !std::isfinite(target_edge))
    return fail("remesh target edge length must be > 0");
  if (iterations < 0) return fail("remesh iterations must be >= 0");
  return true;
}

void remesh(TriMesh& mesh, const RemeshOptions& options, const SurfaceProjector& project,
            const Progress& progress, RemeshSummary* summary) {
  std::string why;
  if (!options.valid(&why)) throw Error::usage(why);
  RemeshSummary local;
  RemeshSummary& s = summary ? *summary : local;
  s = {};
  Remesher remesher(mesh, options, s);
  for (int it = 0; it < options.iterations; ++it) {
    progress.update("remeshing", static_cast<double>(it) / options.iterations);
    remesher.split_long_edges();
    remesher.collapse_short_edges();
    remesher.flip_edges();
    remesher.smooth_and_project(project);
  }
  mesh.garbage_collection();
  mesh.update_normals();
  double total = 0.0;
  for (const auto e : mesh.edges()) total += mesh.calc_edge_length(e);
  s.mean_edge = mesh.n_edges() ? total / static_cast<double>(mesh.n_edges()) : 0.0;
  progress.update("remeshing", 1.0);
}

}  // namespace sketchsurf
