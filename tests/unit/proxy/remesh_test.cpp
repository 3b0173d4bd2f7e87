// Isotropic remeshing: edge lengths near the target, topology kept, vertices on the surface.

#include "surfacing/proxy/remesh.h"

#include <gtest/gtest.h>

#include "surfacing/proxy/proxy.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

void onto_unit_sphere(Eigen::MatrixX3d& p) { p.rowwise().normalize(); }

TEST(Remesh, SphereReachesTargetEdgeAndStaysOnIt) {
  TriMesh mesh = testing::icosphere(2);  // edges about 0.3
  RemeshOptions options;
  options.target_edge = 0.1;
  RemeshSummary summary;
  remesh(mesh, options, onto_unit_sphere, {}, &summary);
  const MeshTopology t = mesh_topology(mesh);
  EXPECT_TRUE(t.closed());
  EXPECT_EQ(t.components, 1u);
  EXPECT_EQ(t.genus, 0);
  EXPECT_NEAR(summary.mean_edge, 0.1, 0.015);
  double shortest = 1, longest = 0;
  for (const auto e : mesh.edges()) {
    shortest = std::min(shortest, mesh.calc_edge_length(e));
    longest = std::max(longest, mesh.calc_edge_length(e));
  }
  EXPECT_GT(shortest, 0.03);
  EXPECT_LT(longest, 0.2);
  for (const auto v : mesh.vertices()) EXPECT_NEAR(mesh.point(v).norm(), 1.0, 1e-9);
  // Outward orientation is kept.
  for (const auto f : mesh.faces())
    EXPECT_GT(mesh.normal(f).dot(mesh.calc_face_centroid(f)), 0.0);
}

TEST(Remesh, TorusCoarsensAndKeepsGenus) {
  TriMesh mesh = testing::torus_mesh(120, 40, 0.5, 0.2);  // fine: edges about 0.03
  RemeshOptions options;
  options.target_edge = 0.06;
  RemeshSummary summary;
  remesh(mesh, options, {}, {}, &summary);
  const MeshTopology t = mesh_topology(mesh);
  EXPECT_TRUE(t.closed());
  EXPECT_EQ(t.genus, 1);
  EXPECT_GT(summary.collapses, 0u);
  EXPECT_NEAR(summary.mean_edge, 0.06, 0.012);
}

TEST(Remesh, RejectsBadOptions) {
  TriMesh mesh = testing::icosphere(1);
  RemeshOptions bad;
  bad.target_edge = -1;
  EXPECT_THROW(remesh(mesh, bad), Error);
}

}  // namespace
}  // namespace sketchsurf
