#include "surfacing/quality/checks.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <unordered_map>

#include "surfacing/closest_face.h"
#include "surfacing/parallel.h"
#include "surfacing/portable_math.h"
#include "surfacing/proxy/proxy.h"
#include "surfacing/quality/sampling.h"
#include "surfacing/self_intersections.h"
#include "surfacing/sketch/stroke_segments.h"

namespace sketchsurf {

namespace {

using V3 = Eigen::Vector3d;

// The curves between regions, traced through the midpoints of the edges whose two vertices have
// different labels (two such edges of a face are joined): their length, and their length after
// smoothing the inner points of every chain (ends and junctions fixed).
std::pair<double, double> border_lengths(const TriMesh& mesh, const std::vector<int>& labels) {
  std::unordered_map<int, int> node_of_edge;
  std::vector<V3> nodes;
  std::vector<std::array<int, 2>> links;
  const auto node = [&](TriMesh::EdgeHandle e) {
    const auto [it, added] = node_of_edge.emplace(e.idx(), static_cast<int>(nodes.size()));
    if (added) {
      const auto h = mesh.halfedge_handle(e, 0);
      nodes.push_back(0.5 * (to_eigen(mesh.point(mesh.from_vertex_handle(h))) +
                             to_eigen(mesh.point(mesh.to_vertex_handle(h)))));
    }
    return it->second;
  };
  for (auto f : mesh.faces()) {
    std::vector<int> crossing;
    for (auto h : mesh.fh_range(f))
      if (labels[mesh.from_vertex_handle(h).idx()] != labels[mesh.to_vertex_handle(h).idx()])
        crossing.push_back(node(mesh.edge_handle(h)));
    for (std::size_t i = 0; i < crossing.size(); ++i)
      for (std::size_t j = i + 1; j < crossing.size(); ++j) links.push_back({crossing[i], crossing[j]});
  }
  const auto length = [&](const std::vector<V3>& at) {
    double sum = 0.0;
    for (const auto& [a, b] : links) sum += (at[a] - at[b]).norm();
    return sum;
  };
  std::vector<std::vector<int>> neighbours(nodes.size());
  for (const auto& [a, b] : links) {
    neighbours[a].push_back(b);
    neighbours[b].push_back(a);
  }
  std::vector<V3> smooth = nodes;
  for (int iteration = 0; iteration < 20; ++iteration) {
    std::vector<V3> next = smooth;
    for (std::size_t i = 0; i < nodes.size(); ++i)
      if (neighbours[i].size() == 2)
        next[i] = 0.5 * smooth[i] + 0.25 * (smooth[neighbours[i][0]] + smooth[neighbours[i][1]]);
    smooth = std::move(next);
  }
  return {length(nodes), length(smooth)};
}

// Whether the stroke points within `reach` of p surround it, seen along the surface (normal n):
// their directions in the tangent plane leave no open angle over 180 degrees.
bool surrounded(const V3& p, const V3& n, const Eigen::MatrixX3d& points, double reach) {
  const V3 u = n.unitOrthogonal(), w = n.cross(u);
  std::vector<double> angles;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const V3 d = V3(points.row(i)) - p;
    if (d.squaredNorm() > reach * reach) continue;
    const double x = d.dot(u), y = d.dot(w);
    if (x * x + y * y > 0.0) angles.push_back(portable::atan2(y, x));
  }
  if (angles.size() < 3) return false;
  std::sort(angles.begin(), angles.end());
  double gap = angles.front() + 2 * M_PI - angles.back();
  for (std::size_t i = 1; i < angles.size(); ++i) gap = std::max(gap, angles[i] - angles[i - 1]);
  return gap <= M_PI;
}

std::string percent(double fraction) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f%%", 100.0 * fraction);
  return text;
}

}  // namespace

ShapeChecks check_shape(const TriMesh& mesh, const std::vector<int>& labels, const Sketch& sketch,
                        bool open_expected, const CheckOptions& options) {
  ShapeChecks out;
  const MeshTopology topology = mesh_topology(mesh);
  out.components = topology.components;
  out.genus = topology.genus;
  out.boundary_loops = topology.boundary_loops;
  out.self_intersections = count_self_intersections(mesh, options.threads);

  const StrokeSegments strokes = stroke_segments(sketch, true);
  const double diagonal = strokes.box.diagonal();
  const SurfaceSamples samples = sample_surface(mesh, options.samples, options.seed);
  if (strokes.segments.rows() > 0 && diagonal > 0.0 && samples.points.rows() > 0) {
    const ClosestFaceTree tree(strokes.points, strokes.segments);
    const std::size_t n = static_cast<std::size_t>(samples.points.rows());
    std::vector<double> distance(n);
    parallel_for(0, n, options.threads, [&](std::size_t i) {
      const V3 p = samples.points.row(static_cast<Eigen::Index>(i));
      V3 q;
      tree.closest_face(p, &q);
      distance[i] = (q - p).norm() / diagonal;
    });
    // A surface cut on the grown box (the automatic proxy's confinement) lies on it, its points
    // off by rounding only: those count as inside.
    const V3 margin = V3::Constant((options.box_margin + 1e-9) * diagonal);
    // Only the samples far from every stroke need the (slower) surround test.
    std::vector<char> beyond(n, 0);
    parallel_for(0, n, options.threads, [&](std::size_t i) {
      if (!(distance[i] > 0.05)) return;
      const auto f = mesh.face_handle(samples.faces[i]);
      beyond[i] = !surrounded(samples.points.row(static_cast<Eigen::Index>(i)),
                              to_eigen(mesh.calc_face_normal(f)), strokes.points, options.reach * diagonal);
    });
    std::size_t far_5 = 0, far_10 = 0, outside = 0, beyond_count = 0;
    for (std::size_t i = 0; i < n; ++i) {
      beyond_count += beyond[i];
      far_5 += distance[i] > 0.05;
      far_10 += distance[i] > 0.10;
      const V3 p = samples.points.row(static_cast<Eigen::Index>(i));
      outside += (p.array() < (strokes.box.min - margin).array()).any() ||
                 (p.array() > (strokes.box.max + margin).array()).any();
    }
    out.far_5 = static_cast<double>(far_5) / static_cast<double>(n);
    out.far_10 = static_cast<double>(far_10) / static_cast<double>(n);
    out.beyond = static_cast<double>(beyond_count) / static_cast<double>(n);
    out.outside_box = static_cast<double>(outside) / static_cast<double>(n);
  }
  if (labels.size() == mesh.n_vertices() && !labels.empty()) {
    std::vector<int> distinct = labels;
    std::sort(distinct.begin(), distinct.end());
    out.regions = static_cast<std::size_t>(std::unique(distinct.begin(), distinct.end()) - distinct.begin());
    const auto [raw, smooth] = border_lengths(mesh, labels);
    if (diagonal > 0.0) out.border_length = raw / diagonal;
    out.border_ratio = smooth > 0.0 ? raw / smooth : 1.0;
  }

  if (out.beyond > options.warn_beyond)
    out.warnings.push_back(percent(out.beyond) + " of the surface runs out beyond the strokes (farther "
                           "than 5% of the diagonal from every stroke, with no stroke on one side): a "
                           "sheet or fin where nothing was drawn?");
  if (out.outside_box > options.warn_outside)
    out.warnings.push_back(percent(out.outside_box) + " of the surface lies outside the strokes' bounding box");
  if (out.genus > options.warn_genus)
    out.warnings.push_back("the surface has genus " + std::to_string(out.genus) +
                           " (that many handles): spurious tunnels between strokes?");
  if (out.boundary_loops > 0 && !open_expected)
    out.warnings.push_back("the surface has " + std::to_string(out.boundary_loops) +
                           " hole(s) although no boundary stroke was marked");
  if (static_cast<double>(out.self_intersections) > options.warn_crossing * static_cast<double>(mesh.n_faces()))
    out.warnings.push_back(std::to_string(out.self_intersections) + " pairs of triangles intersect "
                           "(the surface passes through itself)");
  if (out.border_ratio > options.warn_border) {
    char ratio[16];
    std::snprintf(ratio, sizeof ratio, "%.2f", out.border_ratio);
    out.warnings.push_back(std::string("region borders are ragged (") + ratio +
                           " times the length of smoothed borders)");
  }
  return out;
}

double non_surface_score(const ShapeChecks& checks, double stroke_p95) {
  return checks.beyond * 100.0 * stroke_p95;
}

}  // namespace sketchsurf
