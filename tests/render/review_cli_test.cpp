// `sketchsurf review`: one contact sheet per result (3 x 2 pictures of the requested size) and an
// index page with the checks; a result without its sketch is listed as failed (exit 4).

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "engine/render/image.h"
#include "surfacing/sketch/io/mesh_io.h"
#include "surfacing/sketch/io/sketch_io.h"
#include "tests/support/cli_run.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

namespace fs = std::filesystem;

TEST(ReviewCli, ContactSheetsAndIndex) {
  const fs::path dir = fs::temp_directory_path() / "sketchsurf_review_cli";
  fs::remove_all(dir);
  fs::create_directories(dir / "results");
  const TriMesh mesh = testing::rounded_box_mesh(3, Eigen::Vector3d(0.5, 0.5, 0.5), 0.05);
  MeshAttributes attributes;
  for (auto v : mesh.vertices()) attributes.labels.push_back(mesh.point(v)[1] > 0.49 ? 1 : 0);
  write_mesh(mesh, dir / "results" / "cube.ply", attributes);
  write_sketch(testing::cube_sketch(), dir / "results" / "cube.json");
  write_mesh(mesh, dir / "results" / "orphan.ply");

  const auto run = testing::run_cli("review '" + (dir / "results").string() + "' -o '" +
                                        (dir / "out").string() + "' --tile 96",
                                    dir);
  EXPECT_EQ(run.exit_code, 4) << run.err;  // orphan.ply has no sketch
  EXPECT_NE(run.err.find("orphan"), std::string::npos) << run.err;
  const render::RgbaImage sheet = render::read_png(dir / "out" / "cube.png");
  EXPECT_EQ(sheet.width, 3 * 96 + 2 * 4);
  EXPECT_EQ(sheet.height, 2 * 96 + 4);
  // Not blank: the pictures hold strokes and surface, not only background.
  std::size_t dark = 0;
  for (int y = 0; y < sheet.height; ++y)
    for (int x = 0; x < sheet.width; ++x) dark += sheet.at(x, y)[0] < 200;
  EXPECT_GT(dark, std::size_t(sheet.width * sheet.height / 10));
  std::ifstream in(dir / "out" / "index.html");
  std::stringstream html;
  html << in.rdbuf();
  EXPECT_NE(html.str().find("cube.png"), std::string::npos);
  EXPECT_NE(html.str().find("orphan"), std::string::npos);
  EXPECT_NE(html.str().find("no sketch named orphan"), std::string::npos);
}

}  // namespace
}  // namespace sketchsurf
