#include "surfacing/extract/unfold.h"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <array>
#include <iterator>

#include "surfacing/self_intersections.h"

namespace sketchsurf {

bool UnfoldOptions::valid(std::string* why) const {
  if (rings < 0 || rounds < 1) {
    if (why) *why = "extract.unfold_rings must be >= 0 and extract.unfold_rounds >= 1";
    return false;
  }
  if (!(max_share > 0.0 && max_share <= 1.0)) {
    if (why) *why = "extract.unfold_max_share must be in (0, 1]";
    return false;
  }
  return true;
}

namespace {

// The crossing pairs of `mesh` that are not in `before` (both sorted).
std::vector<std::array<int, 2>> new_crossings(const TriMesh& mesh, const std::vector<std::array<int, 2>>& before) {
  const std::vector<std::array<int, 2>> now = crossing_face_pairs(mesh);
  std::vector<std::array<int, 2>> out;
  std::set_difference(now.begin(), now.end(), before.begin(), before.end(), std::back_inserter(out));
  return out;
}

// The vertices of the crossing triangles, grown by `rings` rings.
std::vector<char> around(const TriMesh& mesh, const std::vector<std::array<int, 2>>& crossing, int rings) {
  std::vector<char> in(mesh.n_vertices(), 0);
  for (const auto& pair : crossing)
    for (int f : pair)
      for (auto v : mesh.fv_range(mesh.face_handle(f))) in[v.idx()] = 1;
  for (int ring = 0; ring < rings; ++ring) {
    std::vector<char> grown = in;
    for (auto v : mesh.vertices())
      if (in[v.idx()])
        for (auto u : mesh.vv_range(v)) grown[u.idx()] = 1;
    in = std::move(grown);
  }
  return in;
}

// Drops from `zone` its connected parts of more than `most` vertices, and those that touch a part
// dropped before, flags them in `skipped` and puts their vertices back where `solved` has them.
void drop_large_parts(TriMesh& mesh, const Eigen::MatrixX3d& solved, std::size_t most, std::vector<char>& zone,
                      std::vector<char>& skipped) {
  std::vector<char> seen(zone.size(), 0);
  std::vector<int> part, stack;
  const auto in = [&](int v) { return zone[v] || skipped[v]; };
  for (auto s : mesh.vertices()) {
    if (!zone[s.idx()] || seen[s.idx()]) continue;
    part.clear();
    stack.assign(1, s.idx());
    seen[s.idx()] = 1;
    bool touches = false;
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      part.push_back(v);
      touches |= skipped[v] != 0;
      for (auto u : mesh.vv_range(mesh.vertex_handle(v)))
        if (in(u.idx()) && !seen[u.idx()]) {
          seen[u.idx()] = 1;
          stack.push_back(u.idx());
        }
    }
    if (part.size() <= most && !touches) continue;
    for (int v : part) {
      zone[v] = 0;
      skipped[v] = 1;
      mesh.set_point(mesh.vertex_handle(v), TriMesh::Point(solved(v, 0), solved(v, 1), solved(v, 2)));
    }
  }
}

// Puts every free vertex of `zone` at the mean of its neighbours, the others fixed: one sparse
// solve of the graph Laplacian. Returns the vertices moved.
std::size_t membrane(TriMesh& mesh, const std::vector<char>& zone, const std::vector<std::uint8_t>& fixed) {
  std::vector<int> index(zone.size(), -1);
  int m = 0;
  for (auto v : mesh.vertices())
    if (zone[v.idx()] && (fixed.empty() || !fixed[v.idx()]) && !mesh.is_boundary(v)) index[v.idx()] = m++;
  if (m == 0) return 0;
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixX3d rhs = Eigen::MatrixX3d::Zero(m, 3);
  for (auto v : mesh.vertices()) {
    const int i = index[v.idx()];
    if (i < 0) continue;
    double degree = 0.0;
    for (auto u : mesh.vv_range(v)) {
      degree += 1.0;
      const int j = index[u.idx()];
      if (j >= 0) {
        entries.emplace_back(i, j, -1.0);
      } else {
        const auto& p = mesh.point(u);
        rhs.row(i) += Eigen::RowVector3d(p[0], p[1], p[2]);
      }
    }
    entries.emplace_back(i, i, degree);
  }
  Eigen::SparseMatrix<double> laplacian(m, m);
  laplacian.setFromTriplets(entries.begin(), entries.end());
  // Every part of the zone touches a fixed vertex (it is smaller than the mesh, or the border and
  // `fixed` bound it): the matrix is positive definite.
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(laplacian);
  if (solver.info() != Eigen::Success) return 0;
  const Eigen::MatrixX3d x = solver.solve(rhs);
  for (auto v : mesh.vertices())
    if (const int i = index[v.idx()]; i >= 0) mesh.set_point(v, TriMesh::Point(x(i, 0), x(i, 1), x(i, 2)));
  return static_cast<std::size_t>(m);
}

}  // namespace

UnfoldSummary unfold(TriMesh& mesh, const Eigen::MatrixX3d& start, const std::vector<std::uint8_t>& fixed,
                     const UnfoldOptions& options) {
  UnfoldSummary summary;
  if (options.rings == 0) return summary;
  const Eigen::MatrixX3d solved = vertex_matrix(mesh);
  const std::vector<std::array<int, 2>> before = crossing_face_pairs(start, face_matrix(mesh));
  std::vector<std::array<int, 2>> crossing = new_crossings(mesh, before);
  summary.crossing_pairs = crossing.size();
  const auto most = static_cast<std::size_t>(options.max_share * static_cast<double>(mesh.n_vertices()));
  std::vector<char> zone(mesh.n_vertices(), 0), skipped(mesh.n_vertices(), 0);
  for (int round = 0; round < options.rounds && !crossing.empty(); ++round) {
    const std::vector<char> grown = around(mesh, crossing, options.rings + round);
    bool wider = false;
    for (std::size_t v = 0; v < zone.size(); ++v)
      if (grown[v] && !zone[v] && !skipped[v]) {
        zone[v] = 1;
        wider = true;
      }
    if (!wider) break;  // what is left crosses in zones left alone
    ++summary.rounds;
    drop_large_parts(mesh, solved, most, zone, skipped);
    summary.moved_vertices = membrane(mesh, zone, fixed);
    crossing = new_crossings(mesh, before);
  }
  summary.left_pairs = crossing.size();
  summary.skipped_vertices = static_cast<std::size_t>(std::count(skipped.begin(), skipped.end(), 1));
  return summary;
}

}  // namespace sketchsurf
