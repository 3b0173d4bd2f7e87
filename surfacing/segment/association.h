#pragma once
// Strokes to proxy (paper §4.1, App. A, App. C): which stroke points each proxy vertex sees, which
// proxy edges the projected strokes cross, and the weighted graph that E_smoothness runs on.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "surfacing/closest_face.h"
#include "surfacing/mesh.h"
#include "surfacing/segment/crease_guides.h"
#include "surfacing/sketch/sketch.h"

namespace sketchsurf {

/// Options for associate().
struct AssociationOptions {
  double crossed_weight = 1.0;     ///< w_e of an edge crossed by a projected stroke segment (§4.1)
  double uncrossed_weight = 100.0; ///< w_e of every other edge (§4.1)
  bool scale_by_edge_size = true;  ///< multiply w_e by c_e / mean(c_e), c_e = distance between the
                                   ///< two vertices opposite the edge (App. C); ~1 on uniform meshes
  double max_segment = 1.0;        ///< stroke segments longer than this many mean proxy edge lengths
                                   ///< are split before tracing, so paths follow the stroke (ours)
  int max_path_faces = 4096;       ///< a dual-graph search that visits more faces than this gives
                                   ///< up: the segment jumps between unconnected parts (ours)
  CreaseGuideOptions guides;       ///< creases joined from the strokes' corners: their edges are
                                   ///< crossed too, with no sample (ours)
  unsigned threads = 0;            ///< worker threads (0 = all); the result does not depend on it
  bool valid(std::string* why) const;
};

/// The proxy as a weighted graph with stroke points attached to its vertices (the paper's
/// P_v, w_e). Units are those of the inputs given to associate().
struct StrokeGraph {
  Eigen::MatrixX3d positions;             ///< #V x 3 proxy vertex positions
  Eigen::MatrixX3d normals;               ///< #V x 3 unit area-weighted vertex normals
  std::vector<std::array<int, 2>> edges;  ///< #E vertex pairs, in the proxy's edge order
  std::vector<double> weights;            ///< #E smoothness weights w_e (times c_e when scaled)
  std::vector<std::uint8_t> crossed;      ///< #E 1 when a projected stroke segment or crease guide
                                          ///< crosses the edge
  double edge_size_reference = 1.0;       ///< mean c_e the weights were divided by (App. C)
  Eigen::MatrixX3d points;                ///< #P x 3 stroke samples attached to some vertex
  std::vector<int> point_offsets;         ///< #V + 1; P_v = point_indices[offsets[v], offsets[v+1])
  std::vector<int> point_indices;         ///< indices into `points`
  std::size_t crossings = 0;              ///< (edge, sample) attachments made while tracing
  std::size_t skipped_segments = 0;       ///< segments whose endpoints were not connected on the proxy
  std::size_t guides = 0;                 ///< crease guides traced (crease_guides.h)

  int vertex_count() const { return static_cast<int>(positions.rows()); }
  /// P_v: indices of the stroke points associated with vertex v.
  std::span<const int> points_of(int v) const {
    return {point_indices.data() + point_offsets[v],
            static_cast<std::size_t>(point_offsets[v + 1] - point_offsets[v])};
  }
  /// N_p of Eq. 2: sum over vertices of |P_v|.
  std::size_t association_count() const { return point_indices.size(); }
};

/// c_e of App. C: the distance between the two vertices opposite edge e; on a border, twice the
/// distance from the one opposite vertex to the edge's midpoint.
double edge_size(const TriMesh& mesh, TriMesh::EdgeHandle e);

/// Associates the sketch's strokes with the proxy (App. A): every stroke point is projected onto
/// its closest face; every stroke segment is traced as a shortest path in the dual graph between
/// the faces of its endpoints; a segment that crosses n primal edges gets n evenly spaced samples,
/// the i-th attached to the i-th crossed edge; each vertex v gets, for every edge of its 1-ring, the
/// attached sample closest to v. Ignored strokes (§6.3) are skipped; boundary strokes are used.
/// Both inputs in the same units (callers normalise to a unit diagonal first, METHOD.md).
/// Throws Error (Processing) when the proxy has no triangle, Error (Usage) on invalid options.
StrokeGraph associate(const Sketch& sketch, const TriMesh& proxy,
                      const AssociationOptions& options = {});

}  // namespace sketchsurf
