#pragma once
// A surface measured against the surface it should be (a ground truth): how far the result lies
// from the truth (accuracy), how far the truth lies from the result (completeness), and how well
// the truth's sharp edges are reproduced as creases. Stroke distance says whether a surface passes
// through the strokes; these say whether it is the right object.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "surfacing/mesh.h"
#include "surfacing/quality/sampling.h"

namespace sketchsurf {

/// Options for evaluate().
struct EvalOptions {
  std::size_t samples = 100000;  ///< area-weighted sample points on each surface
  double sharp_angle = 30.0;     ///< degrees between face normals: truth edges above are sharp
  double crease_angle = 15.0;    ///< degrees: the result has a crease across a sharp truth edge
                                 ///< when its normals on the two sides differ by more than this
  double probe = 0.01;           ///< fraction of the truth's diagonal: how far into each side face
                                 ///< of a sharp edge the result's normal is read
  unsigned seed = 1;             ///< of the sample points
  unsigned threads = 0;          ///< 0 = all; the result does not depend on it
  bool valid(std::string* why) const;
};

/// How the result reproduces the truth's sharp edges.
struct CreaseEvaluation {
  std::size_t sharp_edges = 0;  ///< truth edges whose dihedral angle exceeds sharp_angle
  double found = 0.0;           ///< fraction of their length where the result has a crease
  DistanceStats error;          ///< |result angle - truth angle| in degrees, where found
};

/// The result against the truth. Distances are fractions of the truth's bounding-box diagonal.
struct Evaluation {
  double diagonal = 0.0;        ///< of the truth, its own units
  DistanceStats accuracy;       ///< result samples to the truth surface
  DistanceStats completeness;   ///< truth samples to the result surface
  CreaseEvaluation creases;
  std::vector<double> vertex_deviation;  ///< per result vertex: distance to the truth
};

/// Exact point-to-triangle distances (an AABB tree per surface) from area-weighted samples of each
/// surface to the other, and the creases of the truth's sharp edges in the result (the result's
/// face normals a `probe` away from the edge midpoint on each side). Throws Error (Usage) for
/// invalid options, Error (Processing) when either mesh has no area.
Evaluation evaluate(const TriMesh& result, const TriMesh& truth, const EvalOptions& options = {});

/// A colour for a deviation: blue at 0 through green and yellow to red at `full_scale` and above.
std::array<std::uint8_t, 3> deviation_color(double deviation, double full_scale);

}  // namespace sketchsurf
