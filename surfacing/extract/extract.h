#pragma once
// The final surface (paper §4.3, §5 "Symmetric sketches" and "Open surfaces", App. D): from a
// proxy, its labeling and the region models to a triangle mesh with sharp creases where regions
// meet at an angle. Stages: trim (open surfaces) -> insert seams -> optimise E_mesh -> mirror.

#include <cstdint>
#include <string>
#include <vector>

#include "surfacing/extract/back_sides.h"
#include "surfacing/extract/mirror.h"
#include "surfacing/extract/outline.h"
#include "surfacing/extract/optimize.h"
#include "surfacing/extract/seams.h"
#include "surfacing/extract/smooth_fallback.h"
#include "surfacing/extract/trim.h"
#include "surfacing/extract/unfold.h"
#include "surfacing/mesh.h"
#include "surfacing/progress.h"
#include "surfacing/segment/implicit.h"
#include "surfacing/sketch/sketch.h"

namespace sketchsurf {

/// Every option of the final-surface stages, with the paper's defaults.
struct ExtractOptions {
  SeamOptions seams;         ///< seam insertion (§4.3)
  MeshEnergyOptions energy;  ///< E_mesh and its solver (Eq. 7-9, 13)
  TrimOptions trim;          ///< open surfaces (App. D)
  SmoothFallbackOptions smooth_fallback;  ///< the proxy where the models cannot follow the strokes
  BackSideOptions back_sides;  ///< thin parts' two sides kept apart (back_sides.h)
  OutlineOptions outline;      ///< flat regions end at their drawn outline (outline.h)
  UnfoldOptions unfold;        ///< folds ironed out after the solve (unfold.h)
  double plane_tolerance = 1e-6;  ///< boundary vertices this close to the mirror plane lie on it
                                  ///< (fraction of the diagonal)
  std::vector<Plane> drawn_faces;  ///< faces the automatic proxy drew in (ProxyReport::drawn_faces;
                                   ///< set by the Surfacer): proxy vertices on them are
                                   ///< MeshConstraints::on_drawn_face
  double face_tolerance = 1e-4;    ///< a proxy vertex this close to a drawn face lies on it
                                   ///< (fraction of the diagonal; 0 = no vertex does) ...
  double face_share = 0.5;         ///< ... and counts as on it when at least this share of each of
                                   ///< its regions' vertices lie on drawn faces
  bool valid(std::string* why) const;
};

/// Distance from the stroke points to a surface: fractions of the sketch's bounding-box diagonal.
struct StrokeDistance {
  double median = 0.0;
  double p95 = 0.0;
  double max = 0.0;
  std::size_t points = 0;  ///< stroke points measured (ignored strokes are not)
};

/// Distance from every point of the non-ignored strokes of `sketch` (and their mirror images when
/// sketch.mirror is set and `mirrored` is true) to `mesh`, as fractions of `diagonal`.
/// A mesh without faces gives infinite distances. The points are measured on `threads` threads
/// (0 = all); the result does not depend on them.
StrokeDistance stroke_distance(const TriMesh& mesh, const Sketch& sketch, double diagonal,
                               bool mirrored = false, unsigned threads = 0);

/// What extract() did.
struct ExtractSummary {
  OptimizeSummary optimization;         ///< the solve of E_mesh
  SmoothFallbackSummary smooth_fallback;  ///< regions and parts kept at the proxy
  UnfoldSummary unfold;                 ///< folds ironed out after the solve
  std::size_t proxy_vertices = 0;
  std::size_t trimmed_faces = 0;        ///< proxy faces removed by the open-surface cut
  std::size_t seam_vertices = 0;        ///< inserted vertices with 2 labels
  std::size_t corner_vertices = 0;      ///< inserted vertices with 3 labels
  std::size_t sharp_vertices = 0;       ///< vertices flagged sharp in the output
  std::size_t attracted_vertices = 0;   ///< open-boundary vertices with an Eq. 13 target
  std::size_t back_side_vertices = 0;   ///< thin parts' far sides moved just inside their
                                        ///< region's surface (back_sides.h)
  std::size_t output_vertices = 0;
  std::size_t output_faces = 0;
  bool open = false;                    ///< trimmed along boundary strokes
  bool mirrored = false;                ///< half surface mirrored and welded
  StrokeDistance stroke_distance;       ///< fit of the result to the strokes
  double trim_s = 0.0, seams_s = 0.0, optimize_s = 0.0, mirror_s = 0.0, total_s = 0.0;  ///< seconds
};

/// The final mesh with its per-vertex data.
struct ExtractedSurface {
  TriMesh mesh;
  std::vector<int> labels;           ///< per vertex: its region (the lowest of its labels)
  std::vector<std::uint8_t> sharp;   ///< per vertex: 1 on a crease (seam vertex with w_v < 1)
  ExtractSummary summary;
};

/// Final mesh from a proxy, its labeling and models (paper §4.3).
/// proxy: triangle mesh, in the sketch's units; labels: one per proxy vertex, indices into
/// `models`; sketch: the strokes the labels were computed from. When sketch.mirror is set, the
/// proxy and the sketch are the halves on the positive side of the plane (clip_to_half_space,
/// half_sketch) and the result is mirrored and welded. Boundary strokes (Stroke::boundary) trim
/// the proxy (App. D) and attract the new boundary (Eq. 13).
/// Throws Error (Usage) on mismatched labels/models or invalid options, Error (Processing) for an
/// empty sketch or proxy and when a stage cannot proceed (message says what to do),
/// Error (Cancelled) through `progress`.
ExtractedSurface extract(const TriMesh& proxy, const std::vector<int>& labels,
                         const std::vector<ImplicitModel>& models, const Sketch& sketch,
                         const ExtractOptions& options, const Progress& progress = {});

/// The same, returning the mesh only.
TriMesh extract_surface(const TriMesh& proxy, const std::vector<int>& labels,
                        const std::vector<ImplicitModel>& models, const Sketch& sketch,
                        const ExtractOptions& options, const Progress& progress,
                        ExtractSummary* summary);

}  // namespace sketchsurf
