// glTF output of write_mesh() (surfacing/sketch/io/gltf_io.h), read back with tinygltf.

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cstdlib>
#include <cstring>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "surfacing/palette.h"
#include "surfacing/sketch/io/mesh_io.h"
#include "surfacing/sketch/io/sketch_io.h"
#include "tests/support/shapes.h"
#include "tests/unit/sketch/io_test_support.h"

namespace sketchsurf {
namespace {

using testing::cube_mesh;
using testing::TempDir;

/// The model of a .glb or .gltf file; fails the test when tinygltf cannot load it.
tinygltf::Model load(const std::filesystem::path& file) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string error, warning;
  const bool ok = file.extension() == ".glb" ? loader.LoadBinaryFromFile(&model, &error, &warning, file.string())
                                              : loader.LoadASCIIFromFile(&model, &error, &warning, file.string());
  EXPECT_TRUE(ok) << error;
  EXPECT_TRUE(warning.empty()) << warning;
  return model;
}

/// The float values of attribute `name` of the first primitive (components per element: `size`).
std::vector<float> floats(const tinygltf::Model& model, const std::string& name, int size) {
  const auto& primitive = model.meshes.at(0).primitives.at(0);
  const tinygltf::Accessor& accessor = model.accessors.at(primitive.attributes.at(name));
  EXPECT_EQ(accessor.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT) << name;
  EXPECT_EQ(tinygltf::GetNumComponentsInType(accessor.type), size) << name;
  const tinygltf::BufferView& view = model.bufferViews.at(accessor.bufferView);
  std::vector<float> values(accessor.count * size);
  std::memcpy(values.data(), model.buffers.at(view.buffer).data.data() + view.byteOffset + accessor.byteOffset,
              values.size() * sizeof(float));
  return values;
}

std::vector<std::uint32_t> indices(const tinygltf::Model& model) {
  const tinygltf::Accessor& accessor = model.accessors.at(model.meshes.at(0).primitives.at(0).indices);
  EXPECT_EQ(accessor.componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
  const tinygltf::BufferView& view = model.bufferViews.at(accessor.bufferView);
  std::vector<std::uint32_t> values(accessor.count);
  std::memcpy(values.data(), model.buffers.at(view.buffer).data.data() + view.byteOffset + accessor.byteOffset,
              values.size() * sizeof(std::uint32_t));
  return values;
}

TEST(GltfIo, CubeVerticesSplitAlongItsCreasesWithAxisNormalsColoursAndLabels) {
  TempDir dir;
  const TriMesh mesh = cube_mesh();
  MeshAttributes attributes;
  for (auto v : mesh.vertices()) attributes.labels.push_back(v.idx() % 3 - 1);  // -1 too
  for (const char* name : {"cube.glb", "cube.gltf"}) {
    write_mesh(mesh, dir / name, attributes);
    const tinygltf::Model model = load(dir / name);
    ASSERT_EQ(model.meshes.size(), 1u);
    const auto& primitive = model.meshes[0].primitives.at(0);
    EXPECT_EQ(primitive.mode, TINYGLTF_MODE_TRIANGLES);
    // Each corner of the cube is on three faces, each face flat across its diagonal: 24 vertices.
    const std::vector<float> p = floats(model, "POSITION", 3), n = floats(model, "NORMAL", 3),
                             c = floats(model, "COLOR_0", 3), label = floats(model, "_LABEL", 1);
    EXPECT_EQ(p.size(), 24u * 3);
    EXPECT_EQ(indices(model).size(), 36u);
    const tinygltf::Accessor& position = model.accessors[primitive.attributes.at("POSITION")];
    EXPECT_EQ(position.minValues, (std::vector<double>{0, 0, 0}));
    EXPECT_EQ(position.maxValues, (std::vector<double>{1, 1, 1}));
    for (std::size_t i = 0; i < 24; ++i) {
      // The normal is the face's: one coordinate +-1, the others 0.
      double largest = 0.0, sum = 0.0;
      for (int k = 0; k < 3; ++k) {
        largest = std::max(largest, double(std::abs(n[3 * i + k])));
        sum += std::abs(n[3 * i + k]);
      }
      EXPECT_NEAR(largest, 1.0, 1e-6);
      EXPECT_NEAR(sum, 1.0, 1e-6);
      // Label and colour are the mesh vertex's, found by position.
      const int v = int(p[3 * i] + 0.5) + 2 * int(p[3 * i + 1] + 0.5) + 4 * int(p[3 * i + 2] + 0.5);
      EXPECT_EQ(label[i], float(attributes.labels[v]));
      const Rgb8 rgb = region_color(attributes.labels[v]);
      for (int k = 0; k < 3; ++k) EXPECT_FLOAT_EQ(c[3 * i + k], float(rgb[k] / 255.0));
    }
    // Every triangle's corners share its normal, which points away from the centre.
    const std::vector<std::uint32_t> t = indices(model);
    for (std::size_t f = 0; f < 12; ++f) {
      double outward = 0.0;
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = t[3 * f + k], b = t[3 * f];
        for (int d = 0; d < 3; ++d) {
          EXPECT_EQ(n[3 * a + d], n[3 * b + d]);
          outward += n[3 * a + d] * (p[3 * a + d] - 0.5);
        }
      }
      EXPECT_GT(outward, 0.0);
    }
  }
}

TEST(GltfIo, SmoothSphereKeepsOneVertexPerMeshVertexWithRadialNormals) {
  TempDir dir;
  const TriMesh mesh = testing::icosphere(3, 2.0);
  write_mesh(mesh, dir / "sphere.glb");
  const tinygltf::Model model = load(dir / "sphere.glb");
  const auto& attributes = model.meshes.at(0).primitives.at(0).attributes;
  EXPECT_EQ(attributes.count("COLOR_0"), 0u);  // no labels, no colours
  EXPECT_EQ(attributes.count("_LABEL"), 0u);
  const std::vector<float> p = floats(model, "POSITION", 3), n = floats(model, "NORMAL", 3);
  EXPECT_EQ(p.size(), 3 * mesh.n_vertices());
  EXPECT_EQ(indices(model).size(), 3 * mesh.n_faces());
  for (std::size_t i = 0; i < p.size() / 3; ++i) {
    const Eigen::Vector3d radial = Eigen::Vector3d(p[3 * i], p[3 * i + 1], p[3 * i + 2]).normalized();
    EXPECT_GT(radial.dot(Eigen::Vector3d(n[3 * i], n[3 * i + 1], n[3 * i + 2])), 0.99);
  }
}

TEST(GltfIo, SharpFlagsMakeGentlerEdgesCreases) {
  // A roof of two triangles folded by 30 degrees: smooth by angle alone, a crease when both
  // vertices of the fold are flagged sharp.
  TempDir dir;
  TriMesh mesh;
  const double s = std::sin(M_PI / 6.0), c = std::cos(M_PI / 6.0);
  const auto a = mesh.add_vertex({0, 0, 0}), b = mesh.add_vertex({0, 1, 0}), left = mesh.add_vertex({-1, 0.5, 0}),
             right = mesh.add_vertex({c, 0.5, s});
  mesh.add_face(a, b, left);
  mesh.add_face(b, a, right);
  write_mesh(mesh, dir / "smooth.glb");
  EXPECT_EQ(floats(load(dir / "smooth.glb"), "POSITION", 3).size(), 4u * 3);
  MeshAttributes attributes;
  attributes.sharp = {1, 1, 0, 0};
  write_mesh(mesh, dir / "crease.glb", attributes);
  EXPECT_EQ(floats(load(dir / "crease.glb"), "POSITION", 3).size(), 6u * 3);
}

TEST(GltfIo, StrokesBecomeASecondMeshOfLineStrips) {
  TempDir dir;
  MeshAttributes attributes;
  attributes.strokes = {{{0, 0, 0}, {1, 0, 0}, {1, 2, 0}}, {{5, 5, 5}}, {{0, 0, 1}, {0.25, 0.5, 1}}};
  write_mesh(cube_mesh(), dir / "cube.glb", attributes);
  write_mesh(TriMesh(), dir / "strokes_only.gltf", attributes);
  for (const char* name : {"cube.glb", "strokes_only.gltf"}) {
    SCOPED_TRACE(name);
    const tinygltf::Model model = load(dir / name);
    const bool surface = std::string(name) == "cube.glb";
    ASSERT_EQ(model.nodes.size(), 2u);
    EXPECT_EQ(model.scenes.at(0).nodes, (std::vector<int>{0, 1}));
    EXPECT_EQ(model.nodes[0].mesh, surface ? 0 : -1);
    EXPECT_EQ(model.nodes[1].name, "strokes");
    const tinygltf::Mesh& strokes = model.meshes.at(model.nodes[1].mesh);
    ASSERT_EQ(strokes.primitives.size(), 2u);  // the one-point stroke is left out
    for (std::size_t k = 0; k < 2; ++k) {
      const tinygltf::Primitive& primitive = strokes.primitives[k];
      EXPECT_EQ(primitive.mode, TINYGLTF_MODE_LINE_STRIP);
      const tinygltf::Accessor& accessor = model.accessors.at(primitive.attributes.at("POSITION"));
      const auto& stroke = attributes.strokes[k == 0 ? 0 : 2];
      ASSERT_EQ(accessor.count, stroke.size());
      const tinygltf::BufferView& view = model.bufferViews.at(accessor.bufferView);
      std::vector<float> p(3 * accessor.count);
      std::memcpy(p.data(), model.buffers.at(view.buffer).data.data() + view.byteOffset + accessor.byteOffset,
                  p.size() * sizeof(float));
      for (std::size_t i = 0; i < stroke.size(); ++i)
        for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(p[3 * i + c], static_cast<float>(stroke[i][c]));
    }
  }
}

TEST(GltfIo, SurfaceCommandWritesTheBundledCubeAsGlb) {
  TempDir dir;
  const std::string tests = SKETCHSURF_TESTS_DIR;
  const std::string command = std::string("'") + SKETCHSURF_CLI + "' surface '" + tests + "/data/cube.json' --proxy '" +
                              tests + "/data/cube_proxy.obj' -q -o '" + (dir / "cube.glb").string() + "' --with-strokes";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  const tinygltf::Model model = load(dir / "cube.glb");
  // The strokes as line strips, one per stroke of the sketch.
  const Sketch sketch = read_sketch(tests + "/data/cube.json");
  ASSERT_EQ(model.meshes.size(), 2u);
  EXPECT_EQ(model.meshes[1].primitives.size(), sketch.strokes.size());
  std::size_t points = 0;
  for (const auto& primitive : model.meshes[1].primitives)
    points += model.accessors.at(primitive.attributes.at("POSITION")).count;
  EXPECT_EQ(points, sketch.point_count());
  const std::vector<float> label = floats(model, "_LABEL", 1), n = floats(model, "NORMAL", 3);
  floats(model, "COLOR_0", 3);
  EXPECT_EQ(std::set<float>(label.begin(), label.end()).size(), 6u);  // the six faces
  // The creases split the vertices: most normals are the normal of a face of the cube.
  std::size_t axis = 0;
  for (std::size_t i = 0; i < label.size(); ++i) {
    const Eigen::Vector3d normal(n[3 * i], n[3 * i + 1], n[3 * i + 2]);
    axis += normal.cwiseAbs().maxCoeff() > 0.99;
  }
  EXPECT_GT(axis, label.size() * 9 / 10);
}

}  // namespace
}  // namespace sketchsurf
