#pragma once
// Contact sheets: several pictures of one result side by side, so that a person judging a change
// sees the strokes, the surface over them, its regions and the surface alone at a glance.

#include <array>
#include <cstdint>
#include <vector>

#include "engine/render/image.h"
#include "engine/vk/context.h"
#include "surfacing/mesh.h"
#include "surfacing/sketch/io/mesh_io.h"
#include "surfacing/sketch/sketch.h"

namespace sketchsurf::render {

/// `pictures` (all of the same size) in a grid of `columns`, row by row, separated by `gap`
/// pixels of `gap_color`. Throws Error (Usage) when sizes differ or nothing is given.
RgbaImage tile_images(const std::vector<RgbaImage>& pictures, int columns, int gap = 4,
                      std::array<std::uint8_t, 4> gap_color = {96, 96, 96, 255});

/// How a contact sheet is drawn.
struct SheetOptions {
  int tile = 384;           ///< pixels per (square) picture
  int samples = 4;          ///< MSAA samples (fewer when the device cannot)
  double sharp_angle = 45;  ///< creases outlined above this dihedral angle (degrees)
};

/// The contact sheet of a sketch and its surface (3 x 2 pictures, all framed on the strokes and
/// the surface together): top row the strokes from the three-quarter view and from the opposite
/// side, the surface with the strokes; bottom row the regions (vertex labels of `attributes`), the
/// surface alone from both sides. Without a mesh, only the two pictures of the strokes.
RgbaImage contact_sheet(const vk::Context& context, const Sketch& sketch, const TriMesh* mesh,
                        const MeshAttributes& attributes, const SheetOptions& options = {});

}  // namespace sketchsurf::render
