#pragma once
// Open surfaces (paper §5 "Open surfaces", App. D): a graph cut on the proxy separates the inside
// of the surface from the outside along the strokes marked as boundaries, and the outside is
// trimmed away; the new boundary is then attracted to those strokes (Eq. 13).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "surfacing/extract/optimize.h"
#include "surfacing/mesh.h"
#include "surfacing/sketch/sketch.h"

namespace sketchsurf {

/// Options of trim_open_surface() and boundary_targets(). Distances are fractions of the
/// sketch's bounding-box diagonal.
struct TrimOptions {
  double inside_distance = 0.03;   ///< vertices with stroke points geodesically farther than this
                                   ///< from the boundary strokes are inside (sink seeds, App. D)
  double outside_distance = 0.1;   ///< on a closed proxy (no boundary of its own), vertices
                                   ///< farther than this from every stroke point are outside
                                   ///< (source seeds) (ours)
  double attract_distance = 0.03;  ///< open-boundary vertices farther than this from every boundary
                                   ///< stroke are not attracted (Eq. 13 targets) (ours)
  bool valid(std::string* why) const;
};

/// The trimmed proxy and what the cut did.
struct TrimResult {
  TriMesh mesh;
  std::vector<int> source_vertex;  ///< per vertex of `mesh`: its index in the input proxy
  std::size_t removed_faces = 0;
  std::size_t source_seeds = 0;    ///< vertices tied to the outside
  std::size_t sink_seeds = 0;      ///< vertices tied to the inside
  std::size_t crossed_edges = 0;   ///< proxy edges crossed by boundary strokes (cut cost 0)
  double cut_cost = 0.0;           ///< min-cut cost, in mean proxy edge lengths
};

/// App. D: projects the boundary strokes of `sketch` (Stroke::boundary, not ignored) onto `proxy`
/// (association of App. A); edges they cross cost 0 to cut, every other edge its length. Source
/// (outside): the proxy's boundary vertices, except those within `plane_tolerance` (mesh units) of
/// the mirror plane; when there are none (closed proxy), the vertices that cap a boundary loop
/// with nothing drawn across it (inside its outline, on its empty side: stroke_loop() and
/// loop_sides() of openings.h with their default tests; a loop cut by the mirror plane is
/// completed by its image), or without such a loop the vertices farther than outside_distance
/// from every stroke point. Sink
/// (inside): vertices with stroke points of non-boundary strokes, geodesically farther than
/// inside_distance from the boundary strokes. Faces with an outside corner are removed, then the
/// connected parts without inside vertices.
/// diagonal: the sketch's bounding-box diagonal (mesh units).
/// Throws Error (Processing) with what to do when there is no inside or no outside, Error (Usage)
/// when the sketch has no boundary stroke or the options are invalid.
TrimResult trim_open_surface(const TriMesh& proxy, const Sketch& sketch,
                             const std::optional<Plane>& mirror, double plane_tolerance,
                             double diagonal, const TrimOptions& options = {});

/// Eq. 13 targets: for each boundary vertex of `mesh` not flagged in `exclude` (per vertex, may be
/// empty), the closest point on the polylines of the boundary strokes, when it is within
/// attract_distance * diagonal.
std::vector<AttractTarget> boundary_targets(const TriMesh& mesh, const Sketch& sketch,
                                            const std::vector<std::uint8_t>& exclude,
                                            double diagonal, const TrimOptions& options = {});

}  // namespace sketchsurf
