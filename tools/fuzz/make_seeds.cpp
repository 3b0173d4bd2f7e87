// Writes the seed corpora of the reader fuzzers from what the project made (tests/data): small
// versions of the bundled sketches (every .json there that reads as a sketch; a few strokes of a
// few points, so that mutations stay cheap, with their annotations, mirror plane and parameters)
// in every sketch format, and the bundled proxy and a labelled tetrahedron in every mesh format
// the --proxy reader takes (binary PLY with labels, colours and sharp flags, ASCII and big-endian
// PLY, OBJ with colours and slashed faces).
//   make_fuzz_seeds TESTS_DATA_DIR OUT_DIR
// OUT_DIR gets one folder per target: tilt, tilt_dir (the inputs of the directory-form target:
// a 4-byte little-endian length, data.sketch, metadata.json), curves, obj, json, mesh_obj,
// mesh_ply.

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include <zip.h>

#include "surfacing/error.h"
#include "surfacing/sketch/io/mesh_io.h"
#include "surfacing/sketch/io/sketch_io.h"

namespace {

namespace fs = std::filesystem;
using namespace sketchsurf;

/// The first `strokes` strokes of `sketch`, each cut to its first `points` points.
Sketch shrink(const Sketch& sketch, std::size_t strokes, std::size_t points) {
  Sketch small = sketch;
  small.strokes.resize(std::min(strokes, small.strokes.size()));
  for (Stroke& stroke : small.strokes) {
    const std::size_t n = std::min(points, stroke.points.size());
    stroke.points.resize(n);
    if (!stroke.orientations.empty()) stroke.orientations.resize(n);
    if (!stroke.pressures.empty()) stroke.pressures.resize(n);
    if (!stroke.timestamps_ms.empty()) stroke.timestamps_ms.resize(n);
  }
  return small;
}

void write_text(const fs::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
}

/// The bytes of entry `name` of the zip archive that follows the header of the .tilt `file`.
std::string zip_entry(const fs::path& file, const char* name) {
  std::ifstream in(file, std::ios::binary);
  const std::string tilt((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t header = tilt.size() < 6 ? tilt.size()
                                             : static_cast<std::uint8_t>(tilt[4]) |
                                                   static_cast<std::size_t>(static_cast<std::uint8_t>(tilt[5])) << 8;
  std::string bytes;
  zip_error_t error;
  zip_error_init(&error);
  zip_source_t* source = zip_source_buffer_create(tilt.data() + header, tilt.size() - header, 0, &error);
  zip_t* archive = source ? zip_open_from_source(source, ZIP_RDONLY, &error) : nullptr;
  zip_stat_t st;
  zip_file_t* entry = nullptr;
  if (archive && zip_stat(archive, name, 0, &st) == 0 && (entry = zip_fopen(archive, name, 0))) {
    bytes.resize(st.size);
    if (zip_fread(entry, bytes.data(), st.size) != static_cast<zip_int64_t>(st.size)) bytes.clear();
    zip_fclose(entry);
  }
  if (archive) zip_close(archive);
  else if (source) zip_source_free(source);
  zip_error_fini(&error);
  if (bytes.empty()) throw std::runtime_error(file.string() + ": cannot read zip entry " + name);
  return bytes;
}

/// A .tilt's entries as one input of the directory-form target.
std::string tilt_directory_input(const fs::path& tilt) {
  const std::string sketch = zip_entry(tilt, "data.sketch");
  std::string input;
  for (int b = 0; b < 4; ++b) input.push_back(static_cast<char>((sketch.size() >> (8 * b)) & 0xff));
  return input + sketch + zip_entry(tilt, "metadata.json");
}

/// A tetrahedron in the given PLY encoding, written by hand: the project's writer only writes
/// little-endian binary.
std::string tetrahedron_ply(bool big_endian) {
  const float xyz[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const int faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  std::string text = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "ascii") +
                     " 1.0\ncomment seed\nelement vertex 4\nproperty float x\nproperty float y\n"
                     "property float z\nproperty int label\nproperty uchar red\nproperty uchar green\n"
                     "property uchar blue\nelement face 4\nproperty list uchar int vertex_indices\n"
                     "end_header\n";
  auto put_be = [&](std::uint32_t v, int bytes) {
    for (int b = bytes - 1; b >= 0; --b) text.push_back(static_cast<char>((v >> (8 * b)) & 0xff));
  };
  for (int v = 0; v < 4; ++v) {
    if (big_endian) {
      for (float c : xyz[v]) put_be(std::bit_cast<std::uint32_t>(c), 4);
      put_be(static_cast<std::uint32_t>(v % 2), 4);
      for (int c = 0; c < 3; ++c) put_be(static_cast<std::uint32_t>(60 * v + c), 1);
    } else {
      text += std::to_string(xyz[v][0]) + " " + std::to_string(xyz[v][1]) + " " +
              std::to_string(xyz[v][2]) + " " + std::to_string(v % 2) + " 10 200 30\n";
    }
  }
  for (const auto& f : faces) {
    if (big_endian) {
      put_be(3, 1);
      for (int i : f) put_be(static_cast<std::uint32_t>(i), 4);
    } else {
      text += "3 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) + "\n";
    }
  }
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: make_fuzz_seeds TESTS_DATA_DIR OUT_DIR\n");
    return 2;
  }
  const fs::path data = argv[1], out = argv[2];
  try {
    for (const char* target : {"tilt", "tilt_dir", "curves", "obj", "json", "mesh_obj", "mesh_ply"})
      fs::create_directories(out / target);
    for (const auto& entry : fs::directory_iterator(data)) {
      if (entry.path().extension() != ".json") continue;
      Sketch sketch;
      try {
        sketch = read_sketch(entry.path());
      } catch (const Error& e) {  // another JSON document kept with the examples
        std::fprintf(stderr, "make_fuzz_seeds: skipped %s\n", e.what());
        continue;
      }
      const std::string name = entry.path().stem().string();
      for (const auto& [strokes, points] : {std::pair{2, 3}, std::pair{4, 8}}) {
        const Sketch small = shrink(sketch, strokes, points);
        const std::string stem = name + "_" + std::to_string(strokes) + "x" + std::to_string(points);
        for (const char* format : {"tilt", "curves", "obj", "json"})
          write_sketch(small, out / format / (stem + "." + format));
        write_text(out / "tilt_dir" / stem, tilt_directory_input(out / "tilt" / (stem + ".tilt")));
      }
    }
    write_text(out / "obj" / "segments.obj",
               "# a square and a tail as 2-vertex segments: chains split where 3 meet\n"
               "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\n"
               "l 1 2\nl 2 3\nl 3 4\nl 4 1\nl 2 5\nf 1 2 3\n");
    // Meshes: the bundled rough cube proxy, and a tetrahedron with every vertex attribute.
    const TriMesh cube = read_mesh(data / "cube_proxy.obj");
    write_mesh(cube, out / "mesh_obj" / "cube_proxy.obj");
    write_mesh(cube, out / "mesh_ply" / "cube_proxy.ply");
    const std::string tetra_ascii = tetrahedron_ply(false);
    write_text(out / "mesh_ply" / "tetrahedron_ascii.ply", tetra_ascii);
    write_text(out / "mesh_ply" / "tetrahedron_big_endian.ply", tetrahedron_ply(true));
    const TriMesh tetra = read_mesh(out / "mesh_ply" / "tetrahedron_ascii.ply");
    MeshAttributes attributes{.labels = {0, 1, 0, 1},
                              .colors = {{{10, 200, 30}}, {{70, 201, 31}}, {{130, 202, 32}}, {{190, 203, 33}}},
                              .sharp = {1, 0, 0, 1}};
    write_mesh(tetra, out / "mesh_ply" / "tetrahedron_attributes.ply", attributes);
    write_mesh(tetra, out / "mesh_obj" / "tetrahedron_colours.obj", attributes);
    write_text(out / "mesh_obj" / "quad_slashes.obj",
               "# a unit square as one quad, with texture and normal indices\n"
               "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n"
               "g square\nf 1/1/1 2/1/1 3/1/1 -1/1/1\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_fuzz_seeds: %s\n", e.what());
    return 1;
  }
  return 0;
}
