#pragma once
// Crease edges and vertex normals split along them, shared by the mesh writers that carry normals
// or creases (glTF, OBJ `vn`, the PLY edge element). Private to the io folder.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "surfacing/mesh.h"

namespace sketchsurf::io_detail {

/// An edge of the mesh is a crease when its dihedral angle exceeds kCreaseAngle, or
/// kSharpCreaseAngle when both its vertices are flagged sharp (seam vertices whose region normals
/// differ by more than the extraction's smooth angle, pi / 8). Border edges and edges next to a
/// degenerate triangle are not creases.
inline constexpr double kCreaseAngle = 45.0;       ///< degrees; the renderer's default too
inline constexpr double kSharpCreaseAngle = 22.5;  ///< degrees

/// Per edge (by edge index, deleted edges false): whether it is a crease. `sharp` holds a flag
/// per vertex or is empty.
std::vector<std::uint8_t> crease_edges(const TriMesh& mesh, const std::vector<std::uint8_t>& sharp);

/// Vertex normals that keep creases sharp: the corners of a vertex share an output vertex unless a
/// crease edge separates them, and an output vertex's normal is the angle-weighted mean of the
/// face normals on its side (a face normal when the mean cancels out).
struct SplitNormals {
  std::vector<std::uint32_t> corner_vertex;  ///< output vertex of corner 3 t + k of the t-th live
                                             ///< face (mesh order), k-th vertex in its order
  std::vector<int> source;                   ///< mesh vertex index of each output vertex
  std::vector<Eigen::Vector3d> normals;      ///< unit normal of each output vertex
};

/// Output vertices numbered in corner order. Throws Error (Processing) for a face that is not a
/// triangle.
SplitNormals split_normals(const TriMesh& mesh, const std::vector<std::uint8_t>& sharp);

}  // namespace sketchsurf::io_detail
