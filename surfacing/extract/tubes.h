#pragma once
// Thin tubes round strokes that depict no surface (an antenna, a cable, a handle's wire), when a
// user asks for them: the surfacer ignores such strokes (decorations.h), so without tubes they
// leave nothing in the output; with tubes each becomes a closed tube of its own, apart from the
// surface.

#include <cstddef>
#include <string>

#include "surfacing/mesh.h"
#include "surfacing/sketch/sketch.h"

namespace sketchsurf {

/// Options of stroke_tubes().
struct TubeOptions {
  double radius = 0.004;  ///< tube radius of a stroke without a brush width, fraction of the
                          ///< sketch's bounding-box diagonal
  double max_radius = 0.02;  ///< a stroke with a brush width (Open Brush) gets half of it, at most
                             ///< this (fraction of the diagonal): the tube is as thick as drawn
  int sides = 12;         ///< vertices round each ring of a tube (12: 30 degrees between
                          ///< sides, shaded smooth by viewers and the renderer)
  bool valid(std::string* why) const;
};

/// The tubes made by stroke_tubes().
struct StrokeTubes {
  TriMesh mesh;           ///< every tube, each a closed component of its own
  std::size_t count = 0;  ///< how many (mirror images counted)
};

/// One closed, outward-oriented tube round each stroke of `strokes` (annotations other than the
/// mirror plane are not looked at), of radius half the stroke's brush width (Stroke::width) up to
/// options.max_radius * `diagonal`, or options.radius * `diagonal` when the stroke has no width
/// (`diagonal`: the sketch's bounding-box diagonal, in its units): a ring of options.sides vertices
/// at every stroke point, turned along the stroke by rotation-minimising frames (the double
/// reflection of Wang et al. 2008, so that a tube does not twist), neighbouring rings joined by
/// two triangles per side, each end closed by a cone whose tip lies one radius past the end point.
/// Points closer than a hundredth of the radius to the previous kept one are skipped; a stroke
/// with no two points farther apart gives no tube. With strokes.mirror set, the strokes are first
/// cut to the plane's positive side (as the surface's half sketch is) and every tube is added with
/// its mirror image. Throws Error (Usage) for invalid options or a diagonal that is not positive
/// and finite.
StrokeTubes stroke_tubes(const Sketch& strokes, double diagonal, const TubeOptions& options = {});

}  // namespace sketchsurf
