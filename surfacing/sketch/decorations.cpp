#include "surfacing/sketch/decorations.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include "surfacing/sketch/stroke_point_grid.h"

namespace sketchsurf {

namespace {

using V3 = Eigen::Vector3d;

std::size_t find_root(std::vector<std::size_t>& parent, std::size_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// Grows `box` to contain `other`.
void merge(BoundingBox& box, const BoundingBox& other) {
  box.min = box.min.cwiseMin(other.min);
  box.max = box.max.cwiseMax(other.max);
}

// Share of the points of `stroke` farther than `share` of its length from both ends at which
// `free` does not hold (1 when there are none).
template <class Free>
double middle_taken(const Stroke& stroke, double share, const Free& free) {
  const double length = stroke.length();
  double along = 0.0;
  std::size_t middle = 0, taken = 0;
  for (std::size_t i = 0; i < stroke.size(); ++i) {
    if (i > 0) along += (stroke.points[i] - stroke.points[i - 1]).norm();
    if (along <= share * length || along >= (1.0 - share) * length) continue;
    ++middle;
    taken += !free(stroke.points[i]);
  }
  return middle > 0 ? static_cast<double>(taken) / static_cast<double>(middle) : 1.0;
}

}  // namespace

const char* decoration_kind_name(DecorationKind kind) {
  switch (kind) {
    case DecorationKind::SmallGroup: return "small group";
    case DecorationKind::Dangling: return "dangling";
    case DecorationKind::Dot: return "dot";
  }
  return "";
}

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
  if (!(carried >= 0.0 && carried < 1.0)) return fail("decorations.carried must be in [0, 1)");
  if (!(dot >= 0.0 && dot < 1.0)) return fail("decorations.dot must be in [0, 1)");
  return true;
}

std::vector<Decoration> find_decorations(const Sketch& sketch, const DecorationOptions& options) {
  std::vector<Decoration> out;
  const double diagonal = sketch.bounding_box().diagonal();
  const std::size_t n = sketch.strokes.size();
  if (!(diagonal > 0.0) || n < 2) return out;
  const double r = options.touch * diagonal;
  const StrokePointGrid grid(sketch, r);

  // Which strokes touch which, and where along each stroke: per neighbour, the first and last
  // touching point as fractions of the stroke's length.
  struct Touch {
    std::size_t stroke;
    double first, last;
  };
  std::vector<std::size_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<std::vector<Touch>> touches(n);
  std::vector<BoundingBox> stroke_box(n);
  for (std::size_t s = 0; s < n; ++s) {
    const Stroke& stroke = sketch.strokes[s];
    const double length = stroke.length();
    double along = 0.0;
    std::unordered_map<std::size_t, std::size_t> slot;  // neighbour -> index in touches[s]
    for (std::size_t i = 0; i < stroke.size(); ++i) {
      stroke_box[s].extend(stroke.points[i]);
      if (i > 0) along += (stroke.points[i] - stroke.points[i - 1]).norm();
      const double at = length > 0.0 ? along / length : 0.0;
      for (std::size_t t : grid.strokes_near(stroke.points[i], s, r)) {
        const auto [it, added] = slot.emplace(t, touches[s].size());
        if (added) touches[s].push_back({t, at, at});
        touches[s][it->second].last = at;
        parent[find_root(parent, s)] = find_root(parent, t);
      }
    }
  }

  // Groups of touching strokes and their extent; the largest (by extent) is the object.
  std::vector<BoundingBox> group_box(n);
  for (std::size_t s = 0; s < n; ++s) merge(group_box[find_root(parent, s)], stroke_box[s]);
  std::size_t largest = find_root(parent, 0);
  for (std::size_t s = 0; s < n; ++s)
    if (group_box[find_root(parent, s)].diagonal() > group_box[largest].diagonal()) largest = find_root(parent, s);

  // The strokes that touch stroke `s` away from its end `at_start` (start or end) and reach the
  // other strokes only through `s`, when their extent stays below `limit`: what a stroke hanging
  // by that end carries at its free end. False when they reach the strokes at the attached end,
  // grow larger or include a boundary stroke.
  const auto carried = [&](std::size_t s, bool at_start, double limit, std::vector<std::size_t>& group) {
    const double share = options.end_share;
    const auto attached = [&](const Touch& t) { return at_start ? t.first <= share : t.last >= 1.0 - share; };
    const auto beyond = [&](const Touch& t) { return at_start ? t.last > share : t.first < 1.0 - share; };
    std::vector<char> seen(n, 0);
    seen[s] = 1;
    for (const Touch& t : touches[s])
      if (attached(t)) seen[t.stroke] = 2;  // the way to the object
    group.clear();
    for (const Touch& t : touches[s])
      if (beyond(t) && seen[t.stroke] != 1) {
        if (seen[t.stroke] == 2) return false;
        seen[t.stroke] = 1;
        group.push_back(t.stroke);
      }
    BoundingBox box;
    for (std::size_t k = 0; k < group.size(); ++k) {
      if (sketch.strokes[group[k]].boundary) return false;  // a surface's border the user marked
      merge(box, stroke_box[group[k]]);
      if (box.diagonal() >= limit) return false;
      for (const Touch& t : touches[group[k]]) {
        if (seen[t.stroke] == 2) return false;
        if (seen[t.stroke] == 0) {
          seen[t.stroke] = 1;
          group.push_back(t.stroke);
        }
      }
    }
    return true;
  };

  std::vector<char> small(n, 0), dangling(n, 0), dot(n, 0);
  const double free = options.free_end * diagonal;
  std::vector<std::size_t> group;
  struct Hanging {
    std::size_t stroke;
    std::vector<std::size_t> carried;
  };
  std::vector<Hanging> hanging;  // strokes touching the others by one end, and what they carry
  for (std::size_t s = 0; s < n; ++s) {
    const Stroke& stroke = sketch.strokes[s];
    if (stroke.ignored || stroke.boundary || stroke.size() < 2) continue;
    const std::size_t g = find_root(parent, s);
    if (g != largest && group_box[g].diagonal() < options.small_group * diagonal) {
      small[s] = 1;
      continue;
    }
    const double length = stroke.length();
    if (length < options.dot * diagonal) {
      dot[s] = 1;
      continue;
    }
    if (length < options.min_dangling * diagonal) continue;
    // A closed stroke (a rim, an outline drawn on a face) is never an antenna.
    if ((stroke.points.front() - stroke.points.back()).norm() < free) continue;
    if (touches[s].empty()) {
      const auto end_free = [&](const V3& p) { return grid.strokes_near(p, s, free).empty(); };
      dangling[s] = g != largest && end_free(stroke.points.front()) && end_free(stroke.points.back());
      continue;
    }
    // Touching by one end, and the other end far from every stroke but those it carries: an
    // imprecise junction of a sparse curve network misses its neighbour by a little, an antenna
    // by a lot.
    const double limit = std::min(options.carried * diagonal, 0.5 * length);
    const auto only_group = [&](const V3& p) {
      const std::vector<std::size_t> near = grid.strokes_near(p, s, free);
      return std::all_of(near.begin(), near.end(), [&](std::size_t t) {
        return std::find(group.begin(), group.end(), t) != group.end();
      });
    };
    for (const bool at_start : {true, false}) {
      if (!carried(s, at_start, limit, group)) continue;
      if (!only_group(at_start ? stroke.points.back() : stroke.points.front())) continue;
      // A stroke carrying a group runs free of the rest between its ends (a cable across the
      // floor, a string passing by a handle); one that runs beside other strokes for most of
      // its middle is an edge of a thin part (a chair's leg whose foot ring it touches).
      if (!group.empty() && middle_taken(stroke, options.end_share, only_group) > 0.5) continue;
      hanging.push_back({s, group});
      break;
    }
  }
  // The box of the strokes that depict the object: all but those found above. A hanging stroke
  // lying along a side of that box, within `r` of the side and inside the box grown by `r`, is an
  // edge of a face drawn on that side whose neighbouring edge the hand left out (a box's end drawn
  // by three of its four edges): its free end lies where the object already is. An antenna's, a
  // cable's or a line leg's runs out of it.
  std::vector<char> found(n, 0);
  for (std::size_t s = 0; s < n; ++s) found[s] = small[s] || dot[s] || dangling[s];
  for (const Hanging& h : hanging) {
    found[h.stroke] = 1;
    for (std::size_t t : h.carried) found[t] = 1;
  }
  BoundingBox object;
  for (std::size_t t = 0; t < n; ++t)
    if (!found[t] && !sketch.strokes[t].ignored) merge(object, stroke_box[t]);
  const auto along_side = [&](const std::vector<V3>& points) {
    if (object.empty()) return false;
    const Eigen::Array3d lo = object.min.array() - r, hi = object.max.array() + r;
    if (!std::all_of(points.begin(), points.end(),
                     [&](const V3& p) { return (p.array() >= lo).all() && (p.array() <= hi).all(); }))
      return false;
    for (int axis = 0; axis < 3; ++axis)
      for (const double side : {object.min[axis], object.max[axis]})
        if (std::all_of(points.begin(), points.end(), [&](const V3& p) { return std::abs(p[axis] - side) <= r; }))
          return true;
    return false;
  };
  for (const Hanging& h : hanging) {
    if (along_side(sketch.strokes[h.stroke].points)) continue;
    dangling[h.stroke] = 1;
    for (std::size_t t : h.carried) small[t] = 1;
  }
  for (std::size_t s = 0; s < n; ++s) {
    const Stroke& stroke = sketch.strokes[s];
    if (stroke.ignored || stroke.boundary) continue;
    if (small[s]) out.push_back({s, stroke.id, DecorationKind::SmallGroup});
    else if (dangling[s]) out.push_back({s, stroke.id, DecorationKind::Dangling});
    else if (dot[s]) out.push_back({s, stroke.id, DecorationKind::Dot});
  }
  return out;
}

}  // namespace sketchsurf
