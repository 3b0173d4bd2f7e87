#pragma once
// Symmetric sketches (paper §5, "Symmetric sketches"): surface half of the sketch on half of the
// proxy, then mirror the result and weld it along the plane, so the output is symmetric by
// construction.

#include <vector>

#include "surfacing/mesh.h"
#include "surfacing/sketch/sketch.h"

namespace sketchsurf {

/// The part of a mesh on the kept side of a plane, and where each of its vertices came from.
struct ClippedMesh {
  TriMesh mesh;
  /// Per vertex of `mesh`: the index of the input vertex it copies, or -1 for a vertex inserted
  /// where an input edge crosses the plane.
  std::vector<int> source_vertex;
  /// Per vertex of `mesh`: 1 when it lies exactly on the plane (snapped or inserted).
  std::vector<std::uint8_t> on_plane;
};

/// Keeps the part of `mesh` with plane.signed_distance(x) >= 0, splitting the triangles that cross
/// the plane so that the cut runs exactly on it. Vertices within `snap` (mesh units) of the plane
/// are moved onto it. Faces lying in the plane are dropped (they would be doubled by mirroring).
/// Throws Error (Processing) when nothing is left on the kept side.
ClippedMesh clip_to_half_space(const TriMesh& mesh, const Plane& plane, double snap);

/// The strokes of `sketch` restricted to plane.signed_distance(x) >= 0: each stroke is cut where
/// it crosses the plane (the crossing point is added, exactly on the plane); pieces with fewer
/// than 2 points are dropped. Annotations, ids and attributes of the kept points are preserved
/// (pieces of one stroke share its id). The mirror plane stays set.
Sketch half_sketch(const Sketch& sketch, const Plane& plane);

/// Adds the reflection of `half` across `plane` (with reversed faces, so normals stay outward)
/// and welds every boundary vertex within `weld` (mesh units) of the plane to its mirror image
/// after snapping it exactly onto the plane; faces with all three vertices welded are dropped
/// (they would be doubled). `source_vertex`, when given, receives per output vertex the index of
/// the `half` vertex it copies or reflects (to carry labels across). Result: for every vertex v,
/// plane.reflect(v) is a vertex too, up to rounding (about 1e-16 of the coordinates).
/// Throws Error (Processing) when the welded mesh is not manifold.
TriMesh mirror_and_weld(const TriMesh& half, const Plane& plane, double weld,
                        std::vector<int>* source_vertex = nullptr);

}  // namespace sketchsurf
