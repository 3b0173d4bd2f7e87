#pragma once
// The Surfacer: runs the stages in order (prepare -> proxy -> associate + segment -> extract) with
// a progress callback, cancellation and per-stage timings, and reports on each. The stages
// themselves live in the rooms; this file only orders them.
//
// Surfacing a sketch in a few lines:
//
//   #include "surfacing/pipeline.h"
//   #include "surfacing/sketch/io/sketch_io.h"
//   #include "surfacing/sketch/io/mesh_io.h"
//
//   sketchsurf::Sketch sketch = sketchsurf::read_sketch("chair.curves");
//   sketchsurf::Params params;
//   params.apply(sketch.params);                  // parameters stored with the sketch, if any
//   const sketchsurf::SurfaceResult result = sketchsurf::Surfacer(params).run(sketch);
//   sketchsurf::write_mesh(result.mesh, "chair.ply", {.labels = result.labels, .sharp = result.sharp});

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "surfacing/extract/extract.h"
#include "surfacing/extract/tubes.h"
#include "surfacing/mesh.h"
#include "surfacing/progress.h"
#include "surfacing/proxy/proxy.h"
#include "surfacing/quality/checks.h"
#include "surfacing/segment/pearl.h"
#include "surfacing/sketch/consolidate.h"
#include "surfacing/sketch/decorations.h"
#include "surfacing/sketch/openings.h"
#include "surfacing/sketch/sketch.h"
#include "surfacing/sketch/symmetry.h"

namespace sketchsurf {

/// Input preparation (METHOD.md §0).
struct PrepareOptions {
  double resample_spacing = 0.005;  ///< stroke resampling step, fraction of the diagonal; 0 = keep
  int min_points = 2;               ///< strokes with fewer points after cleaning are dropped
  bool consolidate = false;         ///< passes of an over-sketched curve are pulled onto their
                                    ///< centre line (consolidate.h)
  ConsolidateOptions consolidation;
  bool ignore_decorations = true;   ///< strokes that depict no surface (a dot apart, a stroke
                                    ///< hanging by one end) are marked ignored (decorations.h)
  DecorationOptions decorations;
  bool decoration_tubes = false;    ///< those strokes are drawn as thin closed tubes in the output
                                    ///< (tubes.h), apart from the surface, instead of left out
  TubeOptions tubes;
  bool open_rims = true;            ///< rims with nothing drawn across or beyond them (a cup's top)
                                    ///< become boundary strokes, unless the sketch marks some
                                    ///< boundary itself (openings.h)
  OpeningOptions openings;
  MirrorDetectOptions mirror_detection;  ///< finding a mirror plane the sketch was not given
  bool complete_half = true;        ///< strokes that are one half of a symmetric object (they stop
                                    ///< on a plane, or lie on one side of the plane given) get
                                    ///< their mirror image (symmetry.h): a found half is surfaced
                                    ///< as a whole, a given plane's as a symmetric sketch
  bool valid(std::string* why) const;
};

/// Every tunable number of the pipeline: one options struct per stage.
struct Params {
  PrepareOptions prepare;
  ProxyOptions proxy;
  SegmentOptions segment;
  ExtractOptions extract;
  CheckOptions checks;  ///< the report's shape checks (thresholds decide the warnings only)

  /// Sets parameters by dotted name ("segment.epsilon", "extract.gamma_2d"), as stored in
  /// Sketch::params. Throws Error (Usage) naming an unknown parameter (and listing the known
  /// ones), a non-integer value for an integer parameter, or a result that is not valid().
  void apply(const std::map<std::string, double>& values);
  /// Every name apply() accepts, sorted.
  static std::vector<std::string> names();
  bool valid(std::string* why) const;
};

/// What the Surfacer did, stage by stage (the CLI's report.json).
struct SurfaceReport {
  CleanReport cleaning;
  Consolidation consolidation;          ///< over-sketched passes drawn together
  std::size_t strokes = 0, points = 0;  ///< after preparation (ignored strokes included)
  std::vector<Decoration> decorations;  ///< strokes ignored as depicting no surface
  std::size_t tubes = 0;                ///< tubes drawn round them (decoration_tubes; mirror images
                                        ///< counted)
  std::vector<Opening> openings;        ///< rims found and made boundary strokes
  std::string opening_failure;          ///< why the rims found could not be opened (the surface
                                        ///< was then kept closed); empty otherwise
  std::optional<DetectedMirror> symmetry;  ///< a mirror plane the strokes have, when the sketch
                                           ///< was given none (reported, not applied), or the
                                           ///< plane of half a sketch (half_ends > 0; completed)
  double diagonal = 0.0;                ///< of the prepared sketch's bounding box, sketch units
  bool user_proxy = false;
  ProxyReport proxy;
  SegmentationSummary segmentation;
  ExtractSummary extraction;
  StrokeDistance stroke_distance;  ///< every non-ignored stroke point to the final mesh
  ShapeChecks checks;              ///< signs of a wrong shape (quality/checks.h), with warnings
  double prepare_s = 0.0, proxy_s = 0.0, segment_s = 0.0, extraction_s = 0.0, checks_s = 0.0,
         total_s = 0.0;
};

/// The final mesh and what led to it.
struct SurfaceResult {
  TriMesh mesh;                     ///< the surface, in the sketch's units
  std::vector<int> labels;          ///< per mesh vertex: its region
  std::vector<std::uint8_t> sharp;  ///< per mesh vertex: on a crease
  TriMesh proxy;                    ///< the proxy that was segmented (half of it when mirrored)
  Segmentation segmentation;        ///< labels per proxy vertex and the region models
  SurfaceReport report;
};

/// Runs the whole method on a sketch.
class Surfacer {
 public:
  /// `progress` receives (stage, fraction) and returns false to cancel.
  explicit Surfacer(Params params = {}, ProgressCallback progress = {});

  /// Prepares a copy of `sketch` (clean, resample), builds the automatic proxy or attracts
  /// `user_proxy` to the strokes, halves both at the mirror plane when sketch.mirror is set,
  /// segments (association, PEARL) and extracts the final mesh (seams, E_mesh, trim, mirror).
  /// Throws Error: Input for an empty sketch, every stroke ignored, or a proxy without triangles;
  /// Processing when a stage cannot proceed (a proxy far from the strokes, no surface found) or,
  /// without a user proxy, when the strokes depict no surface (CheckOptions::refuse_score),
  /// Usage for invalid parameters, Cancelled through the callback.
  SurfaceResult run(const Sketch& sketch, const TriMesh* user_proxy = nullptr) const;

  /// The sketch as run() hands it to the proxy (METHOD.md §0): a copy of `sketch` cleaned,
  /// resampled, completed by its mirror image when it is half of a symmetric object, its
  /// over-sketched passes drawn together, the strokes that depict no surface ignored and rims
  /// marked as boundary strokes (as params() ask); with `refuse_scribbles`, scribbled ink refused
  /// (run() does so without a user proxy). Fills report's cleaning, consolidation, decorations,
  /// openings, symmetry, diagonal, strokes, points and prepare_s. Throws as run() does for these
  /// steps.
  Sketch prepare(const Sketch& sketch, bool refuse_scribbles, SurfaceReport& report) const;

  const Params& params() const { return params_; }

 private:
  Params params_;
  ProgressCallback progress_;
};

/// One call: Surfacer(params).run(sketch, user_proxy).
SurfaceResult surface(const Sketch& sketch, const Params& params = {},
                      const TriMesh* user_proxy = nullptr);

}  // namespace sketchsurf
