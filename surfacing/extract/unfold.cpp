#include "surfacing/extract/unfold.h"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <array>
#include <cstddef>
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
  if (!(refit_share >= 0.0 && refit_share <= 1.0)) {
    if (why) *why = "extract.unfold_refit_share must be in [0, 1]";
    return false;
  }
  if (!(hold_fit >= 0.0)) {
    if (why) *why = "extract.unfold_hold_fit must be >= 0";
    return false;
  }
  if (!(zone_share >= 0.0 && zone_share <= 1.0)) {
    if (why) *why = "extract.unfold_zone_share must be in [0, 1]";
    return false;
  }
  return true;
}

namespace {

// The crossing pairs of `mesh` that are not in `before` (both sorted).
std::vector<std::array<int, 2>> new_crossings(const TriMesh& mesh, const std::vector<std::array<int, 2>>& before,
                                              unsigned threads) {
  const std::vector<std::array<int, 2>> now = crossing_face_pairs(mesh, threads);
  std::vector<std::array<int, 2>> out;
  std::set_difference(now.begin(), now.end(), before.begin(), before.end(), std::back_inserter(out));
  return out;
}

// The same after some vertices moved from `was`, where `crossing` were the pairs: those of them
// whose triangles did not move, and the moved triangles' pairs searched again.
std::vector<std::array<int, 2>> new_crossings(const TriMesh& mesh, const Eigen::MatrixX3i& F,
                                              const Eigen::MatrixX3d& was,
                                              const std::vector<std::array<int, 2>>& crossing,
                                              const std::vector<std::array<int, 2>>& before, unsigned threads) {
  const Eigen::MatrixX3d V = vertex_matrix(mesh);
  std::vector<char> moved(static_cast<std::size_t>(F.rows()), 0);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) moved[f] |= V.row(F(f, k)) != was.row(F(f, k));
  const std::vector<std::array<int, 2>> found = crossing_face_pairs(V, F, moved, threads);
  std::vector<std::array<int, 2>> out, kept;
  std::set_difference(found.begin(), found.end(), before.begin(), before.end(), std::back_inserter(out));
  std::copy_if(crossing.begin(), crossing.end(), std::back_inserter(kept),
               [&](const std::array<int, 2>& pair) { return !moved[pair[0]] && !moved[pair[1]]; });
  const std::size_t middle = out.size();
  out.insert(out.end(), kept.begin(), kept.end());
  std::inplace_merge(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(middle), out.end());
  return out;
}

// Drops from `zone` its connected parts of more than `most` vertices, and those that touch a part
// dropped before, flags them in `skipped` and puts their vertices back where `reference` has them.
void drop_large_parts(TriMesh& mesh, const Eigen::MatrixX3d& reference, std::size_t most, std::vector<char>& zone,
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
      mesh.set_point(mesh.vertex_handle(v), TriMesh::Point(reference(v, 0), reference(v, 1), reference(v, 2)));
    }
  }
}

// How a zone is filled: a bi-Laplacian fill continues the slope of the surface round it across
// the zone (the squared graph Laplacian over the zone and its first ring outside is least), so a
// pleat on a curved part or at an edge is replaced by the bend the surface around it makes; a
// membrane spans the zone as tightly as it can (each vertex at the mean of its neighbours), which
// cuts across such a bend but cannot overshoot, and so removes the folds the first one leaves.
enum class Fill { bilaplacian, membrane };

// Fills `zone` (its vertices that are neither fixed nor on the mesh's border) as `fill` says, the
// other vertices held: one sparse solve.
void fill_zone(TriMesh& mesh, const std::vector<char>& zone, const std::vector<std::uint8_t>& fixed, Fill fill) {
  std::vector<int> index(zone.size(), -1);
  int m = 0;
  for (auto v : mesh.vertices())
    if (zone[v.idx()] && (fixed.empty() || !fixed[v.idx()]) && !mesh.is_boundary(v)) index[v.idx()] = m++;
  if (m == 0) return;
  // One row of the graph Laplacian per vertex in the rows (the unknowns, and for the bi-Laplacian
  // their neighbours too): the unknowns' coefficients in `rows`, the held vertices' part in `held`.
  std::vector<char> in_rows(zone.size(), 0);
  for (auto v : mesh.vertices()) {
    if (index[v.idx()] < 0) continue;
    in_rows[v.idx()] = 1;
    if (fill == Fill::bilaplacian)
      for (auto u : mesh.vv_range(v)) in_rows[u.idx()] = 1;
  }
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<Eigen::RowVector3d> held;
  for (auto v : mesh.vertices()) {
    if (!in_rows[v.idx()]) continue;
    const int r = static_cast<int>(held.size());
    Eigen::RowVector3d c = Eigen::RowVector3d::Zero();
    double degree = 0.0;
    for (auto u : mesh.vv_range(v)) {
      degree += 1.0;
      if (const int j = index[u.idx()]; j >= 0) {
        entries.emplace_back(r, j, -1.0);
      } else {
        const auto& p = mesh.point(u);
        c -= Eigen::RowVector3d(p[0], p[1], p[2]);
      }
    }
    if (const int i = index[v.idx()]; i >= 0) {
      entries.emplace_back(r, i, degree);
    } else {
      const auto& p = mesh.point(v);
      c += degree * Eigen::RowVector3d(p[0], p[1], p[2]);
    }
    held.push_back(c);
  }
  Eigen::SparseMatrix<double> rows(static_cast<Eigen::Index>(held.size()), m);
  rows.setFromTriplets(entries.begin(), entries.end());
  Eigen::MatrixX3d rhs(static_cast<Eigen::Index>(held.size()), 3);
  for (std::size_t r = 0; r < held.size(); ++r) rhs.row(static_cast<Eigen::Index>(r)) = -held[r];
  // Every part of the zone touches a held vertex (it is smaller than the mesh, or the border and
  // `fixed` bound it): the membrane's square Laplacian and the bi-Laplacian's normal equations
  // are positive definite.
  Eigen::MatrixX3d x;
  if (fill == Fill::membrane) {
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(rows);
    if (solver.info() != Eigen::Success) return;
    x = solver.solve(rhs);
  } else {
    const Eigen::SparseMatrix<double> normal = rows.transpose() * rows;
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(normal);
    if (solver.info() != Eigen::Success) return;
    x = solver.solve(rows.transpose() * rhs);
  }
  for (auto v : mesh.vertices())
    if (const int i = index[v.idx()]; i >= 0) mesh.set_point(v, TriMesh::Point(x(i, 0), x(i, 1), x(i, 2)));
}

}  // namespace

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

UnfoldSummary unfold(TriMesh& mesh, const Eigen::MatrixX3d& start, const std::vector<std::uint8_t>& fixed,
                     const UnfoldOptions& options, unsigned threads, std::vector<std::array<int, 2>>* left) {
  UnfoldSummary summary;
  if (left) left->clear();
  if (options.rings == 0) return summary;
  const Eigen::MatrixX3d solved = vertex_matrix(mesh);
  const Eigen::MatrixX3i F = face_matrix(mesh);
  const std::vector<std::array<int, 2>> before = crossing_face_pairs(start, F, {}, threads);
  std::vector<std::array<int, 2>> crossing = new_crossings(mesh, before, threads);
  summary.crossing_pairs = crossing.size();
  const auto most = static_cast<std::size_t>(options.max_share * static_cast<double>(mesh.n_vertices()));
  std::vector<char> skipped;
  // The bi-Laplacian fill first; the membrane for the folds it leaves, in zones grown afresh.
  for (const Fill fill : {Fill::bilaplacian, Fill::membrane}) {
    const Eigen::MatrixX3d reference = vertex_matrix(mesh);
    std::vector<char> zone(mesh.n_vertices(), 0);
    skipped.assign(mesh.n_vertices(), 0);
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
      const Eigen::MatrixX3d was = vertex_matrix(mesh);
      drop_large_parts(mesh, reference, most, zone, skipped);
      fill_zone(mesh, zone, fixed, fill);
      crossing = new_crossings(mesh, F, was, crossing, before, threads);
    }
  }
  summary.left_pairs = crossing.size();
  const Eigen::MatrixX3d now = vertex_matrix(mesh);
  for (Eigen::Index v = 0; v < now.rows(); ++v) summary.moved_vertices += now.row(v) != solved.row(v);
  summary.skipped_vertices = static_cast<std::size_t>(std::count(skipped.begin(), skipped.end(), 1));
  if (left) *left = std::move(crossing);
  return summary;
}

}  // namespace sketchsurf
