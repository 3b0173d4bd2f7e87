#pragma once
// Triangle mesh files: .obj and binary .ply (read and written), .glb and .gltf (written), with
// optional per-vertex labels and colours.

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include "surfacing/mesh.h"

namespace sketchsurf {

/// Optional per-vertex and per-edge data written alongside a mesh.
struct MeshAttributes {
  std::vector<int> labels;                       ///< per vertex; empty = none (PLY `label`)
  std::vector<std::array<std::uint8_t, 3>> colors;  ///< per vertex RGB; empty = none
  std::vector<std::uint8_t> sharp;               ///< per vertex sharp flag; empty = none
};

/// Writes .obj, binary little-endian .ply, or glTF 2.0 .glb / .gltf (by extension), atomically.
/// Labels, colours and sharp flags go into PLY vertex properties `label` (int), `red green blue`
/// (uchar), `sharp` (uchar); OBJ gets colours as `v x y z r g b`; glTF gets normals split along
/// creases, COLOR_0 (the colours, else the region palette of the labels) and `_LABEL`
/// (gltf_io.h). Throws Error (Usage) for another extension.
void write_mesh(const TriMesh& mesh, const std::filesystem::path& file,
                const MeshAttributes& attributes = {});

/// Reads a polygon mesh from .obj or .ply (ASCII or binary), triangulating polygons by fans.
/// Throws Error (Input) for unreadable files, non-manifold or degenerate input, naming the file.
/// When `attributes` is given, PLY `label` and colour properties are read into it.
TriMesh read_mesh(const std::filesystem::path& file, MeshAttributes* attributes = nullptr);

}  // namespace sketchsurf
