#pragma once
// Insertion of segmentation boundaries (paper §4.3, "Insertion of segmentation boundaries"):
// split the proxy triangles crossed by region boundaries so that every boundary runs along mesh
// edges and can become a sharp crease.

#include <string>
#include <vector>

#include "surfacing/mesh.h"
#include "surfacing/segment/implicit.h"

namespace sketchsurf {

/// A mesh whose vertices carry one to three region labels: the paper's multi-labeling \hat{l}.
struct LabeledMesh {
  TriMesh mesh;
  /// Per vertex: the labels (indices into the models), sorted, 1 to 3 of them. Proxy vertices
  /// keep their one label; vertices inserted on a crossed edge carry the 2 labels it separates;
  /// a vertex inserted inside a triangle whose corners have 3 labels carries all 3.
  std::vector<std::vector<int>> labels;
  /// Per vertex: the proxy vertex it copies, or -1 for an inserted (seam) vertex.
  std::vector<int> source_vertex;

  bool is_seam(int v) const { return labels[v].size() > 1; }
};

/// The region of face f of `mesh` (F: its faces as a matrix): the label its three vertices share
/// (seams are inserted so that every face lies in one region); the first vertex's first label
/// when none is shared.
int face_region(const LabeledMesh& mesh, const Eigen::MatrixX3i& F, int f);

/// Options for insert_seams().
struct SeamOptions {
  double edge_margin = 0.15;  ///< inserted vertices stay in [margin, 1 - margin] of the crossed
                              ///< edge (fraction of its length), so no triangle degenerates (ours)
  int samples = 24;           ///< samples along an edge (and per side of a triangle's barycentric
                              ///< grid) when searching where the two surfaces are closest (ours)
  unsigned threads = 0;       ///< threads placing the vertices (0 = all); the result does not
                              ///< depend on it
  bool valid(std::string* why) const;
};

/// Splits every triangle of `proxy` whose corners do not all have the same label:
/// - two labels (a, a, b): a vertex on each of the two crossed edges, the b corner becomes its
///   own triangle, the rest a quad split in two (3 triangles);
/// - three labels (a, b, c): a vertex on each edge plus one inside with labels {a, b, c}, each
///   corner keeping a quad (6 triangles).
/// A vertex inserted on edge (u, v) is placed where its two surfaces are closest along the edge:
/// the t in [margin, 1 - margin] minimising dist_a(x(t))^2 + dist_b(x(t))^2 (Taubin distances,
/// Eq. 5), found by sampling then golden-section refinement; the inner vertex likewise over the
/// triangle. Edges are shared, so both triangles of a crossed edge use the same inserted vertex.
/// labels: one per proxy vertex, in [0, #models). The result has the proxy's orientation.
/// Throws Error (Usage) for a label count or a label outside the models, or invalid options.
LabeledMesh insert_seams(const TriMesh& proxy, const std::vector<int>& labels,
                         const std::vector<ImplicitModel>& models, const SeamOptions& options = {});

}  // namespace sketchsurf
