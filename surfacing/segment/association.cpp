#include "surfacing/segment/association.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <queue>
#include <span>

#include "surfacing/error.h"
#include "surfacing/parallel.h"
#include "surfacing/segment/crease_guides.h"

namespace sketchsurf {

namespace {

using V3 = Eigen::Vector3d;
constexpr double kInf = std::numeric_limits<double>::infinity();

// Faces on both sides of every face edge, and the primal edge between them.
struct DualGraph {
  std::vector<int> neighbor;  // 3 per face: the face across local edge i, -1 on a border
  std::vector<int> edge;      // 3 per face: the primal edge index of local edge i
  Eigen::MatrixX3d centroids;
};

// One A* search workspace per chunk of strokes; reset only what a search touched.
struct PathSearch {
  std::vector<double> cost;
  std::vector<int> parent_slot;  // 3 * parent face + local edge index, -1 for the start
  std::vector<int> touched;

  explicit PathSearch(std::size_t faces) : cost(faces, kInf), parent_slot(faces, -1) {}

  // Crossed primal edges of a shortest dual path from face `from` to face `to`, in order, or
  // false when `to` was not reached within `max_faces` settled faces.
  bool trace(const DualGraph& dual, int from, int to, int max_faces, std::vector<int>& crossed) {
    crossed.clear();
    for (int f : touched) {
      cost[f] = kInf;
      parent_slot[f] = -1;
    }
    touched.clear();
    using Entry = std::pair<double, int>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
    const V3 goal = dual.centroids.row(to);
    auto heuristic = [&](int f) { return (V3(dual.centroids.row(f)) - goal).norm(); };
    cost[from] = 0.0;
    touched.push_back(from);
    open.emplace(heuristic(from), from);
    int settled = 0;
    bool found = false;
    while (!open.empty()) {
      const auto [priority, f] = open.top();
      open.pop();
      if (priority > cost[f] + heuristic(f) + 1e-15) continue;  // stale entry
      if (f == to) {
        found = true;
        break;
      }
      if (++settled > max_faces) break;
      const V3 cf = dual.centroids.row(f);
      for (int i = 0; i < 3; ++i) {
        const int g = dual.neighbor[3 * f + i];
        if (g < 0) continue;
        const double c = cost[f] + (V3(dual.centroids.row(g)) - cf).norm();
        if (c < cost[g]) {
          if (cost[g] == kInf) touched.push_back(g);
          cost[g] = c;
          parent_slot[g] = 3 * f + i;
          open.emplace(c + heuristic(g), g);
        }
      }
    }
    if (!found) return false;
    for (int f = to; parent_slot[f] >= 0; f = parent_slot[f] / 3)
      crossed.push_back(dual.edge[parent_slot[f]]);
    std::reverse(crossed.begin(), crossed.end());
    return true;
  }
};

// `mesh` itself when no element is marked deleted (garbage_collection() would be the identity),
// else a collected copy in `storage`: copying the 82k-vertex 01-0-1 proxy costs ~30 ms.
const TriMesh& without_deleted(const TriMesh& mesh, std::optional<TriMesh>& storage) {
  auto any_deleted = [&](auto handle, std::size_t count, bool has_status) {
    using Handle = decltype(handle);
    for (std::size_t i = 0; has_status && i < count; ++i)
      if (mesh.status(Handle(static_cast<int>(i))).deleted()) return true;
    return false;
  };
  if (!any_deleted(TriMesh::VertexHandle(), mesh.n_vertices(), mesh.has_vertex_status()) &&
      !any_deleted(TriMesh::EdgeHandle(), mesh.n_edges(), mesh.has_edge_status()) &&
      !any_deleted(TriMesh::FaceHandle(), mesh.n_faces(), mesh.has_face_status()))
    return mesh;
  storage = mesh;
  storage->garbage_collection();
  return *storage;
}

struct Attachment {
  int edge;
  V3 sample;
};

}  // namespace

bool AssociationOptions::valid(std::string* why) const {
  auto fail = [&](const char* m) {
    if (why) *why = m;
    return false;
  };
  if (!(crossed_weight > 0) || !std::isfinite(crossed_weight))
    return fail("association crossed_weight must be positive");
  if (!(uncrossed_weight > 0) || !std::isfinite(uncrossed_weight))
    return fail("association uncrossed_weight must be positive");
  if (!(max_segment > 0) || !std::isfinite(max_segment))
    return fail("association max_segment must be positive");
  if (max_path_faces < 1) return fail("association max_path_faces must be at least 1");
  return guides.valid(why);
}

// ---------------------------------------------------------------------------------------------
// ---------------------------------------------------------------------------------------------

double edge_size(const TriMesh& mesh, TriMesh::EdgeHandle e) {
  const auto h0 = mesh.halfedge_handle(e, 0), h1 = mesh.halfedge_handle(e, 1);
  const V3 pa = to_eigen(mesh.point(mesh.from_vertex_handle(h0)));
  const V3 pb = to_eigen(mesh.point(mesh.to_vertex_handle(h0)));
  std::array<V3, 2> opposite;  // no heap allocation: called for every edge of the proxy
  int count = 0;
  for (auto h : {h0, h1})
    if (!mesh.is_boundary(h))
      opposite[count++] = to_eigen(mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h))));
  if (count == 2) return (opposite[0] - opposite[1]).norm();
  if (count == 1) return 2.0 * (opposite[0] - 0.5 * (pa + pb)).norm();
  return (pa - pb).norm();
}

StrokeGraph associate(const Sketch& sketch, const TriMesh& proxy_in,
                      const AssociationOptions& options) {
  std::string why;
  if (!options.valid(&why)) throw Error::usage(why);
  std::optional<TriMesh> collected_copy;
  const TriMesh& proxy = without_deleted(proxy_in, collected_copy);
  if (proxy.n_faces() == 0) throw Error::processing("the proxy mesh has no triangle");

  StrokeGraph graph;
  const Eigen::MatrixX3i F = face_matrix(proxy);
  graph.positions = vertex_matrix(proxy);
  const Eigen::MatrixX3d& V = graph.positions;
  const int nv = static_cast<int>(V.rows());
  const int nf = static_cast<int>(F.rows());
  const int ne = static_cast<int>(proxy.n_edges());

  graph.normals = vertex_normals(V, F);

  // Edges, dual graph, and the edge-size factor c_e.
  graph.edges.resize(ne);
  std::vector<double> sizes(ne, 0.0);
  double mean_edge_length = 0.0;
  for (auto e : proxy.edges()) {
    const auto h0 = proxy.halfedge_handle(e, 0);
    const int a = proxy.from_vertex_handle(h0).idx(), b = proxy.to_vertex_handle(h0).idx();
    graph.edges[e.idx()] = {a, b};
    const V3 pa = V.row(a), pb = V.row(b);
    mean_edge_length += (pa - pb).norm();
    sizes[e.idx()] = edge_size(proxy, e);
  }
  mean_edge_length /= std::max(1, ne);

  DualGraph dual;
  dual.neighbor.assign(3 * nf, -1);
  dual.edge.assign(3 * nf, -1);
  dual.centroids.resize(nf, 3);
  for (auto f : proxy.faces()) {
    int i = 0;
    for (auto h : proxy.fh_range(f)) {
      const auto opposite = proxy.opposite_halfedge_handle(h);
      const auto g = proxy.face_handle(opposite);
      dual.neighbor[3 * f.idx() + i] = g.is_valid() ? g.idx() : -1;
      dual.edge[3 * f.idx() + i] = proxy.edge_handle(h).idx();
      ++i;
    }
    dual.centroids.row(f.idx()) = (V.row(F(f.idx(), 0)) + V.row(F(f.idx(), 1)) + V.row(F(f.idx(), 2))) / 3.0;
  }

  // Trace every stroke, then every crease guide (in fixed chunks, so the result does not depend
  // on the thread count). Guides mark the edges they cross but attach no sample.
  const ClosestFaceTree tree(V, F);
  std::vector<std::span<const V3>> lines;
  for (const auto& s : sketch.strokes)
    if (!s.ignored && s.points.size() >= 2) lines.emplace_back(s.points);
  const std::size_t stroke_lines = lines.size();
  const double diagonal = sketch.bounding_box().diagonal();
  const auto guides = guides_on_folds(crease_guides(sketch, diagonal, options.guides), V,
                                      graph.normals, diagonal, options.guides);
  for (const auto& g : guides) lines.emplace_back(g);
  graph.guides = guides.size();
  std::vector<std::vector<Attachment>> attached(lines.size());
  std::vector<std::size_t> skipped(lines.size(), 0);
  const double max_len = options.max_segment * mean_edge_length;
  const std::size_t chunks = std::min<std::size_t>(lines.size(), 64);
  parallel_for(0, chunks, options.threads, [&](std::size_t c) {
    PathSearch search(nf);
    std::vector<int> crossed;
    for (std::size_t s = lines.size() * c / chunks; s < lines.size() * (c + 1) / chunks; ++s) {
      // Split long segments so that each traced path stays close to the stroke.
      std::vector<V3> pts;
      const auto& sp = lines[s];
      pts.push_back(sp[0]);
      for (std::size_t i = 1; i < sp.size(); ++i) {
        const double len = (sp[i] - sp[i - 1]).norm();
        const int pieces = std::max(1, static_cast<int>(std::ceil(len / max_len)));
        for (int k = 1; k <= pieces; ++k)
          pts.push_back(sp[i - 1] + (sp[i] - sp[i - 1]) * (static_cast<double>(k) / pieces));
      }
      std::vector<int> faces(pts.size());
      for (std::size_t i = 0; i < pts.size(); ++i) faces[i] = tree.closest_face(pts[i]);
      for (std::size_t i = 1; i < pts.size(); ++i) {
        if (faces[i] == faces[i - 1]) continue;
        if (!search.trace(dual, faces[i - 1], faces[i], options.max_path_faces, crossed)) {
          ++skipped[s];
          continue;
        }
        const int n = static_cast<int>(crossed.size());
        for (int k = 0; k < n; ++k)
          attached[s].push_back({crossed[k], pts[i - 1] + (pts[i] - pts[i - 1]) * ((k + 0.5) / n)});
      }
    }
  });
  std::vector<std::uint8_t> guided(ne, 0);
  for (std::size_t s = stroke_lines; s < lines.size(); ++s) {
    for (const auto& a : attached[s]) guided[a.edge] = 1;
    attached[s].clear();
  }

  // Samples per edge, in stroke order.
  std::vector<int> edge_offsets(ne + 1, 0);
  std::size_t total = 0;
  for (std::size_t s = 0; s < stroke_lines; ++s) {
    for (const auto& a : attached[s]) ++edge_offsets[a.edge + 1];
    total += attached[s].size();
    graph.skipped_segments += skipped[s];
  }
  graph.crossings = total;
  for (int e = 0; e < ne; ++e) edge_offsets[e + 1] += edge_offsets[e];
  std::vector<V3> samples(total);
  {
    std::vector<int> fill(edge_offsets.begin(), edge_offsets.end() - 1);
    for (const auto& list : attached)
      for (const auto& a : list) samples[fill[a.edge]++] = a.sample;
  }

  // P_v: for every edge of v's 1-ring, the sample on that edge closest to v.
  std::vector<std::vector<int>> per_vertex(nv);
  std::vector<int> new_index(total, -1);
  std::vector<V3> kept;
  graph.crossed = std::move(guided);
  for (int e = 0; e < ne; ++e) {
    if (edge_offsets[e] == edge_offsets[e + 1]) continue;
    graph.crossed[e] = 1;
    for (int end : graph.edges[e]) {
      const V3 pv = V.row(end);
      int best = -1;
      double best_d = kInf;
      for (int k = edge_offsets[e]; k < edge_offsets[e + 1]; ++k) {
        const double d = (samples[k] - pv).squaredNorm();
        if (d < best_d) {
          best_d = d;
          best = k;
        }
      }
      if (new_index[best] < 0) {
        new_index[best] = static_cast<int>(kept.size());
        kept.push_back(samples[best]);
      }
      per_vertex[end].push_back(new_index[best]);
    }
  }
  graph.points.resize(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t i = 0; i < kept.size(); ++i) graph.points.row(static_cast<Eigen::Index>(i)) = kept[i];
  graph.point_offsets.assign(nv + 1, 0);
  for (int v = 0; v < nv; ++v) graph.point_offsets[v + 1] = graph.point_offsets[v] + static_cast<int>(per_vertex[v].size());
  graph.point_indices.reserve(graph.point_offsets[nv]);
  for (int v = 0; v < nv; ++v)
    graph.point_indices.insert(graph.point_indices.end(), per_vertex[v].begin(), per_vertex[v].end());

  // Smoothness weights (§4.1), scaled by the relative edge size (App. C).
  double mean_size = 0.0;
  for (double c : sizes) mean_size += c;
  mean_size /= std::max(1, ne);
  graph.edge_size_reference = options.scale_by_edge_size && mean_size > 0 ? mean_size : 1.0;
  graph.weights.resize(ne);
  for (int e = 0; e < ne; ++e) {
    const double base = graph.crossed[e] ? options.crossed_weight : options.uncrossed_weight;
    graph.weights[e] = options.scale_by_edge_size && mean_size > 0 ? base * sizes[e] / mean_size : base;
  }
  return graph;
}

}  // namespace sketchsurf
