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

void check_capacity(double c, const char* what) {
  if (!(std::isfinite(c) && c >= 0.0))
    throw Error::usage(std::string("MaxFlow: ") + what + " must be finite and >= 0, got " +
                       std::to_string(c));
}

// The same cut with Boost.Graph's boykov_kolmogorov_max_flow (source s = n, sink t = n + 1).
double boost_max_flow(const std::vector<int>& offsets, const std::vector<int>& head,
                      const std::vector<int>& sister, const std::vector<double>& capacity,
                      const std::vector<double>& terminal, std::vector<unsigned char>* source_side) {
  using Graph = boost::compressed_sparse_row_graph<boost::directedS, boost::no_property,
                                                   boost::no_property, boost::no_property, int, int>;
  using GraphEdge = boost::graph_traits<Graph>::edge_descriptor;
  const int n = static_cast<int>(terminal.size()), s = n, t = n + 1;
  // Arcs: the node arcs in order, then s -> v / v -> s and v -> t / t -> v pairs, sorted by tail.
  std::vector<std::pair<int, int>> arcs;
  std::vector<double> arc_capacity;
  std::vector<int> arc_sister, arc_tail;
  std::vector<std::vector<std::pair<int, double>>> out(n + 2);  // (head, capacity) per extra arc
  for (int v = 0; v < n; ++v) {
    if (terminal[v] > 0.0) {
      out[s].push_back({v, terminal[v]});
      out[v].push_back({s, 0.0});
    } else if (terminal[v] < 0.0) {
      out[v].push_back({t, -terminal[v]});
      out[t].push_back({v, 0.0});
    }
  }
  std::vector<int> start(n + 3, 0);
  for (int v = 0; v < n + 2; ++v)
    start[v + 1] = start[v] + (v < n ? offsets[v + 1] - offsets[v] : 0) +
                   static_cast<int>(out[v].size());
  const int total = start[n + 2];
  arcs.resize(total);
  arc_capacity.resize(total);
  arc_sister.assign(total, -1);
  arc_tail.resize(total);
  // Position of node arc a and of the k-th extra arc of v.
  auto node_arc = [&](int a, int v) { return start[v] + (a - offsets[v]); };
  auto extra_arc = [&](int v, int k) {
    return start[v] + (v < n ? offsets[v + 1] - offsets[v] : 0) + k;
  };
  for (int v = 0; v < n; ++v)
    for (int a = offsets[v]; a < offsets[v + 1]; ++a) {
      const int p = node_arc(a, v);
      arcs[p] = {v, head[a]};
      arc_capacity[p] = capacity[a];
      arc_sister[p] = node_arc(sister[a], head[a]);
      arc_tail[p] = v;
    }
  for (int v = 0; v < n + 2; ++v)
    for (int k = 0; k < static_cast<int>(out[v].size()); ++k) {
      const int p = extra_arc(v, k);
      arcs[p] = {v, out[v][k].first};
      arc_capacity[p] = out[v][k].second;
      arc_tail[p] = v;
    }
  // Pair the terminal arcs: for node v, its single terminal arc pairs with the one at s or t.
  int next_at_s = 0, next_at_t = 0;
  for (int v = 0; v < n; ++v) {
    if (terminal[v] == 0.0) continue;
    const int own = extra_arc(v, 0);
    const int other = terminal[v] > 0.0 ? extra_arc(s, next_at_s++) : extra_arc(t, next_at_t++);
    arc_sister[own] = other;
    arc_sister[other] = own;
  }
  const Graph graph(boost::edges_are_sorted, arcs.begin(), arcs.end(), n + 2, total);
  const auto edge_index = get(boost::edge_index, graph);
  std::vector<GraphEdge> reverse(total);
  for (int p = 0; p < total; ++p) reverse[p] = GraphEdge(arc_tail[arc_sister[p]], arc_sister[p]);
  std::vector<double> residual(total);
  std::vector<GraphEdge> predecessor(n + 2);
  std::vector<boost::default_color_type> color(n + 2);
  std::vector<long> distance(n + 2);
  const double flow = boost::boykov_kolmogorov_max_flow(
      graph, boost::make_iterator_property_map(arc_capacity.begin(), edge_index),
      boost::make_iterator_property_map(residual.begin(), edge_index),
      boost::make_iterator_property_map(reverse.begin(), edge_index), predecessor.data(),
      color.data(), distance.data(), get(boost::vertex_index, graph), s, t);
  source_side->resize(n);
  for (int v = 0; v < n; ++v)
    (*source_side)[v] = color[v] == boost::color_traits<boost::default_color_type>::black();
  return flow;
}

}  // namespace

namespace detail {

// Boykov-Kolmogorov augmenting paths on a residual graph in compressed sparse row form: arcs of
// node v are offsets[v] .. offsets[v+1]-1, sister[a] is the reverse arc, terminal[v] > 0 is the
// residual capacity s -> v and terminal[v] < 0 minus the residual capacity v -> t.
// (Boykov and Kolmogorov 2004: two search trees grown from s and t, augment, adopt orphans; with
// the distance / timestamp heuristic for choosing new parents.)
// The work arrays persist between runs (no page faults from fresh allocations on every cut).
class BoykovKolmogorov {
 public:
  // Returns the flow pushed through the non-terminal arcs; on_source_side() then tells the cut.
  double run(const std::vector<int>& offsets, const std::vector<int>& head,
             const std::vector<int>& sister, std::vector<double>& residual,
             std::vector<double>& terminal) {
    offsets_ = offsets.data();
    head_ = head.data();
    sister_ = sister.data();
    residual_ = residual.data();
    terminal_ = terminal.data();
    time_ = 0;
    orphans_.clear();
    const int n = static_cast<int>(terminal.size());
    tree_.assign(n, kFree);
    parent_.assign(n, kNone);
    stamp_.assign(n, 0);
    distance_.assign(n, 0);
    queued_.assign(n, 0);
    active_.clear();
    active_head_ = 0;
    for (int v = 0; v < n; ++v)
      if (terminal_[v] != 0.0) {
        tree_[v] = terminal_[v] > 0.0 ? kSource : kSink;
        parent_[v] = kTerminal;
        distance_[v] = 1;
        activate(v);
      }

    double flow = 0.0;
    int current = -1, position = 0;
    while (true) {
      if (current < 0 || tree_[current] == kFree) {
        current = next_active();
        if (current < 0) break;
        position = offsets_[current];
      }
      const int middle = grow(current, &position);
      if (middle < 0) {
        current = -1;  // exhausted: every neighbour is in a tree
        continue;
      }
      ++time_;
      flow += augment(middle);
      adopt();
      // `current` may have more paths to the other tree: resume its scan at the arc that gave
      // this one. The arcs before it cannot have gained growth capacity, and a neighbour that
      // adoption freed re-activates `current` through the adoption's own rule.
    }
    return flow;
  }

  bool on_source_side(int v) const { return tree_[v] == kSource; }

 private:
  static constexpr unsigned char kFree = 0, kSource = 1, kSink = 2;
  static constexpr int kNone = -1, kTerminal = -2, kOrphan = -3;

  void activate(int v) {
    if (queued_[v]) return;
    queued_[v] = 1;
    active_.push_back(v);
  }
  int next_active() {
    while (active_head_ < active_.size()) {
      const int v = active_[active_head_++];
      queued_[v] = 0;
      if (tree_[v] != kFree) return v;
    }
    active_.clear();
    active_head_ = 0;
    return -1;
  }

  // Residual capacity of arc a in the direction that lets the tree of its tail grow over it:
  // a itself (tail -> head) for the source tree, its sister (head -> tail) for the sink tree.
  double growth_capacity(int a, unsigned char tree) const {
    return tree == kSource ? residual_[a] : residual_[sister_[a]];
  }

  // Grows the tree of node i over its arcs from *position on; returns the arc (source tree ->
  // sink tree) of a found s-t path, leaving *position at the arc that reached it, or -1.
  int grow(int i, int* position) {
    const unsigned char t = tree_[i];
    for (int& a = *position; a < offsets_[i + 1]; ++a) {
      if (growth_capacity(a, t) <= 0.0) continue;
      const int j = head_[a];
      if (tree_[j] == kFree) {
        tree_[j] = t;
        parent_[j] = sister_[a];  // arc j -> i
        stamp_[j] = stamp_[i];
        distance_[j] = distance_[i] + 1;
        activate(j);
      } else if (tree_[j] != t) {
        return t == kSource ? a : sister_[a];
      } else if (stamp_[j] <= stamp_[i] && distance_[j] > distance_[i]) {
        parent_[j] = sister_[a];  // a shorter way to the terminal
        stamp_[j] = stamp_[i];
        distance_[j] = distance_[i] + 1;
      }
    }
    return -1;
  }

  void make_orphan(int v) {
    parent_[v] = kOrphan;
    orphans_.push_back(v);
  }

  // Pushes the bottleneck along s -> ... -> tail(m) -> head(m) -> ... -> t.
  double augment(int m) {
    const int u = head_[sister_[m]], v = head_[m];
    double bottleneck = residual_[m];
    int x = u;
    for (; parent_[x] != kTerminal; x = head_[parent_[x]])
      bottleneck = std::min(bottleneck, residual_[sister_[parent_[x]]]);
    bottleneck = std::min(bottleneck, terminal_[x]);
    for (x = v; parent_[x] != kTerminal; x = head_[parent_[x]])
      bottleneck = std::min(bottleneck, residual_[parent_[x]]);
    bottleneck = std::min(bottleneck, -terminal_[x]);

    residual_[m] -= bottleneck;
    residual_[sister_[m]] += bottleneck;
    // Source side: flow runs parent -> x over sister(parent[x]).
    for (x = u;;) {
      const int a = parent_[x];
      if (a == kTerminal) {
        terminal_[x] -= bottleneck;
        if (terminal_[x] <= 0.0) {
          terminal_[x] = 0.0;
          make_orphan(x);
        }
        break;
      }
      residual_[a] += bottleneck;
      residual_[sister_[a]] -= bottleneck;
      const int next = head_[a];
      if (residual_[sister_[a]] <= 0.0) make_orphan(x);
      x = next;
    }
    // Sink side: flow runs x -> parent over parent[x].
    for (x = v;;) {
      const int a = parent_[x];
      if (a == kTerminal) {
        terminal_[x] += bottleneck;
        if (terminal_[x] >= 0.0) {
          terminal_[x] = 0.0;
          make_orphan(x);
        }
        break;
      }
      residual_[sister_[a]] += bottleneck;
      residual_[a] -= bottleneck;
      const int next = head_[a];
      if (residual_[a] <= 0.0) make_orphan(x);
      x = next;
    }
    return bottleneck;
  }

  // Capacity that lets node j (same tree as x) be x's parent over arc a (x -> j).
  double parent_capacity(int a, unsigned char tree) const {
    return tree == kSource ? residual_[sister_[a]] : residual_[a];
  }

  // Finds each orphan a new parent in its tree whose path reaches the terminal, or frees it.
  void adopt() {
    // First in, first out: parents are adopted (or freed) before their children are looked at.
    for (std::size_t next_orphan = 0; next_orphan < orphans_.size(); ++next_orphan) {
      const int x = orphans_[next_orphan];
      const unsigned char t = tree_[x];
      int best_arc = kNone, best_distance = 0;
      for (int a = offsets_[x]; a < offsets_[x + 1]; ++a) {
        const int j = head_[a];
        if (tree_[j] != t || parent_capacity(a, t) <= 0.0) continue;
        // Is j rooted at the terminal? Walk up, using stamps to stop at checked nodes.
        int d = 0, k = j;
        bool rooted = false;
        while (true) {
          if (stamp_[k] == time_) {
            d += distance_[k];
            rooted = true;
            break;
          }
          const int p = parent_[k];
          ++d;
          if (p == kTerminal) {
            stamp_[k] = time_;
            distance_[k] = 1;
            rooted = true;
            break;
          }
          if (p == kOrphan || p == kNone) break;
          k = head_[p];
        }
        if (!rooted) continue;
        if (best_arc == kNone || d < best_distance) {
          best_arc = a;
          best_distance = d;
        }
        for (k = j; stamp_[k] != time_; k = head_[parent_[k]]) {
          stamp_[k] = time_;
          distance_[k] = d--;
        }
      }
      if (best_arc != kNone) {
        parent_[x] = best_arc;
        stamp_[x] = time_;
        distance_[x] = best_distance + 1;
        continue;
      }
      // No parent: x leaves its tree; neighbours that could feed it become active again, its
      // children become orphans.
      for (int a = offsets_[x]; a < offsets_[x + 1]; ++a) {
        const int j = head_[a];
        if (tree_[j] != t) continue;
        if (parent_capacity(a, t) > 0.0) activate(j);
        const int p = parent_[j];
        if (p >= 0 && head_[p] == x) make_orphan(j);
      }
      tree_[x] = kFree;
      parent_[x] = kNone;
    }
    orphans_.clear();
  }

  const int* offsets_ = nullptr;
  const int* head_ = nullptr;
  const int* sister_ = nullptr;
  double* residual_ = nullptr;
  double* terminal_ = nullptr;
  std::vector<unsigned char> tree_, queued_;
  std::vector<int> parent_, stamp_, distance_, active_, orphans_;
  std::size_t active_head_ = 0;
  int time_ = 0;
};

}  // namespace detail

MaxFlow::MaxFlow(int nodes) : bk_(std::make_unique<detail::BoykovKolmogorov>()) { clear(nodes); }
MaxFlow::~MaxFlow() = default;
MaxFlow::MaxFlow(MaxFlow&&) noexcept = default;
MaxFlow& MaxFlow::operator=(MaxFlow&&) noexcept = default;

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

double MaxFlow::solve() { return solve(MaxFlowSolver::Native); }

double MaxFlow::solve(MaxFlowSolver solver) {
  const int n = node_count();
  // Flow that goes s -> v -> t directly is pushed here: min(source, sink) for every node; what is
  // left is one signed terminal residual per node.
  double flow = 0.0;
  terminal_.resize(n);
  for (int v = 0; v < n; ++v) {
    flow += std::min(source_capacity_[v], sink_capacity_[v]);
    terminal_[v] = source_capacity_[v] - sink_capacity_[v];
  }

  // Arcs in pairs (u -> v, v -> u), sorted by tail with a counting sort.
  offsets_.assign(n + 1, 0);
  for (const Edge& e : edges_) {
    ++offsets_[e.u + 1];
    ++offsets_[e.v + 1];
  }
  for (int v = 0; v < n; ++v) offsets_[v + 1] += offsets_[v];
  const int arcs = offsets_[n];
  arc_head_.resize(arcs);
  arc_sister_.resize(arcs);
  arc_residual_.resize(arcs);
  cursor_.assign(offsets_.begin(), offsets_.end() - 1);
  for (const Edge& e : edges_) {
    const int pu = cursor_[e.u]++, pv = cursor_[e.v]++;
    arc_head_[pu] = e.v;
    arc_head_[pv] = e.u;
    arc_residual_[pu] = e.capacity_uv;
    arc_residual_[pv] = e.capacity_vu;
    arc_sister_[pu] = pv;
    arc_sister_[pv] = pu;
  }

  if (solver == MaxFlowSolver::Boost) {
    flow += boost_max_flow(offsets_, arc_head_, arc_sister_, arc_residual_, terminal_,
                           &source_side_);
  } else {
    // Paths s -> u -> v -> t first, in one pass: on expansion graphs most augmenting paths are
    // this short, and pushing them here leaves the search trees far fewer nodes to grow and
    // adopt. b is the minimum of the three capacities, so the saturated one becomes exactly 0.
    for (int u = 0; u < n; ++u)
      for (int a = offsets_[u]; a < offsets_[u + 1] && terminal_[u] > 0.0; ++a) {
        const int v = arc_head_[a];
        if (terminal_[v] >= 0.0 || arc_residual_[a] <= 0.0) continue;
        const double b = std::min({terminal_[u], arc_residual_[a], -terminal_[v]});
        terminal_[u] -= b;
        terminal_[v] += b;
        arc_residual_[a] -= b;
        arc_residual_[arc_sister_[a]] += b;
        flow += b;
      }
    flow += bk_->run(offsets_, arc_head_, arc_sister_, arc_residual_, terminal_);
    source_side_.resize(n);
    for (int v = 0; v < n; ++v) source_side_[v] = bk_->on_source_side(v);
  }
  solved_ = true;
  return flow;
}

bool MaxFlow::on_source_side(int node) const {
  check_node(node);
  if (!solved_) throw Error::usage("MaxFlow: on_source_side() called before solve()");
  return source_side_[node] != 0;
}

}  // namespace sketchsurf
