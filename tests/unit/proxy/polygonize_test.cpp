// Polygonisation: every component, closed manifold, right genus, outward, close to the surface.

#include "surfacing/proxy/polygonize.h"

#include <gtest/gtest.h>

#include <cmath>

#include "surfacing/proxy/proxy.h"

namespace sketchsurf {
namespace {

double signed_volume(const TriMesh& mesh) {
  double v = 0;
  for (const auto f : mesh.faces()) {
    auto h = f.halfedge();
    const Eigen::Vector3d a = to_eigen(mesh.point(h.from())), b = to_eigen(mesh.point(h.to())),
                          c = to_eigen(mesh.point(h.next().to()));
    v += a.dot(b.cross(c)) / 6.0;
  }
  return v;
}

template <class Sdf>
FieldBatch batch(Sdf sdf) {
  return [sdf](const Eigen::MatrixX3d& p, Eigen::VectorXd& values) {
    values.resize(p.rows());
    for (Eigen::Index i = 0; i < p.rows(); ++i) values[i] = sdf(Eigen::Vector3d(p.row(i)));
  };
}

BoundingBox cube(double h) {
  BoundingBox b;
  b.extend(Eigen::Vector3d::Constant(-h));
  b.extend(Eigen::Vector3d::Constant(h));
  return b;
}

TEST(Polygonize, TwoSpheresGiveTwoClosedOutwardComponents) {
  const Eigen::Vector3d c1(-0.3, 0, 0), c2(0.3, 0.05, 0);
  auto sdf = [&](const Eigen::Vector3d& p) {
    return std::min((p - c1).norm() - 0.2, (p - c2).norm() - 0.15);
  };
  Eigen::MatrixX3d seeds(2, 3);
  seeds.row(0) = (c1 + Eigen::Vector3d(0.2, 0, 0)).transpose();
  seeds.row(1) = (c2 + Eigen::Vector3d(0, 0.15, 0)).transpose();
  PolygonizeOptions options;
  options.cell_size = 0.02;
  const TriMesh mesh = polygonize(batch(sdf), seeds, cube(0.7), options);
  const MeshTopology t = mesh_topology(mesh);
  EXPECT_EQ(t.components, 2u);
  EXPECT_TRUE(t.closed());
  EXPECT_EQ(t.genus, 0);
  EXPECT_EQ(t.euler, 4);
  for (const auto v : mesh.vertices()) EXPECT_LT(std::abs(sdf(to_eigen(mesh.point(v)))), 0.004);
  const double expected = 4.0 / 3.0 * M_PI * (std::pow(0.2, 3) + std::pow(0.15, 3));
  EXPECT_NEAR(signed_volume(mesh), expected, 0.05 * expected);  // positive: outward
}

TEST(Polygonize, OnlyComponentsThroughSeedsAreKept) {
  auto sdf = [](const Eigen::Vector3d& p) {
    return std::min((p - Eigen::Vector3d(-0.3, 0, 0)).norm() - 0.2,
                    (p - Eigen::Vector3d(0.3, 0, 0)).norm() - 0.2);
  };
  Eigen::MatrixX3d seeds(1, 3);
  seeds << -0.1, 0, 0;
  PolygonizeOptions options;
  options.cell_size = 0.02;
  EXPECT_EQ(mesh_topology(polygonize(batch(sdf), seeds, cube(0.7), options)).components, 1u);
}

TEST(Polygonize, TorusHasGenusOneAndInvertedFieldStaysOutward) {
  auto torus = [](const Eigen::Vector3d& p) {
    const double q = std::hypot(p.x(), p.y()) - 0.4;
    return std::hypot(q, p.z()) - 0.15;
  };
  Eigen::MatrixX3d seeds(1, 3);
  seeds << 0.55, 0, 0;
  PolygonizeOptions options;
  options.cell_size = 0.02;
  for (double sign : {1.0, -1.0}) {
    auto field = [&](const Eigen::Vector3d& p) { return sign * torus(p); };
    const TriMesh mesh = polygonize(batch(field), seeds, cube(0.7), options);
    const MeshTopology t = mesh_topology(mesh);
    EXPECT_EQ(t.components, 1u);
    EXPECT_TRUE(t.closed());
    EXPECT_EQ(t.genus, 1);
    EXPECT_GT(signed_volume(mesh), 0.0);
  }
}

TEST(Polygonize, SurfaceLeavingTheBoxIsClosedByIt) {
  auto plane = [](const Eigen::Vector3d& p) { return p.z() - 0.1; };  // outside: z > 0.1
  Eigen::MatrixX3d seeds(1, 3);
  seeds << 0, 0, 0.1;
  PolygonizeOptions options;
  options.cell_size = 0.05;
  const MeshTopology t = mesh_topology(polygonize(batch(plane), seeds, cube(0.5), options));
  // The half-space inside the box, closed by the box's border: a sphere.
  EXPECT_EQ(t.components, 1u);
  EXPECT_TRUE(t.closed());
  EXPECT_EQ(t.genus, 0);
}

TEST(Polygonize, ArraysHoldTheMeshsVerticesAndTrianglesInOrder) {
  auto torus = [](const Eigen::Vector3d& p) {
    return std::hypot(std::hypot(p.x(), p.y()) - 0.4, p.z()) - 0.15;
  };
  Eigen::MatrixX3d seeds(1, 3);
  seeds << 0.55, 0, 0;
  PolygonizeOptions options;
  options.cell_size = 0.03;
  PolygonizeSummary from_arrays, from_mesh;
  const TriangleArrays arrays =
      polygonize_arrays(batch(torus), seeds, cube(0.7), options, {}, &from_arrays);
  const TriMesh mesh = polygonize(batch(torus), seeds, cube(0.7), options, {}, &from_mesh);
  EXPECT_EQ(from_arrays.evaluations, from_mesh.evaluations);
  ASSERT_GT(arrays.F.rows(), 0);
  EXPECT_EQ(arrays.V, vertex_matrix(mesh));
  const Eigen::MatrixX3i F = face_matrix(mesh);
  ASSERT_EQ(F.rows(), arrays.F.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f) {  // the same triangle, up to where it starts
    bool same = false;
    for (int k = 0; k < 3; ++k)
      same |= F(f, 0) == arrays.F(f, k) && F(f, 1) == arrays.F(f, (k + 1) % 3) &&
              F(f, 2) == arrays.F(f, (k + 2) % 3);
    EXPECT_TRUE(same) << "triangle " << f;
  }
}

TEST(Polygonize, RejectsBadOptions) {
  PolygonizeOptions bad;
  bad.cell_size = 0;
  EXPECT_FALSE(bad.valid());
  EXPECT_THROW(polygonize(batch([](const Eigen::Vector3d&) { return 1.0; }), Eigen::MatrixX3d(0, 3),
                          cube(1), bad),
               Error);
}

}  // namespace
}  // namespace sketchsurf
