// Every real sketch gets a proxy, or a clear error when its strokes cannot enclose a surface.
// Built twice: label 'data' runs a quick subset; label 'slow' (PROXY_DATA_ALL) every CASSIE and
// VNS sketch with the default options.

#include <gtest/gtest.h>

#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "surfacing/error.h"
#include "surfacing/proxy/attract.h"
#include "surfacing/proxy/proxy.h"
#include "surfacing/sketch/io/sketch_io.h"
#include "tests/support/sections.h"

namespace sketchsurf {
namespace {

using testing::section_area;
using testing::section_loops;
using testing::section_width;

std::vector<std::string> sketches() {
#ifdef PROXY_DATA_ALL
  std::vector<std::string> out;
  for (const char* folder : {"cassie", "vns"})
    for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(SKETCHSURF_DATA_DIR) / folder)) {
      const std::string ext = e.path().extension().string();
      if (ext == ".curves" || ext == ".obj") out.push_back(std::string(folder) + "/" + e.path().filename().string());
    }
  std::sort(out.begin(), out.end());
  return out;
#else
  return {"cassie/11-2-2.curves", "cassie/computer-mouse.curves", "vns/torus.obj"};
#endif
}

class ProxyData : public ::testing::TestWithParam<std::string> {};

TEST_P(ProxyData, ClosedProxyNearTheStrokesOrAClearError) {
  const std::filesystem::path file = std::filesystem::path(SKETCHSURF_DATA_DIR) / GetParam();
  Sketch sketch = read_sketch(file);
  clean(sketch);
  const double diagonal = sketch.bounding_box().diagonal();
  ProxyReport report;
  TriMesh proxy;
  try {
    proxy = make_proxy(sketch, {}, {}, &report);
  } catch (const Error& e) {
    // Only a processing error that says why is acceptable.
    EXPECT_EQ(e.kind(), ErrorKind::Processing) << e.what();
    EXPECT_GT(std::string(e.what()).size(), 20u);
    return;
  }
  const MeshTopology t = mesh_topology(proxy);
  EXPECT_TRUE(t.closed());
  EXPECT_GE(t.components, 1u);
  EXPECT_GT(proxy.n_vertices(), 100u);
  // VIPSS interpolates the samples: the strokes lie on or near the proxy.
  std::vector<Eigen::Vector3d> points;
  for (const auto& s : sketch.strokes)
    if (!s.ignored) points.insert(points.end(), s.points.begin(), s.points.end());
  Eigen::MatrixX3d targets(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) targets.row(static_cast<Eigen::Index>(i)) = points[i];
  EXPECT_LT(median_nearest_vertex_distance(proxy, targets), 0.02 * diagonal);
  std::cout << GetParam() << ": " << proxy.n_vertices() << " vertices, " << t.components
            << " component(s), genus " << t.genus << ", " << report.total_seconds << " s\n";
}

#ifndef PROXY_DATA_ALL
// Fraction of the mesh's area farther than `distance` from every point of the strokes not ignored
// (face centroids against stroke points, so `distance` should exceed their spacing).
double area_farther_than(const TriMesh& mesh, const Sketch& sketch, double distance) {
  double far = 0.0, total = 0.0;
  for (const auto f : mesh.faces()) {
    auto h = f.halfedge();
    const Eigen::Vector3d c = (to_eigen(mesh.point(h.from())) + to_eigen(mesh.point(h.to())) +
                               to_eigen(mesh.point(h.next().to()))) / 3.0;
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& s : sketch.strokes)
      if (!s.ignored)
        for (const auto& p : s.points) nearest = std::min(nearest, (p - c).squaredNorm());
    const double area = mesh.calc_face_area(f);
    total += area;
    if (nearest > distance * distance) far += area;
  }
  return far / total;
}

// A real sketch as the surfacing pipeline hands it to the proxy: cleaned and resampled (its
// default spacing, 0.005 of the diagonal).
Sketch prepared(const std::string& name) {
  Sketch sketch = read_sketch(std::filesystem::path(SKETCHSURF_DATA_DIR) / name);
  clean(sketch);
  resample(sketch, 0.005 * sketch.bounding_box().diagonal());
  return sketch;
}

TEST(ProxyShapeData, ALampsPoleIsNotWebbedToItsBase) {
  // cassie/10-0-1: a desk lamp, a long arched pole (a line with a zigzag wound round it) between
  // a round base and a shade. VIPSS's smoothest normals spread the pole into a wall down to the
  // base, most of the surface far from every stroke; the pole's own normals keep it a thin tube:
  // cut across between the base and the shade, the section is as narrow as the pole's strokes
  // (the wall's: 0.2 of the diagonal).
  const Sketch sketch = prepared("cassie/10-0-1.curves");
  ProxyReport report;
  const TriMesh proxy = make_proxy(sketch, {}, {}, &report);
  const BoundingBox box = sketch.bounding_box();
  for (const double t : {0.3, 0.4, 0.5, 0.6}) {
    const double height = box.min.y() + t * (box.max.y() - box.min.y());
    EXPECT_EQ(section_loops(proxy, height), 1u) << "at " << t;
    EXPECT_LT(section_width(proxy, height), 0.07 * box.diagonal()) << "at " << t;
  }
  EXPECT_GT(report.part_normals, 0u);
  EXPECT_LT(area_farther_than(proxy, sketch, 0.11 * box.diagonal()), 0.005);
  EXPECT_EQ(mesh_topology(proxy).components, 1u);
  EXPECT_EQ(mesh_topology(proxy).genus, 0) << "a window through the shade by the pole's top "
                                               "(its space across runs into the pole) is closed";
}

TEST(ProxyShapeData, AnArmLampIsNotOneHull) {
  // cassie/01-0-1: an arm lamp, a round base, two arms of paired rods with springs on each side
  // and a shade, drawn by their outlines. VIPSS's smoothest normals wrap all of it in one hull
  // (58% of its surface far from every stroke), its cut at the arms' height a third of the
  // strokes' box or more (0.037-0.049 of the diagonal squared); with the arms' own normals the
  // arms are arms (0.024-0.026), though one side comes apart from the base and the shade.
  const Sketch sketch = prepared("cassie/01-0-1.curves");
  ProxyReport report;
  const TriMesh proxy = make_proxy(sketch, {}, {}, &report);
  const BoundingBox box = sketch.bounding_box();
  const double diagonal = box.diagonal();
  for (const double t : {0.2, 0.25, 0.3}) {
    const double height = box.min.y() + t * (box.max.y() - box.min.y());
    EXPECT_LT(section_area(proxy, height), 0.03 * diagonal * diagonal) << "at " << t;
  }
  EXPECT_GT(report.part_normals, 0u);
  EXPECT_LT(report.far_area, 0.55);
}

TEST(ProxyShapeData, AChairsLegsStandApart) {
  // cassie/chair: a seat on four thin legs, each drawn with rings and lengthwise strokes. VIPSS's
  // smoothest normals melted them into a skirt, its bottom one closed ring; the legs' own
  // normals keep them apart: cut across below the seat, four loops.
  const Sketch sketch = prepared("cassie/chair.curves");
  ProxyReport report;
  const TriMesh proxy = make_proxy(sketch, {}, {}, &report);
  const BoundingBox box = sketch.bounding_box();
  for (const double t : {0.03, 0.08, 0.15})
    EXPECT_EQ(section_loops(proxy, box.min.y() + t * (box.max.y() - box.min.y())), 4u) << "at " << t;
  EXPECT_GT(report.part_normals, 0u);
  EXPECT_EQ(mesh_topology(proxy).genus, 1) << "the back's opening";
}

TEST(ProxyShapeData, FacesFramedByFarStrokesAreNotPitted) {
  // tilt/Dungeon_Chest: a chest whose lid and sides lie between edges far apart (and a webbed
  // part besides); the nearer confinement would pit the lid, so the wide one is kept.
  ProxyOptions options;
  ProxyReport report;
  make_proxy(prepared("tilt/Dungeon_Chest.tilt"), options, {}, &report);
  EXPECT_EQ(report.confine_radius, options.confine_radius);
}
#endif

INSTANTIATE_TEST_SUITE_P(RealSketches, ProxyData, ::testing::ValuesIn(sketches()),
                         [](const ::testing::TestParamInfo<std::string>& param_info) {
                           std::string name = param_info.param;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

}  // namespace
}  // namespace sketchsurf
