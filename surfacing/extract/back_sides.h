#pragma once
// Thin parts whose two sides fall in one region. Where the proxy makes a thin part that the
// strokes draw from one side only (a flange round a base, a brim, a sheet the proxy runs out to
// and that closes back on itself), the segmentation gives both sides the same region, and the
// projection puts both onto the same zero set: the two sides coincide and, with the
// regularisation's small moves, pass through each other (thousands of crossing triangle pairs,
// drawn as dark speckle where the layers fight). A vertex whose proxy normal points against its
// model's gradient is such a far side; the solve puts it on the level set a small gap inside the
// zero set (MeshConstraints::inside), so the two sides lie apart and do not cross.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "surfacing/extract/seams.h"
#include "surfacing/segment/implicit.h"

namespace sketchsurf {

/// Options for find_back_sides(), and the gap the solve leaves between the two sides.
struct BackSideOptions {
  double gap = 0.003;     ///< the far side ends this far inside its model's zero set (fraction of
                          ///< the diagonal); 0 = off (both sides on the zero set)
  double facing = -0.3;   ///< a vertex is a far side when the cosine between its proxy normal and
                          ///< its model's gradient is below this
  bool valid(std::string* why = nullptr) const;
};

/// The single-label vertices of `mesh` (positions: the proxy's, before the solve) whose
/// area-weighted normal makes a cosine below options.facing with the gradient of their region's
/// model there, in increasing order. Seam and corner vertices are never far sides: they lie where
/// regions meet. None when options.gap is 0.
std::vector<int> find_back_sides(const LabeledMesh& mesh, const std::vector<ImplicitModel>& models,
                                 const BackSideOptions& options = {});

}  // namespace sketchsurf
