// Faces the automatic proxy drew in (ExtractOptions::drawn_faces): the vertices of a region that
// lies mostly on one stay on it where the region's model would dent it far from the strokes; a
// region that only touches the face is projected as before.

#include <gtest/gtest.h>

#include <cmath>

#include "surfacing/extract/extract.h"
#include "tests/support/shapes.h"
#include "tests/unit/extract/fixtures.h"

namespace sketchsurf {
namespace {

// The face's region's model: the unit sphere centred at z = 1.2.
ImplicitModel dent() { return testing::sphere_model(Eigen::Vector3d(0.0, 0.0, 1.2)); }

// The unit sphere cut flat at z = 0.6 (the face drawn in: a disc of radius 0.8, plane z = 0.6,
// normal +z), drawn along its rim, its equator and a small ring (radius 0.3) 0.35 below the face.
// The face's region fits a unit sphere centred at z = 1.2: through the rim and the small ring, 0.4
// below the disc's middle, where no stroke is nearer than 0.5. The dent brings the disc's middle
// nearer the small ring, so the trust distance alone does not hold it.
struct Cut {
  TriMesh proxy = testing::icosphere(4, 1.0);
  Sketch sketch;
  ExtractOptions options;
  Cut() {
    for (auto v : proxy.vertices()) proxy.point(v)[2] = std::min(proxy.point(v)[2], 0.6);
    sketch.strokes = {testing::horizontal_ring(0.8, 0.6), testing::horizontal_ring(1.0, 0.0),
                      testing::horizontal_ring(0.3, 0.246)};
    Plane top;
    top.normal = Eigen::Vector3d::UnitZ();
    top.offset = -0.6;
    options.drawn_faces = {top};
    // The regions' models are taken as they are (a model no nearer its strokes than the proxy
    // would otherwise keep its region at the proxy: smooth_fallback.h).
    options.smooth_fallback.enabled = false;
    options.back_sides.gap = 0.0;
  }
  // The lowest of the disc's middle vertices (within 0.2 of the axis) after extraction.
  double middle(const ExtractedSurface& out) const {
    double lowest = 1.0;
    for (auto v : proxy.vertices())
      if (std::hypot(proxy.point(v)[0], proxy.point(v)[1]) < 0.2 && proxy.point(v)[2] == 0.6)
        lowest = std::min<double>(lowest, out.mesh.point(v)[2]);
    return lowest;
  }
};

TEST(DrawnFaces, TheFacesOwnRegionStaysOnTheFaceWhereItsModelWouldDentIt) {
  // Region 0: the disc and a band below it, most of it on the face; region 1, the rest, on the
  // unit sphere where the proxy already lies.
  Cut cut;
  std::vector<int> labels(cut.proxy.n_vertices(), 1);
  for (auto v : cut.proxy.vertices())
    if (cut.proxy.point(v)[2] > 0.5) labels[v.idx()] = 0;
  const std::vector<ImplicitModel> models{dent(), testing::sphere_model()};
  const ExtractedSurface held = extract(cut.proxy, labels, models, cut.sketch, cut.options);
  EXPECT_GT(held.summary.optimization.face_vertices, 0u);
  EXPECT_NEAR(cut.middle(held), 0.6, 0.01);

  cut.options.face_tolerance = 0.0;
  const ExtractedSurface dented = extract(cut.proxy, labels, models, cut.sketch, cut.options);
  EXPECT_EQ(dented.summary.optimization.face_vertices, 0u);
  EXPECT_LT(cut.middle(dented), 0.4);
}

TEST(DrawnFaces, ARegionThatOnlyTouchesTheFaceIsProjected) {
  // One region for the whole proxy: the disc is under a fifth of it (a thin part's side, a web
  // between parts that lies on the box's side is not the face's region).
  Cut cut;
  const std::vector<int> labels(cut.proxy.n_vertices(), 0);
  const ExtractedSurface out = extract(cut.proxy, labels, {dent()}, cut.sketch, cut.options);
  EXPECT_EQ(out.summary.optimization.face_vertices, 0u);
  EXPECT_LT(cut.middle(out), 0.4);
}

}  // namespace
}  // namespace sketchsurf
