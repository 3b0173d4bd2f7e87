// Every .curves and .obj sketch of ../shared/data reads, with stroke and point counts established
// independently, and survives round trips through .json.
//
// The counts come from a separate Python script (not from this reader):
//  - .curves: strokes = number of `v N` lines, points = sum of the N (and equal to the number of
//    other non-blank lines);
//  - .obj (2-vertex `l` segments only): chains = connected components of segments under
//    union-find, joining two segments when they share a vertex of degree 2; points = segments +
//    chains (each chain of k segments has k + 1 points, a closed loop repeating its first vertex).

#include <gtest/gtest.h>

#include "surfacing/sketch/io/curves.h"
#include "surfacing/sketch/io/json.h"
#include "surfacing/sketch/io/obj_polylines.h"
#include "surfacing/sketch/io/sketch_io.h"
#include "tests/unit/sketch/io_test_support.h"

namespace sketchsurf {
namespace {

struct Expected {
  const char* file;
  std::size_t strokes, points;
};

const Expected kExpected[] = {
    {"cassie/01-0-1.curves", 45, 688},     {"cassie/03-1-2.curves", 31, 461},
    {"cassie/11-2-2.curves", 13, 115},     {"cassie/chair.curves", 199, 1237},
    {"cassie/computer-mouse.curves", 34, 257}, {"cassie/hat.curves", 69, 640},
    {"cassie/shield.curves", 82, 683},     {"cassie/teapot.curves", 77, 595},
    {"vns/box.obj", 12, 2922},             {"vns/car_1.obj", 69, 3155},
    {"vns/doghead.obj", 67, 2880},         {"vns/dress.obj", 3, 1342},
    {"vns/guitar.obj", 85, 2238},          {"vns/torus.obj", 9, 2525},
    {"cassie/02-0-1.curves", 61, 839},     {"cassie/02-1-2.curves", 64, 558},
    {"cassie/04-0-2.curves", 71, 804},     {"cassie/04-2-1.curves", 71, 820},
    {"cassie/06-1-1.curves", 34, 462},     {"cassie/06-2-2.curves", 35, 352},
    {"cassie/10-0-1.curves", 55, 550},     {"cassie/12-1-1.curves", 82, 700},
    {"cassie/architecture.curves", 63, 442}, {"cassie/flower.curves", 45, 339},
    {"cassie/dress.curves", 153, 911},     {"cassie/guitar.curves", 148, 770},
    {"cassie/sewing-machine.curves", 140, 758},
    {"vns/bathtub.obj", 19, 5077},         {"vns/boat.obj", 37, 3090},
    {"vns/car.obj", 68, 3313},             {"vns/ellipsetorus.obj", 10, 3385},
    {"vns/expresso_teaser_simplified.obj", 35, 4631},
    {"vns/phone_flowrep.obj", 112, 3246},  {"vns/spherecylinder.obj", 7, 1813},
    {"vns/trebol_flowrep.obj", 36, 2586},
};

std::filesystem::path data(const char* file) {
  return std::filesystem::path(SKETCHSURF_DATA_DIR) / file;
}

TEST(FormatsData, EveryCurvesAndObjFileIsCovered) {
  std::size_t found = 0;
  for (const char* folder : {"cassie", "vns"})
    for (const auto& e : std::filesystem::directory_iterator(data(folder))) {
      const auto ext = e.path().extension();
      if (ext != ".curves" && ext != ".obj") continue;
      ++found;
      const std::string name = std::string(folder) + "/" + e.path().filename().string();
      const bool listed = std::any_of(std::begin(kExpected), std::end(kExpected),
                                      [&](const Expected& x) { return name == x.file; });
      EXPECT_TRUE(listed) << name << " has no expected counts";
    }
  EXPECT_EQ(found, std::size(kExpected));
}

TEST(FormatsData, CountsMatchAnIndependentCount) {
  for (const auto& x : kExpected) {
    SCOPED_TRACE(x.file);
    Warnings warnings;
    const Sketch s = read_sketch(data(x.file), &warnings);
    EXPECT_EQ(s.strokes.size(), x.strokes);
    EXPECT_EQ(s.point_count(), x.points);
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    for (const auto& st : s.strokes) EXPECT_GE(st.size(), 2u);
    // Everything sits within a few metres of the origin (metres, not centimetres).
    const BoundingBox box = s.bounding_box();
    EXPECT_GT(box.diagonal(), 0.1);
    EXPECT_LT(box.diagonal(), 10.0);
  }
}

TEST(FormatsData, ObjChainsAreClosedOrEndAtJunctionsAndEnds) {
  // In the VNS files a chain's inner points are the shared vertices of degree 2: no point of a
  // chain except its ends appears in another chain.
  for (const auto& x : kExpected) {
    if (!std::string(x.file).ends_with(".obj")) continue;
    SCOPED_TRACE(x.file);
    const Sketch s = read_obj_polylines(data(x.file));
    std::map<std::array<double, 3>, int> uses;
    for (const auto& st : s.strokes)
      for (const auto& p : st.points) ++uses[{p.x(), p.y(), p.z()}];
    for (const auto& st : s.strokes)
      for (std::size_t i = 1; i + 1 < st.size(); ++i) {
        const auto& p = st.points[i];
        EXPECT_EQ((uses[{p.x(), p.y(), p.z()}]), 1);
      }
  }
}

TEST(FormatsData, RoundTripsThroughJsonKeepEveryStroke) {
  testing::TempDir dir;
  for (const auto& x : kExpected) {
    SCOPED_TRACE(x.file);
    const std::string ext = std::filesystem::path(x.file).extension().string();
    const Sketch original = read_sketch(data(x.file));
    write_json(original, dir / "s.json");
    const Sketch via_json = read_json(dir / "s.json");
    testing::expect_identical(original, via_json);
    write_sketch(via_json, dir / ("back" + ext));
    const Sketch back = read_sketch(dir / ("back" + ext));
    testing::expect_same_points(original, back, 1e-6);
  }
}

}  // namespace
}  // namespace sketchsurf
