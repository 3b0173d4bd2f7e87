#include "surfacing/segment/simplify.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

#include "surfacing/error.h"

namespace sketchsurf {

namespace {

// Valence of the vertex left when halfedge h (v0 -> v1) collapses: the two merge, losing the
// edge between them and one duplicate per adjacent triangle. `valence` is kept up to date.
int merged_valence(const TriMesh& mesh, const std::vector<int>& valence, TriMesh::HalfedgeHandle h) {
  return valence[mesh.from_vertex_handle(h).idx()] + valence[mesh.to_vertex_handle(h).idx()] - 4;
}

// Halfedges by (resulting valence, halfedge index), smallest first, repeats included: what one
// heap of pairs would give. Per valence (valences are small) a count per halfedge index and two
// levels of bit sets over the non-zero counts: push and pop in a few word operations (heaps of
// the 01-0-1 proxy's ~500k halfedges spent 0.15 s sifting).
class CollapseQueue {
 public:
  CollapseQueue(int max_valence, int index_count)
      : buckets_(static_cast<std::size_t>(max_valence) + 1), index_count_(index_count) {}

  void push(int valence, int index) {
    const int b = std::clamp(valence, 0, static_cast<int>(buckets_.size()) - 1);
    Bucket& bucket = buckets_[b];
    if (bucket.count.empty()) {
      bucket.count.assign(static_cast<std::size_t>(index_count_), 0);
      bucket.words.assign((bucket.count.size() + 63) / 64, 0);
      bucket.summary.assign((bucket.words.size() + 63) / 64, 0);
    }
    if (bucket.count[index]++ == 0) {
      const std::size_t w = static_cast<std::size_t>(index) / 64;
      bucket.words[w] |= std::uint64_t{1} << (index % 64);
      bucket.summary[w / 64] |= std::uint64_t{1} << (w % 64);
      bucket.first = std::min(bucket.first, w / 64);
    }
    ++bucket.size;
    lowest_ = std::min(lowest_, b);
  }

  // Pops the smallest entry into (*valence, *index); false when empty.
  bool pop(int* valence, int* index) {
    while (lowest_ < static_cast<int>(buckets_.size()) && buckets_[lowest_].size == 0) ++lowest_;
    if (lowest_ == static_cast<int>(buckets_.size())) return false;
    Bucket& bucket = buckets_[lowest_];
    while (bucket.summary[bucket.first] == 0) ++bucket.first;
    const std::size_t w = bucket.first * 64 + std::countr_zero(bucket.summary[bucket.first]);
    const int i = static_cast<int>(w * 64 + std::countr_zero(bucket.words[w]));
    if (--bucket.count[i] == 0) {
      bucket.words[w] &= ~(std::uint64_t{1} << (i % 64));
      if (bucket.words[w] == 0) bucket.summary[w / 64] &= ~(std::uint64_t{1} << (w % 64));
    }
    --bucket.size;
    *valence = lowest_;
    *index = i;
    return true;
  }

 private:
  struct Bucket {
    std::vector<std::uint32_t> count;          // entries per halfedge index
    std::vector<std::uint64_t> words, summary;  // bit i: count[i] > 0; bit w: words[w] != 0
    std::size_t first = 0;                      // no summary word before it is non-zero
    std::size_t size = 0;                       // entries
  };
  std::vector<Bucket> buckets_;
  int index_count_;
  int lowest_ = 0;
};

}  // namespace

bool SimplifyOptions::valid(std::string* why) const {
  if (max_valence < 3) {
    if (why) *why = "simplification max_valence must be at least 3";
    return false;
  }
  return true;
}

std::vector<int> SimplifiedGraph::propagate(const std::vector<int>& coarse_labels) const {
  std::vector<int> labels(fine_to_coarse.size());
  for (std::size_t v = 0; v < labels.size(); ++v) labels[v] = coarse_labels[fine_to_coarse[v]];
  return labels;
}

SimplifiedGraph identity_graph(const StrokeGraph& graph) {
  SimplifiedGraph s;
  s.vertex_count = graph.vertex_count();
  s.fine_to_coarse.resize(s.vertex_count);
  for (int v = 0; v < s.vertex_count; ++v) s.fine_to_coarse[v] = v;
  s.coarse_to_fine = s.fine_to_coarse;
  s.edges = graph.edges;
  s.weights = graph.weights;
  return s;
}

SimplifiedGraph simplify_graph(TriMesh mesh, const StrokeGraph& graph,
                               const AssociationOptions& association,
                               const SimplifyOptions& options) {
  std::string why;
  if (!options.valid(&why)) throw Error::usage(why);
  mesh.garbage_collection();
  const int nv = static_cast<int>(mesh.n_vertices());
  if (nv != graph.vertex_count() || mesh.n_edges() != graph.edges.size())
    throw Error::usage("simplify_graph: the stroke graph was not built from this proxy");

  // A vertex on a crossed edge stays (a stroke's vertices have points; a crease guide's need not).
  std::vector<std::uint8_t> on_crossed(nv, 0);
  for (std::size_t e = 0; e < graph.edges.size(); ++e)
    if (graph.crossed[e])
      for (int end : graph.edges[e]) on_crossed[end] = 1;
  auto movable = [&](TriMesh::VertexHandle v) {
    return graph.point_offsets[v.idx()] == graph.point_offsets[v.idx() + 1] && !on_crossed[v.idx()] &&
           !mesh.is_boundary(v);
  };
  std::vector<int> valence(nv);
  for (auto v : mesh.vertices()) valence[v.idx()] = static_cast<int>(mesh.valence(v));
  std::vector<char> can_move(nv);
  for (auto v : mesh.vertices()) can_move[v.idx()] = movable(v);
  auto candidate = [&](TriMesh::HalfedgeHandle h) {
    return !mesh.status(mesh.edge_handle(h)).deleted() && can_move[mesh.from_vertex_handle(h).idx()] &&
           can_move[mesh.to_vertex_handle(h).idx()] &&
           merged_valence(mesh, valence, h) <= options.max_valence;
  };

  CollapseQueue queue(options.max_valence, static_cast<int>(mesh.n_halfedges()));
  for (auto h : mesh.halfedges())
    if (candidate(h)) queue.push(merged_valence(mesh, valence, h), h.idx());

  std::vector<int> parent(nv);
  for (int v = 0; v < nv; ++v) parent[v] = v;
  SimplifiedGraph s;
  int queued = 0, index = 0;
  while (queue.pop(&queued, &index)) {
    const auto h = mesh.halfedge_handle(index);
    if (!candidate(h)) continue;
    const int now = merged_valence(mesh, valence, h);
    if (now != queued) {
      queue.push(now, index);
      continue;
    }
    if (!mesh.is_collapse_ok(h)) continue;
    const auto v0 = mesh.from_vertex_handle(h), v1 = mesh.to_vertex_handle(h);
    // Only v1 and the vertices opposite the collapsed edge (they lose that edge's duplicate) change
    // valence: the link condition leaves no other common neighbour of v0 and v1.
    std::array<TriMesh::VertexHandle, 2> wings;
    for (int side = 0; side < 2; ++side) {
      const auto hs = side == 0 ? h : mesh.opposite_halfedge_handle(h);
      wings[side] = mesh.is_boundary(hs) ? TriMesh::VertexHandle()
                                         : mesh.to_vertex_handle(mesh.next_halfedge_handle(hs));
    }
    mesh.collapse(h);
    parent[v0.idx()] = v1.idx();
    ++s.collapses;
    valence[v1.idx()] = static_cast<int>(mesh.valence(v1));
    for (auto w : wings)
      if (w.is_valid()) valence[w.idx()] = static_cast<int>(mesh.valence(w));
    for (auto out : mesh.voh_range(v1)) {
      for (auto hh : {out, mesh.opposite_halfedge_handle(out)})
        if (candidate(hh)) queue.push(merged_valence(mesh, valence, hh), hh.idx());
    }
  }

  // Coarse vertices: the survivors, in proxy order.
  std::vector<int> coarse_index(nv, -1);
  for (int v = 0; v < nv; ++v)
    if (parent[v] == v) {
      coarse_index[v] = s.vertex_count++;
      s.coarse_to_fine.push_back(v);
    }
  s.fine_to_coarse.resize(nv);
  for (int v = 0; v < nv; ++v) {
    int r = v;
    while (parent[r] != r) r = parent[r];
    s.fine_to_coarse[v] = coarse_index[r];
  }

  // Coarse edges with weights from the coarse geometry (App. C: w_e c_e).
  for (auto e : mesh.edges()) {
    if (mesh.status(e).deleted()) continue;
    const auto h0 = mesh.halfedge_handle(e, 0);
    const int a = mesh.from_vertex_handle(h0).idx(), b = mesh.to_vertex_handle(h0).idx();
    // Edges between two vertices on crossed edges are untouched proxy edges; only those can be
    // crossed, so the proxy's flag of this edge index still applies.
    const bool crossed = graph.crossed[e.idx()] != 0;
    double weight = crossed ? association.crossed_weight : association.uncrossed_weight;
    if (association.scale_by_edge_size) weight *= edge_size(mesh, e) / graph.edge_size_reference;
    s.edges.push_back({coarse_index[a], coarse_index[b]});
    s.weights.push_back(weight);
  }
  return s;
}

}  // namespace sketchsurf
