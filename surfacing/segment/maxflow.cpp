#include "surfacing/segment/maxflow.h"

#include <boost/graph/boykov_kolmogorov_max_flow.hpp>
#include <boost/graph/compressed_sparse_row_graph.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "surfacing/error.h"

namespace sketchsurf {
namespace {

using Graph = boost::compressed_sparse_row_graph<boost::directedS, boost::no_property,
                                                 boost::no_property, boost::no_property, int, int>;
using GraphEdge = boost::graph_traits<Graph>::edge_descriptor;

void check_capacity(double c, const char* what) {
  if (!(std::isfinite(c) && c >= 0.0))
    throw Error::usage(std::string("MaxFlow: ") + what + " must be finite and >= 0, got " +
                       std::to_string(c));
}

}  // namespace

MaxFlow::MaxFlow(int nodes) { clear(nodes); }

void MaxFlow::clear(int nodes) {
  if (nodes < 0) throw Error::usage("MaxFlow: negative node count " + std::to_string(nodes));
  source_capacity_.assign(nodes, 0.0);
  sink_capacity_.assign(nodes, 0.0);
  edges_.clear();
  solved_ = false;
}

int MaxFlow::add_node() {
  source_capacity_.push_back(0.0);
  sink_capacity_.push_back(0.0);
  solved_ = false;
  return node_count() - 1;
}

void MaxFlow::check_node(int node) const {
  if (node < 0 || node >= node_count())
    throw Error::usage("MaxFlow: node " + std::to_string(node) + " out of range 0.." +
                       std::to_string(node_count() - 1));
}

void MaxFlow::add_terminal_weights(int node, double source_capacity, double sink_capacity) {
  check_node(node);
  check_capacity(source_capacity, "source capacity");
  check_capacity(sink_capacity, "sink capacity");
  source_capacity_[node] += source_capacity;
  sink_capacity_[node] += sink_capacity;
  solved_ = false;
}

void MaxFlow::add_edge(int u, int v, double capacity_uv, double capacity_vu) {
  check_node(u);
  check_node(v);
  if (u == v) throw Error::usage("MaxFlow: self-loop on node " + std::to_string(u));
  check_capacity(capacity_uv, "edge capacity");
  check_capacity(capacity_vu, "edge capacity");
  if (capacity_uv == 0.0 && capacity_vu == 0.0) return;
  edges_.push_back({u, v, capacity_uv, capacity_vu});
  solved_ = false;
}

double MaxFlow::solve() {
  const int n = node_count();
  const int s = n, t = n + 1, vertices = n + 2;

  // Flow that goes s -> v -> t directly is pushed here: it is min(source, sink) for every node.
  double flow = 0.0;
  std::vector<double> source_residual(n), sink_residual(n);
  for (int v = 0; v < n; ++v) {
    const double direct = std::min(source_capacity_[v], sink_capacity_[v]);
    flow += direct;
    source_residual[v] = source_capacity_[v] - direct;
    sink_residual[v] = sink_capacity_[v] - direct;
  }

  // Arcs in pairs (a -> b, b -> a), sorted by tail with a counting sort; arc_position_ holds the
  // index of each arc's reverse.
  offsets_.assign(vertices + 1, 0);
  auto for_each_pair = [&](auto&& visit) {
    for (const Edge& e : edges_) visit(e.u, e.v, e.capacity_uv, e.capacity_vu);
    for (int v = 0; v < n; ++v) {
      if (source_residual[v] > 0.0) visit(s, v, source_residual[v], 0.0);
      if (sink_residual[v] > 0.0) visit(v, t, sink_residual[v], 0.0);
    }
  };
  for_each_pair([&](int a, int b, double, double) {
    ++offsets_[a + 1];
    ++offsets_[b + 1];
  });
  for (int v = 0; v < vertices; ++v) offsets_[v + 1] += offsets_[v];
  const int arcs = offsets_[vertices];
  arc_head_.resize(arcs);
  arc_capacity_.resize(arcs);
  arc_position_.resize(arcs);
  std::vector<int> cursor(offsets_.begin(), offsets_.end() - 1);
  for_each_pair([&](int a, int b, double c_ab, double c_ba) {
    const int pa = cursor[a]++, pb = cursor[b]++;
    arc_head_[pa] = b;
    arc_head_[pb] = a;
    arc_capacity_[pa] = c_ab;
    arc_capacity_[pb] = c_ba;
    arc_position_[pa] = pb;
    arc_position_[pb] = pa;
  });

  std::vector<std::pair<int, int>> sorted_arcs(arcs);
  std::vector<int> tail(arcs);
  for (int v = 0; v < vertices; ++v)
    for (int a = offsets_[v]; a < offsets_[v + 1]; ++a) {
      sorted_arcs[a] = {v, arc_head_[a]};
      tail[a] = v;
    }
  const Graph graph(boost::edges_are_sorted, sorted_arcs.begin(), sorted_arcs.end(), vertices,
                    arcs);
  const auto edge_index = get(boost::edge_index, graph);
  std::vector<GraphEdge> reverse(arcs);
  for (int a = 0; a < arcs; ++a) reverse[a] = GraphEdge(tail[arc_position_[a]], arc_position_[a]);
  std::vector<double> residual(arcs);
  std::vector<GraphEdge> predecessor(vertices);
  std::vector<boost::default_color_type> color(vertices);
  std::vector<long> distance(vertices);

  flow += boost::boykov_kolmogorov_max_flow(
      graph, boost::make_iterator_property_map(arc_capacity_.begin(), edge_index),
      boost::make_iterator_property_map(residual.begin(), edge_index),
      boost::make_iterator_property_map(reverse.begin(), edge_index), predecessor.data(),
      color.data(), distance.data(), get(boost::vertex_index, graph), s, t);

  source_side_.resize(n);
  for (int v = 0; v < n; ++v)
    source_side_[v] = color[v] == boost::color_traits<boost::default_color_type>::black();
  solved_ = true;
  return flow;
}

bool MaxFlow::on_source_side(int node) const {
  check_node(node);
  if (!solved_) throw Error::usage("MaxFlow: on_source_side() called before solve()");
  return source_side_[node] != 0;
}

}  // namespace sketchsurf
