#pragma once
// glTF 2.0 output of write_mesh() (.glb binary, .gltf JSON with the buffer embedded), for the
// viewers and tools that read glTF (Blender, three.js, model-viewer). Private to the io folder.

#include <filesystem>

#include "surfacing/mesh.h"
#include "surfacing/sketch/io/mesh_io.h"

namespace sketchsurf::io_detail {

/// An edge of the mesh is a crease in glTF output (its two sides get their own normals) when its
/// dihedral angle exceeds kGltfCreaseAngle, or kGltfSharpCreaseAngle when both its vertices are
/// flagged sharp (seam vertices whose region normals differ by more than the extraction's
/// smooth angle, pi / 8).
inline constexpr double kGltfCreaseAngle = 45.0;       ///< degrees; the renderer's default too
inline constexpr double kGltfSharpCreaseAngle = 22.5;  ///< degrees

/// Writes `mesh` as glTF 2.0 to `file` (binary when `binary`), atomically: one mesh of triangles
/// whose vertices are split along crease edges, with POSITION and NORMAL (float, the normal of a
/// split vertex the angle-weighted mean of the faces on its side), COLOR_0 (float RGB: the given
/// colours, else the region palette of the labels) and `_LABEL` (float scalar, the region label,
/// exact up to 2^24) when labels are given. A mesh without faces gives a scene without a mesh.
/// Attributes are sized as write_mesh() checks.
void write_gltf_mesh(const TriMesh& mesh, const std::filesystem::path& file, const MeshAttributes& attributes,
                     bool binary);

}  // namespace sketchsurf::io_detail
