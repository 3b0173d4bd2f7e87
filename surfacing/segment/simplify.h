#pragma once
// Graph simplification away from the strokes (paper App. C): PEARL labels a coarser graph whose
// vertices near strokes are those of the proxy, and the labels go back to the proxy's vertices.

#include <array>
#include <string>
#include <vector>

#include "surfacing/mesh.h"
#include "surfacing/segment/association.h"

namespace sketchsurf {

/// Options for simplify_graph().
struct SimplifyOptions {
  int max_valence = 12;  ///< no collapse may create a vertex of higher valence (App. C)
  bool valid(std::string* why) const;
};

/// A coarse graph and the map from the proxy's vertices to its vertices.
struct SimplifiedGraph {
  int vertex_count = 0;                   ///< coarse vertices
  std::vector<int> fine_to_coarse;        ///< #V proxy vertex -> coarse vertex it was merged into
  std::vector<int> coarse_to_fine;        ///< coarse vertex -> the proxy vertex that survived
  std::vector<std::array<int, 2>> edges;  ///< coarse edges (coarse vertex pairs)
  std::vector<double> weights;            ///< w_e c_e on the coarse mesh (App. C)
  int collapses = 0;                      ///< edge collapses performed

  /// Labels of the proxy's vertices from labels of the coarse vertices (App. C propagation: a
  /// vertex takes the label of the coarse vertex it was collapsed into, its nearest survivor).
  std::vector<int> propagate(const std::vector<int>& coarse_labels) const;
};

/// Greedy halfedge collapses on `proxy` (the mesh given to associate(), same units; a copy
/// is collapsed: move the mesh in when it is no longer needed), never
/// touching a vertex with stroke points, on a crossed edge (a crease guide's) or on a mesh border, lowest resulting valence first,
/// stopping when every remaining collapse would exceed options.max_valence. Weights of the coarse
/// edges: the proxy's w_e for edges crossed by strokes (those are never collapsed), the uncrossed
/// weight otherwise, times c_e / graph.edge_size_reference when `scale_by_edge_size` (App. C).
/// Throws Error (Usage) on invalid options or when graph and proxy do not match.
SimplifiedGraph simplify_graph(TriMesh proxy, const StrokeGraph& graph,
                               const AssociationOptions& association,
                               const SimplifyOptions& options = {});

/// The identity simplification (every vertex its own coarse vertex, the graph's edges and weights).
SimplifiedGraph identity_graph(const StrokeGraph& graph);

}  // namespace sketchsurf
