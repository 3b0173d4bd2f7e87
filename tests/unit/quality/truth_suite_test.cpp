// The ground-truth suite: every shape has its stated topology, orientation, size and creases.

#include "tests/support/truth_suite.h"

#include <gtest/gtest.h>

#include <set>

#include "surfacing/error.h"
#include "surfacing/proxy/proxy.h"

namespace sketchsurf {
namespace {

double signed_volume(const TriMesh& mesh) {
  double v = 0;
  for (const auto f : mesh.faces()) {
    const auto h = f.halfedge();
    const Eigen::Vector3d a = to_eigen(mesh.point(h.from())), b = to_eigen(mesh.point(h.to())),
                          c = to_eigen(mesh.point(h.next().to()));
    v += a.dot(b.cross(c)) / 6.0;
  }
  return v;
}

/// Largest dihedral angle (degrees) between the normals of two faces sharing an edge.
double largest_dihedral(const TriMesh& mesh) {
  double worst = 0;
  for (const auto e : mesh.edges()) {
    if (e.is_boundary()) continue;
    const double c = std::clamp(mesh.calc_face_normal(e.h0().face()).dot(
                                    mesh.calc_face_normal(e.h1().face())), -1.0, 1.0);
    worst = std::max(worst, std::acos(c) * 180.0 / M_PI);
  }
  return worst;
}

TEST(TruthSuite, EveryShapeHasItsStatedTopologyOrientationAndSize) {
  const std::vector<testing::TruthShape> suite = testing::truth_suite();
  ASSERT_GE(suite.size(), 20u);
  std::set<std::string> names;
  for (const auto& s : suite) {
    SCOPED_TRACE(s.name);
    EXPECT_TRUE(names.insert(s.name).second);
    const MeshTopology t = mesh_topology(s.mesh);
    EXPECT_EQ(t.components, static_cast<std::size_t>(s.components));
    EXPECT_EQ(t.genus, s.genus);
    EXPECT_EQ(t.closed(), !s.open);
    EXPECT_GE(s.mesh.n_faces(), 2000u);
    EXPECT_LE(s.mesh.n_faces(), 20000u);
    // Manifold: OpenMesh refuses non-manifold faces, so every face made it in; no vertex is
    // left alone and none is a non-manifold fan.
    for (const auto v : s.mesh.vertices()) {
      EXPECT_FALSE(s.mesh.is_isolated(v));
      EXPECT_TRUE(v.is_manifold());
    }
    BoundingBox box;
    for (const auto v : s.mesh.vertices()) box.extend(to_eigen(s.mesh.point(v)));
    EXPECT_LT((box.min + box.max).norm(), 1e-9);  // centred
    const double size = (box.max - box.min).maxCoeff();
    EXPECT_GT(size, 0.7);
    EXPECT_LT(size, 1.3);
    if (!s.open) {
      EXPECT_GT(signed_volume(s.mesh), 0.0);  // outward
    }
    if (s.sharp) {
      EXPECT_GT(largest_dihedral(s.mesh), 60.0);
    }
    if (s.mirror) {  // the mirror image of a vertex is near a vertex (within an edge length)
      for (const auto v : s.mesh.vertices()) {
        if (v.idx() % 25 != 0) continue;
        const Eigen::Vector3d image = s.mirror->reflect(to_eigen(s.mesh.point(v)));
        double nearest = INFINITY;
        for (const auto w : s.mesh.vertices())
          nearest = std::min(nearest, (to_eigen(s.mesh.point(w)) - image).norm());
        EXPECT_LT(nearest, 0.03);
      }
    }
  }
}

TEST(TruthSuite, OpenShapesFaceOutward) {
  // The cup's bottom faces down (-y, away from its inside): the face nearest the bottom centre.
  const TriMesh cup = testing::truth_shape("cup").mesh;
  double lowest = INFINITY;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (const auto f : cup.faces()) {
    const Eigen::Vector3d c = to_eigen(cup.calc_face_centroid(f));
    if (c.y() < lowest - 1e-12 || (c.y() < lowest + 1e-12 && std::hypot(c.x(), c.z()) < 0.05)) {
      lowest = c.y();
      normal = to_eigen(cup.calc_face_normal(f));
    }
  }
  EXPECT_LT(normal.y(), -0.99);
}

TEST(TruthSuite, ShapesAreMadeOneByOneAndUnknownNamesAreErrors) {
  const auto names = testing::truth_shape_names();
  EXPECT_EQ(testing::truth_shape(names.front()).name, names.front());
  try {
    testing::truth_shape("teapot");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    EXPECT_NE(std::string(e.what()).find("wineglass"), std::string::npos);
  }
}

}  // namespace
}  // namespace sketchsurf
