#include "surfacing/extract/back_sides.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "surfacing/extract/extract.h"
#include "surfacing/quality/checks.h"
#include "surfacing/self_intersections.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

using namespace testing;

// A thin lens, the proxy of a disc drawn from one side: radius 1 in the xy plane, 0.04 thick.
// Its two sides fall in one region whose model is the plane z = 0 (gradient +z, towards the top
// side's normals).
TriMesh lens() {
  TriMesh mesh = icosphere(4, 1.0);
  for (auto v : mesh.vertices()) {
    Eigen::Vector3d p = to_eigen(mesh.point(v));
    p.z() *= 0.04;
    mesh.set_point(v, to_openmesh(p));
  }
  return mesh;
}

ImplicitModel plane_z() {
  ImplicitModel m;
  m.degree = 1;
  m.coefficients = Eigen::VectorXd::Zero(4);
  m.coefficients[3] = 1.0;  // monomials 1, x, y, z
  return m;
}

// The disc's outline and two diameters, in its plane.
Sketch disc_sketch() {
  Sketch sketch;
  Stroke outline;
  for (int i = 0; i <= 96; ++i) {
    const double a = 2.0 * M_PI * i / 96.0;
    outline.points.push_back({std::cos(a), std::sin(a), 0.0});
  }
  sketch.strokes.push_back(outline);
  for (const Eigen::Vector3d& d : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0)}) {
    Stroke line;
    for (int i = 0; i <= 40; ++i) line.points.push_back(-0.95 * d + 1.9 * d * (i / 40.0));
    sketch.strokes.push_back(line);
  }
  return sketch;
}

TEST(BackSides, TheFarSideOfAThinPartIsFoundAndMovedInsideItsModel) {
  LabeledMesh mesh;
  mesh.mesh = lens();
  mesh.labels.assign(mesh.mesh.n_vertices(), {0});
  mesh.source_vertex.assign(mesh.mesh.n_vertices(), -1);
  const std::vector<ImplicitModel> models{plane_z()};
  const std::vector<int> back = find_back_sides(mesh, models);
  std::vector<char> is_back(mesh.mesh.n_vertices(), 0);
  for (int v : back) is_back[v] = 1;
  std::size_t lower = 0;
  for (auto v : mesh.mesh.vertices()) {
    const double z = mesh.mesh.point(v)[2];
    // The faces below are far sides; the rim (normals in the plane) and the top are not.
    if (z < -0.03) {
      EXPECT_TRUE(is_back[v.idx()]) << "a vertex of the lower side";
      ++lower;
    }
    if (z >= 0.0) {
      EXPECT_FALSE(is_back[v.idx()]) << "a vertex of the upper side";
    }
  }
  EXPECT_GT(lower, 0u);
  EXPECT_TRUE(std::is_sorted(back.begin(), back.end()));
  // The start of the solve puts the far side onto the plane 0.01 below the model's.
  std::vector<double> inside(mesh.mesh.n_vertices(), 0.0);
  for (int v : back) inside[v] = 0.01;
  project_vertices(mesh, models, 1, 1.0, 1, std::vector<char>(mesh.mesh.n_vertices(), 0), inside);
  for (auto v : mesh.mesh.vertices())
    EXPECT_NEAR(mesh.mesh.point(v)[2], is_back[v.idx()] ? -0.01 : 0.0, 1e-6);  // damped steps
}

TEST(BackSides, NoneOnSeamsAndNoneWhenOff) {
  LabeledMesh mesh;
  mesh.mesh = lens();
  mesh.labels.assign(mesh.mesh.n_vertices(), {0, 1});  // every vertex on a seam
  mesh.source_vertex.assign(mesh.mesh.n_vertices(), -1);
  const std::vector<ImplicitModel> models{plane_z(), plane_z()};
  EXPECT_TRUE(find_back_sides(mesh, models).empty());
  mesh.labels.assign(mesh.mesh.n_vertices(), {0});
  EXPECT_FALSE(find_back_sides(mesh, models).empty());
  BackSideOptions off;
  off.gap = 0.0;
  EXPECT_TRUE(find_back_sides(mesh, models, off).empty());
}

TEST(BackSides, TheTwoSidesOfAFlattenedLensStayApartAndDoNotCross) {
  // The lens's rim (within 5% of its radius) is a second region on the cylinder x^2 + y^2 = 1
  // through the outline, which holds the disc's extent.
  const TriMesh proxy = lens();
  std::vector<int> labels(proxy.n_vertices(), 0);
  for (auto v : proxy.vertices())
    if (to_eigen(proxy.point(v)).head<2>().norm() > 0.95) labels[v.idx()] = 1;
  ImplicitModel cylinder;
  cylinder.degree = 2;
  cylinder.coefficients = Eigen::VectorXd::Zero(10);
  cylinder.coefficients[0] = -1.0;
  cylinder.coefficients[4] = cylinder.coefficients[7] = 1.0;  // x^2 + y^2 - 1
  const std::vector<ImplicitModel> models{plane_z(), cylinder};
  const Sketch sketch = disc_sketch();
  const double diagonal = sketch.bounding_box().diagonal();
  ExtractOptions options;
  const ExtractedSurface apart = extract(proxy, labels, models, sketch, options);
  EXPECT_GT(apart.summary.back_side_vertices, 0u);
  EXPECT_EQ(count_self_intersections(apart.mesh), 0u);
  // In the middle, the top on the plane and the bottom the gap below it (nearer the rim both
  // bend to meet it); the output keeps the regions' own labels.
  const double gap = options.back_sides.gap * diagonal;
  for (auto v : apart.mesh.vertices()) {
    EXPECT_LE(apart.labels[v.idx()], 1);
    const Eigen::Vector3d p = to_eigen(apart.mesh.point(v));
    if (v.idx() >= static_cast<int>(proxy.n_vertices()) || p.head<2>().norm() > 0.3) continue;
    const bool top = proxy.point(TriMesh::VertexHandle(v.idx()))[2] > 0.0;
    EXPECT_NEAR(p.z(), top ? 0.0 : -gap, 0.2 * gap) << (top ? "top" : "bottom") << " side";
  }

  // Without the gap both sides land on the one plane and pass through each other.
  options.back_sides.gap = 0.0;
  const ExtractedSurface together = extract(proxy, labels, models, sketch, options);
  EXPECT_EQ(together.summary.back_side_vertices, 0u);
  EXPECT_GT(count_self_intersections(together.mesh), 100u);
}

}  // namespace
}  // namespace sketchsurf
