#pragma once
// Shape checks that need no ground truth: signs that a surface is not the object its strokes
// depict (sheets where no stroke is, surface outside the strokes' extent, spurious handles, holes,
// self-intersections, ragged region borders). Every `surface` report carries them.

#include <cstddef>
#include <string>
#include <vector>

#include "surfacing/mesh.h"
#include "surfacing/sketch/sketch.h"

namespace sketchsurf {

/// Options for check_shape() (the thresholds decide which warnings are written) and for the
/// Surfacer's refusal of scenes that depict no surface.
struct CheckOptions {
  std::size_t samples = 20000;  ///< area-weighted sample points on the surface
  double box_margin = 0.02;     ///< the strokes' bounding box is grown by this fraction of its
                                ///< diagonal on every side before area outside it is counted
                                ///< (area on the grown box is inside)
  double reach = 0.4;           ///< fraction of the diagonal: strokes this close to a surface
                                ///< point count when deciding whether strokes surround it
  double warn_beyond = 0.02;    ///< warn when more than this fraction of the area lies beyond
                                ///< the strokes (see ShapeChecks::beyond)
  double warn_outside = 0.01;   ///< warn when more than this fraction lies outside the grown box
  double warn_border = 1.35;    ///< warn when region borders are this much longer than smoothed
  long warn_genus = 4;          ///< warn when the genus exceeds this
  double warn_crossing = 0.01;  ///< warn when crossing triangle pairs exceed this fraction of the
                                ///< triangles (a few stray pairs where thin parts touch are common)
  double refuse_score = 0.3;    ///< the Surfacer refuses a result (Error Processing) whose
                                ///< `beyond` times its stroke distance p95 (percent of the
                                ///< diagonal) exceeds this: a surface that neither passes through
                                ///< the strokes nor stays within them is not what they depict
                                ///< (hatching, writing, a painterly scene); 0 = never refuse
                                ///< (neither this, nor scribbles, nor unmet strokes)
  double refuse_scribbled = 0.5;  ///< ... and refuses a sketch, before surfacing, when more than
                                  ///< this share of its ink is scribbles (scribbles.h); 0 = off
  double scribble_fill = 5.0;     ///< a stroke is a scribble when its stroke_fill() exceeds this
  double refuse_unmet = 0.9;      ///< ... and refuses a sketch, before surfacing, when more than
                                  ///< this share of its ink is in strokes that meet no other
                                  ///< stroke crosswise (crossings.h: hatching, writing); 0 = off
  double meet_reach = 0.01;       ///< strokes meet within this distance (fraction of diagonal) ...
  double meet_angle = 30.0;       ///< ... at more than this angle (degrees); only in sketches of
  std::size_t meet_least_strokes = 10;  ///< at least this many strokes (fewer: a dab, an arrow
                                        ///< in a plane, which the proxy refuses more precisely)
  unsigned seed = 1;
  unsigned threads = 0;         ///< 0 = all; the result does not depend on it
};


/// What the checks found. Area fractions are of the whole surface; lengths of the diagonal.
struct ShapeChecks {
  double far_5 = 0.0;   ///< area fraction farther than 5% of the diagonal from every stroke
  double far_10 = 0.0;  ///< ... farther than 10%
  double beyond = 0.0;  ///< area fraction farther than 5% from every stroke and not surrounded by
                        ///< strokes: seen along the surface, the strokes within `reach` leave an
                        ///< open angle of more than 180 degrees (a sheet or fin running out past
                        ///< the strokes, not the inside of a face the strokes frame)
  double outside_box = 0.0;            ///< area fraction outside the strokes' box grown by the margin
  std::size_t components = 0;
  long genus = 0;
  std::size_t boundary_loops = 0;
  std::size_t self_intersections = 0;  ///< pairs of triangles (sharing no vertex) that cross
  std::size_t regions = 0;             ///< distinct labels (0 when none were given)
  double border_length = 0.0;          ///< length of the curves between regions
  double border_ratio = 1.0;           ///< border length over the length of the same curves
                                       ///< smoothed: ~1 for clean borders, large for ragged ones
  std::vector<std::string> warnings;   ///< one sentence per check that looks wrong
};

/// Runs every check on `mesh` (with per-vertex region `labels`, or none) against the non-ignored
/// strokes of `sketch` (and their mirror images when the sketch has a mirror plane, as the mesh is
/// then the whole mirrored surface). `open_expected`: boundary loops are wanted (boundary strokes),
/// so no warning for them.
ShapeChecks check_shape(const TriMesh& mesh, const std::vector<int>& labels, const Sketch& sketch,
                        bool open_expected, const CheckOptions& options = {});

/// The score CheckOptions::refuse_score is compared with: `beyond` (area fraction) times the
/// stroke distance p95 in percent of the diagonal.
double non_surface_score(const ShapeChecks& checks, double stroke_p95);

}  // namespace sketchsurf
