// Scene building and camera math without a GPU (label unit).

#include <gtest/gtest.h>

#include "engine/render/camera.h"
#include "engine/render/palette.h"
#include "engine/render/scene.h"
#include "engine/vk/context.h"
#include "surfacing/error.h"
#include "tests/render/render_support.h"

namespace sketchsurf::testing {
namespace {

using render::build_scene;

TEST(Scene, RibbonsHaveTwoVerticesPerPointAndTwoTrianglesPerSegment) {
  const Sketch sketch = cube_sketch(1.0, false);
  render::SceneOptions all_points;
  all_points.stroke_tolerance = 0.0;
  const auto scene = build_scene(sketch, nullptr, nullptr, all_points);
  std::size_t points = 0, segments = 0;
  for (const auto& s : sketch.strokes) points += s.size(), segments += s.size() - 1;
  EXPECT_EQ(scene.stroke_points, points);
  EXPECT_EQ(scene.ribbon_vertices.size(), 2 * points);
  EXPECT_EQ(scene.stroke_index_count, 6 * segments);
  EXPECT_TRUE(scene.mesh_indices.empty());
  // Positions are relative to the bbox centre, half widths are a fraction of the diagonal.
  const double diag = sketch.bounding_box().diagonal();
  for (const auto& v : scene.ribbon_vertices) {
    EXPECT_NEAR(v.half_width, 0.5 * render::SceneOptions{}.stroke_width * diag, 1e-6);
    EXPECT_NEAR(glm::length(v.tangent), 1.0f, 1e-5f);
  }
  // Simplified (the default), each straight edge keeps only its two ends.
  const auto simplified = build_scene(sketch);
  EXPECT_EQ(simplified.stroke_points, points);
  EXPECT_EQ(simplified.ribbon_points, 2 * sketch.strokes.size());
}

TEST(Scene, SimplifiedStrokesStayWithinTheTolerance) {
  // Noisy circles: every input point is within tolerance * width of the kept polyline.
  Sketch sketch = torus_sketch();
  add_noise(sketch, 1e-4, 7);
  const render::SceneOptions options;
  const auto scene = build_scene(sketch, nullptr, nullptr, options);
  EXPECT_LT(scene.ribbon_points, scene.stroke_points);
  const double width = options.stroke_width * sketch.bounding_box().diagonal();
  std::size_t vertex = 0;
  for (const Stroke& s : sketch.strokes) {
    std::vector<Eigen::Vector3d> kept;
    const std::size_t first = vertex;
    while (vertex < scene.ribbon_vertices.size() &&
           (vertex == first || kept.back() != s.points.back())) {
      const glm::vec3 p = scene.ribbon_vertices[vertex].position;
      kept.push_back(Eigen::Vector3d(p.x, p.y, p.z) + scene.origin);
      vertex += 2;
      if ((kept.back() - s.points.back()).norm() < 1e-6) kept.back() = s.points.back();
    }
    for (const auto& p : s.points) {
      double best = 1e300;
      for (std::size_t i = 0; i + 1 < kept.size(); ++i) {
        const Eigen::Vector3d ab = kept[i + 1] - kept[i];
        const double t = std::clamp((p - kept[i]).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
        best = std::min(best, (kept[i] + t * ab - p).norm());
      }
      EXPECT_LE(best, options.stroke_tolerance * width * 1.001 + 1e-6);
    }
  }
}

TEST(Scene, ScaleInvariantUpToTheOrigin) {
  // Scaling the sketch by 1e3 and moving it far away scales the relative positions and widths.
  Sketch big = torus_sketch();
  transform(big, 1e3, Eigen::Vector3d(1e5, 2e5, -3e5));
  // Exact with every point kept; simplification may break ties between equally distant points
  // differently (regular circles), so there only the amount kept is compared.
  render::SceneOptions all_points;
  all_points.stroke_tolerance = 0.0;
  const auto a = build_scene(torus_sketch(), nullptr, nullptr, all_points);
  const auto b = build_scene(big, nullptr, nullptr, all_points);
  const auto sa = build_scene(torus_sketch()), sb = build_scene(big);
  EXPECT_NEAR(double(sa.ribbon_points), double(sb.ribbon_points), 0.02 * sa.ribbon_points);
  ASSERT_EQ(a.ribbon_vertices.size(), b.ribbon_vertices.size());
  for (std::size_t i = 0; i < a.ribbon_vertices.size(); ++i) {
    EXPECT_LT(glm::length(b.ribbon_vertices[i].position / 1e3f - a.ribbon_vertices[i].position), 1e-5f);
    EXPECT_NEAR(b.ribbon_vertices[i].half_width / 1e3f, a.ribbon_vertices[i].half_width, 1e-7);
  }
}

TEST(Scene, RegionsSplitMixedFacesAlongMidpoints) {
  // Two labels split by the plane x = 0 on a sphere: every face with mixed labels is split,
  // the boundary segments lie where the labels change, and colours follow the palette.
  const TriMesh sphere = icosphere(3, 1.0);
  MeshAttributes attributes;
  std::size_t mixed = 0;
  for (auto v : sphere.vertices()) attributes.labels.push_back(sphere.point(v)[0] > 0.05 ? 1 : 0);
  for (auto f : sphere.faces()) {
    std::set<int> labels;
    for (auto v : sphere.fv_range(f)) labels.insert(attributes.labels[v.idx()]);
    mixed += labels.size() > 1;
  }
  render::SceneOptions options;
  options.regions = true;
  options.sharp_angle = 180.0;
  const auto scene = build_scene(Sketch{}, &sphere, &attributes, options);
  ASSERT_GT(mixed, 0u);
  EXPECT_EQ(scene.outlined_edges, mixed);
  EXPECT_EQ(scene.mesh_indices.size(), 3 * (sphere.n_faces() + 2 * mixed));
  const auto pack = [](const render::Rgb8& c) {
    return render::pack_rgba(c[0] / 255.f, c[1] / 255.f, c[2] / 255.f);
  };
  for (std::size_t i = 0; i < sphere.n_vertices(); ++i)
    EXPECT_EQ(scene.mesh_vertices[i].color, pack(render::region_color(attributes.labels[i])));
  // Boundary points are midpoints of edges that cross x = 0.05: |x - 0.05| is within an edge.
  for (std::size_t i = scene.stroke_index_count; i < scene.ribbon_indices.size(); ++i)
    EXPECT_LT(std::abs(scene.ribbon_vertices[scene.ribbon_indices[i]].position.x + scene.origin.x() - 0.05), 0.3);
}

TEST(Scene, CreasesOfABoxAreOutlined) {
  // An icosphere has no crease; a sharp-edged box mesh has 12 box edges, each of several
  // mesh edges, all at 90 degrees; mesh boundaries count as outlines.
  const TriMesh sphere = icosphere(2, 1.0);
  EXPECT_EQ(build_scene(Sketch{}, &sphere).outlined_edges, 0u);
  render::SceneOptions off;
  off.sharp_angle = 180.0;
  const TriMesh torus = torus_mesh(6, 4, 1.0, 0.3);  // coarse: 90-degree tube angles
  EXPECT_GT(build_scene(Sketch{}, &torus).outlined_edges, 0u);
  EXPECT_EQ(build_scene(Sketch{}, &torus, nullptr, off).outlined_edges, 0u);
}

TEST(Scene, ClosedOutwardMeshesAreMarkedForBackFaceCulling) {
  const TriMesh sphere = icosphere(2, 1.0);
  EXPECT_TRUE(build_scene(Sketch{}, &sphere).mesh_closed);
  EXPECT_TRUE(build_scene(Sketch{}, nullptr).mesh_closed == false);
  // Inward: the same faces, reversed.
  Eigen::MatrixX3i F = face_matrix(sphere);
  F.col(1).swap(F.col(2));
  const TriMesh inward = mesh_from_matrices(vertex_matrix(sphere), F);
  EXPECT_FALSE(build_scene(Sketch{}, &inward).mesh_closed);
  // Open: one face fewer.
  const TriMesh open = mesh_from_matrices(vertex_matrix(sphere), face_matrix(sphere).topRows(F.rows() - 1));
  EXPECT_FALSE(build_scene(Sketch{}, &open).mesh_closed);
}

TEST(Scene, CreasesSplitNormals) {
  // A box of flat n x n grids: split at its 90-degree creases, every face keeps its own
  // vertices, 6 (n+1)^2 of them, with the face's normal exactly; smoothing everything instead
  // gives one vertex per mesh vertex and tilted normals along the edges.
  const int n = 3;
  const TriMesh box = box_grid_mesh(n, Eigen::Vector3d(1.0, 0.5, 0.25));
  const auto sharp = build_scene(Sketch{}, &box);
  EXPECT_EQ(sharp.mesh_vertices.size(), std::size_t(6 * (n + 1) * (n + 1)));
  for (const auto& v : sharp.mesh_vertices)
    EXPECT_NEAR(glm::max(glm::max(std::abs(v.normal.x), std::abs(v.normal.y)), std::abs(v.normal.z)),
                1.0f, 1e-6f);
  EXPECT_EQ(sharp.outlined_edges, std::size_t(12 * n));
  render::SceneOptions smooth;
  smooth.sharp_angle = 180.0;
  const auto soft = build_scene(Sketch{}, &box, nullptr, smooth);
  EXPECT_EQ(soft.mesh_vertices.size(), box.n_vertices());
  EXPECT_EQ(soft.outlined_edges, 0u);
}

TEST(Scene, BadInputIsAnError) {
  const TriMesh sphere = icosphere(1, 1.0);
  MeshAttributes attributes;
  attributes.labels = {0, 1, 2};
  try {
    build_scene(Sketch{}, &sphere, &attributes);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    EXPECT_NE(std::string(e.what()).find("3 labels"), std::string::npos) << e.what();
  }
  render::SceneOptions options;
  options.stroke_width = 0.0;
  std::string why;
  EXPECT_FALSE(options.valid(&why));
  EXPECT_NE(why.find("stroke_width"), std::string::npos);
  EXPECT_THROW(build_scene(cube_sketch(), nullptr, nullptr, options), Error);
}

TEST(Camera, ViewsAndParsing) {
  EXPECT_EQ(render::view_names().size(), 6u);
  for (const auto& n : render::view_names()) EXPECT_TRUE(render::parse_view(n)) << n;
  EXPECT_FALSE(render::parse_view("diagonal"));

  BoundingBox box;
  box.extend(Eigen::Vector3d(-1, -1, -1));
  box.extend(Eigen::Vector3d(1, 1, 1));
  const auto c = render::parse_camera("0,0,10, 0,0,0", box);
  EXPECT_EQ(c.eye, Eigen::Vector3d(0, 0, 10));
  EXPECT_EQ(c.up, Eigen::Vector3d(0, 1, 0));
  EXPECT_LT(c.near_plane, 10.0 - std::sqrt(3.0));
  EXPECT_GT(c.far_plane, 10.0 + std::sqrt(3.0));
  // The target projects to the centre of the picture; +x to the right, +y up.
  const Eigen::Vector3d centre = c.project(Eigen::Vector3d::Zero(), 100, 50);
  EXPECT_NEAR(centre.x(), 50.0, 1e-9);
  EXPECT_NEAR(centre.y(), 25.0, 1e-9);
  EXPECT_GT(c.project(Eigen::Vector3d(1, 0, 0), 100, 50).x(), 50.0);
  EXPECT_LT(c.project(Eigen::Vector3d(0, 1, 0), 100, 50).y(), 25.0);
  EXPECT_EQ(render::parse_camera("1,2,3,4,5,6,0,0,1", box).up, Eigen::Vector3d(0, 0, 1));
  for (const char* bad : {"1,2,3", "1,2,3,4,5,x", "0,0,0,0,0,0", "0,5,0,0,0,0", "1,2,3,4,5,6,7"})
    EXPECT_THROW(render::parse_camera(bad, box), Error) << bad;
}

TEST(Camera, OrbitKeepsDistanceAndTarget) {
  BoundingBox box;
  box.extend(Eigen::Vector3d(-1, -2, -3));
  box.extend(Eigen::Vector3d(4, 5, 6));
  const auto c = render::fit_camera(box, render::View::Iso, 1.5);
  for (double a : {0.3, 1.0, M_PI}) {
    const auto o = render::orbit(c, a);
    EXPECT_NEAR((o.eye - o.target).norm(), (c.eye - c.target).norm(), 1e-9);
    EXPECT_NEAR(o.eye.y(), c.eye.y(), 1e-9);  // turns around +y
    EXPECT_EQ(o.target, c.target);
  }
  EXPECT_LT((render::orbit(c, 2 * M_PI).eye - c.eye).norm(), 1e-9);
}

TEST(Camera, EyeFrustumPutsItsEdgesAtThePictureEdges) {
  // An eye at (1, 2, 3) turned 30 degrees about +y, with an asymmetric field of view (a headset's).
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(M_PI / 6, Eigen::Vector3d::UnitY()));
  const render::Frustum f{-0.8, 0.6, 0.7, -0.75};
  const render::Camera c = render::eye_camera({1, 2, 3}, turn, f, 0.1, 50.0);
  const int w = 400, h = 300;
  // A point on the ray through each edge of the frustum lands on that edge of the picture, at any
  // depth; the depth maps near -> 0 and far -> 1.
  const auto at = [&](double tx, double ty, double depth) -> Eigen::Vector3d {
    return Eigen::Vector3d(1, 2, 3) + turn * (depth * Eigen::Vector3d(tx, ty, -1.0));
  };
  for (double depth : {0.1, 2.0, 50.0}) {
    EXPECT_NEAR(c.project(at(std::tan(f.left), 0, depth), w, h).x(), 0.0, 1e-9);
    EXPECT_NEAR(c.project(at(std::tan(f.right), 0, depth), w, h).x(), w, 1e-9);
    EXPECT_NEAR(c.project(at(0, std::tan(f.up), depth), w, h).y(), 0.0, 1e-9) << "up is the top row";
    EXPECT_NEAR(c.project(at(0, std::tan(f.down), depth), w, h).y(), h, 1e-9);
  }
  EXPECT_NEAR(c.project(at(0, 0, 0.1), w, h).z(), 0.0, 1e-9);
  EXPECT_NEAR(c.project(at(0, 0, 50.0), w, h).z(), 1.0, 1e-9);
  // A symmetric frustum is the symmetric camera of the same vertical field and aspect.
  render::Camera sym = render::eye_camera({0, 0, 0}, Eigen::Quaterniond::Identity(), {-0.6, 0.6, 0.5, -0.5}, 0.1, 50.0);
  render::Camera plain = sym;
  plain.frustum.reset();
  plain.fov_y = 2.0 * 0.5 * 180.0 / M_PI;
  const double aspect = std::tan(0.6) / std::tan(0.5);
  EXPECT_LT((sym.projection_matrix(1.0) - plain.projection_matrix(aspect)).norm(), 1e-12);
}

TEST(DeviceChoice, PrefersGpusFallsBackToCpuAndHonoursRequests) {
  using vk::DeviceInfo;
  const DeviceInfo cpu{"llvmpipe (LLVM 15)", VK_PHYSICAL_DEVICE_TYPE_CPU, true};
  const DeviceInfo igpu{"Intel UHD 620", VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU, true};
  const DeviceInfo dgpu{"NVIDIA RTX 3060", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, true};
  const DeviceInfo no_graphics{"Compute only", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, false};

  auto choice = vk::choose_device({cpu, igpu, dgpu}, "");
  ASSERT_TRUE(choice.index);
  EXPECT_EQ(*choice.index, 2u);
  EXPECT_FALSE(choice.software);
  EXPECT_TRUE(choice.message.empty());

  choice = vk::choose_device({no_graphics, cpu}, "");
  ASSERT_TRUE(choice.index);
  EXPECT_EQ(*choice.index, 1u);
  EXPECT_TRUE(choice.software);
  EXPECT_NE(choice.message.find("llvmpipe"), std::string::npos);  // the one log line

  choice = vk::choose_device({cpu, dgpu}, "LLVMPIPE");
  ASSERT_TRUE(choice.index);
  EXPECT_EQ(*choice.index, 0u);

  choice = vk::choose_device({cpu, dgpu}, "radeon");
  EXPECT_FALSE(choice.index);
  EXPECT_NE(choice.message.find("'NVIDIA RTX 3060'"), std::string::npos) << choice.message;

  choice = vk::choose_device({}, "");
  EXPECT_FALSE(choice.index);
  EXPECT_FALSE(choice.message.empty());
}

TEST(Palette, DistinctColoursForTheFirstTwelveLabels) {
  std::set<render::Rgb8> colours;
  for (int i = 0; i < 12; ++i) colours.insert(render::region_color(i));
  EXPECT_EQ(colours.size(), 12u);
  EXPECT_EQ(colours.count(render::kUnlabelledColor), 0u);
  EXPECT_EQ(render::region_color(12), render::region_color(0));
  EXPECT_EQ(render::region_color(-1), render::kUnlabelledColor);
}

}  // namespace
}  // namespace sketchsurf::testing
