#include "surfacing/proxy/polygonize.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "surfacing/error.h"
#include "surfacing/flat_key_map.h"

namespace sketchsurf {

namespace {

using Key = std::uint64_t;

// The sparse grid: vertex (i, j, k), 0 <= i <= nx, and cell (i, j, k), 0 <= i < nx, keyed by
// their linear index in an (nx + 1)^3 numbering (cells use their lowest corner's key).
struct Grid {
  Eigen::Vector3d origin;
  double h = 0;
  std::array<std::int64_t, 3> cells{};  // cells per axis

  Key key(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return static_cast<Key>(i + (cells[0] + 1) * (j + (cells[1] + 1) * k));
  }
  std::array<std::int64_t, 3> index(Key key) const {
    const auto n0 = static_cast<Key>(cells[0] + 1), n1 = static_cast<Key>(cells[1] + 1);
    return {static_cast<std::int64_t>(key % n0), static_cast<std::int64_t>((key / n0) % n1),
            static_cast<std::int64_t>(key / (n0 * n1))};
  }
  Eigen::Vector3d position(Key key) const {
    const auto ijk = index(key);
    return origin + h * Eigen::Vector3d(static_cast<double>(ijk[0]), static_cast<double>(ijk[1]),
                                        static_cast<double>(ijk[2]));
  }
  bool on_border(Key key) const {
    const auto ijk = index(key);
    for (int a = 0; a < 3; ++a)
      if (ijk[a] == 0 || ijk[a] == cells[a]) return true;
    return false;
  }
  // Key of corner c (bit 0 = +x, bit 1 = +y, bit 2 = +z) of the cell with lowest corner `cell`.
  Key corner(Key cell, int c) const {
    const auto ijk = index(cell);
    return key(ijk[0] + (c & 1), ijk[1] + ((c >> 1) & 1), ijk[2] + ((c >> 2) & 1));
  }
};

// The 6 Kuhn tetrahedra of a cube, as corner indices: paths 0 -> 7 adding one axis at a time.
constexpr std::array<std::array<int, 4>, 6> kTets = {{{0, 1, 3, 7},
                                                     {0, 1, 5, 7},
                                                     {0, 2, 3, 7},
                                                     {0, 2, 6, 7},
                                                     {0, 4, 5, 7},
                                                     {0, 4, 6, 7}}};

// The 4 corners of each of the 6 faces of a cube, and the direction of the neighbour across it.
struct Face {
  std::array<int, 4> corners;
  int axis, step;
};
constexpr std::array<Face, 6> kFaces = {{{{0, 2, 4, 6}, 0, -1},
                                         {{1, 3, 5, 7}, 0, +1},
                                         {{0, 1, 4, 5}, 1, -1},
                                         {{2, 3, 6, 7}, 1, +1},
                                         {{0, 1, 2, 3}, 2, -1},
                                         {{4, 5, 6, 7}, 2, +1}}};

class Polygonizer {
 public:
  Polygonizer(const FieldBatch& field, const Grid& grid) : field_(field), grid_(grid) {}

  // Field values, sign-normalised so that outside (the box corners' side) is >= 0.
  void evaluate(const std::vector<Key>& cells) {
    std::vector<Key> needed;
    for (Key cell : cells)
      for (int c = 0; c < 8; ++c) {
        const Key v = grid_.corner(cell, c);
        if (!values_.contains(v)) needed.push_back(v);
      }
    std::sort(needed.begin(), needed.end());
    needed.erase(std::unique(needed.begin(), needed.end()), needed.end());
    std::vector<Key> inner;
    for (Key v : needed) {
      if (grid_.on_border(v))
        values_.set(v, grid_.h);  // border: forced outside, so every surface is closed
      else
        inner.push_back(v);
    }
    if (inner.empty()) return;
    Eigen::MatrixX3d points(static_cast<Eigen::Index>(inner.size()), 3);
    for (std::size_t i = 0; i < inner.size(); ++i)
      points.row(static_cast<Eigen::Index>(i)) = grid_.position(inner[i]).transpose();
    Eigen::VectorXd values;
    field_(points, values);
    evaluations += inner.size();
    for (std::size_t i = 0; i < inner.size(); ++i) values_.set(inner[i], sign_ * values[i]);
  }

  void set_outside_sign(double sign) { sign_ = sign; }

  // Grows the band from `frontier` through crossed faces; returns the crossed cells, sorted.
  std::vector<Key> grow(std::vector<Key> frontier, const Progress& progress) {
    FlatKeyMap<char> visited(frontier.size());
    for (Key cell : frontier) visited.try_emplace(cell, 1);
    std::vector<Key> active;
    bool first = true;
    while (!frontier.empty()) {
      progress.update("polygonising", 0.0);
      evaluate(frontier);
      std::vector<Key> next;
      for (Key cell : frontier) {
        const Corners k = corners(cell);
        const bool hit = k.inside_count > 0 && k.inside_count < 8;
        if (hit) active.push_back(cell);
        for (const Face& face : kFaces) {
          auto n = k.ijk;
          n[face.axis] += face.step;
          if (n[face.axis] < 0 || n[face.axis] >= grid_.cells[face.axis]) continue;
          int in = 0;
          for (int c : face.corners) in += k.inside[c];
          // A seed cell the surface misses (it may bulge in and out of one face between
          // corners) still looks at its neighbours once.
          const bool through = hit ? (in > 0 && in < 4) : first;
          const Key nk = grid_.key(n[0], n[1], n[2]);
          if (through && visited.try_emplace(nk, 1).second) next.push_back(nk);
        }
      }
      first = false;
      std::sort(next.begin(), next.end());
      frontier = std::move(next);
    }
    std::sort(active.begin(), active.end());
    return active;
  }

  // Marching tetrahedra over the crossed cells.
  TriangleArrays triangulate(const std::vector<Key>& active) {
    for (Key cell : active) {
      const Corners k = corners(cell);
      for (const auto& tet : kTets) {
        std::array<int, 4> in{}, out{};
        int ni = 0, no = 0;
        for (int i = 0; i < 4; ++i) (k.inside[tet[i]] ? in[ni++] : out[no++]) = tet[i];
        if (ni == 0 || no == 0) continue;
        Eigen::Vector3d from = Eigen::Vector3d::Zero(), to = Eigen::Vector3d::Zero();
        for (int i = 0; i < ni; ++i) from += k.position[in[i]] / ni;
        for (int i = 0; i < no; ++i) to += k.position[out[i]] / no;
        const Eigen::Vector3d outward = to - from;
        auto edge = [](int a, int b) { return std::array<int, 2>{a, b}; };
        if (ni == 1 || no == 1) {
          const int apex = ni == 1 ? in[0] : out[0];
          const auto& others = ni == 1 ? out : in;
          triangle(k, {edge(apex, others[0]), edge(apex, others[1]), edge(apex, others[2])}, outward);
        } else {
          const auto ik = edge(in[0], out[0]), il = edge(in[0], out[1]);
          const auto jl = edge(in[1], out[1]), jk = edge(in[1], out[0]);
          triangle(k, {ik, il, jl}, outward);
          triangle(k, {ik, jl, jk}, outward);
        }
      }
    }
    TriangleArrays out;
    out.V.resize(static_cast<Eigen::Index>(positions_.size()), 3);
    for (std::size_t i = 0; i < positions_.size(); ++i)
      out.V.row(static_cast<Eigen::Index>(i)) = positions_[i].transpose();
    out.F.resize(static_cast<Eigen::Index>(faces_.size()), 3);
    for (std::size_t i = 0; i < faces_.size(); ++i)
      out.F.row(static_cast<Eigen::Index>(i)) << faces_[i][0], faces_[i][1], faces_[i][2];
    return out;
  }

  std::size_t evaluations = 0;

 private:
  // A cell's corners (bit 0 = +x, bit 1 = +y, bit 2 = +z), looked up once for all its tests.
  struct Corners {
    std::array<std::int64_t, 3> ijk;
    std::array<Key, 8> key;
    std::array<double, 8> value;
    std::array<char, 8> inside;
    std::array<Eigen::Vector3d, 8> position;
    int inside_count = 0;
  };

  Corners corners(Key cell) const {
    Corners k;
    k.ijk = grid_.index(cell);
    for (int c = 0; c < 8; ++c) {
      const std::int64_t i = k.ijk[0] + (c & 1), j = k.ijk[1] + ((c >> 1) & 1), l = k.ijk[2] + ((c >> 2) & 1);
      k.key[c] = grid_.key(i, j, l);
      k.value[c] = *values_.find(k.key[c]);
      k.inside[c] = k.value[c] < 0.0;
      k.inside_count += k.inside[c];
      k.position[c] = grid_.origin + grid_.h * Eigen::Vector3d(static_cast<double>(i), static_cast<double>(j),
                                                               static_cast<double>(l));
    }
    return k;
  }

  // The mesh vertex on the edge between corners a and b of a cell (one a subset of the other's
  // axes: the edges of Kuhn tetrahedra), created once by linear interpolation. The edge is keyed
  // by its lower end's grid key and the axes it steps along.
  int edge_vertex(const Corners& k, std::array<int, 2> e) {
    if (e[0] > e[1]) std::swap(e[0], e[1]);
    const Key edge_key = k.key[e[0]] * 8 + static_cast<Key>(e[1] & ~e[0]);
    auto [index, fresh] = edge_vertices_.try_emplace(edge_key, 0);
    if (fresh) {
      const double wa = k.value[e[0]], wb = k.value[e[1]];
      const double t = std::clamp(wa / (wa - wb), 0.0, 1.0);
      const Eigen::Vector3d& pa = k.position[e[0]];
      const Eigen::Vector3d& pb = k.position[e[1]];
      *index = static_cast<int>(positions_.size());
      positions_.push_back(pa + t * (pb - pa));
    }
    return *index;
  }

  // Adds a triangle on three edges of a cell, oriented so that its normal (computed on the edges'
  // midpoints, which are exact and never degenerate) points along `outward`.
  void triangle(const Corners& k, const std::array<std::array<int, 2>, 3>& edges,
                const Eigen::Vector3d& outward) {
    std::array<Eigen::Vector3d, 3> mid;
    for (int i = 0; i < 3; ++i) mid[i] = 0.5 * (k.position[edges[i][0]] + k.position[edges[i][1]]);
    const bool flip = (mid[1] - mid[0]).cross(mid[2] - mid[0]).dot(outward) < 0.0;
    std::array<int, 3> f{edge_vertex(k, edges[0]), edge_vertex(k, edges[1]), edge_vertex(k, edges[2])};
    if (flip) std::swap(f[1], f[2]);
    faces_.push_back(f);
  }

  const FieldBatch& field_;
  const Grid& grid_;
  double sign_ = 1.0;
  FlatKeyMap<double> values_;
  FlatKeyMap<int> edge_vertices_;
  std::vector<Eigen::Vector3d> positions_;
  std::vector<std::array<int, 3>> faces_;
};

}  // namespace

bool PolygonizeOptions::valid(std::string* why) const {
  if (!(cell_size > 0.0) || !std::isfinite(cell_size)) {
    if (why) *why = "polygonisation cell size must be > 0";
    return false;
  }
  return true;
}

TriMesh polygonize(const FieldBatch& field, const Eigen::MatrixX3d& seeds, const BoundingBox& box,
                   const PolygonizeOptions& options, const Progress& progress,
                   PolygonizeSummary* summary) {
  const TriangleArrays t = polygonize_arrays(field, seeds, box, options, progress, summary);
  return mesh_from_matrices(t.V, t.F);
}

TriangleArrays polygonize_arrays(const FieldBatch& field, const Eigen::MatrixX3d& seeds,
                                 const BoundingBox& box, const PolygonizeOptions& options,
                                 const Progress& progress, PolygonizeSummary* summary) {
  std::string why;
  if (!options.valid(&why)) throw Error::usage(why);
  if (box.empty()) throw Error::usage("polygonisation box is empty");
  Grid grid;
  grid.h = options.cell_size;
  grid.origin = box.min;
  double vertices = 1.0;
  for (int a = 0; a < 3; ++a) {
    grid.cells[a] =
        std::max<std::int64_t>(2, static_cast<std::int64_t>(std::ceil((box.max[a] - box.min[a]) / grid.h)));
    vertices *= static_cast<double>(grid.cells[a] + 1);
  }
  if (vertices > 4e9)
    throw Error::usage("polygonisation grid too fine: " + std::to_string(vertices) +
                       " vertices; use a larger cell size");

  Polygonizer polygonizer(field, grid);
  // The outside sign: the majority sign of the field at the box corners.
  {
    Eigen::MatrixX3d corners(8, 3);
    for (int c = 0; c < 8; ++c)
      corners.row(c) << ((c & 1) ? box.max.x() : box.min.x()), ((c & 2) ? box.max.y() : box.min.y()),
          ((c & 4) ? box.max.z() : box.min.z());
    Eigen::VectorXd values;
    field(corners, values);
    int positive = 0;
    for (int c = 0; c < 8; ++c) positive += values[c] >= 0.0;
    polygonizer.set_outside_sign(positive >= 4 ? 1.0 : -1.0);
  }

  std::vector<Key> frontier;
  for (Eigen::Index s = 0; s < seeds.rows(); ++s) {
    std::array<std::int64_t, 3> c{};
    for (int a = 0; a < 3; ++a)
      c[a] = std::clamp<std::int64_t>(
          static_cast<std::int64_t>(std::floor((seeds(s, a) - grid.origin[a]) / grid.h)), 0,
          grid.cells[a] - 1);
    frontier.push_back(grid.key(c[0], c[1], c[2]));
  }
  std::sort(frontier.begin(), frontier.end());
  frontier.erase(std::unique(frontier.begin(), frontier.end()), frontier.end());

  const std::vector<Key> active = polygonizer.grow(std::move(frontier), progress);
  TriangleArrays out = polygonizer.triangulate(active);
  progress.update("polygonising", 1.0);
  if (summary) {
    summary->evaluations = polygonizer.evaluations;
    summary->active_cells = active.size();
  }
  return out;
}

}  // namespace sketchsurf
