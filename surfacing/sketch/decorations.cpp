#include "surfacing/sketch/decorations.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

namespace sketchsurf {

namespace {

using V3 = Eigen::Vector3d;

// Points of every stroke in a uniform grid of cell `cell`, for "is a point of another stroke
// within r <= cell" queries.
class StrokePointGrid {
 public:
  StrokePointGrid(const Sketch& sketch, double cell) : cell_(cell) {
    for (std::size_t s = 0; s < sketch.strokes.size(); ++s)
      for (const V3& p : sketch.strokes[s].points) cells_[key(p)].push_back({p, s});
  }

  /// The strokes other than `self` with a point within `r` of p, sorted, unique.
  std::vector<std::size_t> strokes_near(const V3& p, std::size_t self, double r) const {
    std::vector<std::size_t> out;
    const Eigen::Vector3i c = index(p);
    const int reach = static_cast<int>(std::ceil(r / cell_));
    for (int dx = -reach; dx <= reach; ++dx)
      for (int dy = -reach; dy <= reach; ++dy)
        for (int dz = -reach; dz <= reach; ++dz) {
          const auto it = cells_.find(cell_key(c + Eigen::Vector3i(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (const auto& [q, s] : it->second)
            if (s != self && (q - p).squaredNorm() <= r * r) out.push_back(s);
        }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

 private:
  Eigen::Vector3i index(const V3& p) const { return (p / cell_).array().floor().cast<int>(); }
  static std::uint64_t cell_key(const Eigen::Vector3i& c) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(c.x())) * 73856093ull) ^
           (static_cast<std::uint64_t>(static_cast<std::uint32_t>(c.y())) * 19349663ull) ^
           (static_cast<std::uint64_t>(static_cast<std::uint32_t>(c.z())) * 83492791ull);
  }
  std::uint64_t key(const V3& p) const { return cell_key(index(p)); }

  double cell_;
  std::unordered_map<std::uint64_t, std::vector<std::pair<V3, std::size_t>>> cells_;
};

std::size_t find_root(std::vector<std::size_t>& parent, std::size_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

bool DecorationOptions::valid(std::string* why) const {
  const auto fail = [&](const char* message) {
    if (why) *why = message;
    return false;
  };
  if (!(touch > 0.0 && touch < 0.5)) return fail("decorations.touch must be in (0, 0.5)");
  if (!(small_group >= 0.0 && small_group < 1.0)) return fail("decorations.small_group must be in [0, 1)");
  if (!(end_share > 0.0 && end_share <= 0.5)) return fail("decorations.end_share must be in (0, 0.5]");
  if (!(min_dangling >= 0.0)) return fail("decorations.min_dangling must be >= 0");
  if (!(free_end > touch && free_end < 1.0)) return fail("decorations.free_end must be in (touch, 1)");
  return true;
}

std::vector<Decoration> find_decorations(const Sketch& sketch, const DecorationOptions& options) {
  std::vector<Decoration> out;
  const double diagonal = sketch.bounding_box().diagonal();
  const std::size_t n = sketch.strokes.size();
  if (!(diagonal > 0.0) || n < 2) return out;
  const double r = options.touch * diagonal;
  const StrokePointGrid grid(sketch, r);

  // Which strokes touch which, and where along each stroke (arc length of touching points).
  std::vector<std::size_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<std::vector<double>> touching_at(n);  // fractions of the stroke's length
  for (std::size_t s = 0; s < n; ++s) {
    const Stroke& stroke = sketch.strokes[s];
    const double length = stroke.length();
    double along = 0.0;
    for (std::size_t i = 0; i < stroke.size(); ++i) {
      if (i > 0) along += (stroke.points[i] - stroke.points[i - 1]).norm();
      const std::vector<std::size_t> near = grid.strokes_near(stroke.points[i], s, r);
      if (near.empty()) continue;
      touching_at[s].push_back(length > 0.0 ? along / length : 0.0);
      for (std::size_t t : near) parent[find_root(parent, s)] = find_root(parent, t);
    }
  }

  // Groups of touching strokes and their extent; the largest (by extent) is the object.
  std::vector<BoundingBox> group_box(n);
  for (std::size_t s = 0; s < n; ++s)
    for (const V3& p : sketch.strokes[s].points) group_box[find_root(parent, s)].extend(p);
  std::size_t largest = find_root(parent, 0);
  for (std::size_t s = 0; s < n; ++s)
    if (group_box[find_root(parent, s)].diagonal() > group_box[largest].diagonal()) largest = find_root(parent, s);

  for (std::size_t s = 0; s < n; ++s) {
    const Stroke& stroke = sketch.strokes[s];
    if (stroke.ignored || stroke.boundary || stroke.size() < 2) continue;
    const std::size_t group = find_root(parent, s);
    if (group != largest && group_box[group].diagonal() < options.small_group * diagonal) {
      out.push_back({s, stroke.id, DecorationKind::SmallGroup});
      continue;
    }
    if (stroke.length() < options.min_dangling * diagonal) continue;
    // A closed stroke (a rim, an outline drawn on a face) is never an antenna.
    if ((stroke.points.front() - stroke.points.back()).norm() < options.free_end * diagonal) continue;
    // Touching by one end at most, and the other end(s) far from every other stroke: an imprecise
    // junction of a sparse curve network misses its neighbour by a little, an antenna by a lot.
    const auto& at = touching_at[s];
    const double free = options.free_end * diagonal;
    const auto end_free = [&](const V3& p) { return grid.strokes_near(p, s, free).empty(); };
    const bool start_free = end_free(stroke.points.front()), end_is_free = end_free(stroke.points.back());
    bool dangling = false;
    if (at.empty()) dangling = start_free && end_is_free && group != largest;
    else if (at.back() <= options.end_share) dangling = end_is_free;  // touches near its start only
    else if (at.front() >= 1.0 - options.end_share) dangling = start_free;  // near its end only
    if (dangling) out.push_back({s, stroke.id, DecorationKind::Dangling});
  }
  return out;
}

}  // namespace sketchsurf
