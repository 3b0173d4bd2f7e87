#include "surfacing/proxy/proxy.h"

#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>

#include <Eigen/Eigenvalues>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <algorithm>
#include <array>
#include <numeric>
#include <optional>
#include <sstream>
#include <vector>

#include "surfacing/closest_face.h"
#include "surfacing/error.h"
#include "surfacing/flat_key_map.h"
#include "surfacing/parallel.h"
#include "surfacing/portable_math.h"
#include "surfacing/proxy/attract.h"
#include "surfacing/proxy/face_holes.h"
#include "surfacing/proxy/loft.h"
#include "surfacing/proxy/misfit.h"
#include "surfacing/proxy/part_normals.h"
#include "surfacing/proxy/point_grid.h"
#include "surfacing/proxy/polygonize.h"
#include "surfacing/proxy/remesh.h"
#include "surfacing/proxy/saddles.h"
#include "surfacing/proxy/sampling.h"
#include "surfacing/sketch/crossings.h"
#include "surfacing/sketch/io/sketch_io.h"

namespace sketchsurf {

namespace {

using Clock = std::chrono::steady_clock;
// The most area a neck cut may lose (the neck's own surface; more: it cut off a part).
constexpr double kNeckLoss = 0.03;
// The most times windows are searched again round the membranes already placed.
constexpr int kWindowRounds = 2;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The unit-diagonal frame of the strokes that are not ignored: x_unit = (x - centre) * scale.
struct Frame {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double scale = 1.0;
};

Frame stroke_frame(const Sketch& sketch) {
  BoundingBox box;
  for (const auto& s : sketch.strokes)
    if (!s.ignored)
      for (const auto& p : s.points)
        if (p.allFinite()) box.extend(p);
  if (box.empty() || !(box.diagonal() > 0.0))
    throw Error::processing("the sketch has no strokes to build a proxy from (all empty, ignored "
                            "or at a single point)");
  return {0.5 * (box.min + box.max), 1.0 / box.diagonal()};
}

// The strokes that are not ignored, geometry only, in the unit frame; non-finite points dropped.
Sketch unit_strokes(const Sketch& sketch, const Frame& frame) {
  Sketch out;
  for (const auto& s : sketch.strokes) {
    if (s.ignored) continue;
    Stroke t;
    for (const auto& p : s.points)
      if (p.allFinite()) t.points.push_back((p - frame.centre) * frame.scale);
    if (!t.points.empty()) out.strokes.push_back(std::move(t));
  }
  return out;
}

// Into the unit frame. Normals are left stale: remeshing and attraction recompute what they use
// and finish() sets them (each update_normals() of the 82k-vertex 01-0-1 proxy costs ~25 ms).
void to_unit_frame(TriMesh& mesh, const Frame& frame) {
  for (const auto v : mesh.vertices())
    mesh.set_point(v, to_openmesh((to_eigen(mesh.point(v)) - frame.centre) * frame.scale));
}

// Refuses samples that cannot enclose a volume: too few, or (nearly) on a plane or a line.
void check_encloses(const Eigen::MatrixX3d& x) {
  if (x.rows() < 10)
    throw Error::processing("the strokes are too short to build a proxy surface (" +
                            std::to_string(x.rows()) + " distinct sample points, need 10)");
  const Eigen::MatrixX3d c = x.rowwise() - x.colwise().mean();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(c.transpose() * c / x.rows());
  const double thickness = std::sqrt(std::max(0.0, eig.eigenvalues()[0]));
  if (thickness < 0.005)
    throw Error::processing(
        "the strokes lie in a plane (or on a line): they do not enclose a surface, so no proxy "
        "can be built automatically; draw strokes around the shape or give a proxy mesh");
}

// The smoothing weights to try, in order: the given one, or the ladder from lambda_min. Each
// larger weight lets the zero set pass farther from the samples and bends it less: an
// interpolating VIPSS surface through sparse, noisy strokes folds between them and runs out as
// sheets to the box (real sketches: genus 12-50), while too smooth a surface shrinks away from
// thin parts, hence the smallest weight whose zero set closes within the strokes' extent.
std::vector<double> lambda_ladder(const ProxyOptions& options) {
  if (options.lambda >= 0.0) return {options.lambda};
  std::vector<double> out;
  for (double l = options.lambda_min;; l *= options.lambda_step) {
    if (l >= options.lambda_max * (1.0 - 1e-9)) {
      out.push_back(options.lambda_max);
      return out;
    }
    out.push_back(l);
  }
}

void fill_topology(const TriMesh& mesh, ProxyReport& report) {
  report.vertices = mesh.n_vertices();
  report.faces = mesh.n_faces();
  report.topology = mesh_topology(mesh);
}

// Stroke points every half edge length (unit frame): the Least-Squares Mesh targets.
Eigen::MatrixX3d stroke_targets(const Sketch& unit, double edge, std::vector<int>* stroke_of = nullptr) {
  std::vector<Eigen::Vector3d> points;
  for (std::size_t k = 0; k < unit.strokes.size(); ++k) {
    const Stroke& s = unit.strokes[k];
    const Stroke dense = s.points.size() > 1 ? resample(s, 0.5 * edge) : s;
    points.insert(points.end(), dense.points.begin(), dense.points.end());
    if (stroke_of) stroke_of->resize(points.size(), static_cast<int>(k));
  }
  Eigen::MatrixX3d targets(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i)
    targets.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  return targets;
}

// The sketch's outline: stroke points whose nearby strokes lie on one side of them, each with the
// half-space (x - p).n <= gap the surface keeps to (n: away from those strokes). The direction is
// minus the mean direction (weighted by (1 - (r/reach)^2)^2) from the point to the strokes within
// `outline_reach` (those closer than two cells left out); its length says how one-sided the
// strokes around the point are (0: all round, 1: all on one side). The gap is outline_gap where
// that length is above outline_to, growing smoothly to no limit at outline_from.
struct Outline {
  Outline() = default;
  Outline(const Outline&) = delete;  // `grid` refers to `points`
  Outline& operator=(const Outline&) = delete;

  Eigen::MatrixX3d points, normals;
  Eigen::VectorXd gaps;
  std::unique_ptr<PointGrid> grid;
  double blend = 0.0;

  // The blended half-space distance at x: the mean of (x - p).n - gap over the outline points,
  // weighted by exp(-(|x - p|^2 - d0^2) / blend^2) (d0: the nearest one's distance), so that the
  // cut is smooth across the points' Voronoi cells. -inf when there is no outline.
  double value(const Eigen::Vector3d& x, Eigen::Vector3d* normal) const {
    if (!grid) return -std::numeric_limits<double>::infinity();
    const double d0 = grid->nearest(x).second;
    double sum = 0.0, weight = 0.0;
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    grid->for_each_within(x, std::sqrt(d0 + 9.0 * blend * blend), [&](int j, double d2) {
      const double w = portable::exp(-(d2 - d0) / (blend * blend));
      sum += w * ((x - points.row(j).transpose()).dot(normals.row(j).transpose()) - gaps[j]);
      n += w * normals.row(j).transpose();
      weight += w;
    });
    if (normal) *normal = n.normalized();
    return sum / weight;
  }
};

// Fills `out` (empty when outline_gap is 0 or no point is on the outline).
void find_outline(const Sketch& unit, const ProxyOptions& options, Outline& out) {
  if (!(options.outline_gap > 0.0)) return;
  const Eigen::MatrixX3d coarse = stroke_targets(unit, 4.0 * options.cell);  // every 2 cells
  const double reach = options.outline_reach, skip = 2.0 * options.cell;
  Eigen::MatrixX3d mean = Eigen::MatrixX3d::Zero(coarse.rows(), 3);
  parallel_for(0, static_cast<std::size_t>(coarse.rows()), options.threads, [&](std::size_t k) {
    const auto i = static_cast<Eigen::Index>(k);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    double weight = 0.0;
    for (Eigen::Index j = 0; j < coarse.rows(); ++j) {
      const Eigen::Vector3d d = (coarse.row(j) - coarse.row(i)).transpose();
      const double r2 = d.squaredNorm();
      if (r2 > reach * reach || r2 < skip * skip) continue;
      const double u = 1.0 - r2 / (reach * reach), w = u * u;
      sum += w * d / std::sqrt(r2);
      weight += w;
    }
    if (weight > 0.0) mean.row(i) = (sum / weight).transpose();
  });
  std::vector<Eigen::Index> kept;
  for (Eigen::Index i = 0; i < coarse.rows(); ++i)
    if (mean.row(i).norm() > options.outline_from) kept.push_back(i);
  if (kept.empty()) return;
  const auto n = static_cast<Eigen::Index>(kept.size());
  out.points.resize(n, 3);
  out.normals.resize(n, 3);
  out.gaps.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Vector3d m = mean.row(kept[static_cast<std::size_t>(k)]).transpose();
    const double length = m.norm();
    const double t = std::min(1.0, (length - options.outline_from) / (options.outline_to - options.outline_from));
    out.points.row(k) = coarse.row(kept[static_cast<std::size_t>(k)]);
    out.normals.row(k) = (-m / length).transpose();
    out.gaps[k] = options.outline_gap / std::max(t * t * (3.0 - 2.0 * t), 0.05);
  }
  out.grid = std::make_unique<PointGrid>(out.points);
  out.blend = options.outline_blend;
}

// The surface the automatic proxy follows: VIPSS's zero set inside the strokes' neighbourhood,
// g(x) = max(s f(x), d(x) - radius), with s = sign / G making f positive outside (at the box
// corners) and a distance to first order near the samples (G: the median |grad f| there), and d
// the distance to the nearest stroke point. Inside VIPSS's surface and within `radius` of a
// stroke is inside; so where the zero set leaves the strokes (a sheet running to the box, a fin)
// it is cut at `radius` and closed by the strokes' offset surface; where it stays near the
// strokes, it is VIPSS's. The offset surface itself stops at `within` (the strokes' box, grown a
// little): a cap never reaches past the strokes' extent. radius = 0: f alone. Windows to close
// and gaps to bridge (saddles.h) lower s f by their bumps.
class ConfinedField {
 public:
  ConfinedField(const HermiteRbf& f, double scale, const Eigen::MatrixX3d& strokes,
                const PointGrid& grid, double radius, const BoundingBox& within, double band)
      : f_(f), scale_(scale), strokes_(strokes), grid_(grid), radius_(radius), within_(within),
        band_(band) {}

  double scale() const { return scale_; }
  void set_bumps(std::vector<Bump> bumps) { bumps_ = std::move(bumps); }
  const std::vector<Bump>& bumps() const { return bumps_; }
  void set_outline(const Outline* outline) { outline_ = outline; }
  void set_radius(double radius) { radius_ = radius; }
  void set_within(const BoundingBox& within) { within_ = within; }
  void set_planes(std::vector<Plane> planes) { planes_ = std::move(planes); }

  // g at p and the Newton step that moves p onto g = 0 to first order (value_from() gives g
  // alone).
  double value(const Eigen::Vector3d& p, Eigen::Vector3d* to_surface) const {
    to_surface->setZero();
    Eigen::Vector3d away = Eigen::Vector3d::Zero();
    const double c = cap(p, &away);
    if (c == kFar) return band_;
    Eigen::Vector3d g;
    const double value = f_.value_gradient(p, &g);
    Eigen::Vector3d down = Eigen::Vector3d::Zero();
    const double own = scale_ * value - (bumps_.empty() ? 0.0 : bumps_value(bumps_, p, &down));
    if (c > own) {
      *to_surface = -c * away;
      return c;
    }
    if (!bumps_.empty()) g = scale_ * g - down;  // the gradient of own, not of f
    const double g2 = g.squaredNorm();
    const double over = bumps_.empty() ? value : own;
    *to_surface = g2 > 0.0 ? Eigen::Vector3d(-over / g2 * g) : Eigen::Vector3d::Zero();
    return own;
  }

  // The strokes' part of g at p: the largest of the offset surface's, the outline's and the box
  // slabs' signed distances (-inf with no radius), or kFar beyond radius + band of every stroke.
  // `away`, if given, is that distance's gradient.
  double cap(const Eigen::Vector3d& p, Eigen::Vector3d* away) const {
    if (!(radius_ > 0.0)) return -std::numeric_limits<double>::infinity();
    const auto [i, d2] = grid_.nearest(p, radius_ + band_);
    if (i < 0) return kFar;
    const double d = std::sqrt(d2);
    double c = d - radius_;
    if (away && d > 0.0) *away = (p - strokes_.row(i).transpose()) / d;
    if (outline_) {  // beyond the outline's half-spaces
      Eigen::Vector3d n = Eigen::Vector3d::Zero();
      const double beyond = outline_->value(p, away ? &n : nullptr);
      if (beyond > c) {
        c = beyond;
        if (away) *away = n;
      }
    }
    for (int a = 0; a < 3; ++a)  // the box's slabs: signed distance outside each face
      for (const double side : {-1.0, 1.0}) {
        const double wall = side * (p[a] - (side > 0 ? within_.max[a] : within_.min[a]));
        if (wall > c) {
          c = wall;
          if (away) *away = side * Eigen::Vector3d::Unit(a);
        }
      }
    for (const Plane& plane : planes_) {  // slanted faces: signed distance outside each
      const double wall = plane.signed_distance(p);
      if (wall > c) {
        c = wall;
        if (away) *away = plane.normal;
      }
    }
    return c;
  }
  // True when g at a point whose cap is `c` does not depend on f: outside whatever f says.
  bool outside(double c) const { return c > band_; }
  // g at p from its cap `c` and s f there (`sf`, unused when outside(c)).
  double value_from(const Eigen::Vector3d& p, double c, double sf) const {
    if (c == kFar) return band_;
    if (outside(c)) return c;
    return std::max(c, sf - bumps_value(bumps_, p, nullptr));
  }
  // s f at p.
  double scaled(const Eigen::Vector3d& p) const { return scale_ * f_.value(p); }

  static constexpr double kFar = std::numeric_limits<double>::infinity();

 private:
  const HermiteRbf& f_;
  double scale_;
  const Eigen::MatrixX3d& strokes_;
  const PointGrid& grid_;  // over strokes_
  double radius_;
  BoundingBox within_;
  std::vector<Plane> planes_;
  double band_;
  const Outline* outline_ = nullptr;
  std::vector<Bump> bumps_;
};

// Values of a function at the vertices of one polygonisation grid (origin, spacing h), kept
// between polygonisations on that grid: every solve's confined field has the same strokes' part,
// and one solve's plain, bumped and cut fields the same s f. Only unknown values are computed.
class GridMemo {
 public:
  GridMemo(const Eigen::Vector3d& origin, double h) : origin_(origin), h_(h) {}

  // fn(row of p) for every row of `p` into `out`; fn runs on `threads` threads, only for rows
  // where `wanted` (when given) is true, and only for grid vertices not seen before (and points
  // off the grid's vertices, such as the polygonisation box's corners, which are not kept).
  template <class Fn>
  void values(const Eigen::MatrixX3d& p, const std::vector<char>* wanted, unsigned threads,
              Eigen::VectorXd& out, Fn&& fn) {
    const auto rows = static_cast<std::size_t>(p.rows());
    out.resize(p.rows());
    std::vector<std::uint64_t> keys(rows);
    std::vector<std::size_t> unknown;
    for (std::size_t i = 0; i < rows; ++i) {
      if (wanted && !(*wanted)[i]) continue;
      keys[i] = key(p.row(static_cast<Eigen::Index>(i)).transpose());
      const double* known = keys[i] != kOffGrid ? known_.find(keys[i]) : nullptr;
      if (known)
        out[static_cast<Eigen::Index>(i)] = *known;
      else
        unknown.push_back(i);
    }
    constexpr std::size_t kChunk = 64;
    parallel_for(0, (unknown.size() + kChunk - 1) / kChunk, threads, [&](std::size_t c) {
      for (std::size_t k = c * kChunk; k < std::min(unknown.size(), (c + 1) * kChunk); ++k) {
        const auto i = static_cast<Eigen::Index>(unknown[k]);
        out[i] = fn(Eigen::Vector3d(p.row(i).transpose()));
      }
    });
    for (const std::size_t i : unknown)
      if (keys[i] != kOffGrid) known_.try_emplace(keys[i], out[static_cast<Eigen::Index>(i)]);
  }

 private:
  static constexpr std::uint64_t kOffGrid = FlatKeyMap<double>::kEmpty;

  // The vertex's index triple packed in 21 bits each; kOffGrid for a point off the vertices.
  std::uint64_t key(const Eigen::Vector3d& p) const {
    std::uint64_t k = 0;
    for (int a = 0; a < 3; ++a) {
      const double t = (p[a] - origin_[a]) / h_, i = std::round(t);
      if (!(std::abs(t - i) < 1e-6 && i >= 0.0 && i < 0x1FFFFF)) return kOffGrid;
      k = (k << 21) | static_cast<std::uint64_t>(i);
    }
    return k;
  }

  Eigen::Vector3d origin_;
  double h_;
  FlatKeyMap<double> known_;
};

// The solve's unit normals at its samples `at`, signed to point outside (where s f > 0, `scale` s):
// VIPSS's sign is arbitrary; the one that agrees with s f's gradient at most samples.
Eigen::MatrixX3d outward_normals(const VipssResult& vipss, double scale, const Eigen::MatrixX3d& at) {
  double agree = 0.0;
  for (Eigen::Index i = 0; i < at.rows(); ++i) {
    Eigen::Vector3d g;
    vipss.function.value_gradient(at.row(i).transpose(), &g);
    agree += (scale * g).normalized().dot(vipss.normals.row(i).transpose());
  }
  return (agree >= 0.0 ? 1.0 : -1.0) * vipss.normals;
}

// The rows of `points` whose flag is set.
Eigen::MatrixX3d rows_where(const Eigen::MatrixX3d& points, const std::vector<char>& flags) {
  Eigen::MatrixX3d out(std::count(flags.begin(), flags.end(), 1), 3);
  Eigen::Index row = 0;
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    if (flags[static_cast<std::size_t>(i)]) out.row(row++) = points.row(i);
  return out;
}

// The factor that turns f into a distance to first order near the samples, positive outside:
// the sign f has on most of the faces of `box` (a grid on each; a sheet running out crosses a
// few of these points, or a few corners, so corners alone can outvote the truth) over the median
// gradient norm at the samples.
double distance_scale(const HermiteRbf& f, const Eigen::MatrixX3d& samples, const BoundingBox& box) {
  constexpr int kSide = 9;
  int positive = 0, total = 0;
  for (int axis = 0; axis < 3; ++axis)
    for (const double side : {box.min[axis], box.max[axis]})
      for (int i = 0; i < kSide; ++i)
        for (int j = 0; j < kSide; ++j) {
          const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
          Eigen::Vector3d p;
          p[axis] = side;
          p[a1] = box.min[a1] + (box.max[a1] - box.min[a1]) * i / (kSide - 1);
          p[a2] = box.min[a2] + (box.max[a2] - box.min[a2]) * j / (kSide - 1);
          positive += f.value(p) >= 0.0;
          ++total;
        }
  std::vector<double> norms(static_cast<std::size_t>(samples.rows()));
  for (Eigen::Index i = 0; i < samples.rows(); ++i) {
    Eigen::Vector3d g;
    f.value_gradient(samples.row(i).transpose(), &g);
    norms[static_cast<std::size_t>(i)] = g.norm();
  }
  const auto mid = norms.begin() + static_cast<std::ptrdiff_t>(norms.size() / 2);
  std::nth_element(norms.begin(), mid, norms.end());
  return (2 * positive >= total ? 1.0 : -1.0) / std::max(*mid, 1e-300);
}

// Removes the connected components whose area is below `min_fraction` of the whole: specks of
// VIPSS's inside cut off by the confinement (a bubble between two strokes), not parts of the object.
void drop_specks(TriangleArrays& mesh, double min_fraction) {
  const Eigen::MatrixX3d& V = mesh.V;
  const Eigen::MatrixX3i& F = mesh.F;
  const std::vector<int> part = vertex_components(F, V.rows());
  const auto find = [&](int v) { return part[static_cast<std::size_t>(v)]; };
  std::vector<double> area(part.size(), 0.0);
  double total = 0.0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const double fa = triangle_area(V, F, f);
    area[find(F(f, 0))] += fa;
    total += fa;
  }
  std::vector<Eigen::Index> kept;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    if (area[find(F(f, 0))] >= min_fraction * total) kept.push_back(f);
  if (kept.size() == static_cast<std::size_t>(F.rows())) return;
  Eigen::MatrixX3i G(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t i = 0; i < kept.size(); ++i) G.row(static_cast<Eigen::Index>(i)) = F.row(kept[i]);
  // Unused vertices dropped, the others renumbered in order.
  std::vector<int> index(part.size(), -1);
  int used = 0;
  for (Eigen::Index f = 0; f < G.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (index[G(f, k)] < 0) index[G(f, k)] = 0;
  for (auto& i : index)
    if (i == 0) i = used++;
  Eigen::MatrixX3d W(used, 3);
  for (std::size_t v = 0; v < index.size(); ++v)
    if (index[v] >= 0) W.row(index[v]) = V.row(static_cast<Eigen::Index>(v));
  for (Eigen::Index f = 0; f < G.rows(); ++f)
    for (int k = 0; k < 3; ++k) G(f, k) = index[G(f, k)];
  mesh.V = std::move(W);
  mesh.F = std::move(G);
}

// Components and genus of a closed mesh given as arrays (a polygonisation: closed and manifold,
// so no border loops), as mesh_topology() counts them.
MeshTopology closed_topology(const TriangleArrays& mesh) {
  MeshTopology t;
  const std::vector<int> part = vertex_components(mesh.F, mesh.V.rows());
  // The edges {a, b} (a < b), grouped by a: each distinct b in a's group is one edge.
  const std::size_t n = part.size();
  std::vector<std::size_t> start(n + 1, 0);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) ++start[static_cast<std::size_t>(std::min(mesh.F(f, k), mesh.F(f, (k + 1) % 3))) + 1];
  for (std::size_t i = 0; i < n; ++i) start[i + 1] += start[i];
  std::vector<int> other(start[n]);
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
      other[fill[static_cast<std::size_t>(std::min(a, b))]++] = std::max(a, b);
    }
  // Per component (keyed by its lowest vertex): V, E, F.
  std::vector<long> v(n, 0), e(n, 0), f(n, 0);
  std::vector<char> used(n, 0);
  for (Eigen::Index i = 0; i < mesh.F.rows(); ++i) {
    ++f[static_cast<std::size_t>(part[static_cast<std::size_t>(mesh.F(i, 0))])];
    for (int k = 0; k < 3; ++k) used[static_cast<std::size_t>(mesh.F(i, k))] = 1;
  }
  for (std::size_t a = 0; a < n; ++a) {
    const auto first = other.begin() + static_cast<std::ptrdiff_t>(start[a]);
    const auto last = other.begin() + static_cast<std::ptrdiff_t>(start[a + 1]);
    std::sort(first, last);
    e[static_cast<std::size_t>(part[a])] += std::distance(first, std::unique(first, last));
  }
  for (std::size_t i = 0; i < n; ++i)
    if (used[i]) ++v[static_cast<std::size_t>(part[i])];
  for (std::size_t r = 0; r < n; ++r) {
    if (v[r] == 0) continue;
    ++t.components;
    const long chi = v[r] - e[r] + f[r];
    t.euler += chi;
    t.genus += (2 - chi) / 2;
  }
  return t;
}

// The total area of the triangles (a neck cut that loses more than its neck cut off a part).
double surface_area(const TriangleArrays& mesh) {
  double total = 0.0;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) total += triangle_area(mesh.V, mesh.F, f);
  return total;
}

// Area fraction of `mesh` whose faces' centroids lie farther than `distance` from every point of
// `strokes` (a grid over the stroke points). Faces are tested on `threads` threads and their
// areas summed in order: the same whatever the threads.
double far_fraction(const TriangleArrays& mesh, const PointGrid& strokes, double distance,
                    unsigned threads) {
  const auto faces = static_cast<std::size_t>(mesh.F.rows());
  std::vector<double> area(faces), far(faces, 0.0);
  parallel_for(0, faces, threads, [&](std::size_t k) {
    const auto f = static_cast<Eigen::Index>(k);
    const Eigen::Vector3d centroid =
        (mesh.V.row(mesh.F(f, 0)) + mesh.V.row(mesh.F(f, 1)) + mesh.V.row(mesh.F(f, 2))).transpose() / 3.0;
    area[k] = triangle_area(mesh.V, mesh.F, f);
    if (!strokes.any_within(centroid, distance)) far[k] = area[k];
  });
  double total = 0.0, far_total = 0.0;
  for (std::size_t k = 0; k < faces; ++k) {
    total += area[k];
    far_total += far[k];
  }
  return total > 0.0 ? far_total / total : 0.0;
}

// The fraction of `points` (the strokes, a cell apart) farther than `distance` from every vertex of
// `mesh` (a polygonised zero set: its vertices lie under a cell apart). A stroke lies on the
// surface it depicts; a smoothing that leaves many of them off its surface has melted away thin
// parts (a lamp's neck inside a web from its head to its base, a chair's legs in a block).
double missed_fraction(const TriangleArrays& mesh, const Eigen::MatrixX3d& points, double distance,
                       unsigned threads) {
  if (points.rows() == 0 || mesh.V.rows() == 0) return 1.0;
  const PointGrid vertices(mesh.V);
  std::vector<char> missed(static_cast<std::size_t>(points.rows()), 0);
  parallel_for(0, missed.size(), threads, [&](std::size_t i) {
    missed[i] = !vertices.any_within(points.row(static_cast<Eigen::Index>(i)).transpose(), distance);
  });
  return static_cast<double>(std::count(missed.begin(), missed.end(), 1)) /
         static_cast<double>(points.rows());
}

// How the surface farther than `radius` from every stroke (`strokes`, the stroke points) is held
// by the strokes around it, as fractions of the surface's area: `framed` where, seen in a face's
// tangent plane, the strokes within twice its distance (and within 30 degrees of that plane)
// surround it with no gap of `gap` radians or more (a face between its drawn edges), `open` where
// they leave such a gap or none is near (a web beside a single pole, a fin past the last stroke, a
// wall between two legs). The directions are those of `points` (over `grid`), the strokes sampled
// coarsely: a gap of a third of a turn needs no finer angles, and the faces farther than `radius`
// may see most of the sketch.
struct Framing {
  double framed = 0.0, open = 0.0;
};
Framing surface_framing(const TriangleArrays& mesh, const PointGrid& strokes, const Eigen::MatrixX3d& points,
                        const PointGrid& grid, double radius, double gap, unsigned threads) {
  constexpr double kCone = 0.5;  // sine of the largest angle between a stroke's direction and the plane
  const auto faces = static_cast<std::size_t>(mesh.F.rows());
  std::vector<double> framed(faces, 0.0), open(faces, 0.0), area(faces, 0.0);
  parallel_for(0, faces, threads, [&](std::size_t k) {
    const auto f = static_cast<Eigen::Index>(k);
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)),
                          c = mesh.V.row(mesh.F(f, 2));
    area[k] = triangle_area(mesh.V, mesh.F, f);
    const Eigen::Vector3d x = (a + b + c) / 3.0;
    if (strokes.any_within(x, radius)) return;
    const double d = std::sqrt(strokes.nearest(x).second);
    Eigen::Vector3d n = (b - a).cross(c - a);
    if (!(d > radius) || !(n.norm() > 0.0)) return;
    n.normalize();
    const Eigen::Vector3d u =
        (std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY()).cross(n).normalized();
    const Eigen::Vector3d v = n.cross(u);
    std::vector<double> angles;
    grid.for_each_within(x, 2.0 * d, [&](int i, double) {
      const Eigen::Vector3d e = points.row(i).transpose() - x;
      if (std::abs(n.dot(e)) <= kCone * e.norm()) angles.push_back(portable::atan2(v.dot(e), u.dot(e)));
    });
    double widest = 2.0 * M_PI;
    if (!angles.empty()) {
      std::sort(angles.begin(), angles.end());
      widest = angles.front() + 2.0 * M_PI - angles.back();
      for (std::size_t i = 1; i < angles.size(); ++i) widest = std::max(widest, angles[i] - angles[i - 1]);
    }
    (widest < gap ? framed : open)[k] = area[k];
  });
  Framing out;
  double total = 0.0;
  for (std::size_t k = 0; k < faces; ++k) {  // summed in order: the same whatever the threads
    total += area[k];
    out.framed += framed[k];
    out.open += open[k];
  }
  if (total > 0.0) {
    out.framed /= total;
    out.open /= total;
  }
  return out;
}

// Least-Squares Mesh attraction of `mesh` (unit frame, remeshed at 2^attract_levels times the
// target edge) to `targets`, then Loop subdivision back to the target edge (each level halves
// the edges; smooth, no overshoot at creases).
void attract_and_subdivide(TriMesh& mesh, const Eigen::MatrixX3d& targets,
                           const ProxyOptions& options, const Progress& progress, double scale,
                           ProxyReport& r) {
  const auto t0 = Clock::now();
  AttractOptions attract;
  attract.weight = options.attract_weight;
  attract.rounds = options.attract_rounds;
  attract.threads = options.threads;
  AttractSummary summary;
  attract_to_points(mesh, targets, attract, progress, &summary);
  if (options.attract_levels > 0) {
    OpenMesh::Subdivider::Uniform::LoopT<TriMesh, double> loop;
    loop.attach(mesh);
    loop(static_cast<std::size_t>(options.attract_levels));
    loop.detach();  // normals: set by finish()
    summary.median_after = median_nearest_vertex_distance(mesh, targets, options.threads);
  }
  r.attract_seconds = seconds_since(t0);
  r.anchors = summary.anchors;
  r.median_distance_before = summary.median_before / scale;
  r.median_distance_after = summary.median_after / scale;
}

// Back to the sketch's frame; topology, total time and the report.
TriMesh finish(TriMesh mesh, const Frame& frame, Clock::time_point start, ProxyReport& r,
               ProxyReport* report) {
  const double unscale = 1.0 / frame.scale;
  for (const auto v : mesh.vertices())
    mesh.set_point(v, to_openmesh(to_eigen(mesh.point(v)) * unscale + frame.centre));
  mesh.update_normals();
  fill_topology(mesh, r);
  r.total_seconds = seconds_since(start);
  if (report) *report = r;
  return mesh;
}

// The runs of `points[begin, end)` (one stroke's, in order) whose points all satisfy `inside`:
// visit(i, j, length) for each longest run [i, j), length its polyline length. A face drawn by
// strokes is one they run along, where a curved surface's strokes only cross it.
template <typename Point, typename Inside, typename Visit>
void for_each_run(std::size_t begin, std::size_t end, Point&& point, Inside&& inside, Visit&& visit) {
  for (std::size_t i = begin; i < end;) {
    if (!inside(i)) {
      ++i;
      continue;
    }
    std::size_t j = i + 1;
    double length = 0.0;
    for (; j < end && inside(j); ++j) length += (point(j) - point(j - 1)).norm();
    visit(i, j, length);
    i = j;
  }
}

// The flat runs of `unit`'s strokes near their extreme along `n` (`extreme`, the largest n.p of
// their points): runs of consecutive points whose depth below it is at most `band`, at least
// `run_least` long, whose depth varies by at most `flat`; visit(stroke, i, j) for each run
// stroke.points[i, j). Such runs are strokes drawn along a face there.
template <typename Visit>
void for_each_flat_run(const Sketch& unit, const Eigen::Vector3d& n, double extreme, double band, double run_least,
                       double flat, Visit&& visit) {
  for (const Stroke& stroke : unit.strokes) {
    const auto depth = [&](std::size_t i) { return extreme - n.dot(stroke.points[i]); };
    const auto point = [&](std::size_t i) -> const Eigen::Vector3d& { return stroke.points[i]; };
    const auto inside = [&](std::size_t i) { return depth(i) <= band; };
    for_each_run(0, stroke.points.size(), point, inside, [&](std::size_t i, std::size_t j, double length) {
      if (length < run_least) return;
      double lo = depth(i), hi = lo;
      for (std::size_t q = i + 1; q < j; ++q) {
        lo = std::min(lo, depth(q));
        hi = std::max(hi, depth(q));
      }
      if (hi - lo <= flat) visit(stroke, i, j);
    });
  }
}

// The points of `unit`'s strokes at least `overshoot` (along the stroke) from both of its ends
// (0: every point); a stroke shorter than twice that keeps its middle point.
Eigen::MatrixX3d stroke_bodies(const Sketch& unit, double overshoot) {
  std::vector<Eigen::Vector3d> body;
  for (const Stroke& stroke : unit.strokes) {
    if (stroke.points.empty()) continue;
    std::vector<double> at(stroke.points.size(), 0.0);  // arc length from the first point
    for (std::size_t i = 1; i < at.size(); ++i) at[i] = at[i - 1] + (stroke.points[i] - stroke.points[i - 1]).norm();
    const double length = at.back();
    const std::size_t before = body.size();
    for (std::size_t i = 0; i < at.size(); ++i)
      if (at[i] >= overshoot && length - at[i] >= overshoot) body.push_back(stroke.points[i]);
    if (body.size() == before)
      body.push_back(stroke.points[static_cast<std::size_t>(
          std::lower_bound(at.begin(), at.end(), 0.5 * length) - at.begin())]);
  }
  Eigen::MatrixX3d points(static_cast<Eigen::Index>(body.size()), 3);
  for (std::size_t i = 0; i < body.size(); ++i) points.row(static_cast<Eigen::Index>(i)) = body[i].transpose();
  return points;
}

// Where a face drawn near the strokes' extreme `extreme` lies, from the outermost point of the
// flat runs along it (`runs`, -infinity where no stroke runs along it) and of the strokes'
// `bodies` (stroke_bodies): at the farther of the two; at the extreme where no stroke runs along
// the face (a chair's feet, drawn by the ends of its legs' strokes) or where the two are within a
// quarter of confine_box of it (a hand's tremor). A hand drawing mid-air runs on past the edge
// where a stroke across the face should stop: the face is where the strokes drawn along it are,
// not at those ends, while a curved top keeps the crown its cross-sections reach.
double face_depth(double extreme, double runs, double bodies, const ProxyOptions& options) {
  if (!std::isfinite(runs)) return extreme;
  const double depth = std::max(runs, bodies);
  return extreme - depth >= 0.25 * options.confine_box ? depth : extreme;
}

// face_depth of the side of the strokes' box where the strokes reach `extreme` along `n` (an axis),
// the runs along it at least `run_least` long.
double side_depth(const Sketch& unit, const Eigen::MatrixX3d& bodies, const Eigen::Vector3d& n, double extreme,
                  double run_least, const ProxyOptions& options) {
  double runs = -std::numeric_limits<double>::infinity();
  for_each_flat_run(unit, n, extreme, 2.0 * options.confine_box, run_least, 0.5 * options.confine_box,
                    [&](const Stroke& stroke, std::size_t i, std::size_t j) {
                      for (std::size_t q = i; q < j; ++q) runs = std::max(runs, n.dot(stroke.points[q]));
                    });
  return face_depth(extreme, runs, (bodies * n).maxCoeff(), options);
}

// How long a flat run along a side of `strokes_box` across `axis` is at least: half of
// confine_box_span of the side's narrower direction.
double side_run_least(const BoundingBox& strokes_box, int axis, const ProxyOptions& options) {
  const Eigen::Vector3d width = strokes_box.max - strokes_box.min;
  return 0.5 * options.confine_box_span * std::min(width[(axis + 1) % 3], width[(axis + 2) % 3]);
}

// The sides of the strokes' box (`strokes_box`, of `points`; [axis][0: low, 1: high]) where the
// strokes draw a face: those within confine_box of the side span at least confine_box_span of the
// box along both of its directions (a box's side, a plate's face, a cup's rim and base). Where
// the strokes only touch a side (the top of a dome drawn by a few meridians), a cut closer to
// them would flatten the surface they leave to the smoothing. A face that fills only part of its
// side (the thin end of an L-bracket's arm, a step) is drawn when flat runs of the strokes of
// `unit` (their depth varying by at most half the band) span confine_box_span along one of the side's directions and
// confine_box_partial along the other: a dome's meridians are not flat over the band, its
// parallels near the top are short, and a lying cylinder's top has one flat line only.
std::array<std::array<bool, 2>, 3> drawn_faces(const BoundingBox& strokes_box, const Eigen::MatrixX3d& points,
                                               const Sketch& unit, const ProxyOptions& options) {
  std::array<std::array<bool, 2>, 3> faces{};
  const Eigen::Vector3d width = strokes_box.max - strokes_box.min;
  for (int a = 0; a < 3; ++a)
    for (const bool high : {false, true}) {
      const int u = (a + 1) % 3, v = (a + 2) % 3;
      const auto gap_of = [&](const Eigen::Vector3d& p) {
        return high ? strokes_box.max[a] - p[a] : p[a] - strokes_box.min[a];
      };
      BoundingBox near;
      for (Eigen::Index i = 0; i < points.rows(); ++i)
        if (gap_of(points.row(i).transpose()) <= options.confine_box) near.extend(points.row(i).transpose());
      faces[a][high] = !near.empty() && near.max[u] - near.min[u] >= options.confine_box_span * width[u] &&
                       near.max[v] - near.min[v] >= options.confine_box_span * width[v];
      if (faces[a][high] || !(options.confine_box_partial < options.confine_box_span)) continue;
      // Runs of consecutive points within the band whose depth varies by at most half of it.
      const double run_least = side_run_least(strokes_box, a, options);
      const Eigen::Vector3d n = (high ? 1.0 : -1.0) * Eigen::Vector3d::Unit(a);
      BoundingBox flat;
      for_each_flat_run(unit, n, n.dot(high ? strokes_box.max : strokes_box.min), options.confine_box, run_least,
                        0.5 * options.confine_box, [&](const Stroke& stroke, std::size_t i, std::size_t j) {
                          for (std::size_t q = i; q < j; ++q) flat.extend(stroke.points[q]);
                        });
      if (flat.empty()) continue;
      const double su = (flat.max[u] - flat.min[u]) / width[u], sv = (flat.max[v] - flat.min[v]) / width[v];
      faces[a][high] = std::max(su, sv) >= options.confine_box_span && std::min(su, sv) >= options.confine_box_partial;
    }
  return faces;
}

// The strokes' supporting planes, other than the box's sides, where the strokes draw a face: a
// wedge's slope, a roof's pitch. Searched from directions spread over the sphere: the plane
// farthest along a direction (all points on its inner side), fitted again to the points within
// confine_box of it until it settles. A face when strokes run along it, each over at least half
// of confine_box_span of the points' extent along the plane's longer principal direction, and
// those runs span at least confine_box_span of that extent along both principal directions. A
// smooth shape's supporting plane only touches it: the strokes over a dome or a lobe stay near it
// for a short arc, and the surface between them bulges past it. Planes within a few degrees of an
// axis are the box's sides (drawn_faces). Each face lies at face_depth of its runs and of the
// strokes' `bodies` (stroke_bodies).
std::vector<Plane> drawn_planes(const Sketch& unit, const Eigen::MatrixX3d& bodies, const ProxyOptions& options) {
  constexpr int kDirections = 256, kRefits = 4;
  const double axis_near = portable::cos(5.0 * M_PI / 180.0), same = portable::cos(2.0 * M_PI / 180.0);
  std::vector<Plane> planes;
  std::size_t count = 0;
  for (const Stroke& stroke : unit.strokes) count += stroke.size();
  if (count < 3) return planes;
  Eigen::MatrixX3d points(static_cast<Eigen::Index>(count), 3);
  std::vector<std::size_t> starts;  // each stroke's first row
  for (Eigen::Index i = 0; const Stroke& stroke : unit.strokes) {
    starts.push_back(static_cast<std::size_t>(i));
    for (const Eigen::Vector3d& p : stroke.points) points.row(i++) = p.transpose();
  }
  starts.push_back(count);
  const auto support = [&](const Eigen::Vector3d& n) { return (points * n).maxCoeff(); };
  const auto extent = [](const Eigen::VectorXd& x) { return x.maxCoeff() - x.minCoeff(); };
  for (int k = 0; k < kDirections; ++k) {
    // Fibonacci sphere: evenly spread, the same on every machine.
    const double z = 1.0 - (2.0 * k + 1.0) / kDirections, r = std::sqrt(1.0 - z * z);
    const double phi = k * M_PI * (3.0 - std::sqrt(5.0));
    Plane plane{Eigen::Vector3d(r * portable::cos(phi), r * portable::sin(phi), z), 0.0};
    std::vector<char> in(count, 0);
    Eigen::Vector3d first, second;
    Eigen::Index near = 0;
    for (int refit = 0; refit < kRefits; ++refit) {
      plane.offset = -support(plane.normal);
      const Eigen::VectorXd gap = -plane.offset - (points * plane.normal).array();
      for (std::size_t i = 0; i < count; ++i) in[i] = gap[static_cast<Eigen::Index>(i)] <= options.confine_box;
      near = std::count(in.begin(), in.end(), 1);
      if (near < 3) break;
      Eigen::MatrixX3d band(near, 3);
      for (Eigen::Index i = 0, j = 0; i < points.rows(); ++i)
        if (in[static_cast<std::size_t>(i)]) band.row(j++) = points.row(i);
      const Eigen::RowVector3d mean = band.colwise().mean();
      const Eigen::Matrix3d cov = (band.rowwise() - mean).transpose() * (band.rowwise() - mean);
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
      Eigen::Vector3d n = eig.eigenvectors().col(0);
      if (n.dot(plane.normal) < 0.0) n = -n;
      plane.normal = n;
      second = eig.eigenvectors().col(1);
      first = eig.eigenvectors().col(2);
    }
    if (near < 3 || plane.normal.cwiseAbs().maxCoeff() >= axis_near) continue;
    plane.offset = -support(plane.normal);
    // The runs of consecutive stroke points within the band, the long ones kept.
    const double run_least = 0.5 * options.confine_box_span * extent(points * first);
    std::vector<Eigen::Index> kept;
    const auto row = [&](std::size_t i) { return points.row(static_cast<Eigen::Index>(i)); };
    const auto inside = [&](std::size_t i) { return in[i] != 0; };
    for (std::size_t s = 0; s + 1 < starts.size(); ++s)
      for_each_run(starts[s], starts[s + 1], row, inside, [&](std::size_t i, std::size_t j, double length) {
        if (length >= run_least)
          for (std::size_t q = i; q < j; ++q) kept.push_back(static_cast<Eigen::Index>(q));
      });
    if (kept.size() < 3) continue;
    const Eigen::MatrixX3d runs = points(kept, Eigen::all);
    const auto spans = [&](const Eigen::Vector3d& e) {
      return extent(runs * e) >= options.confine_box_span * extent(points * e);
    };
    if (!spans(first) || !spans(second)) continue;
    // The face lies where its runs do, not at the ends of strokes across it that run on past it.
    plane.offset = -face_depth(-plane.offset, (runs * plane.normal).maxCoeff(), (bodies * plane.normal).maxCoeff(), options);
    const bool known = std::any_of(planes.begin(), planes.end(), [&](const Plane& q) {
      return q.normal.dot(plane.normal) >= same && std::abs(q.offset - plane.offset) <= options.confine_box;
    });
    if (!known) planes.push_back(plane);
  }
  return planes;
}

}  // namespace


bool ProxyOptions::valid(std::string* why) const {
  auto fail = [&](const std::string& msg) {
    if (why) *why = msg;
    return false;
  };
  const auto count_ok = [&](std::size_t count, const std::string& name) {
    if (count < 10) return fail("proxy " + name + " must be at least 10");
    if (count > 20000) return fail("proxy " + name + " above 20000 need too much memory (n^2)");
    return true;
  };
  if (!count_ok(points, "points") || !count_ok(clean_points, "clean_points")) return false;
  if (!std::isfinite(lambda)) return fail("proxy lambda must be finite (< 0: chosen per sketch)");
  if (!(lambda_min > 0.0 && lambda_max >= lambda_min && std::isfinite(lambda_max)))
    return fail("proxy lambda_min and lambda_max must satisfy 0 < lambda_min <= lambda_max");
  if (!(lambda_step > 1.0) || !std::isfinite(lambda_step)) return fail("proxy lambda_step must be > 1");
  if (!(clean_gap >= 0.0 && clean_gap < 1.0)) return fail("proxy clean_gap must be in [0, 1)");
  if (clean_crossings < 1) return fail("proxy clean_crossings must be at least 1");
  if (!(clean_lambda >= 0.0 && clean_lambda < lambda_min))
    return fail("proxy clean_lambda must be in [0, lambda_min)");
  if (!(confine_margin > 0.0 && confine_margin < 1.0))
    return fail("proxy confine_margin must be in (0, 1)");
  if (!(confine_radius >= 0.0 && confine_radius < 1.0))
    return fail("proxy confine_radius must be in [0, 1)");
  if (!(confine_near >= 0.0 && confine_near < 1.0)) return fail("proxy confine_near must be in [0, 1)");
  if (!(near_open_ratio >= 0.0)) return fail("proxy near_open_ratio must be >= 0");
  if (!(part_reach >= 0.0 && part_reach < 1.0)) return fail("proxy part_reach must be in [0, 1)");
  if (part_webs < 1) return fail("proxy part_webs must be at least 1");
  if (!(part_free >= 0.0 && part_free < 1.0)) return fail("proxy part_free must be in [0, 1)");
  if (!(part_far_ratio >= 0.0 && part_far_ratio <= 1.0))
    return fail("proxy part_far_ratio must be in [0, 1]");
  if (!(framed_gap > 0.0 && framed_gap <= 360.0)) return fail("proxy framed_gap must be in (0, 360]");
  if (!(near_open_least >= 0.0 && near_open_least <= 1.0))
    return fail("proxy near_open_least must be in [0, 1]");
  if (!(confine_box >= 0.0 && confine_box < 1.0)) return fail("proxy confine_box must be in [0, 1)");
  if (!(confine_box_tight >= 0.0 && confine_box_tight <= confine_box))
    return fail("proxy confine_box_tight must be in [0, confine_box]");
  if (!(confine_box_span >= 0.0 && confine_box_span <= 1.0))
    return fail("proxy confine_box_span must be in [0, 1]");
  if (!(confine_box_partial >= 0.0 && confine_box_partial <= 1.0))
    return fail("proxy confine_box_partial must be in [0, 1]");
  if (!(overshoot >= 0.0 && overshoot < 1.0)) return fail("proxy overshoot must be in [0, 1)");
  if (!(outline_gap >= 0.0 && outline_gap < 1.0)) return fail("proxy outline_gap must be in [0, 1)");
  if (!(outline_reach > 0.0 && outline_reach < 1.0))
    return fail("proxy outline_reach must be in (0, 1)");
  if (!(outline_from >= 0.0 && outline_to > outline_from && outline_to <= 1.0))
    return fail("proxy outline_from and outline_to must satisfy 0 <= outline_from < outline_to <= 1");
  if (!(outline_blend > 0.0 && outline_blend < 1.0))
    return fail("proxy outline_blend must be in (0, 1)");
  if (!(outline_most >= 0.0 && outline_most <= 1.0)) return fail("proxy outline_most must be in [0, 1]");
  if (!(loft_fit >= 0.0 && loft_fit < 1.0)) return fail("proxy loft_fit must be in [0, 1)");
  if (!(vipss_tolerance > 0.0 && vipss_tolerance < 1.0))
    return fail("proxy vipss_tolerance must be in (0, 1)");
  if (!(edge > 1e-4 && edge < 0.5)) return fail("proxy edge must be in (1e-4, 0.5) of the diagonal");
  if (!(cell > 1e-3 && cell < 0.5)) return fail("proxy cell must be in (1e-3, 0.5) of the diagonal");
  if (!(padding >= 0.0 && padding < 1.0)) return fail("proxy padding must be in [0, 1)");
  if (!(sample_spacing > 0.0 && sample_spacing < 0.1))
    return fail("proxy sample_spacing must be in (0, 0.1)");
  if (remesh_iterations < 0 || vipss_remesh_iterations < 0)
    return fail("proxy remesh_iterations and vipss_remesh_iterations must be >= 0");
  if (!(far_distance > 0.0 && far_distance < 1.0)) return fail("proxy far_distance must be in (0, 1)");
  if (!(far_tie >= 0.0 && far_tie < 1.0)) return fail("proxy far_tie must be in [0, 1)");
  if (far_extra_genus < 0) return fail("proxy far_extra_genus must be >= 0");
  if (!std::isfinite(rounded_misfit)) return fail("proxy rounded_misfit must be finite");
  if (!(rounded_far >= 0.0 && rounded_far < 1.0)) return fail("proxy rounded_far must be in [0, 1)");
  if (!(misfit_reach > 0.0 && misfit_reach < 0.5)) return fail("proxy misfit_reach must be in (0, 0.5)");
  if (!(far_most > 0.0 && far_most <= 1.0)) return fail("proxy far_most must be in (0, 1]");
  if (!(miss_distance > 0.0 && miss_distance < 1.0)) return fail("proxy miss_distance must be in (0, 1)");
  if (!(window_value >= 0.0 && window_value < 0.5))
    return fail("proxy window_value must be in [0, 0.5)");
  if (!(window_undrawn >= 0.0 && window_undrawn < 0.5))
    return fail("proxy window_undrawn must be in [0, 0.5)");
  if (!(face_hole_thickness >= 0.0 && face_hole_thickness <= 0.2))
    return fail("proxy face_hole_thickness must be in [0, 0.2]");
  if (!(window_reach >= 0.0 && window_reach <= 2.0))
    return fail("proxy window_reach must be in [0, 2]");
  if (!(window_points >= 0 && window_points <= 100000))
    return fail("proxy window_points must be in [0, 100000]");
  if (!(bridge_value >= 0.0 && bridge_value < 0.5))
    return fail("proxy bridge_value must be in [0, 0.5)");
  if (!(neck_value >= 0.0 && neck_value < 0.5)) return fail("proxy neck_value must be in [0, 0.5)");
  if (!(min_component >= 0.0 && min_component < 1.0))
    return fail("proxy min_component must be in [0, 1)");
  if (projection_steps < 0) return fail("proxy projection_steps must be >= 0");
  if (!(attract_weight > 0.0)) return fail("proxy attract_weight must be > 0");
  if (attract_rounds < 1) return fail("proxy attract_rounds must be >= 1");
  if (attract_levels < 0 || attract_levels > 3) return fail("proxy attract_levels must be in [0, 3]");
  if (!(max_proxy_distance > 0.0)) return fail("proxy max_proxy_distance must be > 0");
  return true;
}

MeshTopology mesh_topology(const TriMesh& mesh) {
  MeshTopology t;
  const std::size_t nv = mesh.n_vertices();
  std::vector<std::size_t> parent(nv);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](std::size_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  for (const auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    const std::size_t a = find(mesh.from_vertex_handle(h).idx()),
                      b = find(mesh.to_vertex_handle(h).idx());
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
  // Per component (keyed by root): V, E, F, border loops.
  std::vector<long> v(nv, 0), e(nv, 0), f(nv, 0), b(nv, 0);
  for (const auto vh : mesh.vertices()) ++v[find(vh.idx())];
  for (const auto eh : mesh.edges()) ++e[find(mesh.from_vertex_handle(mesh.halfedge_handle(eh, 0)).idx())];
  for (const auto fh : mesh.faces()) ++f[find(fh.halfedge().from().idx())];
  std::vector<bool> seen(mesh.n_halfedges(), false);
  for (const auto h : mesh.halfedges()) {
    if (!mesh.is_boundary(h) || seen[h.idx()]) continue;
    ++t.boundary_loops;
    ++b[find(mesh.from_vertex_handle(h).idx())];
    auto g = h;
    do {
      seen[g.idx()] = true;
      g = mesh.next_halfedge_handle(g);
    } while (g != h && !seen[g.idx()]);
  }
  for (std::size_t r = 0; r < nv; ++r) {
    if (find(r) != r || v[r] == 0) continue;
    ++t.components;
    const long chi = v[r] - e[r] + f[r];
    t.euler += chi;
    t.genus += (2 - chi - b[r]) / 2;
  }
  return t;
}

TriMesh make_proxy(const Sketch& sketch, const ProxyOptions& options, const Progress& progress,
                   ProxyReport* report) {
  std::string why;
  if (!options.valid(&why)) throw Error::usage(why);
  ProxyReport r;
  const auto start = Clock::now();
  const Frame frame = stroke_frame(sketch);
  const Sketch unit = unit_strokes(sketch, frame);

  // Where strokes cross, how far apart they pass: a clean curve network (a modelling tool's or a
  // mesh's curves) lies on the surface, and is sampled more densely and smoothed less. Pairs of
  // strokes closer than kCrossReach (unit frame) are looked at, and those whose directions there
  // are more than kCrossAngle apart (radians) cross: any reach of a few tremor amplitudes will do.
  // Crossings where a stroke turns more than kCrossBend within that reach (a section across a
  // crease) are left out: a polyline cuts the corner there, a network's too.
  constexpr double kCrossReach = 0.02, kCrossAngle = M_PI / 6.0, kCrossBend = M_PI / 9.0;
  r.crossing_gap = crossing_gap(unit, kCrossReach, kCrossAngle,
                                static_cast<std::size_t>(options.clean_crossings), kCrossBend);
  bool clean = r.crossing_gap >= 0.0 && r.crossing_gap < options.clean_gap;

  auto t0 = Clock::now();
  progress.update("sampling strokes", 0.0);
  SamplingOptions sampling;
  sampling.count = options.points;
  sampling.spacing = options.sample_spacing;
  sampling.min_distance = std::min(options.sample_spacing, 0.5 * options.cell);
  const Eigen::MatrixX3d samples = sample_strokes(unit, sampling);
  check_encloses(samples);
  // A clean network's first solve (clean_lambda) on denser samples: nearly interpolating, it
  // follows the strokes between the samples only as closely as they lie.
  const auto sample_densely = [&] {
    sampling.count = std::max(options.clean_points, options.points);
    return sample_strokes(unit, sampling);
  };
  Eigen::MatrixX3d dense;
  if (clean && options.lambda < 0.0) dense = sample_densely();
  progress.update("sampling strokes", 1.0);
  r.sampling_seconds = seconds_since(t0);

  t0 = Clock::now();
  VipssOptions vipss_options;
  vipss_options.box_padding = options.confine_margin;
  vipss_options.function_tolerance = options.vipss_tolerance;
  vipss_options.threads = options.threads;
  const unsigned threads = options.threads;
  BoundingBox box;
  for (Eigen::Index i = 0; i < samples.rows(); ++i) box.extend(samples.row(i).transpose());
  box.min.array() -= options.padding;
  box.max.array() += options.padding;
  const Eigen::MatrixX3d stroke_points = stroke_targets(unit, options.cell);
  std::vector<int> misfit_strokes;
  const Eigen::MatrixX3d misfit_points = stroke_targets(unit, 2.0 * options.cell, &misfit_strokes);
  const PointGrid stroke_grid(stroke_points);
  Outline outline;
  find_outline(unit, options, outline);
  r.confine_radius = options.confine_radius;
  BoundingBox strokes_box;
  for (Eigen::Index i = 0; i < stroke_points.rows(); ++i) strokes_box.extend(stroke_points.row(i).transpose());
  BoundingBox within = strokes_box;
  within.min.array() -= options.confine_box;
  within.max.array() += options.confine_box;
  PolygonizeOptions poly;
  poly.cell_size = options.cell;
  constexpr std::size_t kChunk = 64;
  // One solve of the ladder: VIPSS, its confined field and that field's zero set.
  struct Candidate {
    std::unique_ptr<VipssResult> vipss;  // on the heap: `field` refers to its function
    std::unique_ptr<ConfinedField> field;
    std::unique_ptr<GridMemo> rbf;  // s f at the grid's vertices
    TriangleArrays mesh;
    double lambda = 0.0, far = 0.0;
    long genus = 0;
    std::size_t samples = 0, components = 0, evaluations = 0;
    std::size_t windows = 0, bridges = 0, necks = 0;  // bumps kept
    std::vector<Bump> undrawn;  // membranes over the wider windows no stroke depicts, not applied
    std::vector<Bump> tight;    // bumps over the windows whose space across does not open, not applied
  };
  // The strokes' part of every field without the outline cut: the same for every solve.
  auto caps = std::make_unique<GridMemo>(box.min, options.cell);
  // The zero set of g, polygonised (values from the memos of its strokes' part and of its s f);
  // specks dropped.
  const auto polygonise = [&](const ConfinedField& g, GridMemo& g_caps, GridMemo& rbf,
                              TriangleArrays& mesh, std::size_t& evaluations) {
    const FieldBatch field = [&](const Eigen::MatrixX3d& p, Eigen::VectorXd& values) {
      Eigen::VectorXd c, sf;
      g_caps.values(p, nullptr, threads, c, [&](const Eigen::Vector3d& x) { return g.cap(x, nullptr); });
      std::vector<char> wanted(static_cast<std::size_t>(p.rows()));
      for (Eigen::Index i = 0; i < p.rows(); ++i) wanted[static_cast<std::size_t>(i)] = !g.outside(c[i]);
      rbf.values(p, &wanted, threads, sf,
                 [&](const Eigen::Vector3d& x) { return g.scaled(x); });
      values.resize(p.rows());
      for (Eigen::Index i = 0; i < p.rows(); ++i)
        values[i] = g.value_from(p.row(i).transpose(), c[i], sf[i]);
    };
    PolygonizeSummary poly_summary;
    mesh = polygonize_arrays(field, samples, box, poly, progress, &poly_summary);
    evaluations += poly_summary.evaluations;
    if (mesh.F.rows() > 0) drop_specks(mesh, options.min_component);
    return closed_topology(mesh);
  };
  SaddleSearch search;
  search.near = 10.0 * options.cell;
  search.step = 2.0 * options.cell;
  search.across = 4.0 * options.cell;
  search.window_reach = options.window_reach;
  search.window_points = options.window_points;
  search.bridge_most = options.bridge_value;
  search.neck_most = options.neck_value;
  search.window_aliased = 0.5 * options.cell;
  // Windows closed where that removes handles without splitting the surface; then bridges
  // built where that splits nothing (a bridge adds a handle or joins two parts); then necks cut
  // where that splits the surface or removes handles, adds none, and loses no part (at most
  // kNeckLoss of the area: more, and a part fell away as a speck).
  enum class Kind { kWindows, kTight, kBridges, kNecks };
  const auto try_bumps = [&](Candidate& c, MeshTopology& topology, const std::vector<Bump>& bumps,
                             Kind kind) {
    if (bumps.empty()) return false;
    auto bumped = std::make_unique<ConfinedField>(*c.field);
    std::vector<Bump> all = c.field->bumps();
    all.insert(all.end(), bumps.begin(), bumps.end());
    bumped->set_bumps(std::move(all));
    TriangleArrays mesh;
    const MeshTopology with = polygonise(*bumped, *caps, *c.rbf, mesh, c.evaluations);
    if (mesh.F.rows() == 0) return false;
    if (kind == Kind::kNecks) {
      if (with.genus > topology.genus ||
          !(with.components > topology.components || with.genus < topology.genus) ||
          surface_area(mesh) < (1.0 - kNeckLoss) * surface_area(c.mesh))
        return false;
    } else if (with.components > topology.components ||
               ((kind == Kind::kWindows || kind == Kind::kTight) && with.genus >= topology.genus) ||
               (kind == Kind::kTight && with.components < topology.components)) {
      return false;
    }
    c.field = std::move(bumped);
    c.mesh = std::move(mesh);
    topology = with;
    return true;
  };
  // The windows' membranes, then (while handles are left) the thin strips round those whose saddle
  // lies just inside the surface, each kept where it removes handles: a strip flooded where the
  // polygonisation did not open would only thicken the wall. Returns the bumps kept.
  const auto close_windows = [&](Candidate& c, MeshTopology& topology, const Saddles& found) {
    std::size_t closed = 0;
    if (try_bumps(c, topology, found.windows, Kind::kWindows)) closed += found.windows.size();
    if (topology.genus > 0 && try_bumps(c, topology, found.thin, Kind::kWindows))
      closed += found.thin.size();
    return closed;
  };
  // Bumps a solve set aside (`bumps`, one of its own lists), closed where that removes handles
  // (try_bumps' test for `kind`), once: the list is emptied.
  const auto close_set_aside = [&](Candidate& c, std::vector<Bump>& bumps, Kind kind) {
    if (c.genus == 0 || bumps.empty()) return;
    const auto t = Clock::now();
    MeshTopology topology;
    topology.genus = c.genus;
    topology.components = c.components;
    if (try_bumps(c, topology, bumps, kind)) {
      c.windows += bumps.size();
      c.genus = topology.genus;
      c.far = far_fraction(c.mesh, stroke_grid, options.far_distance, threads);
    }
    bumps.clear();
    r.polygonize_seconds += seconds_since(t);
  };
  // The wider windows that no stroke depicts, closed where that removes handles.
  const auto close_undrawn = [&](Candidate& c) { close_set_aside(c, c.undrawn, Kind::kWindows); };
  const auto solve = [&](double lambda, const Eigen::MatrixX3d& at, const VipssStart* from) {
    auto t = Clock::now();
    Candidate c;
    vipss_options.lambda = lambda;
    c.vipss = std::make_unique<VipssResult>(solve_vipss(at, vipss_options, progress, from));
    c.lambda = lambda;
    c.samples = static_cast<std::size_t>(at.rows());
    ++r.vipss_solves;
    r.vipss_seconds += seconds_since(t);
    t = Clock::now();
    c.field = std::make_unique<ConfinedField>(c.vipss->function,
                                              distance_scale(c.vipss->function, at, box),
                                              stroke_points, stroke_grid, r.confine_radius, within,
                                              2.0 * options.cell);
    c.rbf = std::make_unique<GridMemo>(box.min, options.cell);
    MeshTopology topology = polygonise(*c.field, *caps, *c.rbf, c.mesh, c.evaluations);
    // Saddles searched on a grid of two cells within ten cells of a stroke: a window lies on a
    // wall between strokes, a gap between two parts a stroke runs across, a few cells from them.
    SaddleSearch here = search;
    here.window_most = topology.genus > 0 ? options.window_value : 0.0;
    here.window_undrawn_most = topology.genus > 0 ? options.window_undrawn : 0.0;
    const Saddles saddles = find_saddles(c.vipss->function, c.field->scale(), {}, unit,
                                         stroke_grid, box, here, threads);
    c.windows = close_windows(c, topology, saddles);
    if (c.windows > 0) {
      // Windows left open round the membranes (a membrane is flat; a curved wall leaves it) are
      // saddles of the lowered field: searched again while that removes handles.
      SaddleSearch again = here;
      again.bridge_most = again.neck_most = again.window_undrawn_most = 0.0;
      for (int round = 0; round < kWindowRounds && topology.genus > 0; ++round) {
        const Saddles more = find_saddles(c.vipss->function, c.field->scale(), c.field->bumps(),
                                          unit, stroke_grid, box, again, threads);
        const std::size_t closed = close_windows(c, topology, more);
        if (closed == 0) break;
        c.windows += closed;
      }
    }
    c.undrawn = saddles.undrawn;
    c.tight = saddles.tight;
    if (try_bumps(c, topology, saddles.bridges, Kind::kBridges)) c.bridges = saddles.bridges.size();
    if (try_bumps(c, topology, saddles.necks, Kind::kNecks)) c.necks = saddles.necks.size();
    if (c.mesh.F.rows() > 0) {
      c.far = far_fraction(c.mesh, stroke_grid, options.far_distance, threads);
      c.genus = topology.genus;
      c.components = topology.components;
    }
    r.polygonize_seconds += seconds_since(t);
    return c;
  };
  // From the ladder's second weight, the first whose zero set closes within the strokes' extent
  // (else the largest tried), unless a smaller one has clearly less surface far from every stroke
  // (but not most of it: then the strokes frame no surface either way) and not many more handles.
  // More smoothing pulls in a zero set that runs out as a sheet and closes the windows that a less
  // smooth one opens through thin double walls (a mug's, a shell's), but where the strokes depict
  // thin parts (a chair's legs, seat and back, a lamp's arm, a mug's handle) it melts them into a
  // block or webs them to the body, with faces far from every stroke. The ladder's first weight is
  // solved only when the second's surface has at least far_tie of its area far (else the first
  // could not be kept): most sketches need the second's smoothing. A clean curve network starts
  // at clean_lambda, below the first: its strokes lie on the surface, and any smoothing rounds its
  // shape off them.
  std::vector<double> ladder = lambda_ladder(options);
  if (dense.rows() > 0) ladder.insert(ladder.begin(), options.clean_lambda);
  Candidate kept;
  // Keeps `c` instead of `kept` unless `kept` has clearly less surface far from the strokes;
  // returns the one not kept.
  const auto consider = [&](Candidate c) {
    const bool kept_better = kept.far + options.far_tie <= c.far && kept.far <= options.far_most &&
                             kept.genus <= c.genus + options.far_extra_genus;
    if (kept.mesh.F.rows() == 0 || (c.mesh.F.rows() > 0 && !kept_better)) std::swap(kept, c);
    return c;
  };
  const auto misfit_of = [&](const Candidate& c) {
    return shared_misfit(c.vipss->function, misfit_points, misfit_strokes, options.misfit_reach, threads);
  };
  // Where the second weight's zero set closes but rounds the shape off its strokes (their misfits
  // shared between neighbouring strokes, misfit.h), the first weight, solved on the denser samples
  // (clean_points), is kept instead when its zero set closes too with no more handles (each with
  // its undrawn windows closed), parts or surface far from every stroke: less smoothing there
  // follows the shape, not the tremor.
  // Whether the less smoothed `least` frames no more handles, parts or far surface than `c`.
  const auto frames_no_more = [&](const Candidate& least, const Candidate& c) {
    return least.mesh.F.rows() > 0 && least.genus <= c.genus && least.components == c.components &&
           least.far <= c.far + options.rounded_far;
  };
  const auto holds_as_well = [&](Candidate& least, Candidate& c) {
    close_undrawn(least);
    close_undrawn(c);
    return least.vipss->summary.closed && frames_no_more(least, c);
  };
  // A clean network's first solve with many more handles (far_extra_genus) than a drawn sketch's
  // first (the ladder's second weight), its own undrawn windows closed: windows through a thin
  // part's walls (an L-bracket's, two boxes' touching sides) drawn by a network's few sections,
  // between which the nearly interpolating surface sinks through the part, not openings the
  // strokes depict (a mug's handle, which the smoother solve may fill). The ladder then goes on as
  // for a drawn sketch, from that solve.
  std::optional<Candidate> ahead;  // the loop's first solve, made before it
  std::optional<Candidate> clean_first;  // a clean network's first solve, once a smoother one replaced it
  if (clean && ladder.size() > 2) {
    Candidate first = solve(ladder[0], dense, nullptr);
    close_undrawn(first);
    if (first.mesh.F.rows() > 0 && first.genus > 0) {
      Candidate drawn = solve(ladder[2], samples, nullptr);
      if (drawn.mesh.F.rows() > 0 && first.genus > drawn.genus + options.far_extra_genus) {
        clean = false;
        r.clean_windows = true;
        ladder.erase(ladder.begin());
        dense = Eigen::MatrixX3d();
        ahead = std::move(drawn);
      }
    }
    if (!ahead) ahead = std::move(first);
  }
  for (std::size_t i = ladder.size() > 1 && !clean ? 1 : 0; i < ladder.size(); ++i) {
    Candidate c = ahead ? std::move(*ahead) : solve(ladder[i], i == 0 && dense.rows() > 0 ? dense : samples, nullptr);
    ahead.reset();
    const bool closed = c.vipss->summary.closed;
    if (i == 1 && !clean && c.mesh.F.rows() > 0) {
      if (closed && options.rounded_misfit < 1.0)
        r.shared_misfit = misfit_of(c);
      if (closed && r.shared_misfit > options.rounded_misfit) {
        dense = sample_densely();
        Candidate least = solve(ladder[0], dense, nullptr);
        if (holds_as_well(least, c)) {
          kept = std::move(least);
          r.rounded = true;
          break;
        }
      }
      if (c.far >= options.far_tie) consider(solve(ladder[0], samples, nullptr));
    }
    // A clean network's strokes lie on the surface: where the ladder's last weight rounds the shape
    // off them, the least smoothed solve that frames no more handles, parts or far surface stays,
    // closed or not (an open cup's rim confined by the strokes' neighbourhood; a chair's legs,
    // which every weight above the first webs a little more to the seat).
    if (clean && i + 1 == ladder.size() && i > 0 && c.mesh.F.rows() > 0 && options.rounded_misfit < 1.0) {
      Candidate* stays = clean_first && frames_no_more(*clean_first, c) ? &*clean_first
                         : frames_no_more(kept, c)                         ? &kept
                                                                           : nullptr;
      if (stays) {
        r.shared_misfit = misfit_of(c);
        if (r.shared_misfit > options.rounded_misfit) {
          r.rounded = true;
          if (stays != &kept) kept = std::move(*stays);
          break;
        }
      }
    }
    Candidate out = consider(std::move(c));
    if (clean && out.mesh.F.rows() > 0 && out.lambda == ladder[0]) clean_first = std::move(out);
    if (closed) break;
  }
  clean_first.reset();  // its field and meshes are not needed past the ladder
  // A nearer confinement where the surface beyond it is mostly a web or a fin, not faces between
  // drawn edges: a lamp's pole webbed to its base and shade is cut back to a tube round the pole.
  // Faces framed by strokes far apart (a box's sides, a shield, a chest's lid) would be pitted by
  // it: sketches with more than a little of them keep the wider radius. Not where the strokes frame
  // no surface (outline_most, as for the outline cut). Kept when it adds no handle and splits
  // nothing.
  if (options.confine_near > 0.0 && options.confine_near < r.confine_radius && kept.mesh.F.rows() > 0 &&
      kept.far <= options.outline_most) {
    const auto t = Clock::now();
    const Eigen::MatrixX3d coarse = stroke_targets(unit, 6.0 * options.cell);
    const Framing framing =
        surface_framing(kept.mesh, stroke_grid, coarse, PointGrid(coarse), options.confine_near,
                        options.framed_gap * M_PI / 180.0, threads);
    if (framing.open >= options.near_open_least && framing.open >= options.near_open_ratio * framing.framed) {
      auto near = std::make_unique<ConfinedField>(*kept.field);
      near->set_radius(options.confine_near);
      auto near_caps = std::make_unique<GridMemo>(box.min, options.cell);
      TriangleArrays mesh;
      const MeshTopology topology = polygonise(*near, *near_caps, *kept.rbf, mesh, kept.evaluations);
      if (mesh.F.rows() > 0 && topology.genus <= kept.genus && topology.components <= kept.components) {
        kept.field = std::move(near);
        kept.mesh = std::move(mesh);
        kept.genus = topology.genus;
        kept.components = topology.components;
        kept.far = far_fraction(kept.mesh, stroke_grid, options.far_distance, threads);
        caps = std::move(near_caps);
        r.confine_radius = options.confine_near;
      }
    }
    r.polygonize_seconds += seconds_since(t);
  }
  // Thin parts webbed together (a chair's legs into a skirt, a torch's handle into a sail): where
  // the strokes round samples surround axes and the space in front of them, clear of strokes with
  // another part's strokes ahead, lies inside the surface, VIPSS's normals are those of a blob
  // round the parts (part_normals.h). Solved again with the parts' normals kept and the normals
  // near the webs free to follow; kept when much less of the surface lies far from every stroke
  // (the web was such surface), without more than one handle more or another part. Also where
  // most of the surface lies far from every stroke: a web can be most of it (a lamp's pole
  // spread into a wall down to its base, its arms and shade in one hull).
  if (options.part_reach > 0.0 && kept.mesh.F.rows() > 0) {
    const auto t = Clock::now();
    const Eigen::MatrixX3d& at = kept.samples == static_cast<std::size_t>(samples.rows()) ? samples : dense;
    PartSearch search_parts;
    search_parts.reach = options.part_reach;
    search_parts.threads = threads;
    const PartNormals parts = part_normals(kept.vipss->function, kept.field->scale(), at,
                                           stroke_points, stroke_grid, search_parts);
    const auto webs = static_cast<std::size_t>(std::count(parts.between.begin(), parts.between.end(), 1));
    r.polygonize_seconds += seconds_since(t);
    if (webs >= options.part_webs) {
      VipssStart from;
      from.normals = outward_normals(*kept.vipss, kept.field->scale(), at);
      from.fixed.assign(static_cast<std::size_t>(at.rows()), 1);
      const Eigen::MatrixX3d web_samples = rows_where(at, parts.web);
      const PointGrid web_grid(web_samples);
      for (Eigen::Index i = 0; i < at.rows(); ++i) {
        const auto ii = static_cast<std::size_t>(i);
        if (parts.known[ii])
          from.normals.row(i) = parts.normals.row(i);
        else
          from.fixed[ii] = web_grid.nearest(at.row(i).transpose(), options.part_free).second >=
                           options.part_free * options.part_free;
      }
      Candidate c = solve(kept.lambda, at, &from);
      // Where most of the surface is far from every stroke (far_most), the kept solve is a hull
      // round all the parts (a lamp's base, arms and shade): a solve with clearly less such
      // surface follows the parts better, even when one part it frees comes apart.
      const bool hull = kept.far > options.far_most;
      const std::size_t parts_more = hull ? 1 : 0;
      if (c.mesh.F.rows() > 0 && c.genus <= kept.genus + 1 && c.components <= kept.components + parts_more &&
          (hull || c.far <= options.part_far_ratio * kept.far) && c.far + options.far_tie <= kept.far) {
        kept = std::move(c);
        r.part_normals = static_cast<std::size_t>(std::count(parts.known.begin(), parts.known.end(), 1));
      }
    }
  }
  // The wider windows that no stroke depicts are closed on the kept solve only: on every solve
  // they would change the choice above, which weighs handles (a smoother solve that webs a chair's
  // back, its last window closed, would win over one that keeps the back open).
  close_undrawn(kept);
  // Windows whose space across does not open (beside another face: a chair seat's underside by a
  // leg) cannot be told from a gap between two faces by their saddles: closed on the kept solve
  // only, all together, where that removes handles and neither splits nor joins parts (two boxes
  // side by side stay apart).
  if (options.window_tight) close_set_aside(kept, kept.tight, Kind::kTight);
  // The outline cut, where the strokes frame a surface (a sketch whose surface lies mostly far
  // from every stroke, a flower's petals, is left whole: cut, it falls apart into pieces that no
  // longer show that it depicts no surface). Kept when it adds no handle and splits nothing.
  const auto crosses_outline = [&](const TriangleArrays& mesh) {
    std::vector<char> beyond(static_cast<std::size_t>(mesh.V.rows()), 0);
    parallel_for(0, beyond.size(), threads, [&](std::size_t v) {
      beyond[v] = outline.value(mesh.V.row(static_cast<Eigen::Index>(v)).transpose(), nullptr) > 0.0;
    });
    return std::find(beyond.begin(), beyond.end(), 1) != beyond.end();
  };
  // The kept solve's field changed by `change` (a further cut) and polygonised again; kept when
  // that adds no handle (with `fewer_handles`: removes one or more) and splits nothing. Returns
  // whether it was kept.
  const auto try_cut = [&](auto&& change, bool fewer_handles = false) {
    const auto t = Clock::now();
    auto cut = std::make_unique<ConfinedField>(*kept.field);
    change(*cut);
    TriangleArrays mesh;
    GridMemo cut_caps(box.min, options.cell);
    const MeshTopology topology = polygonise(*cut, cut_caps, *kept.rbf, mesh, kept.evaluations);
    const bool keep = mesh.F.rows() > 0 &&
                      (fewer_handles ? topology.genus < kept.genus : topology.genus <= kept.genus) &&
                      topology.components <= kept.components;
    if (keep) {
      kept.field = std::move(cut);
      kept.mesh = std::move(mesh);
      kept.genus = topology.genus;
      kept.components = topology.components;
    }
    r.polygonize_seconds += seconds_since(t);
    return keep;
  };
  if (outline.grid && kept.mesh.F.rows() > 0 && kept.far <= options.outline_most &&
      crosses_outline(kept.mesh))
    r.outline_cut = try_cut([&](ConfinedField& g) { g.set_outline(&outline); });
  // The box drawn in on its sides where the strokes draw a face (drawn_faces) and the surface
  // reaches past: such a face is cut close to its strokes instead of at the wider box. Kept when
  // it adds no handle and splits nothing; where the close cut would (a thin foot whose top dips
  // towards its flat bottom would be pierced), the face is cut halfway out instead.
  const auto faces = drawn_faces(strokes_box, stroke_points, unit, options);
  int face_count = 0;
  for (const auto& axis : faces) face_count += axis[0] + axis[1];
  // Faces are drawn in on their strokes, else halfway out to the box; whether either cut was kept.
  const bool faces_drawn_in = r.confine_radius > 0.0 && options.confine_box_tight > 0.0 &&
                              options.confine_box_tight < options.confine_box;
  // The sides where faces are drawn in: where the strokes drawn along each lie (side_depth); the
  // strokes' bodies place the slanted faces too (drawn_planes).
  const Eigen::MatrixX3d bodies = faces_drawn_in ? stroke_bodies(unit, options.overshoot) : Eigen::MatrixX3d(0, 3);
  BoundingBox face_box = strokes_box;
  if (faces_drawn_in && face_count > 0)
    for (int a = 0; a < 3; ++a) {
      const double run_least = side_run_least(strokes_box, a, options);
      const Eigen::Vector3d n = Eigen::Vector3d::Unit(a);
      face_box.max[a] = side_depth(unit, bodies, n, strokes_box.max[a], run_least, options);
      face_box.min[a] = -side_depth(unit, bodies, -n, -strokes_box.min[a], run_least, options);
    }
  // Per side of the box ([axis][0: low, 1: high]), how far out of the strokes it is drawn in
  // (0: not drawn in, left at the confinement's box).
  using FaceMargins = std::array<std::array<double, 2>, 3>;
  // The kept solve cut at the strokes' box grown by `margins` on the sides drawn in, when the
  // surface reaches past that; whether the cut was kept.
  const auto draw_in = [&](const FaceMargins& margins) {
    BoundingBox tight = within;
    for (int a = 0; a < 3; ++a) {
      if (margins[a][0] > 0.0) tight.min[a] = face_box.min[a] - margins[a][0];
      if (margins[a][1] > 0.0) tight.max[a] = face_box.max[a] + margins[a][1];
    }
    const auto reaches_past = [&](const TriangleArrays& mesh) {
      for (Eigen::Index i = 0; i < mesh.V.rows(); ++i)
        if ((mesh.V.row(i).array() < tight.min.transpose().array()).any() ||
            (mesh.V.row(i).array() > tight.max.transpose().array()).any())
          return true;
      return false;
    };
    return kept.mesh.F.rows() > 0 && reaches_past(kept.mesh) &&
           try_cut([&](ConfinedField& g) { g.set_within(tight); });
  };
  // The margin of the cut kept, if either was.
  const auto close_or_halfway = [&](auto&& cut) -> std::optional<double> {
    for (const double margin : {options.confine_box_tight, 0.5 * (options.confine_box_tight + options.confine_box)})
      if (cut(margin)) return margin;
    return std::nullopt;
  };
  // The planes of the faces drawn in (unit frame, outward normals): the surface lies on them
  // where they cut it.
  std::vector<Plane> drawn;
  if (faces_drawn_in && face_count > 0) {
    // All faces together; where neither cut is kept, each face on its own over those kept before
    // it: one face that no cut can draw in (a glass's thin foot, pierced even halfway out) does
    // not keep the others (the glass's mouth) out at the box.
    FaceMargins kept_margins{};
    const auto with = [&](int axis, int side, double margin) {  // axis < 0: every face
      FaceMargins m = kept_margins;
      for (int a = 0; a < 3; ++a)
        for (int s = 0; s < 2; ++s)
          if (faces[a][s] && (axis < 0 || (a == axis && s == side))) m[a][s] = margin;
      return m;
    };
    if (const std::optional<double> margin = close_or_halfway([&](double m) { return draw_in(with(-1, 0, m)); }))
      kept_margins = with(-1, 0, *margin);
    else if (face_count > 1)
      for (int a = 0; a < 3; ++a)
        for (int side = 0; side < 2; ++side)
          if (faces[a][side])
            if (const std::optional<double> alone =
                    close_or_halfway([&](double m) { return draw_in(with(a, side, m)); }))
              kept_margins = with(a, side, *alone);
    for (int a = 0; a < 3; ++a)
      for (int side = 0; side < 2; ++side)
        if (kept_margins[a][side] > 0.0) {
          ++r.box_drawn_in;
          Plane face;
          face.normal = (side == 1 ? 1.0 : -1.0) * Eigen::Vector3d::Unit(a);
          face.offset = side == 1 ? -(face_box.max[a] + kept_margins[a][side])
                                  : face_box.min[a] - kept_margins[a][side];
          drawn.push_back(face);
        }
  }
  // The slanted faces the strokes draw (drawn_planes), cut close to their strokes in the same way
  // where the surface reaches past them.
  const std::vector<Plane> planes = faces_drawn_in ? drawn_planes(unit, bodies, options) : std::vector<Plane>{};
  const auto moved_out = [&](double face_margin) {
    std::vector<Plane> moved = planes;
    for (Plane& plane : moved) plane.offset -= face_margin;
    return moved;
  };
  const auto cut_planes = [&](double face_margin) {
    const std::vector<Plane> moved = moved_out(face_margin);
    const auto reaches_past = [&](const TriangleArrays& mesh) {
      for (const Plane& plane : moved)
        if (((mesh.V * plane.normal).array() + plane.offset > 0.0).any()) return true;
      return false;
    };
    return kept.mesh.F.rows() > 0 && reaches_past(kept.mesh) &&
           try_cut([&](ConfinedField& g) { g.set_planes(moved); });
  };
  if (!planes.empty())
    if (const std::optional<double> margin = close_or_halfway(cut_planes)) {
      r.planes_drawn_in = planes.size();
      for (const Plane& face : moved_out(*margin)) drawn.push_back(face);
    }
  // Holes that the faces drawn in cut through the surface where it dips through them (a glass's
  // thin foot, its top below its drawn bottom between the strokes across it), closed by a membrane
  // on the face where no stroke depicts an opening there (face_holes.h).
  if (options.face_hole_thickness > 0.0 && kept.genus > 0 && !drawn.empty()) {
    const auto t = Clock::now();
    FaceHoleSearch search_holes;
    search_holes.step = options.cell;
    search_holes.thickness = options.face_hole_thickness;
    const ConfinedField& field = *kept.field;
    const auto g = [&](const Eigen::Vector3d& p) {
      Eigen::Vector3d step;
      return field.value(p, &step);
    };
    FaceHoles holes;
    for (const Plane& face : drawn) {
      FaceHoles more = face_holes(g, face, strokes_box, unit, stroke_grid, search_holes, threads);
      holes.holes += more.holes;
      holes.membranes.insert(holes.membranes.end(), more.membranes.begin(), more.membranes.end());
    }
    r.polygonize_seconds += seconds_since(t);
    if (holes.holes > 0 && try_cut([&](ConfinedField& cut) {
          std::vector<Bump> all = cut.bumps();
          all.insert(all.end(), holes.membranes.begin(), holes.membranes.end());
          cut.set_bumps(std::move(all));
        }, true))
      r.face_holes = holes.holes;
  }
  r.lambda = kept.lambda;
  r.samples = kept.samples;
  r.windows = kept.windows;
  r.bridges = kept.bridges;
  r.necks = kept.necks;
  r.far_area = kept.far;
  if (kept.mesh.F.rows() > 0)
    r.missed_strokes = missed_fraction(kept.mesh, stroke_points, options.miss_distance, threads);
  r.vipss = kept.vipss->summary;
  r.evaluations = kept.evaluations;
  // Sections too sparse for VIPSS (a dress's waist and hem and a profile: its zero set runs out
  // between them to the box): the surface lofted through them, when it holds every stroke.
  if (options.loft_fit > 0.0 && (kept.mesh.F.rows() == 0 || kept.far > options.outline_most)) {
    const auto t = Clock::now();
    LoftOptions loft_options;
    loft_options.edge = options.edge;
    loft_options.fit = options.loft_fit;
    if (std::optional<Loft> loft = loft_sections(unit, loft_options)) {
      r.loft_sections = loft->sections;
      r.far_area = far_fraction(loft->mesh, stroke_grid, options.far_distance, threads);
      r.missed_strokes = missed_fraction(loft->mesh, stroke_points, options.miss_distance, threads);
      r.polygonize_seconds += seconds_since(t);
      t0 = Clock::now();
      TriMesh mesh = mesh_from_matrices(loft->mesh.V, loft->mesh.F);
      const ClosestFaceTree tree(loft->mesh.V, loft->mesh.F);
      const SurfaceProjector onto_loft = [&](Eigen::MatrixX3d& p) {
        parallel_for(0, static_cast<std::size_t>(p.rows()), threads, [&](std::size_t i) {
          Eigen::Vector3d q;
          tree.closest_face(p.row(static_cast<Eigen::Index>(i)).transpose(), &q);
          p.row(static_cast<Eigen::Index>(i)) = q.transpose();
        });
      };
      RemeshOptions remesh_options;
      remesh_options.target_edge = options.edge;
      remesh_options.iterations = options.vipss_remesh_iterations;
      remesh(mesh, remesh_options, onto_loft, progress);
      r.remesh_seconds = seconds_since(t0);
      return finish(std::move(mesh), frame, start, r, report);
    }
    r.polygonize_seconds += seconds_since(t);
  }
  if (kept.mesh.F.rows() == 0)
    throw Error::processing("VIPSS found no closed surface through the strokes");
  TriMesh mesh = mesh_from_matrices(kept.mesh.V, kept.mesh.F);
  const ConfinedField& g = *kept.field;

  t0 = Clock::now();
  const int steps = options.projection_steps;
  const double max_move = 2.0 * std::max(options.cell, options.edge);
  const SurfaceProjector project = [&](Eigen::MatrixX3d& p) {
    const auto rows = static_cast<std::size_t>(p.rows());
    parallel_for(0, (rows + kChunk - 1) / kChunk, threads, [&](std::size_t c) {
      for (std::size_t i = c * kChunk; i < std::min(rows, (c + 1) * kChunk); ++i) {
        const Eigen::Vector3d from = p.row(static_cast<Eigen::Index>(i)).transpose();
        Eigen::Vector3d x = from;
        for (int s = 0; s < steps; ++s) {  // Newton on the term of g that is active
          Eigen::Vector3d step;
          g.value(x, &step);
          x += step;
        }
        // Vertices start within a grid cell of the surface; a longer jump (a nearly vanishing
        // gradient) would tear the mesh, so such a vertex stays where smoothing put it.
        if (!x.allFinite() || (x - from).norm() > max_move) x = from;
        p.row(static_cast<Eigen::Index>(i)) = x.transpose();
      }
    });
  };
  RemeshOptions remesh_options;
  remesh_options.target_edge =
      options.attract_vipss ? std::ldexp(options.edge, options.attract_levels) : options.edge;
  remesh_options.iterations = options.vipss_remesh_iterations;
  remesh(mesh, remesh_options, project, progress);
  r.remesh_seconds = seconds_since(t0);
  if (options.attract_vipss)
    attract_and_subdivide(mesh, stroke_targets(unit, options.edge), options, progress, frame.scale, r);
  // n . x_unit + o = scale (n . x + o / scale - n . centre).
  for (Plane face : drawn) {
    face.offset = face.offset / frame.scale - face.normal.dot(frame.centre);
    r.drawn_faces.push_back(face);
  }
  return finish(std::move(mesh), frame, start, r, report);
}

std::string proxy_mesh_problem(const TriMesh& mesh, const Sketch& sketch) {
  if (mesh.n_faces() == 0) return "has no triangles (points or lines only); give a surface mesh";
  BoundingBox box;
  for (const auto v : mesh.vertices()) {
    const Eigen::Vector3d p = to_eigen(mesh.point(v));
    if (!p.allFinite() || p.cwiseAbs().maxCoeff() > kMaxCoordinate) {
      std::ostringstream what;
      what << "has vertex " << v.idx() << " at (" << p.x() << ", " << p.y() << ", " << p.z()
           << "): " << (p.allFinite() ? "a coordinate is beyond +-" : "not finite (NaN or Inf)");
      if (p.allFinite()) what << kMaxCoordinate;
      return what.str();
    }
    box.extend(p);
  }
  double area = 0.0;
  for (const auto f : mesh.faces()) area += mesh.calc_face_area(f);
  const double diagonal = box.diagonal();
  // Relative to the squared diagonal: round-off leaves flat meshes a tiny area.
  if (!(area > 1e-12 * diagonal * diagonal))
    return "has no area: every triangle is degenerate (its vertices on a point or a line)";
  const double strokes = sketch.bounding_box().diagonal();
  const double scale = diagonal / strokes;
  if (strokes > 0 && (scale > kMaxProxyScale || scale < kMinProxyScale)) {
    std::ostringstream what;
    what << "is " << (scale > 1 ? scale : 1 / scale) << " times " << (scale > 1 ? "larger" : "smaller")
         << " than the strokes (bounding-box diagonal " << diagonal << " against " << strokes
         << "; at most " << kMaxProxyScale << " times larger, " << 1 / kMinProxyScale
         << " times smaller): is it in the sketch's units?";
    return what.str();
  }
  return {};
}

TriMesh attract_proxy(const TriMesh& user_mesh, const Sketch& sketch, const ProxyOptions& options,
                      const Progress& progress, ProxyReport* report) {
  std::string why;
  if (!options.valid(&why)) throw Error::usage(why);
  if (const std::string problem = proxy_mesh_problem(user_mesh, sketch); !problem.empty())
    throw Error::processing("the proxy mesh " + problem);
  ProxyReport r;
  const auto start = Clock::now();
  const Frame frame = stroke_frame(sketch);
  const Sketch unit = unit_strokes(sketch, frame);
  const Eigen::MatrixX3d targets = stroke_targets(unit, options.edge);

  TriMesh mesh = user_mesh;
  to_unit_frame(mesh, frame);
  auto refuse_far = [&](double median_distance) {
    if (median_distance > options.max_proxy_distance)
      throw Error::processing("the proxy mesh is far from the strokes: median distance " +
                              std::to_string(median_distance) + " of the sketch diagonal (at most " +
                              std::to_string(options.max_proxy_distance) +
                              "); is it in the sketch's units and position?");
  };
  {
    // Cheap early refusal before remeshing: distances to the mesh's bounding box are lower
    // bounds of the distances to the mesh.
    BoundingBox mesh_box;
    for (const auto v : mesh.vertices()) mesh_box.extend(to_eigen(mesh.point(v)));
    std::vector<double> d(static_cast<std::size_t>(targets.rows()));
    for (std::size_t i = 0; i < d.size(); ++i) {
      const Eigen::Vector3d p = targets.row(static_cast<Eigen::Index>(i)).transpose();
      d[i] = (p - p.cwiseMax(mesh_box.min).cwiseMin(mesh_box.max)).norm();
    }
    std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
    refuse_far(d[d.size() / 2]);
  }
  auto t0 = Clock::now();
  RemeshOptions remesh_options;
  remesh_options.target_edge = std::ldexp(options.edge, options.attract_levels);
  remesh_options.iterations = options.remesh_iterations;
  remesh(mesh, remesh_options, {}, progress);
  r.remesh_seconds = seconds_since(t0);

  refuse_far(median_nearest_vertex_distance(mesh, targets, options.threads));
  attract_and_subdivide(mesh, targets, options, progress, frame.scale, r);
  return finish(std::move(mesh), frame, start, r, report);
}

}  // namespace sketchsurf
