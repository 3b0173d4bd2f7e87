#include "surfacing/sketch/consolidate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "surfacing/error.h"

namespace sketchsurf {

bool ConsolidateOptions::valid(std::string* why) const {
  const auto fail = [&](const char* message) {
    if (why) *why = message;
    return false;
  };
  if (!(radius >= 0.0 && radius < 0.5)) return fail("consolidation radius must be in [0, 0.5)");
  if (!(parallel >= 0.0 && parallel <= 1.0)) return fail("consolidation parallel must be in [0, 1]");
  if (rounds < 0 || rounds > 100) return fail("consolidation rounds must be in [0, 100]");
  if (!(taper >= 0.0 && taper < 1.0)) return fail("consolidation taper must be in [0, 1)");
  return true;
}

namespace {

// The points of the movable strokes, flattened, with where each came from.
struct Points {
  std::vector<Eigen::Vector3d> position, tangent;
  std::vector<int> stroke;     // index into sketch.strokes
  std::vector<double> arc;     // arc length from the stroke's first point
  std::vector<std::size_t> first;  // per listed stroke: its first point; plus the end
  std::vector<int> listed;         // the strokes listed, in order
};

void set_tangents(Points& pts) {
  for (std::size_t s = 0; s + 1 < pts.first.size(); ++s) {
    const std::size_t a = pts.first[s], b = pts.first[s + 1];
    for (std::size_t i = a; i < b; ++i) {
      const Eigen::Vector3d d = pts.position[std::min(i + 1, b - 1)] - pts.position[i > a ? i - 1 : a];
      const double n = d.norm();
      pts.tangent[i] = n > 0.0 ? Eigen::Vector3d(d / n) : Eigen::Vector3d::Zero();
    }
  }
}

// Points sorted by the cell (of side `cell`) they fall in: the cells around a point are looked up
// by binary search, which keeps the query order, and so the result, independent of hashing.
class CellIndex {
 public:
  CellIndex(const std::vector<Eigen::Vector3d>& p, double cell) : cell_(cell) {
    keyed_.reserve(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) keyed_.push_back({key(coords(p[i])), i});
    std::sort(keyed_.begin(), keyed_.end());
  }

  template <class Fn>
  void for_each_near(const Eigen::Vector3d& q, Fn&& fn) const {
    const std::array<std::int64_t, 3> c = coords(q);
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const std::uint64_t k = key({c[0] + dx, c[1] + dy, c[2] + dz});
          auto it = std::lower_bound(keyed_.begin(), keyed_.end(), std::pair<std::uint64_t, std::size_t>{k, 0});
          for (; it != keyed_.end() && it->first == k; ++it) fn(it->second);
        }
  }

 private:
  std::array<std::int64_t, 3> coords(const Eigen::Vector3d& p) const {
    return {static_cast<std::int64_t>(std::floor(p.x() / cell_)),
            static_cast<std::int64_t>(std::floor(p.y() / cell_)),
            static_cast<std::int64_t>(std::floor(p.z() / cell_))};
  }
  static std::uint64_t key(const std::array<std::int64_t, 3>& c) {
    constexpr std::uint64_t kMask = (1u << 21) - 1;  // 21 bits a coordinate (wraps far away only)
    return (static_cast<std::uint64_t>(c[0]) & kMask) | ((static_cast<std::uint64_t>(c[1]) & kMask) << 21) |
           ((static_cast<std::uint64_t>(c[2]) & kMask) << 42);
  }

  double cell_;
  std::vector<std::pair<std::uint64_t, std::size_t>> keyed_;
};

// Smooths per-point moves along each stroke with `passes` rounds of the (1/4, 1/2, 1/4) filter
// (ends kept by reflection), so a pull fades in and out over the taper length.
void smooth_along_strokes(const Points& pts, std::vector<Eigen::Vector3d>& move, int passes) {
  std::vector<Eigen::Vector3d> tmp;
  for (std::size_t s = 0; s + 1 < pts.first.size(); ++s) {
    const std::size_t a = pts.first[s], b = pts.first[s + 1];
    if (b - a < 3) continue;
    for (int pass = 0; pass < passes; ++pass) {
      tmp.assign(move.begin() + static_cast<std::ptrdiff_t>(a), move.begin() + static_cast<std::ptrdiff_t>(b));
      const std::size_t n = b - a;
      for (std::size_t i = 0; i < n; ++i) {
        const Eigen::Vector3d& l = tmp[i > 0 ? i - 1 : 1];
        const Eigen::Vector3d& r = tmp[i + 1 < n ? i + 1 : n - 2];
        move[a + i] = 0.25 * l + 0.5 * tmp[i] + 0.25 * r;
      }
    }
  }
}

}  // namespace

Consolidation consolidate_overdrawn(Sketch& sketch, const ConsolidateOptions& options) {
  std::string why;
  if (!options.valid(&why)) throw Error::usage(why);
  Consolidation out;
  const double diagonal = sketch.bounding_box().diagonal();
  if (!(diagonal > 0.0) || options.radius == 0.0 || options.rounds == 0) return out;
  const double radius = options.radius * diagonal;

  Points pts;
  double spacing_sum = 0.0;
  std::size_t segments = 0;
  for (std::size_t s = 0; s < sketch.strokes.size(); ++s) {
    const Stroke& stroke = sketch.strokes[s];
    if (stroke.ignored || stroke.points.size() < 2) continue;
    pts.listed.push_back(static_cast<int>(s));
    pts.first.push_back(pts.position.size());
    double arc = 0.0;
    for (std::size_t i = 0; i < stroke.points.size(); ++i) {
      if (i > 0) {
        const double step = (stroke.points[i] - stroke.points[i - 1]).norm();
        arc += step;
        spacing_sum += step;
        ++segments;
      }
      pts.position.push_back(stroke.points[i]);
      pts.stroke.push_back(static_cast<int>(s));
      pts.arc.push_back(arc);
    }
  }
  pts.first.push_back(pts.position.size());
  if (pts.listed.size() == 0 || segments == 0) return out;
  pts.tangent.resize(pts.position.size());
  const std::vector<Eigen::Vector3d> original = pts.position;
  // n passes of the binomial filter spread a move over a standard deviation of sqrt(n / 2) points.
  const double spacing = spacing_sum / static_cast<double>(segments);
  const double half_taper = 0.5 * options.taper * diagonal / std::max(spacing, 1e-300);
  const int passes = std::clamp(static_cast<int>(std::lround(2.0 * half_taper * half_taper)), 0, 64);
  // A retrace within one stroke: the same stroke again, farther along than a hairpin's width.
  const double same_stroke_gap = 3.0 * radius;

  std::vector<Eigen::Vector3d> move(pts.position.size());
  for (int round = 0; round < options.rounds; ++round) {
    set_tangents(pts);
    const CellIndex cells(pts.position, radius);
    for (std::size_t i = 0; i < pts.position.size(); ++i) {
      move[i].setZero();
      const Eigen::Vector3d& p = pts.position[i];
      const Eigen::Vector3d& t = pts.tangent[i];
      if (t.isZero()) continue;
      // The nearest running-together point of each other pass (pass = stroke).
      struct Nearest {
        int stroke;
        double d2;
        std::size_t j;
      };
      std::vector<Nearest> nearest;
      cells.for_each_near(p, [&](std::size_t j) {
        const double d2 = (pts.position[j] - p).squaredNorm();
        if (d2 >= radius * radius || std::abs(pts.tangent[j].dot(t)) < options.parallel) return;
        if (pts.stroke[j] == pts.stroke[i] && std::abs(pts.arc[j] - pts.arc[i]) <= same_stroke_gap) return;
        auto it = std::find_if(nearest.begin(), nearest.end(),
                               [&](const Nearest& n) { return n.stroke == pts.stroke[j]; });
        if (it == nearest.end())
          nearest.push_back({pts.stroke[j], d2, j});
        else if (d2 < it->d2 || (d2 == it->d2 && j < it->j))
          *it = {pts.stroke[j], d2, j};
      });
      if (nearest.empty()) continue;
      Eigen::Vector3d mean = p;
      for (const Nearest& n : nearest) mean += pts.position[n.j];
      mean /= static_cast<double>(nearest.size() + 1);
      const Eigen::Vector3d d = mean - p;
      move[i] = d - d.dot(t) * t;  // across the stroke only: its spacing stays
    }
    smooth_along_strokes(pts, move, passes);
    for (std::size_t i = 0; i < pts.position.size(); ++i) pts.position[i] += move[i];
  }

  std::vector<char> touched(sketch.strokes.size(), 0);
  for (std::size_t i = 0; i < pts.position.size(); ++i) {
    const double shift = (pts.position[i] - original[i]).norm();
    out.max_shift = std::max(out.max_shift, shift / diagonal);
    if (shift > 0.05 * radius) {
      ++out.points;
      touched[static_cast<std::size_t>(pts.stroke[i])] = 1;
    }
  }
  out.strokes = static_cast<std::size_t>(std::count(touched.begin(), touched.end(), 1));
  for (std::size_t s = 0; s + 1 < pts.first.size(); ++s) {
    Stroke& stroke = sketch.strokes[static_cast<std::size_t>(pts.listed[s])];
    for (std::size_t i = pts.first[s]; i < pts.first[s + 1]; ++i) stroke.points[i - pts.first[s]] = pts.position[i];
  }
  return out;
}

}  // namespace sketchsurf
