#pragma once
// Folds ironed out of the final mesh. Where the projection moves neighbouring vertices onto
// surfaces that disagree (two regions' models meeting at a seam they do not share, a plane's model
// running past the side it meets, a thin part squeezed from both sides), the mesh can fold: the
// surface passes through itself in a frayed fin, a lip or a pleat that its proxy did not have.
// Round the triangles that cross where they did not cross in the proxy, the surface is filled
// afresh from the ring round them, in a zone grown ring by ring until nothing there crosses any
// more: first by a bi-Laplacian fill, which carries the bend of the surface around the zone across
// it (a pleat on a curved part or at an edge gives way to the curve or the edge), then, where folds
// are left (the fill can overshoot where the surface round a fold turns sharply), by a membrane
// spanning the zone (each vertex at the mean of its neighbours), which cannot overshoot.
// A fold is a few triangles wide and the fill over it is as small; a zone that grows past
// max_share of the mesh is a shape a fill would flatten (a cap, a whole part), and is left as it
// was before that fill. The rest of the surface is not touched.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "surfacing/mesh.h"

namespace sketchsurf {

/// Options for unfold().
struct UnfoldOptions {
  int rings = 2;            ///< rings of vertices round the crossing triangles that are smoothed
                            ///< too; 0 = off (nothing is smoothed)
  int rounds = 6;           ///< at most this many passes of each fill, each one ring wider than
                            ///< the last
  double max_share = 0.15;  ///< a connected zone with more than this share of the mesh's
                            ///< vertices is left alone
  double refit_share = 0.5;  ///< the regions on at least this share of the triangles that still
                             ///< cross after both fills are fitted again as a plane, then as a
                             ///< quadric (fold_refit.h), and the mesh solved again with them
                             ///< (extract()), the solve with the fewest folds kept under
                             ///< hold_fit's test; 0 = off
  double hold_fit = 1.25;   ///< regions whose triangles still cross after both fills are held at
                            ///< the proxy and the mesh solved again (extract()), kept when it
                            ///< has fewer folds and its stroke distance median and 95th
                            ///< percentile are each at most this times the first's; 0 = off
  double zone_share = 0.05;  ///< where folds are still left then, the crossing triangles and
                             ///< `rings` rings round them are held at the proxy and the mesh
                             ///< solved again (extract(), under hold_fit's test), when that zone
                             ///< has at most this share of the mesh's vertices (a few folds where
                             ///< regions meet, not a whole part); 0 = off
  bool valid(std::string* why = nullptr) const;
};

/// What unfold() did.
struct UnfoldSummary {
  std::size_t crossing_pairs = 0;  ///< crossing triangle pairs the proxy did not have, before
  std::size_t left_pairs = 0;      ///< ... and after
  std::size_t moved_vertices = 0;  ///< vertices that moved
  std::size_t skipped_vertices = 0;  ///< vertices of zones the membrane left alone (larger than
                                     ///< max_share)
  int rounds = 0;                  ///< passes made, of both fills
  std::size_t refitted_regions = 0;  ///< regions fitted again at a lower degree for the folds
                                     ///< left (extract()): the figures are then that solve's
  int refit_degree = 0;            ///< ... the degree they were fitted at (0: none kept)
  std::size_t held_regions = 0;    ///< regions held at the proxy for the folds left (extract()):
                                   ///< the figures above are then the second solve's
  std::size_t held_zone = 0;       ///< vertices round the folds still left held at the proxy
                                   ///< (extract()): the figures above are then that solve's
};

/// Per vertex of `mesh`, 1 for the vertices of the `crossing` face pairs' triangles and those
/// within `rings` rings of them.
std::vector<char> around(const TriMesh& mesh, const std::vector<std::array<int, 2>>& crossing, int rings);

/// Irons out the folds of `mesh` (see the file comment): the triangles that cross at the mesh's
/// positions but not at `start` (its positions before the solve, one row per vertex). Vertices
/// flagged in `fixed` (empty: none) and those on the mesh's border keep their positions.
/// Crossings are searched on `threads` threads (0 = all; the result does not depend on them).
/// `left` (if given) receives the crossing face pairs left (UnfoldSummary::left_pairs of them).
UnfoldSummary unfold(TriMesh& mesh, const Eigen::MatrixX3d& start, const std::vector<std::uint8_t>& fixed,
                     const UnfoldOptions& options = {}, unsigned threads = 0,
                     std::vector<std::array<int, 2>>* left = nullptr);

}  // namespace sketchsurf
