#include "surfacing/self_intersections.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

#include "surfacing/parallel.h"

namespace sketchsurf {

namespace {

using V3 = Eigen::Vector3d;

// Whether segment pq crosses triangle abc (Moller-Trumbore; a segment in the triangle's plane
// does not count).
bool segment_hits_triangle(const V3& p, const V3& q, const V3& a, const V3& b, const V3& c) {
  const V3 d = q - p, e1 = b - a, e2 = c - a;
  const V3 h = d.cross(e2);
  const double det = e1.dot(h);
  const double scale = e1.norm() * e2.norm() * d.norm();
  if (!(std::abs(det) > 1e-12 * scale)) return false;
  const V3 s = p - a;
  const double u = s.dot(h) / det;
  if (u < 0.0 || u > 1.0) return false;
  const V3 r = s.cross(e1);
  const double v = d.dot(r) / det;
  if (v < 0.0 || u + v > 1.0) return false;
  const double t = e2.dot(r) / det;
  return t >= 0.0 && t <= 1.0;
}

bool triangles_cross(const std::array<V3, 3>& A, const std::array<V3, 3>& B) {
  for (int i = 0; i < 3; ++i) {
    if (segment_hits_triangle(A[i], A[(i + 1) % 3], B[0], B[1], B[2])) return true;
    if (segment_hits_triangle(B[i], B[(i + 1) % 3], A[0], A[1], A[2])) return true;
  }
  return false;
}

}  // namespace

std::vector<std::array<int, 2>> crossing_face_pairs(const TriMesh& mesh, unsigned threads) {
  return crossing_face_pairs(vertex_matrix(mesh), face_matrix(mesh), {}, threads);
}

std::vector<std::array<int, 2>> crossing_face_pairs(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F,
                                                    const std::vector<char>& among, unsigned threads) {
  if (F.rows() < 2) return {};
  const auto flagged = [&](int f) { return among.empty() || among[static_cast<std::size_t>(f)] != 0; };
  double edge_sum = 0.0;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) edge_sum += (V.row(F(f, k)) - V.row(F(f, (k + 1) % 3))).norm();
  const double cell = std::max(2.0 * edge_sum / (3.0 * static_cast<double>(F.rows())), 1e-300);
  const V3 origin = V.colwise().minCoeff();
  const auto cell_of = [&](const V3& p) {
    return ((p - origin) / cell).array().floor().cast<long long>().matrix().eval();
  };
  const auto key = [](const Eigen::Matrix<long long, 3, 1>& c) {
    return static_cast<std::uint64_t>(c.x()) * 73856093ull ^ static_cast<std::uint64_t>(c.y()) * 19349663ull ^
           static_cast<std::uint64_t>(c.z()) * 83492791ull;
  };
  std::vector<V3> lo(static_cast<std::size_t>(F.rows())), hi(lo.size());
  for (int f = 0; f < F.rows(); ++f) {
    lo[f] = V.row(F(f, 0)).cwiseMin(V.row(F(f, 1))).cwiseMin(V.row(F(f, 2)));
    hi[f] = V.row(F(f, 0)).cwiseMax(V.row(F(f, 1))).cwiseMax(V.row(F(f, 2)));
  }
  // The flagged triangles in the cells their boxes overlap; every triangle then meets those in
  // the cells its own box overlaps.
  std::unordered_map<std::uint64_t, std::vector<int>> grid;
  V3 flagged_lo = V3::Constant(std::numeric_limits<double>::infinity()), flagged_hi = -flagged_lo;
  for (int f = 0; f < F.rows(); ++f) {
    if (!flagged(f)) continue;
    flagged_lo = flagged_lo.cwiseMin(lo[f]);
    flagged_hi = flagged_hi.cwiseMax(hi[f]);
    const auto c0 = cell_of(lo[f]), c1 = cell_of(hi[f]);
    for (long long x = c0.x(); x <= c1.x(); ++x)
      for (long long y = c0.y(); y <= c1.y(); ++y)
        for (long long z = c0.z(); z <= c1.z(); ++z) grid[key({x, y, z})].push_back(f);
  }
  // Blocks of triangles met in parallel, each with its own list (the lists are sorted together).
  constexpr int kBlock = 1024;
  const auto blocks = static_cast<std::size_t>((F.rows() + kBlock - 1) / kBlock);
  std::vector<std::vector<std::array<int, 2>>> found(blocks);
  parallel_for(0, blocks, threads, [&](std::size_t block) {
    std::vector<std::array<int, 2>>& pairs = found[block];
    const int first = static_cast<int>(block) * kBlock;
    const int last = std::min<int>(first + kBlock, static_cast<int>(F.rows()));
    for (int a = first; a < last; ++a) {
      if ((lo[a].array() > flagged_hi.array()).any() || (flagged_lo.array() > hi[a].array()).any()) continue;
      const auto c0 = cell_of(lo[a]), c1 = cell_of(hi[a]);
      for (long long x = c0.x(); x <= c1.x(); ++x)
        for (long long y = c0.y(); y <= c1.y(); ++y)
          for (long long z = c0.z(); z <= c1.z(); ++z) {
            const std::uint64_t cell_key = key({x, y, z});
            const auto faces = grid.find(cell_key);
            if (faces == grid.end()) continue;
            for (const int b : faces->second) {
              if (b == a || (flagged(a) && b < a)) continue;  // a flagged pair is met from its lower triangle
              if ((lo[a].array() > hi[b].array()).any() || (lo[b].array() > hi[a].array()).any()) continue;
              // Count the pair in one cell only: the one holding the low corner of the boxes' overlap.
              if (key(cell_of(lo[a].cwiseMax(lo[b]))) != cell_key) continue;
              bool shared = false;
              for (int k = 0; k < 3; ++k)
                for (int l = 0; l < 3; ++l) shared |= F(a, k) == F(b, l);
              if (shared) continue;
              const std::array<V3, 3> A = {V.row(F(a, 0)), V.row(F(a, 1)), V.row(F(a, 2))};
              const std::array<V3, 3> B = {V.row(F(b, 0)), V.row(F(b, 1)), V.row(F(b, 2))};
              if (triangles_cross(A, B)) pairs.push_back({std::min(a, b), std::max(a, b)});
            }
          }
    }
  });
  std::vector<std::array<int, 2>> pairs;
  for (const auto& block : found) pairs.insert(pairs.end(), block.begin(), block.end());
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());  // cells whose keys collide
  return pairs;
}

std::size_t count_self_intersections(const TriMesh& mesh, unsigned threads) {
  return crossing_face_pairs(mesh, threads).size();
}

}  // namespace sketchsurf
