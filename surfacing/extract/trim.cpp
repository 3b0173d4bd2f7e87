#include "surfacing/extract/trim.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <unordered_map>

#include "surfacing/error.h"
#include "surfacing/segment/association.h"
#include "surfacing/segment/maxflow.h"
#include "surfacing/sketch/openings.h"

namespace sketchsurf {

bool TrimOptions::valid(std::string* why) const {
  auto fail = [&](const char* what) {
    if (why) *why = what;
    return false;
  };
  if (!(inside_distance >= 0.0)) return fail("trim.inside_distance must be >= 0");
  if (!(outside_distance > 0.0)) return fail("trim.outside_distance must be > 0");
  if (!(attract_distance > 0.0)) return fail("trim.attract_distance must be > 0");
  return true;
}

namespace {

/// The strokes of `sketch` that pass `keep`, as a sketch of their own.
template <class Keep>
Sketch strokes_where(const Sketch& sketch, Keep keep) {
  Sketch out;
  out.units = sketch.units;
  for (const Stroke& s : sketch.strokes)
    if (!s.ignored && keep(s)) out.strokes.push_back(s);
  return out;
}

/// Whether a point lies within `radius` of any of `points`: a uniform grid of cell `radius`.
class NearPoints {
 public:
  NearPoints(const std::vector<Eigen::Vector3d>& points, double radius)
      : points_(points), radius_(radius) {
    for (std::size_t i = 0; i < points.size(); ++i) cells_[key(cell(points[i]))].push_back(i);
  }
  bool near(const Eigen::Vector3d& p) const {
    const Eigen::Vector3i c = cell(p);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          auto it = cells_.find(key(c + Eigen::Vector3i(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (std::size_t i : it->second)
            if ((points_[i] - p).squaredNorm() <= radius_ * radius_) return true;
        }
    return false;
  }

 private:
  Eigen::Vector3i cell(const Eigen::Vector3d& p) const {
    return (p / radius_).array().floor().cast<int>();
  }
  static std::int64_t key(const Eigen::Vector3i& c) {
    return (std::int64_t(c.x()) * 73856093) ^ (std::int64_t(c.y()) * 19349663) ^
           (std::int64_t(c.z()) * 83492791);
  }
  const std::vector<Eigen::Vector3d>& points_;
  double radius_;
  std::unordered_map<std::int64_t, std::vector<std::size_t>> cells_;
};

/// Dijkstra distances along mesh edges from the seed vertices.
std::vector<double> geodesic_distance(const TriMesh& mesh, const std::vector<int>& seeds) {
  std::vector<double> dist(mesh.n_vertices(), std::numeric_limits<double>::infinity());
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  for (int s : seeds) {
    dist[s] = 0.0;
    queue.emplace(0.0, s);
  }
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > dist[v]) continue;
    for (auto h : mesh.voh_range(TriMesh::VertexHandle(v))) {
      const int u = h.to().idx();
      const double du = d + mesh.calc_edge_length(h);
      if (du < dist[u]) {
        dist[u] = du;
        queue.emplace(du, u);
      }
    }
  }
  return dist;
}

/// The boundary strokes of `sketch` that close into a loop (completed by their mirror image when
/// `mirror` cuts them), each oriented toward its empty side; loops with strokes across them or on
/// both sides are left out.
std::vector<StrokeLoop> boundary_openings(const Sketch& sketch, const std::optional<Plane>& mirror) {
  std::vector<Eigen::Vector3d> interior;
  for (const Stroke& s : sketch.strokes)
    if (!s.ignored && !s.boundary) interior.insert(interior.end(), s.points.begin(), s.points.end());
  std::vector<StrokeLoop> loops;
  for (const Stroke& s : sketch.strokes) {
    if (!s.boundary || s.ignored) continue;
    std::optional<StrokeLoop> loop = stroke_loop(s.points);
    if (!loop && mirror) {
      std::vector<Eigen::Vector3d> whole = s.points;
      for (auto p = s.points.rbegin(); p != s.points.rend(); ++p) whole.push_back(mirror->reflect(*p));
      loop = stroke_loop(whole);
    }
    if (!loop) continue;
    const LoopSides sides = loop_sides(*loop, interior);
    if (sides.across > 0 || (sides.above > 0) == (sides.below > 0)) continue;
    if (sides.above > 0) loop->flip();
    loops.push_back(std::move(*loop));
  }
  return loops;
}

}  // namespace

TrimResult trim_open_surface(const TriMesh& proxy, const Sketch& sketch,
                             const std::optional<Plane>& mirror, double plane_tolerance,
                             double diagonal, const TrimOptions& options) {
  std::string why;
  if (!options.valid(&why)) throw Error::usage(why);
  const Sketch boundary = strokes_where(sketch, [](const Stroke& s) { return s.boundary; });
  const Sketch interior = strokes_where(sketch, [](const Stroke& s) { return !s.boundary; });
  if (boundary.strokes.empty()) throw Error::usage("trim_open_surface: the sketch has no boundary stroke");
  const int nv = static_cast<int>(proxy.n_vertices());

  // Edges crossed by the projected boundary strokes (the strokes themselves: no crease guide), and
  // the vertices with interior stroke points.
  AssociationOptions strokes_only;
  strokes_only.guides.enabled = false;
  const StrokeGraph crossed = associate(boundary, proxy, strokes_only);
  std::vector<int> crossed_vertices;
  TrimResult result;
  for (std::size_t e = 0; e < crossed.edges.size(); ++e)
    if (crossed.crossed[e]) {
      ++result.crossed_edges;
      crossed_vertices.push_back(crossed.edges[e][0]);
      crossed_vertices.push_back(crossed.edges[e][1]);
    }
  const std::vector<double> from_boundary = geodesic_distance(proxy, crossed_vertices);

  std::vector<std::uint8_t> inside(nv, 0), outside(nv, 0);
  if (!interior.strokes.empty()) {
    const StrokeGraph attached = associate(interior, proxy, strokes_only);
    for (int v = 0; v < nv; ++v)
      inside[v] = !attached.points_of(v).empty() &&
                  from_boundary[v] > options.inside_distance * diagonal;
  }
  // Outside: the proxy's own boundary (not the mirror cut); a closed proxy has none, then the
  // vertices far from every stroke.
  for (auto v : proxy.vertices()) {
    const Eigen::Vector3d p = to_eigen(proxy.point(v));
    const bool on_mirror = mirror && std::abs(mirror->signed_distance(p)) <= plane_tolerance;
    outside[v.idx()] = !inside[v.idx()] && proxy.is_boundary(v) && !on_mirror;
  }
  if (std::find(outside.begin(), outside.end(), 1) == outside.end()) {
    std::vector<Eigen::Vector3d> stroke_points;
    for (const Stroke& s : sketch.strokes)
      if (!s.ignored) stroke_points.insert(stroke_points.end(), s.points.begin(), s.points.end());
    const NearPoints near_strokes(stroke_points, options.outside_distance * diagonal);
    const std::vector<StrokeLoop> openings = boundary_openings(sketch, mirror);
    const OpeningOptions loop_options;
    const auto in_opening = [&](const Eigen::Vector3d& p) {
      return std::any_of(openings.begin(), openings.end(), [&](const StrokeLoop& loop) {
        return loop.height(p) >= -loop_options.thickness * loop.radius &&
               loop.encloses(p, loop_options.margin * loop.radius);
      });
    };
    // A boundary loop with an empty side says where the outside is; without one, whatever lies
    // far from the strokes is (between sparse strokes the wall of a cup is far from them too).
    for (auto v : proxy.vertices()) {
      const Eigen::Vector3d p = to_eigen(proxy.point(v));
      outside[v.idx()] = !inside[v.idx()] && (openings.empty() ? !near_strokes.near(p) : in_opening(p));
    }
  }
  result.sink_seeds = std::count(inside.begin(), inside.end(), 1);
  result.source_seeds = std::count(outside.begin(), outside.end(), 1);
  if (result.sink_seeds == 0)
    throw Error::processing("open surface: no stroke lies inside the boundary strokes (at least " +
                            std::to_string(options.inside_distance) +
                            " of the diagonal away from them); draw strokes across the surface or "
                            "remove the boundary marks");
  if (result.source_seeds == 0)
    throw Error::processing("open surface: the proxy is closed and lies near the strokes "
                            "everywhere, so nothing can be trimmed; give an open proxy that extends "
                            "beyond the boundary strokes, or remove the boundary marks");

  // Min cut: crossed edges are free, others cost their length (in mean edge lengths).
  double mean_length = 0.0;
  for (auto e : proxy.edges()) mean_length += proxy.calc_edge_length(e);
  mean_length /= std::max<std::size_t>(1, proxy.n_edges());
  MaxFlow flow(nv);
  double total = 0.0;
  for (std::size_t e = 0; e < crossed.edges.size(); ++e) {
    const double c = crossed.crossed[e] ? 0.0
                                        : proxy.calc_edge_length(TriMesh::EdgeHandle(static_cast<int>(e))) /
                                              mean_length;
    total += c;
    flow.add_edge(crossed.edges[e][0], crossed.edges[e][1], c, c);
  }
  const double infinite = 1.0 + 2.0 * total;
  for (int v = 0; v < nv; ++v)
    if (outside[v] || inside[v])
      flow.add_terminal_weights(v, outside[v] ? infinite : 0.0, inside[v] ? infinite : 0.0);
  result.cut_cost = flow.solve();

  // Keep the faces whose corners are all inside, then the parts that hold inside seeds.
  std::vector<std::uint8_t> keep_face(proxy.n_faces(), 0);
  for (auto f : proxy.faces()) {
    bool in = true;
    for (auto v : f.vertices()) in = in && !flow.on_source_side(v.idx());
    keep_face[f.idx()] = in;
  }
  std::vector<int> component(proxy.n_faces(), -1);
  std::vector<std::uint8_t> component_inside;
  for (auto f0 : proxy.faces()) {
    if (!keep_face[f0.idx()] || component[f0.idx()] >= 0) continue;
    const int id = static_cast<int>(component_inside.size());
    component_inside.push_back(0);
    std::vector<OpenMesh::SmartFaceHandle> stack{f0};
    component[f0.idx()] = id;
    while (!stack.empty()) {
      const auto f = stack.back();
      stack.pop_back();
      for (auto v : f.vertices()) component_inside[id] |= inside[v.idx()];
      for (auto g : f.faces())
        if (keep_face[g.idx()] && component[g.idx()] < 0) {
          component[g.idx()] = id;
          stack.push_back(g);
        }
    }
  }
  TriMesh mesh = proxy;
  auto original = OpenMesh::VPropHandleT<int>();
  mesh.add_property(original);
  for (auto v : mesh.vertices()) mesh.property(original, v) = v.idx();
  for (auto f : mesh.faces())
    if (!keep_face[f.idx()] || !component_inside[component[f.idx()]]) {
      mesh.delete_face(f, true);
      ++result.removed_faces;
    }
  mesh.garbage_collection();
  result.source_vertex.resize(mesh.n_vertices());
  for (auto v : mesh.vertices()) result.source_vertex[v.idx()] = mesh.property(original, v);
  mesh.remove_property(original);
  mesh.update_normals();
  result.mesh = std::move(mesh);
  return result;
}

std::vector<AttractTarget> boundary_targets(const TriMesh& mesh, const Sketch& sketch,
                                            const std::vector<std::uint8_t>& exclude,
                                            double diagonal, const TrimOptions& options) {
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> segments;
  for (const Stroke& s : sketch.strokes) {
    if (!s.boundary || s.ignored) continue;
    for (std::size_t i = 0; i + 1 < s.points.size(); ++i)
      segments.emplace_back(s.points[i], s.points[i + 1]);
    if (s.points.size() == 1) segments.emplace_back(s.points[0], s.points[0]);
  }
  std::vector<AttractTarget> targets;
  const double reach = options.attract_distance * diagonal;
  for (auto v : mesh.vertices()) {
    if (!mesh.is_boundary(v) || (!exclude.empty() && exclude[v.idx()])) continue;
    const Eigen::Vector3d p = to_eigen(mesh.point(v));
    double best = std::numeric_limits<double>::infinity();
    Eigen::Vector3d target = p;
    for (const auto& [a, b] : segments) {
      const Eigen::Vector3d d = b - a;
      const double len2 = d.squaredNorm();
      const double t = len2 > 0.0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
      const Eigen::Vector3d q = a + t * d;
      const double dist = (q - p).squaredNorm();
      if (dist < best) {
        best = dist;
        target = q;
      }
    }
    if (std::sqrt(best) <= reach) targets.push_back({v.idx(), target});
  }
  return targets;
}

}  // namespace sketchsurf
