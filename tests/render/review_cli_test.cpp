// `sketchsurf review`: one contact sheet per result (3 x 2 pictures of the requested size) and an
// index page with the checks; a result without its sketch is listed as failed (exit 4). Its
// outputs are checked before any work and written together, as every command's. A batch's output
// folder is reviewed as it is: its subfolders searched, its summary naming the sketches.

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

TEST(ReviewCli, OutputsAreCheckedBeforeAnyWorkAndNoneIsChangedOnRefusal) {
  const fs::path dir = testing::scratch_dir("sketchsurf_review_cli_");
  const TriMesh mesh = testing::rounded_box_mesh(2, Eigen::Vector3d(0.5, 0.5, 0.5), 0.05);
  for (const char* folder : {"a", "b"}) {
    fs::create_directories(dir / folder);
    write_mesh(mesh, dir / folder / "cube.ply");
    write_sketch(testing::cube_sketch(), dir / folder / "cube.json");
  }
  fs::create_directories(dir / "out");
  {
    std::ofstream(dir / "out" / "index.html") << "earlier review\n";
  }
  const std::string out = testing::quoted(dir / "out");
  // Two results named cube: their contact sheets would be one file.
  auto run = testing::run_cli("review " + testing::quoted(dir / "a" / "cube.ply") + " " +
                                  testing::quoted(dir / "b" / "cube.ply") + " -o " + out,
                              dir);
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("is also the output"), std::string::npos) << run.err;
  // A contact sheet's name taken by a folder.
  fs::create_directories(dir / "out" / "cube.png");
  run = testing::run_cli("review " + testing::quoted(dir / "a") + " -o " + out, dir);
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("cube.png is a directory"), std::string::npos) << run.err;
  EXPECT_EQ(run.err.find("review: [1/1]"), std::string::npos) << "refused only after rendering";
  // Neither run changed the earlier index nor left a temporary file.
  std::ifstream in(dir / "out" / "index.html");
  std::stringstream html;
  html << in.rdbuf();
  EXPECT_EQ(html.str(), "earlier review\n");
  for (const auto& entry : fs::directory_iterator(dir / "out"))
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
  // Once the folder is out of the way, the same run writes both.
  fs::remove(dir / "out" / "cube.png");
  run = testing::run_cli("review " + testing::quoted(dir / "a") + " -o " + out + " --tile 64", dir);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(render::read_png(dir / "out" / "cube.png").width, 3 * 64 + 2 * 4);
  EXPECT_GT(fs::file_size(dir / "out" / "index.html"), 500u);
}

TEST(ReviewCli, ABatchsOutputFolderIsReviewedWithTheSketchesItsSummaryNames) {
  // `sketchsurf batch` keeps the input folders' structure and writes a report NAME.json beside
  // each result (not a sketch); summary.json names each result's sketch.
  const fs::path dir = testing::scratch_dir("sketchsurf_review_batch_");
  const TriMesh mesh = testing::rounded_box_mesh(2, Eigen::Vector3d(0.5, 0.5, 0.5), 0.05);
  fs::create_directories(dir / "sketches" / "boxes");
  write_sketch(testing::cube_sketch(), dir / "sketches" / "boxes" / "cube.curves");
  fs::create_directories(dir / "batch" / "boxes");
  write_mesh(mesh, dir / "batch" / "boxes" / "cube.ply");
  std::ofstream(dir / "batch" / "boxes" / "cube.json") << "{\"regions\": 1}\n";
  std::ofstream(dir / "batch" / "summary.json")
      << "[{\"sketch\": \"" << (dir / "sketches" / "boxes" / "cube.curves").generic_string()
      << "\", \"output\": \"boxes/cube.ply\", \"status\": \"ok\"}]\n";
  const std::string out = testing::quoted(dir / "out");
  auto run = testing::run_cli("review " + testing::quoted(dir / "batch") + " -o " + out + " --tile 64", dir);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(render::read_png(dir / "out" / "boxes" / "cube.png").width, 3 * 64 + 2 * 4);
  std::ifstream in(dir / "out" / "index.html");
  std::stringstream html;
  html << in.rdbuf();
  EXPECT_NE(html.str().find("boxes/cube.png"), std::string::npos);
  EXPECT_NE(html.str().find("cube.curves"), std::string::npos);
  // The Python package's batch names the output by its whole path.
  std::ofstream(dir / "batch" / "summary.json")
      << "[{\"sketch\": \"" << (dir / "sketches" / "boxes" / "cube.curves").generic_string()
      << "\", \"output\": \"" << (dir / "batch" / "boxes" / "cube.ply").generic_string()
      << "\", \"status\": \"ok\"}]\n";
  run = testing::run_cli("review " + testing::quoted(dir / "batch") + " -o " + out + " --tile 64", dir);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  // Without the summary, --sketches finds it at the same place under its folder.
  fs::remove(dir / "batch" / "summary.json");
  run = testing::run_cli("review " + testing::quoted(dir / "batch") + " -o " + out + " --tile 64 --sketches " +
                             testing::quoted(dir / "sketches"),
                         dir);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  // Neither: the report beside the result is no sketch, and the error says what to do.
  run = testing::run_cli("review " + testing::quoted(dir / "batch") + " -o " + out + " --tile 64", dir);
  EXPECT_EQ(run.exit_code, 4) << run.err;
  EXPECT_NE(run.err.find("set --sketches"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace sketchsurf
