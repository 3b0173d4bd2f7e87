#include "surfacing/extract/seams.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "surfacing/error.h"
#include "tests/support/shapes.h"
#include "tests/unit/extract/fixtures.h"

namespace sketchsurf {
namespace {

using testing::box_labels;
using testing::box_models;
using testing::plane_model;

const Eigen::Vector3d kHalf(0.5, 0.5, 0.5);

std::vector<int> common_labels(const LabeledMesh& m, TriMesh::FaceHandle f) {
  std::vector<int> common;
  bool first = true;
  for (auto v : m.mesh.fv_range(f)) {
    const auto& l = m.labels[v.idx()];
    if (first) {
      common = l;
      first = false;
    } else {
      std::vector<int> both;
      std::set_intersection(common.begin(), common.end(), l.begin(), l.end(), std::back_inserter(both));
      common = both;
    }
  }
  return common;
}

TEST(InsertSeams, EveryFaceLiesInOneRegionAndTheMeshStaysClosed) {
  const TriMesh proxy = testing::rounded_box_mesh(3, kHalf, 0.1);
  const std::vector<int> labels = box_labels(proxy, kHalf);
  const auto models = box_models(kHalf);
  const LabeledMesh seamed = insert_seams(proxy, labels, models);

  std::size_t crossed = 0, three = 0;
  for (auto e : proxy.edges()) crossed += labels[e.v0().idx()] != labels[e.v1().idx()];
  for (auto f : proxy.faces()) {
    std::vector<int> l;
    for (auto v : f.vertices()) l.push_back(labels[v.idx()]);
    std::sort(l.begin(), l.end());
    three += std::unique(l.begin(), l.end()) - l.begin() == 3;
  }
  ASSERT_GT(crossed, 0u);
  EXPECT_EQ(seamed.mesh.n_vertices(), proxy.n_vertices() + crossed + three);
  for (auto f : seamed.mesh.faces()) EXPECT_FALSE(common_labels(seamed, f).empty()) << "face " << f.idx();
  for (auto v : seamed.mesh.vertices()) EXPECT_FALSE(seamed.mesh.is_boundary(v));
  const long euler = long(seamed.mesh.n_vertices()) - long(seamed.mesh.n_edges()) + long(seamed.mesh.n_faces());
  EXPECT_EQ(euler, 2);
  // Proxy vertices are copied unchanged and keep their one label.
  for (auto v : proxy.vertices()) {
    EXPECT_EQ(seamed.source_vertex[v.idx()], v.idx());
    EXPECT_EQ(seamed.labels[v.idx()], std::vector<int>{labels[v.idx()]});
    EXPECT_EQ(seamed.mesh.point(TriMesh::VertexHandle(v.idx())), proxy.point(v));
  }
  // Inserted vertices lie on their crossed edge, away from its ends, no farther from their two
  // planes than the edge's midpoint is.
  for (auto v : seamed.mesh.vertices()) {
    if (seamed.labels[v.idx()].size() != 2) continue;
    EXPECT_EQ(seamed.source_vertex[v.idx()], -1);
    const Eigen::Vector3d x = to_eigen(seamed.mesh.point(v));
    int ends = 0;
    for (auto u : v.vertices()) {
      if (seamed.source_vertex[u.idx()] < 0) continue;
      ++ends;
    }
    EXPECT_GE(ends, 2);
    auto cost = [&](const Eigen::Vector3d& p) {
      double c = 0.0;
      for (int l : seamed.labels[v.idx()]) c += std::pow(models[l].distance(p), 2);
      return c;
    };
    // The two proxy neighbours that carry exactly the two labels are the crossed edge's ends.
    for (auto a : v.vertices())
      for (auto b : v.vertices()) {
        if (seamed.source_vertex[a.idx()] < 0 || seamed.source_vertex[b.idx()] < 0) continue;
        const auto& la = seamed.labels[a.idx()];
        const auto& lb = seamed.labels[b.idx()];
        if (la[0] == seamed.labels[v.idx()][0] && lb[0] == seamed.labels[v.idx()][1]) {
          const Eigen::Vector3d pa = to_eigen(seamed.mesh.point(a)), pb = to_eigen(seamed.mesh.point(b));
          if (((pa + pb) / 2 - x).norm() > 0.5 * (pb - pa).norm() + 1e-12) continue;  // not the edge
          const double t = (x - pa).dot(pb - pa) / (pb - pa).squaredNorm();
          if (((1 - t) * pa + t * pb - x).norm() > 1e-9) continue;
          EXPECT_GE(t, 0.15 - 1e-9);
          EXPECT_LE(t, 0.85 + 1e-9);
          EXPECT_LE(cost(x), cost((pa + pb) / 2) + 1e-12);
        }
      }
  }
}

TEST(InsertSeams, PlacesTheVertexWhereBothSurfacesCrossTheEdge) {
  // Two triangles sharing the edge (0,0,0)-(1,0,0); both planes contain (0.3, 0, 0).
  Eigen::MatrixX3d V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, -1, 0;
  Eigen::MatrixX3i F(2, 3);
  F << 0, 1, 2, 1, 0, 3;
  const TriMesh mesh = mesh_from_matrices(V, F);
  const std::vector<ImplicitModel> models{plane_model({1, 0, 0}, 0.3),
                                          plane_model(Eigen::Vector3d(1, 1, 0).normalized(), 0.3 / std::sqrt(2.0))};
  const LabeledMesh seamed = insert_seams(mesh, {0, 1, 0, 1}, models);
  int found = 0;
  for (auto v : seamed.mesh.vertices()) {
    if (seamed.source_vertex[v.idx()] >= 0) continue;
    const Eigen::Vector3d x = to_eigen(seamed.mesh.point(v));
    if (std::abs(x.y()) < 1e-12) {
      EXPECT_NEAR(x.x(), 0.3, 1e-6);
      EXPECT_EQ(seamed.labels[v.idx()], (std::vector<int>{0, 1}));
      ++found;
    }
  }
  EXPECT_EQ(found, 1);  // one vertex shared by both triangles
}

TEST(InsertSeams, ThreeRegionsMeetAtAnInnerVertexNearTheCorner) {
  const TriMesh proxy = testing::rounded_box_mesh(3, kHalf, 0.1);
  const LabeledMesh seamed = insert_seams(proxy, box_labels(proxy, kHalf), box_models(kHalf));
  int corners = 0;
  for (auto v : seamed.mesh.vertices()) {
    if (seamed.labels[v.idx()].size() != 3) continue;
    ++corners;
    // Closest to the cube corner that the three faces define, within the triangle it splits.
    const Eigen::Vector3d x = to_eigen(seamed.mesh.point(v));
    const Eigen::Vector3d corner = x.cwiseSign().cwiseProduct(kHalf);
    EXPECT_LT((x - corner).norm(), 0.15);
  }
  EXPECT_GE(corners, 8);
}

TEST(InsertSeams, OneRegionLeavesTheMeshAlone) {
  const TriMesh proxy = testing::icosphere(2);
  const LabeledMesh seamed =
      insert_seams(proxy, std::vector<int>(proxy.n_vertices(), 0), {plane_model({0, 0, 1}, 0)});
  EXPECT_EQ(seamed.mesh.n_vertices(), proxy.n_vertices());
  EXPECT_EQ(seamed.mesh.n_faces(), proxy.n_faces());
}

TEST(InsertSeams, RejectsLabelsThatDoNotMatch) {
  const TriMesh proxy = testing::icosphere(1);
  const std::vector<ImplicitModel> one{plane_model({0, 0, 1}, 0)};
  EXPECT_THROW(insert_seams(proxy, std::vector<int>(3, 0), one), Error);
  EXPECT_THROW(insert_seams(proxy, std::vector<int>(proxy.n_vertices(), 1), one), Error);
  SeamOptions bad;
  bad.edge_margin = 0.5;
  EXPECT_THROW(insert_seams(proxy, std::vector<int>(proxy.n_vertices(), 0), one, bad), Error);
}

}  // namespace
}  // namespace sketchsurf
