#pragma once
// Shared helpers of the render tests: one Vulkan context per test binary, scene shortcuts and the
// golden-image check.

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "engine/render/headless.h"
#include "engine/render/palette.h"
#include "engine/vk/context.h"
#include "tests/support/shapes.h"

namespace sketchsurf::testing {

/// The context shared by the tests of one binary (created on first use; lavapipe on CI).
const vk::Context& render_context();

/// A picture of `geometry` from the fitted `view` (default draw options unless given).
render::RgbaImage render_picture(const render::SceneGeometry& geometry, int width, int height,
                                 render::View view = render::View::Iso,
                                 const render::DrawOptions& draw = {});

/// Per-vertex labels for a box-like mesh centred at the origin with half extents `half`: the axis
/// and sign of the largest component of p / half (0..5: +x, -x, +y, -y, +z, -z), i.e. one region
/// per face of the box.
std::vector<int> box_face_labels(const TriMesh& mesh, const Eigen::Vector3d& half);

/// A closed box centred at the origin with half extents `half`, each face an n x n grid of
/// quads split in two, outward oriented; the box's edges are mesh edges (90-degree creases).
TriMesh box_grid_mesh(int n, const Eigen::Vector3d& half);

/// Compares `actual` with tests/render/golden/NAME.png: fails when 1% or more of the pixels differ
/// by more than 8/255 in a channel, writing NAME_actual.png and NAME_diff.png (differences in
/// red) to the working directory. With SKETCHSURF_UPDATE_GOLDEN=1 it writes the golden instead.
void expect_golden(const render::RgbaImage& actual, const std::string& name);

/// Pixels that differ from `background` by more than 8/255 in some channel.
std::size_t non_background_pixels(const render::RgbaImage& image, const render::Rgb8& background);

}  // namespace sketchsurf::testing
