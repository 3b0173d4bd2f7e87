#pragma once
// Triangle mesh files: .obj and binary .ply (read and written), .glb and .gltf (written), with
// optional per-vertex labels and colours.

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "surfacing/mesh.h"

namespace sketchsurf {

/// Optional per-vertex and per-edge data written alongside a mesh.
struct MeshAttributes {
  std::vector<int> labels;                       ///< per vertex; empty = none (PLY `label`)
  std::vector<std::array<std::uint8_t, 3>> colors;  ///< per vertex RGB; empty = none
  std::vector<std::uint8_t> sharp;               ///< per vertex sharp flag; empty = none
  /// Read only: the edges a PLY `edge` element flags `sharp` (vertex index pairs). The writers
  /// find the creases themselves (split_normals.h).
  std::vector<std::array<int, 2>> sharp_edges;
  /// glTF only: polylines (the strokes) written as a second mesh of line strips, "strokes".
  std::vector<std::vector<Eigen::Vector3d>> strokes;
};

/// Writes .obj, binary little-endian .ply, or glTF 2.0 .glb / .gltf (by extension), atomically.
/// Normals are split along creases (an edge whose dihedral angle is over 45 degrees, or over 22.5
/// when both its vertices are flagged sharp: split_normals.h). PLY: vertex properties `label`
/// (int), `red green blue` (uchar), `sharp` (uchar) and, with sharp flags, an `edge` element
/// (`vertex1`, `vertex2`, `sharp`: 1 on creases) so that a reader knows which edges are sharp.
/// OBJ: colours as `v x y z r g b`, `vn` normals (`f v//vn`), and with labels the faces grouped
/// by region (`g region_L`, a face's region the label of most of its vertices). glTF: normals,
/// COLOR_0 (the colours, else the region palette of the labels), `_LABEL` and the strokes
/// (gltf_io.h). Throws Error (Usage) for another extension.
void write_mesh(const TriMesh& mesh, const std::filesystem::path& file,
                const MeshAttributes& attributes = {});

/// Reads a polygon mesh from .obj or .ply (ASCII or binary), triangulating polygons by fans.
/// Throws Error (Input) for unreadable files, non-manifold or degenerate input, naming the file.
/// When `attributes` is given, PLY `label` and colour properties are read into it.
TriMesh read_mesh(const std::filesystem::path& file, MeshAttributes* attributes = nullptr);

}  // namespace sketchsurf
