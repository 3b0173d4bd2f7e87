// Reads a sketch, checks the default parameters and writes the sketch back as .json: enough to
// compile against the installed headers and link the installed libraries.
#include <iostream>
#include <string>

#include "surfacing/pipeline.h"
#include "surfacing/sketch/io/sketch_io.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: consumer SKETCH OUT.json\n";
    return 2;
  }
  const sketchsurf::Sketch sketch = sketchsurf::read_sketch(argv[1]);
  std::string why;
  if (!sketchsurf::Params().valid(&why)) {
    std::cerr << "default parameters invalid: " << why << "\n";
    return 1;
  }
  sketchsurf::write_sketch(sketch, argv[2]);
  std::cout << sketch.strokes.size() << " strokes\n";
  return 0;
}
