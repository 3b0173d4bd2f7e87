// Writes the bundled example sketches of tests/data/ from the generators in shapes.h, so every
// bundled example is made by the project:  make_examples OUTPUT_DIR
// The test BundledExamples.MatchTheirGenerators checks that the committed files are up to date.

#include <iostream>

#include "surfacing/error.h"
#include "surfacing/sketch/io/json.h"
#include "surfacing/sketch/io/mesh_io.h"
#include "tests/support/examples.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: make_examples OUTPUT_DIR\n";
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
  } catch (const sketchsurf::Error& e) {
    std::cerr << "make_examples: " << e.what() << "\n";
    return 4;
  }
  return 0;
}
