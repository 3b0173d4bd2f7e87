#pragma once
// Synthetic sketches drawn on a known surface: the strokes a person would draw to describe the
// mesh (its creases, cross sections and outlines), clean or with the flaws of mid-air drawing.
// With the mesh as ground truth they measure how close a surfacing of the sketch gets to it.

#include <string>

#include "surfacing/mesh.h"
#include "surfacing/sketch/sketch.h"

namespace sketchsurf {

/// Options for synthesize_sketch(). Lengths are fractions of the mesh's bounding-box diagonal.
struct SynthOptions {
  /// Net: clean strokes lying on the mesh (a curve network, as in sketch-based modelling tools).
  /// Vr: the same strokes drawn the way people draw mid-air: tremor, gaps, overshoots,
  /// over-sketched duplicates and forgotten strokes.
  enum class Style { Net, Vr };
  Style style = Style::Net;
  unsigned seed = 1;           ///< seed of the vr style's flaws (the net style is not random)

  // What is drawn (both styles).
  double sharp_angle = 30.0;   ///< degrees: mesh edges whose dihedral angle (between the normals of
                               ///< their two faces) is larger are drawn as feature curves;
                               ///< mesh borders are always drawn
  double corner_angle = 45.0;  ///< degrees: a feature curve is split where it turns by more
  int sections = 3;            ///< cross sections per principal (PCA) axis, evenly spaced
  double thin_extent = 0.2;    ///< no sections across an axis along which the mesh is shorter than
                               ///< this fraction of its longest extent (a plate's thickness)
  int silhouettes = 3;         ///< view directions whose contour (n . d = 0) is drawn
  double spacing = 0.005;      ///< point spacing along a stroke, fraction of the diagonal
  double min_length = 0.03;    ///< shorter pieces are dropped, fraction of the diagonal

  // Flaws of the vr style (fractions of the diagonal, or probabilities per stroke).
  double tremor = 0.002;       ///< RMS amplitude of the smooth hand tremor, fraction of the diagonal
  double tremor_wavelength = 0.1;  ///< typical wavelength of the tremor, fraction of the diagonal
  double gap = 0.15;           ///< probability that a stroke is drawn in two pieces with a hole
  double gap_length = 0.02;    ///< length of that hole, fraction of the diagonal
  double overshoot = 0.02;     ///< largest tangential extension past each open end, fraction of
                               ///< the diagonal (each end draws uniformly in [0, overshoot])
  double duplicate = 0.3;      ///< probability that a stroke is drawn a second time over itself
  double duplicate_offset = 0.004;  ///< distance between the two copies, fraction of the diagonal
  double drop = 0.1;           ///< probability that a stroke is not drawn at all

  /// True when the options can be used; otherwise `why` (if given) says which field is wrong.
  bool valid(std::string* why = nullptr) const;
};

/// A sketch drawn on `mesh` the way people describe a shape with strokes:
/// - feature curves: chains of mesh edges whose dihedral angle exceeds `sharp_angle`, and the
///   mesh's borders, split at junctions (where more than two meet) and at corners;
/// - cross sections: the mesh cut by `sections` evenly spaced planes perpendicular to each of its
///   principal axes (area-weighted PCA) that is not thin, each connected polyline one stroke;
/// - silhouette-like curves: the zero set of n . d (interpolated vertex normals) for
///   `silhouettes` view directions d spread over a hemisphere of the principal frame, away from
///   the feature curves (there the contour is the crease, already drawn).
/// Net style: every point lies on a triangle of the mesh (to rounding), strokes resampled to
/// `spacing`, pieces shorter than `min_length` dropped. Vr style then, per stroke and in stroke
/// order: drops it, extends its open ends tangentially, adds a smooth low-frequency tremor (a sum
/// of sinusoids of arc length, not white noise), splits it by a gap, draws a second offset copy.
/// The same mesh, options and seed give the same sketch bit for bit on every platform (the random
/// numbers come from std::mt19937 through distributions written here).
/// Strokes get ids 0, 1, 2, ...; the provenance names the style and seed.
/// @throws Error (Usage) for invalid options; Error (Input) for an empty or degenerate mesh.
Sketch synthesize_sketch(const TriMesh& mesh, const SynthOptions& options = {});

}  // namespace sketchsurf
