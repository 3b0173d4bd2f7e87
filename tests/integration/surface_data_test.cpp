// Stroke fit of the final surface on the real sketches (label `data`): every CASSIE (.curves) and
// VNS (.obj) sketch in ../shared/data, through the whole pipeline with an automatic proxy built by
// the test at a coarser resolution than the paper's (to keep the test short): the median distance
// from the stroke points to the surface must stay under 1% of the bounding-box diagonal. And the
// flower, a scene of single lines that depicts no surface, and an Open Brush sketch of scribbled
// masses are refused with the default parameters;
// a lamp's cable and its plug, a torch's ring on a string, and an espresso machine's two dots are
// left out of the surface (the machine's cap then does not pass through itself); a
// shield's back drawn by its rim comes out as a cap, not folded; a dress drawn as sections comes
// out as a tube lofted through them; a lamp's pole is not spread into a wall; a mouse's flat
// bottom, drawn by its outline, stays flat; a boat's stern does not fold through itself.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <tuple>

#include "surfacing/error.h"
#include "surfacing/pipeline.h"
#include "surfacing/self_intersections.h"
#include "surfacing/sketch/io/sketch_io.h"
#include "surfacing/sketch/openings.h"
#include "tests/support/sections.h"

namespace sketchsurf {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> real_sketches() {
  std::vector<std::string> files;
  for (const char* dir : {"cassie", "vns"})
    for (const auto& entry : fs::directory_iterator(fs::path(SKETCHSURF_DATA_DIR) / dir))
      if (entry.path().extension() == ".curves" || entry.path().extension() == ".obj")
        files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

// The defaults but for a coarser proxy and fewer restarts, to keep the tests short. The proxy's
// edge is 0.014 of the diagonal, twice the paper's: at 0.02 thin parts (the guitar's neck) are
// under-resolved and its median distance rises to 1.25%; at 0.014 it is 0.56%.
Params coarse_params() {
  Params params;
  params.proxy.edge = 0.014;
  params.segment.restarts = 2;
  return params;
}

class SurfaceData : public ::testing::TestWithParam<std::string> {};

TEST_P(SurfaceData, MedianStrokeDistanceUnderOnePercent) {
  const Sketch sketch = read_sketch(GetParam());
  Params params = coarse_params();
  params.checks.refuse_score = 0.0;  // the stroke fit of every sketch, the flower's too
  const SurfaceResult r = Surfacer(params).run(sketch);
  EXPECT_LT(r.report.stroke_distance.median, 0.01) << GetParam();
  EXPECT_GT(r.mesh.n_faces(), 0u);
  std::cerr << fs::path(GetParam()).filename().string() << ": median "
            << 100 * r.report.stroke_distance.median << "%, p95 " << 100 * r.report.stroke_distance.p95
            << "%, " << r.segmentation.models.size() << " regions, " << r.mesh.n_vertices()
            << " vertices, " << r.report.total_s << " s (extraction " << r.report.extraction_s << " s)\n";
}

// Surfacing `file` (under the data folder) with the default parameters is refused as depicting no
// surface, the message containing `why`.
void expect_refused(const fs::path& file, const std::string& why) {
  const fs::path path = fs::path(SKETCHSURF_DATA_DIR) / file;
  try {
    surface(read_sketch(path));
    FAIL() << path << " was surfaced";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Processing) << e.what();
    EXPECT_NE(std::string(e.what()).find("do not seem to depict one surface"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
  }
}

TEST(NonSurfaceData, TheFlowerIsRefused) { expect_refused("cassie/flower.curves", "runs out beyond the strokes"); }

TEST(NonSurfaceData, TheScribbledSketchIsRefused) { expect_refused("tilt/sketch1.tilt", "of the ink is scribbles"); }

TEST(DecorationData, ALampsCableAndPlugAreLeftOut) {
  // cassie/02-0-1: a table lamp whose cable (its longest stroke) runs from the base across the
  // floor to a plug of six small strokes. Surfaced, they made a sheet as long as the cable.
  const Sketch sketch = read_sketch(fs::path(SKETCHSURF_DATA_DIR) / "cassie" / "02-0-1.curves");
  std::size_t cable = 0;
  for (std::size_t s = 0; s < sketch.strokes.size(); ++s)
    if (sketch.strokes[s].length() > sketch.strokes[cable].length()) cable = s;
  const SurfaceResult r = Surfacer(coarse_params()).run(sketch);
  std::size_t dangling = 0, carried = 0;
  for (const Decoration& d : r.report.decorations) {
    if (d.stroke == cable) {
      EXPECT_EQ(d.kind, DecorationKind::Dangling);
    }
    dangling += d.kind == DecorationKind::Dangling;
    carried += d.stroke > cable && d.stroke <= cable + 6 && d.kind == DecorationKind::SmallGroup;
  }
  EXPECT_EQ(dangling, 1u);
  EXPECT_EQ(carried, 6u);
  // The surface stays with the lamp: its extent is the lamp's, not the lamp's and the cable's.
  std::vector<char> left_out(sketch.strokes.size(), 0);
  for (const Decoration& d : r.report.decorations) left_out[d.stroke] = 1;
  BoundingBox lamp, surface;
  for (std::size_t s = 0; s < sketch.strokes.size(); ++s)
    if (!left_out[s])
      for (const auto& p : sketch.strokes[s].points) lamp.extend(p);
  for (const auto v : r.mesh.vertices()) surface.extend(to_eigen(r.mesh.point(v)));
  EXPECT_LT(surface.diagonal(), 1.1 * lamp.diagonal());
}

TEST(DecorationData, ATorchsHangingRingIsLeftOutAndItsHandleKept) {
  // tilt/Dungeon_Torch: a ring on a string hangs from the handle; the string passes by the
  // handle's strokes for part of its length, the handle's own strokes run beside each other.
  const Sketch sketch = read_sketch(fs::path(SKETCHSURF_DATA_DIR) / "tilt" / "Dungeon_Torch.tilt");
  const SurfaceResult r = Surfacer(coarse_params()).run(sketch);
  ASSERT_EQ(r.report.decorations.size(), 2u);
  EXPECT_EQ(r.report.decorations[0].kind, DecorationKind::Dangling);
  EXPECT_EQ(r.report.decorations[1].kind, DecorationKind::SmallGroup);
}

TEST(DecorationData, AnEspressoMachinesTwoDotsAreLeftOutAndItsCapIsWhole) {
  // vns/expresso_teaser_simplified: two taps of 2 and 3 points (0.3% and 0.6% of the diagonal)
  // on the cap. Kept as strokes, the cap came out as one wavy region folded through itself (1833
  // crossing triangle pairs); left out, a smooth top and rim (none).
  const Sketch sketch = read_sketch(fs::path(SKETCHSURF_DATA_DIR) / "vns" / "expresso_teaser_simplified.obj");
  const SurfaceResult r = Surfacer().run(sketch);
  ASSERT_EQ(r.report.decorations.size(), 2u);
  for (const Decoration& d : r.report.decorations) {
    EXPECT_EQ(d.kind, DecorationKind::Dot);
    const auto drawn = std::find_if(sketch.strokes.begin(), sketch.strokes.end(),
                                    [&](const Stroke& s) { return s.id == d.id; });
    ASSERT_NE(drawn, sketch.strokes.end());
    EXPECT_LT(drawn->length(), 0.01 * sketch.bounding_box().diagonal());
  }
  EXPECT_LT(r.report.checks.self_intersections, 100u);
}

TEST(TieData, AShieldsBackDrawnByItsRimAndOneMeridianIsNotFolded) {
  // cassie/shield: the back is drawn by the rim and one meridian only. Of the ten PEARL runs, the
  // lowest in energy fits it with a quartic that folds across the face through the front (913
  // crossing triangle pairs, the front crumpled; projecting the proxy onto the models moves 33% of
  // its vertices farther than 3% of the diagonal); another, 9.5% above that energy, moves 2.9% and
  // makes it a smooth cap (262 pairs). Of the runs within the fold window, the one that moves the
  // proxy least far is kept when the kept run moves far more.
  const Sketch sketch = read_sketch(fs::path(SKETCHSURF_DATA_DIR) / "cassie" / "shield.curves");
  const SurfaceResult r = Surfacer().run(sketch);
  EXPECT_LT(r.report.checks.self_intersections, 600u);
  const auto& summary = r.segmentation.summary;
  const auto& e = summary.restart_energies;
  const double lowest = *std::min_element(e.begin(), e.end());
  EXPECT_LE(e[summary.best_restart], (1.0 + Params().segment.fold) * lowest);
  ASSERT_EQ(summary.restart_departures.size(), e.size());
  EXPECT_LT(summary.restart_departures[summary.best_restart], 0.1);
}

TEST(ThinPartData, ALampsPoleIsNotAWall) {
  // cassie/10-0-1: a desk lamp whose long arched pole (a line with a zigzag wound round it) the
  // proxy spread into a wall down to the base, and the surface kept it (sections 0.12-0.22 of the
  // diagonal wide). Now the pole is a tube (pinched to a line over a short stretch, at 0.4 of the
  // height, where its region's model fits the axis stroke): cut across between the base and the
  // shade, the surface is one narrow section.
  const Sketch sketch = read_sketch(fs::path(SKETCHSURF_DATA_DIR) / "cassie" / "10-0-1.curves");
  const SurfaceResult r = Surfacer().run(sketch);
  const BoundingBox box = sketch.bounding_box();
  for (const double t : {0.3, 0.4, 0.5, 0.6}) {
    const double height = box.min.y() + t * (box.max.y() - box.min.y());
    EXPECT_EQ(testing::section_loops(r.mesh, height), 1u) << "at " << t;
    EXPECT_LT(testing::section_width(r.mesh, height), 0.07 * box.diagonal()) << "at " << t;
  }
}

TEST(FaceData, AMousesFlatBottomIsNotDentedByTheShellsModel) {
  // cassie/computer-mouse: a shell drawn with its bottom outline, no stroke across the bottom. The
  // proxy draws the bottom in as a flat face; the region that holds the bottom and the skirt fits
  // the skirt's strokes with a quartic whose zero set dips 3-8% of the diagonal into the body
  // under the bottom's middle: a grooved bottom and a lip round it where the skirt passed through
  // the shell (4,818 crossing triangle pairs; the proxy has 9). The bottom stays on its face.
  const Sketch sketch = read_sketch(fs::path(SKETCHSURF_DATA_DIR) / "cassie" / "computer-mouse.curves");
  const SurfaceResult r = Surfacer().run(sketch);
  const double diagonal = sketch.bounding_box().diagonal();
  const auto bottom = std::find_if(r.report.proxy.drawn_faces.begin(), r.report.proxy.drawn_faces.end(),
                                   [](const Plane& face) { return face.normal.y() < -0.99; });
  ASSERT_NE(bottom, r.report.proxy.drawn_faces.end()) << "the proxy draws the bottom in";
  EXPECT_GT(r.report.extraction.optimization.face_vertices, 0u);
  // The lowest point of the surface over each cell of the bottom (cells 1% of the diagonal wide,
  // in x and z), where the proxy lies on the face farther than 5% from every stroke point.
  const double cell = 0.01 * diagonal;
  const auto key = [&](const Eigen::Vector3d& p) {
    return std::pair{static_cast<long>(std::floor(p.x() / cell)), static_cast<long>(std::floor(p.z() / cell))};
  };
  std::map<std::pair<long, long>, double> lowest;
  for (auto v : r.mesh.vertices()) {
    const Eigen::Vector3d p = to_eigen(r.mesh.point(v));
    const auto [it, added] = lowest.emplace(key(p), p.y());
    if (!added) it->second = std::min(it->second, p.y());
  }
  std::size_t inner = 0, dented = 0;
  for (auto v : r.proxy.vertices()) {
    const Eigen::Vector3d p = to_eigen(r.proxy.point(v));
    if (std::abs(bottom->signed_distance(p)) > 1e-4 * diagonal) continue;
    double to_strokes = std::numeric_limits<double>::infinity();
    for (const Stroke& s : sketch.strokes)
      for (const Eigen::Vector3d& q : s.points) to_strokes = std::min(to_strokes, (q - p).norm());
    if (to_strokes < 0.05 * diagonal) continue;
    ++inner;
    const auto it = lowest.find(key(p));
    dented += it == lowest.end() || it->second > p.y() + 0.02 * diagonal;
  }
  ASSERT_GT(inner, 1000u);
  EXPECT_LT(static_cast<double>(dented) / inner, 0.05) << dented << " of " << inner;
  EXPECT_LT(r.report.checks.self_intersections, 1000u);
}

// A real sketch (path under the data folder) surfaced with the defaults, checked for what every
// fold test asks: no fold left, and no more crossing triangles than its proxy has.
SurfaceResult surfaced_without_folds(const fs::path& file) {
  SurfaceResult r = Surfacer().run(read_sketch(fs::path(SKETCHSURF_DATA_DIR) / file));
  EXPECT_EQ(r.report.extraction.unfold.left_pairs, 0u) << file;
  EXPECT_LE(count_self_intersections(r.mesh), count_self_intersections(r.proxy)) << file;
  return r;
}

TEST(FoldData, ABoatsSternDoesNotFoldThroughItself) {
  // vns/boat: where the transom's regions meet the hull's, the solve folds the surface through
  // itself (a frayed fin at the stern's corner and pleats along the seams: 215 crossing triangle
  // pairs where the proxy has 9). Ironed out, the surface crosses itself no more than its proxy.
  const SurfaceResult r = surfaced_without_folds(fs::path("vns") / "boat.obj");
  EXPECT_GT(r.report.extraction.unfold.crossing_pairs, 50u);
  EXPECT_LT(r.report.extraction.unfold.moved_vertices, r.mesh.n_vertices() / 10);
  EXPECT_LT(r.report.stroke_distance.median, 0.003);
}

TEST(FoldData, ATorchsFlameDoesNotFoldThroughItself) {
  // tilt/Dungeon_Torch: where the flame's back meets its collar the solve folds the surface
  // through itself (261 crossing triangle pairs the proxy lacks) over a zone of about a seventh of
  // the mesh; the first fill leaves folds there, the membrane removes them.
  const SurfaceResult r = surfaced_without_folds(fs::path("tilt") / "Dungeon_Torch.tilt");
  EXPECT_GT(r.report.extraction.unfold.crossing_pairs, 100u);
  EXPECT_EQ(r.report.extraction.unfold.skipped_vertices, 0u);
  EXPECT_LT(r.report.extraction.unfold.moved_vertices, r.mesh.n_vertices() / 5);
  EXPECT_LT(r.report.stroke_distance.median, 0.005);
}

TEST(FoldData, AnArmLampIsALampNotAFoldedHull) {
  // cassie/01-0-1: an arm lamp drawn by its outlines. On a proxy that wrapped base, arms and shade
  // in one hull, the regions' models folded the hull through itself (3,575 crossing triangle
  // pairs the proxy lacked). On the proxy that keeps the arms' own normals, the final is base,
  // arms and shade, and folds no more than its proxy.
  const SurfaceResult r = surfaced_without_folds(fs::path("cassie") / "01-0-1.curves");
  EXPECT_GT(r.report.proxy.part_normals, 0u);
  EXPECT_LT(r.report.stroke_distance.median, 0.0045);
}

TEST(FoldData, AChestsFoldTooWideToFillIsHeldAtTheProxy) {
  // tilt/Dungeon_Chest: the solve folds a region's surface through another's over more than a fill
  // may span (both fills leave over a hundred crossing pairs). That region is held at the proxy
  // and the mesh solved again: no fold is left and the strokes stay about as near.
  const SurfaceResult r = surfaced_without_folds(fs::path("tilt") / "Dungeon_Chest.tilt");
  EXPECT_GE(r.report.extraction.unfold.held_regions, 1u);
  EXPECT_LT(r.report.stroke_distance.median, 0.006);
}

TEST(FoldData, ADressHemRefittedAsAQuadricDoesNotFold) {
  // cassie/dress: the hem's quartic cap flares out through the skirt (3,011 crossing triangle
  // pairs, too wide to fill; held at the proxy the hem turns lumpy and the gate refuses it). The
  // hem's region, on nearly all of the crossing triangles, fitted again as a quadric: no fold is
  // left and the strokes stay as near.
  const SurfaceResult r = surfaced_without_folds(fs::path("cassie") / "dress.curves");
  EXPECT_EQ(r.report.extraction.unfold.refit_degree, 2);
  EXPECT_EQ(r.report.extraction.unfold.refitted_regions, 1u);
  EXPECT_EQ(r.report.extraction.unfold.held_regions, 0u);
  EXPECT_LT(r.report.stroke_distance.median, 0.0025);
}

TEST(FoldData, AShoesSoleRefittedAsAPlaneStaysAlongItsStrokes) {
  // cassie/03-1-2: the sole's quartic curls up inside the shoe's sides (2,581 crossing triangle
  // pairs) and bulges below the drawn sole. Fitted again as a plane, the sole lies along its
  // strokes; the few crossing pairs left where it meets the sides (8) are held at the proxy with
  // the rings round them: no fold is left, the strokes as near as before.
  const SurfaceResult r = surfaced_without_folds(fs::path("cassie") / "03-1-2.curves");
  const UnfoldSummary& unfold = r.report.extraction.unfold;
  EXPECT_EQ(unfold.refit_degree, 1);
  EXPECT_EQ(unfold.held_regions, 0u);
  EXPECT_GT(unfold.held_zone, 0u);
  EXPECT_LT(unfold.held_zone, r.mesh.n_vertices() / 100);
  EXPECT_LT(r.report.stroke_distance.median, 0.0025);
}

TEST(SectionData, ADressDrawnAsSectionsIsALoftedTube) {
  // vns/dress: a waist circle, a four-lobed hem below it and a profile through both. VIPSS's
  // surface ran out between them to the strokes' box (its cross-section a rectangle round the
  // hem); lofted, the dress follows the hem's lobes and valleys and stays within its sections.
  const Sketch sketch = read_sketch(fs::path(SKETCHSURF_DATA_DIR) / "vns" / "dress.obj");
  const SurfaceResult r = Surfacer(coarse_params()).run(sketch);
  EXPECT_EQ(r.report.proxy.loft_sections, 2u);
  // The waist and the hem: the two loops whose planes are parallel.
  std::vector<StrokeLoop> loops;
  std::vector<std::size_t> strokes;
  for (std::size_t s = 0; s < sketch.strokes.size(); ++s)
    if (const auto loop = stroke_loop(sketch.strokes[s].points)) {
      loops.push_back(*loop);
      strokes.push_back(s);
    }
  ASSERT_EQ(loops.size(), 3u);  // and the profile, at right angles to them
  std::size_t a = 0, b = 1;
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = i + 1; j < 3; ++j)
      if (std::abs(loops[i].plane.normal.dot(loops[j].plane.normal)) >
          std::abs(loops[a].plane.normal.dot(loops[b].plane.normal)))
        std::tie(a, b) = std::tie(i, j);
  const Eigen::Vector3d axis = (loops[b].center - loops[a].center).normalized();
  const auto radial = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d d = p - loops[a].center;
    return (d - d.dot(axis) * axis).norm();
  };
  double widest = 0.0;
  for (std::size_t s : {strokes[a], strokes[b]})
    for (const Eigen::Vector3d& p : sketch.strokes[s].points) widest = std::max(widest, radial(p));
  const double length = (loops[b].center - loops[a].center).norm();
  const double tolerance = 0.01 * sketch.bounding_box().diagonal();
  for (const auto v : r.mesh.vertices()) {
    const Eigen::Vector3d p = to_eigen(r.mesh.point(v));
    const double along = (p - loops[a].center).dot(axis);
    ASSERT_LE(radial(p), widest + tolerance) << "vertex " << v.idx();
    ASSERT_GE(along, -tolerance) << "vertex " << v.idx();
    ASSERT_LE(along, length + tolerance) << "vertex " << v.idx();
  }
  EXPECT_LT(r.report.stroke_distance.p95, 0.01);
  EXPECT_EQ(r.report.checks.self_intersections, 0u);
}

INSTANTIATE_TEST_SUITE_P(RealSketches, SurfaceData, ::testing::ValuesIn(real_sketches()),
                         [](const ::testing::TestParamInfo<std::string>& param_info) {
                           std::string name = fs::path(param_info.param).stem().string();
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return fs::path(param_info.param).parent_path().filename().string() + "_" + name;
                         });

}  // namespace
}  // namespace sketchsurf
