#pragma once
// Scene building: turns a sketch and a mesh into GPU-ready vertex and index arrays (CPU side).
// Built once per scene; the renderer uploads the arrays once and draws them many times.

#include <cstdint>
#include <string>
#include <vector>

#include "engine/render/gpu_types.h"
#include "surfacing/mesh.h"
#include "surfacing/sketch/io/mesh_io.h"
#include "surfacing/sketch/sketch.h"

namespace sketchsurf::render {

/// How strokes and meshes become geometry. Widths are fractions of the scene's bounding-box
/// diagonal (strokes and mesh together), so pictures do not depend on the sketch's units.
struct SceneOptions {
  double stroke_width = 0.006;   ///< ribbon width of strokes, fraction of the bbox diagonal
  double stroke_tolerance = 0.05; ///< strokes are simplified (Douglas-Peucker) as long as no point
                                  ///< moves more than this fraction of the stroke width; 0 = keep all
  bool stroke_colors = false;    ///< strokes in their own colours (else palette.h kStrokeColor)
  bool stroke_alpha = false;     ///< with stroke_colors, their alpha too (for DrawOptions::
                                 ///< translucent_strokes; else opaque)
  bool regions = false;          ///< colour the mesh by vertex labels (palette.h), when it has them
  bool region_boundaries = true; ///< with `regions`: outline the curves between regions
  double sharp_angle = 45.0;     ///< edges with a dihedral angle above this (degrees) are creases:
                                 ///< outlined and not smoothed across; mesh boundary edges are
                                 ///< outlined too; >= 180 turns both off
  bool wireframe = false;        ///< draw every mesh edge thinly
  double edge_width = 0.004;     ///< ribbon width of outlined edges, fraction of the bbox diagonal
  double wire_width = 0.0015;    ///< ribbon width of wireframe edges, fraction of the bbox diagonal
  double reference_diagonal = 0.0; ///< when > 0, the widths are fractions of this length instead
                                   ///< of the scene's diagonal (the studio: strokes keep their width
                                   ///< as the sketch grows, and match across separately built scenes)

  /// False (with the reason in `why`) when a width is not positive and finite or the angle negative.
  bool valid(std::string* why) const;
};

/// GPU-ready arrays of one scene. Positions are relative to `origin`, so that single precision
/// keeps its digits for sketches far from the origin.
struct SceneGeometry {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< world position of the vertices' (0,0,0)
  BoundingBox bounds;                                ///< strokes + mesh, world coordinates
  std::vector<RibbonVertex> ribbon_vertices;         ///< strokes first, then outlined/wire edges
  std::vector<std::uint32_t> ribbon_indices;         ///< triangle list
  std::uint32_t stroke_index_count = 0;              ///< the first indices draw strokes, the rest edges
  std::vector<MeshVertex> mesh_vertices;
  std::vector<std::uint32_t> mesh_indices;           ///< triangle list
  std::size_t stroke_points = 0;                     ///< stroke points in the input (drawn strokes)
  std::size_t ribbon_points = 0;                     ///< of which kept after simplification
  std::size_t outlined_edges = 0;                    ///< crease, boundary and region-boundary segments
  bool mesh_closed = false;  ///< the mesh is closed and oriented outward (positive volume): its
                             ///< back faces are never seen, so the renderer culls them

  bool empty() const { return ribbon_indices.empty() && mesh_indices.empty(); }
};

/// Builds the geometry of `sketch` (strokes with fewer than 2 points are skipped; dense strokes
/// are simplified within `options.stroke_tolerance`, a small fraction of their width) and, when
/// `mesh` is given, of the mesh with its `attributes` (labels for regions, colours).
/// Throws Error (Usage) when `options` is not valid or an attribute array's size differs from the
/// mesh's vertex count.
SceneGeometry build_scene(const Sketch& sketch, const TriMesh* mesh = nullptr,
                          const MeshAttributes* attributes = nullptr,
                          const SceneOptions& options = {});

}  // namespace sketchsurf::render
