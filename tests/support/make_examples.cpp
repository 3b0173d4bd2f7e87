// Writes the bundled example sketches of tests/data/ from the generators in shapes.h, so every
// bundled example is made by the project:  make_examples OUTPUT_DIR [SUITE_DIR]
// The test BundledExamples.MatchTheirGenerators checks that the committed files are up to date.
// With SUITE_DIR, the meshes of the ground-truth suite (truth_suite.h) are written there too, as
// NAME.ply, to look at; they are not bundled (generated on demand, in a few seconds).

#include <iostream>

#include "surfacing/error.h"
#include "surfacing/sketch/io/json.h"
#include "surfacing/sketch/io/mesh_io.h"
#include "tests/support/examples.h"
#include "tests/support/truth_suite.h"

int main(int argc, char** argv) {
  if (argc != 2 && argc != 3) {
    std::cerr << "usage: make_examples OUTPUT_DIR [SUITE_DIR]\n";
    return 2;
  }
  try {
    for (const auto& [name, sketch] : sketchsurf::testing::bundled_examples()) {
      const auto file = std::filesystem::path(argv[1]) / (name + ".json");
      sketchsurf::write_json(sketch, file);
      std::cout << "wrote " << file.string() << "\n";
    }
    for (const auto& [name, mesh] : sketchsurf::testing::bundled_example_proxies()) {
      const auto file = std::filesystem::path(argv[1]) / (name + ".obj");
      sketchsurf::write_mesh(mesh, file);
      std::cout << "wrote " << file.string() << "\n";
    }
    if (argc == 3) {
      std::filesystem::create_directories(argv[2]);
      for (const auto& name : sketchsurf::testing::truth_shape_names()) {
        const auto file = std::filesystem::path(argv[2]) / (name + ".ply");
        sketchsurf::write_mesh(sketchsurf::testing::truth_shape(name).mesh, file);
        std::cout << "wrote " << file.string() << "\n";
      }
    }
  } catch (const sketchsurf::Error& e) {
    std::cerr << "make_examples: " << e.what() << "\n";
    return 4;
  }
  return 0;
}
