#include "surfacing/proxy/saddles.h"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "surfacing/parallel.h"
#include "surfacing/portable_math.h"

namespace sketchsurf {

double Bump::value(const Eigen::Vector3d& p, Eigen::Vector3d* gradient) const {
  const Eigen::Vector3d local = (axes.transpose() * (p - centre)).cwiseQuotient(radii);
  const double q = local.squaredNorm();
  if (q >= 1.0) return 0.0;
  const double u = 1.0 - q;
  if (gradient) *gradient += axes * (-6.0 * depth * u * u * local.cwiseQuotient(radii));
  return depth * u * u * u;
}

double bumps_value(const std::vector<Bump>& bumps, const Eigen::Vector3d& p,
                   Eigen::Vector3d* gradient) {
  double sum = 0.0;
  for (const Bump& b : bumps) sum += b.value(p, gradient);
  return sum;
}

namespace {

constexpr double kUnknown = std::numeric_limits<double>::infinity();
// The bump's profile (1 - q)^3 at a quarter of its squared radius (half its radius): a bump of
// radius 2 r whose depth is v / kHalfway lowers the field by v at distance r from its centre.
constexpr double kHalfway = 0.421875;

// The search grid over the box: spacing h, values of s f at the points near a stroke.
class SearchGrid {
 public:
  SearchGrid(const HermiteRbf& f, double scale, const std::vector<Bump>& lowered,
             const PointGrid& strokes, const BoundingBox& box, const SaddleSearch& search,
             unsigned threads)
      : f_(f), scale_(scale), lowered_(lowered), box_(box), h_(search.step) {
    const Eigen::Vector3d extent = box.max - box.min;
    for (int a = 0; a < 3; ++a) n_[a] = static_cast<int>(std::ceil(extent[a] / h_)) + 1;
    count_ = static_cast<std::size_t>(n_[0]) * n_[1] * n_[2];
    // The points near a stroke, slice by slice (in parallel), in increasing id.
    std::vector<std::vector<std::size_t>> slices(static_cast<std::size_t>(n_[2]));
    parallel_for(0, slices.size(), threads, [&](std::size_t kk) {
      const int k = static_cast<int>(kk);
      for (int j = 0; j < n_[1]; ++j)
        for (int i = 0; i < n_[0]; ++i)
          if (strokes.finds_within(point(i, j, k), search.near))
            slices[kk].push_back(id(i, j, k));
    });
    std::vector<std::size_t> near_ids;
    for (const auto& slice : slices) near_ids.insert(near_ids.end(), slice.begin(), slice.end());
    Eigen::MatrixX3d points(static_cast<Eigen::Index>(near_ids.size()), 3);
    for (std::size_t r = 0; r < near_ids.size(); ++r) {
      const std::size_t q = near_ids[r];
      points.row(static_cast<Eigen::Index>(r)) =
          point(static_cast<int>(q % n_[0]), static_cast<int>(q / n_[0] % n_[1]),
                static_cast<int>(q / n_[0] / n_[1]))
              .transpose();
    }
    Eigen::VectorXd near_values;
    f.values(points, near_values, threads);
    value_.assign(count_, kUnknown);
    parallel_for(0, near_ids.size(), threads, [&](std::size_t r) {
      const auto i = static_cast<Eigen::Index>(r);
      value_[near_ids[r]] =
          scale * near_values[i] - bumps_value(lowered_, points.row(i).transpose(), nullptr);
    });
  }

  const std::array<int, 3>& size() const { return n_; }
  std::size_t count() const { return count_; }
  double step() const { return h_; }
  std::size_t id(int i, int j, int k) const {
    return (static_cast<std::size_t>(k) * n_[1] + j) * n_[0] + i;
  }
  bool inside(const std::array<int, 3>& c) const {
    return c[0] >= 0 && c[1] >= 0 && c[2] >= 0 && c[0] < n_[0] && c[1] < n_[1] && c[2] < n_[2];
  }
  Eigen::Vector3d point(int i, int j, int k) const {
    return box_.min + h_ * Eigen::Vector3d(i, j, k);
  }
  std::array<int, 3> cell_of(const Eigen::Vector3d& x) const {
    const Eigen::Vector3d o = (x - box_.min) / h_;
    return {static_cast<int>(std::lround(o.x())), static_cast<int>(std::lround(o.y())),
            static_cast<int>(std::lround(o.z()))};
  }
  double grid_value(std::size_t q) const { return value_[q]; }

  // s f, less the bumps, at x and its gradient.
  double value_gradient(const Eigen::Vector3d& x, Eigen::Vector3d* g) const {
    const double v = scale_ * f_.value_gradient(x, g);
    *g *= scale_;
    if (lowered_.empty()) return v;
    Eigen::Vector3d down = Eigen::Vector3d::Zero();
    const double b = bumps_value(lowered_, x, &down);
    *g -= down;
    return v - b;
  }
  double value(const Eigen::Vector3d& x) const {
    Eigen::Vector3d g;
    return value_gradient(x, &g);
  }

 private:
  const HermiteRbf& f_;
  double scale_;
  const std::vector<Bump>& lowered_;
  BoundingBox box_;
  double h_;
  std::array<int, 3> n_{};
  std::size_t count_ = 0;
  std::vector<double> value_;
};

struct Saddle {
  Eigen::Vector3d centre;
  double value = 0.0;
  Eigen::Vector3d curvature;  // ascending
  Eigen::Matrix3d axes;       // the curvatures' directions, as columns
};

// The grid points where the central-difference gradient norm of s f is a local minimum below
// 0.8 among the 26 neighbours on their side of the surface, with a value in (0, outside_most)
// (outside) or (-inside_most, 0) (inside).
struct Candidates {
  std::vector<std::array<int, 3>> outside, inside;
};
Candidates candidates(const SearchGrid& grid, double outside_most, double inside_most) {
  const auto& n = grid.size();
  const double h = grid.step();
  std::vector<double> slope(grid.count(), kUnknown);
  const auto at = [&](int i, int j, int k) { return grid.grid_value(grid.id(i, j, k)); };
  for (int k = 1; k + 1 < n[2]; ++k)
    for (int j = 1; j + 1 < n[1]; ++j)
      for (int i = 1; i + 1 < n[0]; ++i) {
        const Eigen::Vector3d d(at(i + 1, j, k) - at(i - 1, j, k),
                                at(i, j + 1, k) - at(i, j - 1, k),
                                at(i, j, k + 1) - at(i, j, k - 1));
        if (d.allFinite()) slope[grid.id(i, j, k)] = d.norm() / (2.0 * h);
      }
  const auto inner = [&](int i, int j, int k) {
    return i > 0 && j > 0 && k > 0 && i + 1 < n[0] && j + 1 < n[1] && k + 1 < n[2];
  };
  Candidates out;
  for (int k = 1; k + 1 < n[2]; ++k)
    for (int j = 1; j + 1 < n[1]; ++j)
      for (int i = 1; i + 1 < n[0]; ++i) {
        const int side = at(i, j, k) > 0.0 ? 1 : -1;
        const double v = side * at(i, j, k), g = slope[grid.id(i, j, k)];
        if (!(v > 0.0 && v < (side > 0 ? outside_most : inside_most) && g < 0.8)) continue;
        bool minimum = true;
        for (int c = -1; c <= 1 && minimum; ++c)
          for (int b = -1; b <= 1 && minimum; ++b)
            for (int a = -1; a <= 1 && minimum; ++a)
              if ((a || b || c) && inner(i + a, j + b, k + c) &&
                  side * at(i + a, j + b, k + c) > 0.0)
                minimum = !(slope[grid.id(i + a, j + b, k + c)] < g);
        if (minimum) (side > 0 ? out.outside : out.inside).push_back({i, j, k});
      }
  return out;
}

// Newton's method from `start` to a critical point of s f within 5 h of it (finite-difference
// Hessian of the analytic gradient); false when it does not converge there.
bool newton(const SearchGrid& grid, const Eigen::Vector3d& start, Saddle& out) {
  const double h = grid.step();
  Eigen::Vector3d x = start, grad;
  Eigen::Matrix3d hessian;
  bool converged = false;
  for (int step = 0; step < 20 && !converged; ++step) {
    constexpr double kDelta = 1e-5;
    for (int a = 0; a < 3; ++a) {
      Eigen::Vector3d plus, minus;
      grid.value_gradient(x + kDelta * Eigen::Vector3d::Unit(a), &plus);
      grid.value_gradient(x - kDelta * Eigen::Vector3d::Unit(a), &minus);
      hessian.col(a) = (plus - minus) / (2.0 * kDelta);
    }
    hessian = (0.5 * (hessian + hessian.transpose())).eval();
    grid.value_gradient(x, &grad);
    converged = grad.norm() < 1e-6;
    Eigen::Vector3d move = -hessian.fullPivLu().solve(grad);
    if (!move.allFinite()) break;
    if (move.norm() > h) move *= h / move.norm();
    if (!converged) x += move;
  }
  if (!converged || (x - start).norm() > 5.0 * h) return false;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(hessian);
  out.centre = x;
  out.value = grid.value(x);
  out.curvature = eig.eigenvalues();
  out.axes = eig.eigenvectors();
  return true;
}

// True when s f grows along `axis` from x, at distances t = across / 2, across and twice that
// on either side, to at least 0.3 t above `base`: a window through a wall opens onto space on
// both sides (s f about the distance to its rim, t or more), where in the gap between two faces
// (two boxes side by side, the axis along the gap) s f stays about the gap's half-width. `base`
// is 0, or the value of a window saddle just inside the surface: the polygonisation opens it as
// if it were at zero, and the space beside it is that much nearer the surface.
bool open_across(const SearchGrid& grid, const Eigen::Vector3d& x, const Eigen::Vector3d& axis,
                 double across, double base = 0.0) {
  for (const double t : {0.5 * across, across, 2.0 * across})
    if (!(grid.value(x + t * axis) - base > 0.3 * t && grid.value(x - t * axis) - base > 0.3 * t))
      return false;
  return true;
}

// The window's own bump: the hole's radius in each plane direction is sqrt(2 value / |curvature|)
// (the saddle as a quadric; for a saddle just inside, value + aliased: where the polygonisation
// can open it); the bump covers twice that (at most 5 h), `across` across, and lowers s f by
// value + across / 4 at the centre.
Bump window_bump(const Saddle& s, double h, double across, double aliased) {
  Bump b;
  b.centre = s.centre;
  b.axes = s.axes;
  const double open = s.value > 0.0 ? s.value : s.value + aliased;
  for (int a = 0; a < 2; ++a)
    b.radii[a] = std::min(5.0 * h, 2.0 * std::sqrt(2.0 * open / -s.curvature[a]));
  b.radii[2] = across;
  b.depth = s.value + across / 4.0;
  return b;
}

// The window's open region, flooded over the grid from its saddle: each grid point moved to the
// minimum of s f along the saddle's across axis within one step, kept when that minimum is in
// (least, most), rises on both sides, opens onto space across (open_across, from the minimum
// when it is below zero), lies within `reach` of the saddle and within across / 2 of its plane
// (a flat wall; past that, the flood would crawl along any surface that runs parallel to the axis
// a little way off, a box's edges). Each gets a bump with radius 2 h in the wall's plane that
// lowers s f to zero at `half` either side of the mid-surface (the membrane's faces). `least` is
// 0, or below it for a saddle just inside the surface: the wall's inside layer thinner than the
// polygonisation's cells runs on round it and opens there as well. `taken` marks the grid cells
// that already hold a bump.
void flood_window(const SearchGrid& grid, const Saddle& s, const SaddleSearch& search,
                  double least, double most, std::vector<char>& taken, std::vector<Bump>& out) {
  const double h = grid.step(), half = 0.35 * search.across;
  const Eigen::Vector3d axis = s.axes.col(2);
  std::vector<char> seen(grid.count(), 0);
  std::vector<std::array<int, 3>> stack{grid.cell_of(s.centre)};
  int added = 0;
  while (!stack.empty() && added < search.window_points) {
    const std::array<int, 3> c = stack.back();
    stack.pop_back();
    if (!grid.inside(c) || seen[grid.id(c[0], c[1], c[2])]) continue;
    seen[grid.id(c[0], c[1], c[2])] = 1;
    const Eigen::Vector3d p = grid.point(c[0], c[1], c[2]);
    double best = kUnknown;
    Eigen::Vector3d at = p;
    for (int k = -4; k <= 4; ++k) {
      const Eigen::Vector3d y = p + (k * h / 4.0) * axis;
      const double v = grid.value(y);
      if (v < best) best = v, at = y;
    }
    const Eigen::Vector3d from = at - s.centre;
    if (!(best > least && best < most) || from.norm() > search.window_reach ||
        std::abs(from.dot(axis)) > 0.5 * search.across ||
        !(grid.value(at + (h / 4.0) * axis) > best && grid.value(at - (h / 4.0) * axis) > best) ||
        !open_across(grid, at, axis, search.across, std::min(best, 0.0)))
      continue;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if (dx || dy || dz) stack.push_back({c[0] + dx, c[1] + dy, c[2] + dz});
    const std::array<int, 3> home = grid.cell_of(at);
    if (!grid.inside(home) || taken[grid.id(home[0], home[1], home[2])]) continue;
    taken[grid.id(home[0], home[1], home[2])] = 1;
    Bump b;
    b.centre = at;
    b.axes = s.axes;
    b.radii = Eigen::Vector3d(2.0 * h, 2.0 * h, 2.0 * half);
    b.depth =
        std::max({grid.value(at + half * axis), grid.value(at - half * axis), best}) / kHalfway;
    out.push_back(b);
    ++added;
  }
}

// The strokes within `reach` of `centre`, seen along `axes`' third column (an opening's axis) and
// split into 12 equal sectors round it.
struct AroundSaddle {
  bool winds = false;  ///< one stroke turns at least kDepictedTurn round the axis
  int sectors = 0;     ///< sectors that hold a stroke
  int along = 0;       ///< sectors that hold a stroke running within 45 degrees of the axis
};

constexpr double kDepictedTurn = 3.5;

AroundSaddle strokes_around(const Eigen::Vector3d& centre, const Eigen::Matrix3d& axes,
                            const Sketch& unit, double reach) {
  const Eigen::Vector3d axis = axes.col(2), u = axes.col(0), v = axes.col(1);
  const auto angle_of = [&](const Eigen::Vector3d& d) { return portable::atan2(d.dot(v), d.dot(u)); };
  const auto sector_of = [&](const Eigen::Vector3d& d) {
    return std::min(11, static_cast<int>((angle_of(d) + M_PI) / (2.0 * M_PI) * 12.0));
  };
  std::array<char, 12> any{}, along{};
  AroundSaddle out;
  for (const Stroke& stroke : unit.strokes) {
    if (stroke.ignored) continue;
    double turn = 0.0;  // along the current stretch of the stroke within reach
    for (std::size_t i = 1; i < stroke.points.size(); ++i) {
      const Eigen::Vector3d a = stroke.points[i - 1] - centre, b = stroke.points[i] - centre;
      if (a.norm() > reach || b.norm() > reach) {
        turn = 0.0;
        continue;
      }
      turn += std::remainder(angle_of(b) - angle_of(a), 2.0 * M_PI);
      out.winds = out.winds || std::abs(turn) >= kDepictedTurn;
      const Eigen::Vector3d t = b - a;
      const int sector = sector_of(0.5 * (a + b));
      any[sector] = 1;
      if (std::abs(t.dot(axis)) > std::sqrt(0.5) * t.norm()) along[sector] = 1;
    }
  }
  out.sectors = static_cast<int>(std::count(any.begin(), any.end(), 1));
  out.along = static_cast<int>(std::count(along.begin(), along.end(), 1));
  return out;
}

// A wider window-shaped saddle is a window to close when, within twice the distance from it to
// the nearest stroke:
// - the strokes stand round it (in at least kSurrounded of the 12 sectors): a window through a
//   wall lies in a cell of the wall's strokes, where a hole in a web that VIPSS stretched between
//   two parts (a chair's legs) has open space on a side;
// - the nearest stroke lies within kSpanned times its value (the hole's radius): the hole spans
//   the gap between the strokes (windows through double walls 1.5-2.1), not a small hole in a web
//   far from every stroke (a chair back's frame);
// - and they do not depict an opening: no stroke winds kDepictedTurn round the opening's axis (a
//   hole's drawn rim, a handle's C, a torus's inner circle), and the strokes that run along the
//   axis stand in fewer than kWallSectors sectors (a bore drawn by its wall's lines, its rims left
//   out, stands all round it). The strokes that frame a window lie in the wall, passing by it.
constexpr int kSurrounded = 8;
constexpr double kSpanned = 2.5;
constexpr int kWallSectors = 7;

bool undrawn_window(const Saddle& s, const Sketch& unit, const PointGrid& strokes) {
  const double nearest = std::sqrt(strokes.nearest(s.centre).second);
  if (nearest > kSpanned * s.value) return false;
  const AroundSaddle around = strokes_around(s.centre, s.axes, unit, 2.0 * nearest);
  return around.sectors >= kSurrounded && !around.winds && around.along < kWallSectors;
}

// Where the strokes cross the plane through the saddle normal to its negative curvature (a gap's
// or a neck's mid-plane).
std::vector<Eigen::Vector3d> mid_plane_crossings(const Saddle& s, const Sketch& unit) {
  const Eigen::Vector3d axis = s.axes.col(0);
  std::vector<Eigen::Vector3d> out;
  for (const Stroke& stroke : unit.strokes) {
    if (stroke.ignored) continue;
    for (std::size_t i = 1; i < stroke.points.size(); ++i) {
      const Eigen::Vector3d& a = stroke.points[i - 1];
      const Eigen::Vector3d& b = stroke.points[i];
      const double ta = (a - s.centre).dot(axis), tb = (b - s.centre).dot(axis);
      if (ta * tb > 0.0 || ta == tb) continue;
      out.push_back(a + (ta / (ta - tb)) * (b - a));
    }
  }
  return out;
}

// The bridge over a gap saddle when strokes cross the gap's mid-plane (through the saddle, normal
// to its negative curvature) within 2.5 h of it at least h / 2 outside the surface: a ball twice
// as wide as the farthest such crossing that lowers s f there below zero. False when none crosses.
bool bridge(const SearchGrid& grid, const Saddle& s, const Sketch& unit, Bump& out) {
  const double h = grid.step(), reach = 2.5 * h;
  double farthest = 0.0, miss = 0.0;
  for (const Eigen::Vector3d& crossing : mid_plane_crossings(s, unit)) {
    const double r = (crossing - s.centre).norm();
    if (r > reach) continue;
    const double value = grid.value(crossing);
    if (value < 0.5 * h) continue;
    farthest = std::max(farthest, r);
    miss = std::max(miss, value);
  }
  if (!(miss > 0.0)) return false;
  const double radius = 2.0 * std::max(farthest, h);
  out.centre = s.centre;
  out.axes = s.axes;
  out.radii = Eigen::Vector3d::Constant(radius);
  out.depth = (miss + h / 4.0) / kHalfway;
  return true;
}

// The cut through a neck saddle (inside the surface, along the neck's axis a maximum of s f)
// when no stroke crosses the neck's mid-plane (through the saddle, normal to its negative
// curvature) within twice the neck's radius or 2 h of the saddle (a stem that VIPSS pinched
// thinner than its strokes is still crossed by them): no stroke depicts the connection, as where
// two parts drawn apart merge, their strokes parallel to the gap. The cut is a disc h thick across
// the neck, twice the neck's radius in each direction (at most 5 h), that raises s f there above
// zero.
bool neck_cut(const Saddle& s, double h, const Sketch& unit, Bump& out) {
  Eigen::Vector3d radii(h, 0.0, 0.0);
  for (int a = 1; a < 3; ++a)
    radii[a] = std::min(5.0 * h, 2.0 * std::sqrt(-2.0 * s.value / s.curvature[a]));
  const double reach = std::max({radii[1], radii[2], 2.0 * h});
  for (const Eigen::Vector3d& crossing : mid_plane_crossings(s, unit))
    if ((crossing - s.centre).norm() <= reach) return false;
  out.centre = s.centre;
  out.axes = s.axes;
  out.radii = radii;
  out.depth = -(-s.value + h / 4.0) / kHalfway;
  return true;
}

}  // namespace

bool opening_drawn(const Eigen::Vector3d& centre, const Eigen::Vector3d& axis, double reach,
                   const Sketch& unit) {
  Eigen::Matrix3d axes;
  axes.col(2) = axis.normalized();
  axes.col(0) = axes.col(2).unitOrthogonal();
  axes.col(1) = axes.col(2).cross(axes.col(0));
  const AroundSaddle around = strokes_around(centre, axes, unit, reach);
  return around.winds || around.along >= kWallSectors;
}

Saddles find_saddles(const HermiteRbf& f, double scale, const std::vector<Bump>& lowered,
                     const Sketch& unit, const PointGrid& strokes, const BoundingBox& box,
                     const SaddleSearch& search, unsigned threads) {
  Saddles found;
  const double most = std::max({search.window_most, search.window_undrawn_most, search.bridge_most});
  if (!(most > 0.0) && !(search.neck_most > 0.0)) return found;
  const SearchGrid grid(f, scale, lowered, strokes, box, search, threads);
  const double h = grid.step();
  std::vector<char> taken(grid.count(), 0);
  std::vector<Eigen::Vector3d> seen;
  // False when a saddle already taken lies within h of x; else x is taken.
  const auto take = [&](const Eigen::Vector3d& x) {
    if (std::any_of(seen.begin(), seen.end(),
                    [&](const Eigen::Vector3d& y) { return (y - x).norm() < h; }))
      return false;
    seen.push_back(x);
    return true;
  };
  const Candidates found_at = candidates(grid, most, search.neck_most);
  for (const std::array<int, 3>& c : found_at.outside) {
    Saddle s;
    if (!newton(grid, grid.point(c[0], c[1], c[2]), s) || !(s.value > -search.window_aliased))
      continue;
    const bool narrow = search.window_most > 0.0 && s.value < search.window_most;
    const bool wider = !narrow && s.value < search.window_undrawn_most;
    const bool curved = s.curvature[1] < 0.0 && s.curvature[2] > 0.0;
    const bool open = curved && (narrow || wider) &&
                      open_across(grid, s.centre, s.axes.col(2), search.across, std::min(s.value, 0.0));
    const bool window = open && narrow;
    const bool undrawn = open && wider && undrawn_window(s, unit, strokes);
    const bool tight = curved && !open && narrow && s.value > 0.0 &&
                       !opening_drawn(s.centre, s.axes.col(2),
                                      2.0 * std::sqrt(strokes.nearest(s.centre).second), unit);
    const bool gap = s.value > 0.0 && s.value < search.bridge_most && s.curvature[0] < 0.0 &&
                     s.curvature[1] > 0.0;
    if (!window && !undrawn && !gap && !tight) continue;
    if (!take(s.centre)) continue;
    if (tight) {
      found.tight.push_back(window_bump(s, h, 0.5 * search.across, search.window_aliased));
    } else if (window || undrawn) {
      std::vector<Bump>& out = window ? found.windows : found.undrawn;
      out.push_back(window_bump(s, h, search.across, search.window_aliased));
      std::vector<Bump>& region = s.value > 0.0 ? out : found.thin;
      const std::size_t first = region.size();
      flood_window(grid, s, search, s.value > 0.0 ? 0.0 : -search.window_aliased,
                   window ? search.window_most : s.value + 0.25 * h, taken, region);
      for (std::size_t i = first; i < region.size(); ++i)
        seen.push_back(region[i].centre);  // a saddle in a flooded region is that window's
    } else {
      Bump b;
      if (bridge(grid, s, unit, b)) found.bridges.push_back(b);
    }
  }
  for (const std::array<int, 3>& c : found_at.inside) {
    Saddle s;
    if (!newton(grid, grid.point(c[0], c[1], c[2]), s) ||
        !(s.value < 0.0 && s.value > -search.neck_most && s.curvature[0] < 0.0 &&
          s.curvature[1] > 0.0) ||
        !take(s.centre))
      continue;
    Bump b;
    if (neck_cut(s, h, unit, b)) found.necks.push_back(b);
  }
  return found;
}

}  // namespace sketchsurf
