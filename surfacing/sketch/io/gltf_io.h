#pragma once
// glTF 2.0 output of write_mesh() (.glb binary, .gltf JSON with the buffer embedded), for the
// viewers and tools that read glTF (Blender, three.js, model-viewer). Private to the io folder.

#include <filesystem>

#include "surfacing/mesh.h"
#include "surfacing/sketch/io/mesh_io.h"

namespace sketchsurf::io_detail {

/// Writes `mesh` as glTF 2.0 to `file` (binary when `binary`), atomically: one mesh of triangles
/// whose vertices are split along crease edges, with POSITION and NORMAL (split_normals.h, as
/// float), COLOR_0 (float RGB: the given colours, else the region palette of the labels) and
/// `_LABEL` (float scalar, the region label, exact up to 2^24) when labels are given; the
/// attributes' strokes, when given, as a second mesh "strokes" of line strips (node 1). A mesh
/// without faces gives a node without a mesh. Attributes are sized as write_mesh() checks.
void write_gltf_mesh(const TriMesh& mesh, const std::filesystem::path& file, const MeshAttributes& attributes,
                     bool binary);

}  // namespace sketchsurf::io_detail
