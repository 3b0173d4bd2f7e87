#include "surfacing/sketch/io/mesh_io.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <sstream>
#include <string>

#include "tests/support/shapes.h"
#include "tests/unit/sketch/io_test_support.h"

namespace sketchsurf {
namespace {

using testing::expect_error;
using testing::TempDir;

MeshAttributes attributes_for(const TriMesh& mesh) {
  MeshAttributes a;
  for (auto v : mesh.vertices()) {
    const auto p = mesh.point(v);
    a.labels.push_back(v.idx() % 7 - 3);  // negative labels too
    a.colors.push_back({static_cast<std::uint8_t>(v.idx() % 256), static_cast<std::uint8_t>(p[2] > 0 ? 255 : 0),
                        static_cast<std::uint8_t>(v.idx() * 37 % 256)});
    a.sharp.push_back(v.idx() % 3 == 0);
  }
  return a;
}

void expect_same_mesh(const TriMesh& a, const TriMesh& b, double tolerance) {
  EXPECT_EQ(vertex_matrix(a).rows(), vertex_matrix(b).rows());
  ASSERT_EQ(a.n_vertices(), b.n_vertices());
  ASSERT_EQ(a.n_faces(), b.n_faces());
  EXPECT_LE((vertex_matrix(a) - vertex_matrix(b)).cwiseAbs().maxCoeff(), tolerance);
  EXPECT_EQ(face_matrix(a), face_matrix(b));
}

TEST(MeshIo, PlyRoundTripKeepsPositionsFacesLabelsColoursAndSharpFlags) {
  TempDir dir;
  const TriMesh mesh = testing::icosphere(2, 1.3, Eigen::Vector3d(0.1, -2, 3));
  const MeshAttributes attributes = attributes_for(mesh);
  write_mesh(mesh, dir / "m.ply", attributes);
  MeshAttributes back;
  const TriMesh read = read_mesh(dir / "m.ply", &back);
  expect_same_mesh(mesh, read, 0.0);  // doubles in binary: exact
  EXPECT_EQ(back.labels, attributes.labels);
  EXPECT_EQ(back.colors, attributes.colors);
  EXPECT_EQ(back.sharp, attributes.sharp);
  EXPECT_TRUE(testing::read_text(dir / "m.ply").starts_with("ply\nformat binary_little_endian 1.0\n"));

  // Without attributes: none written, none read back.
  write_mesh(mesh, dir / "plain.ply");
  MeshAttributes none;
  none.labels = {1};
  read_mesh(dir / "plain.ply", &none);
  EXPECT_TRUE(none.labels.empty() && none.colors.empty() && none.sharp.empty());
}

TEST(MeshIo, ObjRoundTripKeepsPositionsFacesAndColours) {
  TempDir dir;
  const TriMesh mesh = testing::torus_mesh(12, 8, 1.0, 0.3);
  MeshAttributes attributes = attributes_for(mesh);
  attributes.labels.clear();
  attributes.sharp.clear();
  write_mesh(mesh, dir / "m.obj", attributes);
  MeshAttributes back;
  const TriMesh read = read_mesh(dir / "m.obj", &back);
  expect_same_mesh(mesh, read, 0.0);
  EXPECT_EQ(back.colors, attributes.colors);
  // The torus is closed: every edge has two faces after reading.
  for (auto e : read.edges()) EXPECT_FALSE(read.is_boundary(e));
}

TEST(MeshIo, ObjNormalsAreSplitAlongCreasesAndFacesGroupedByRegion) {
  TempDir dir;
  const TriMesh mesh = testing::cube_mesh();
  MeshAttributes attributes;
  for (auto v : mesh.vertices()) attributes.labels.push_back(static_cast<int>(mesh.point(v)[0]));  // x
  write_mesh(mesh, dir / "cube.obj", attributes);
  const TriMesh back = read_mesh(dir / "cube.obj");  // the faces in region order
  EXPECT_EQ(back.n_faces(), mesh.n_faces());
  EXPECT_EQ(vertex_matrix(back), vertex_matrix(mesh));
  std::vector<Eigen::Vector3d> v, vn;
  std::vector<std::string> groups;
  std::size_t faces = 0;
  std::istringstream text(testing::read_text(dir / "cube.obj"));
  for (std::string line; std::getline(text, line);) {
    std::istringstream in(line);
    std::string tag;
    in >> tag;
    if (tag == "v" || tag == "vn") {
      Eigen::Vector3d p;
      in >> p.x() >> p.y() >> p.z();
      (tag == "v" ? v : vn).push_back(p);
    } else if (tag == "g") {
      groups.push_back(line.substr(2));
    } else if (tag == "f") {
      // Every corner names its normal (v//vn), and the normal is the face's: the cube's 90-degree
      // edges are all creases.
      std::array<Eigen::Vector3d, 3> p, n;
      for (int k = 0; k < 3; ++k) {
        std::string corner;
        in >> corner;
        const auto slashes = corner.find("//");
        ASSERT_NE(slashes, std::string::npos) << line;
        p[k] = v.at(std::stoul(corner.substr(0, slashes)) - 1);
        n[k] = vn.at(std::stoul(corner.substr(slashes + 2)) - 1);
      }
      const Eigen::Vector3d normal = (p[1] - p[0]).cross(p[2] - p[0]).normalized();
      for (const auto& nk : n) EXPECT_NEAR(nk.dot(normal), 1.0, 1e-12) << line;
      ++faces;
    }
  }
  EXPECT_EQ(faces, 12u);
  EXPECT_EQ(vn.size(), 24u);  // 4 corners on each of the 6 sides
  // Faces in one group per region label, each group once.
  EXPECT_EQ(groups, (std::vector<std::string>{"region_0", "region_1"}));
}

TEST(MeshIo, PlyEdgeElementFlagsTheCreases) {
  TempDir dir;
  const TriMesh cube = testing::cube_mesh();
  MeshAttributes attributes;
  attributes.sharp.assign(cube.n_vertices(), 0);
  write_mesh(cube, dir / "cube.ply", attributes);
  MeshAttributes back;
  expect_same_mesh(cube, read_mesh(dir / "cube.ply", &back), 0.0);
  // The 12 edges of the cube, not the 6 diagonals of its sides.
  ASSERT_EQ(back.sharp_edges.size(), 12u);
  for (const auto& [a, b] : back.sharp_edges) {
    const auto d = cube.point(TriMesh::VertexHandle(a)) - cube.point(TriMesh::VertexHandle(b));
    EXPECT_DOUBLE_EQ(d.norm(), 1.0);
  }
  // A smooth sphere has none; without sharp flags there is no edge element at all.
  const TriMesh sphere = testing::icosphere(2, 1.0);
  attributes.sharp.assign(sphere.n_vertices(), 1);
  write_mesh(sphere, dir / "sphere.ply", attributes);
  EXPECT_NE(testing::read_text(dir / "sphere.ply").find("element edge " + std::to_string(sphere.n_edges())),
            std::string::npos);
  read_mesh(dir / "sphere.ply", &back);
  EXPECT_TRUE(back.sharp_edges.empty());
  write_mesh(cube, dir / "plain.ply");
  EXPECT_EQ(testing::read_text(dir / "plain.ply").find("element edge"), std::string::npos);
  // An edge naming a vertex that does not exist is an input error.
  testing::write_text(dir / "bad.ply",
                      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                      "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                      "element edge 1\nproperty int vertex1\nproperty int vertex2\nproperty uchar sharp\n"
                      "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n0 7 1\n");
  expect_error([&] { read_mesh(dir / "bad.ply", &back); }, ErrorKind::Input,
               {"bad.ply", "edge 0: vertex index 7"});
}

TEST(MeshIo, NegativeListLengthsAndFloatIndicesOutOfRangeAreInputErrors) {
  // Found by the .ply fuzzer (tools/fuzz): a negative int16 list length, and float vertex indices
  // that no integer holds, were converted to integers regardless (undefined behaviour).
  TempDir dir;
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\n";
  std::string vertices;
  for (const float c : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f})
    vertices.append(reinterpret_cast<const char*>(&c), 4);
  const std::int16_t negative = -30464;
  testing::write_text(dir / "negative.ply",
                      header + "property list int16 int vertex_indices\nend_header\n" + vertices +
                          std::string(reinterpret_cast<const char*>(&negative), 2));
  expect_error([&] { read_mesh(dir / "negative.ply"); }, ErrorKind::Input,
               {"negative.ply", "face 0: a list of -30464 items is impossible"});
  for (const float index : {std::nanf(""), 1e30f, -1e30f, 1.5f}) {
    std::string face(1, '\3');
    for (const float i : {0.f, 1.f, index}) face.append(reinterpret_cast<const char*>(&i), 4);
    testing::write_text(dir / "float.ply",
                        header + "property list uchar float vertex_indices\nend_header\n" + vertices + face);
    expect_error([&] { read_mesh(dir / "float.ply"); }, ErrorKind::Input, {"float.ply", "is not a vertex index"});
  }
  // Whole float indices are indices.
  std::string face(1, '\3');
  for (const float i : {0.f, 1.f, 2.f}) face.append(reinterpret_cast<const char*>(&i), 4);
  testing::write_text(dir / "float.ply",
                      header + "property list uchar float vertex_indices\nend_header\n" + vertices + face);
  EXPECT_EQ(read_mesh(dir / "float.ply").n_faces(), 1u);
}

TEST(MeshIo, AsciiPlyWithQuadsFloatColoursAndExtraElements) {
  TempDir dir;
  testing::write_text(dir / "q.ply",
                      "ply\r\nformat ascii 1.0\r\ncomment a unit square as two quads\r\n"
                      "element vertex 6\r\nproperty float x\r\nproperty float y\r\nproperty float z\r\n"
                      "property float nx\r\nproperty float red\r\nproperty float green\r\n"
                      "property float blue\r\nproperty list uchar float texcoord\r\n"
                      "element face 2\r\nproperty list uchar int vertex_index\r\n"
                      "element edge 1\r\nproperty int vertex1\r\nproperty int vertex2\r\nend_header\r\n"
                      "0 0 0 0 1 0 0 2 0.5 0.5\r\n0.5 0 0 0 0 1 0 0\r\n1 0 0 0 0 0 1 0\r\n"
                      "1 1 0 0 1 1 1 1 9\r\n0.5 1 0 0 0.5 0.5 0.5 0\r\n0 1 0 0 0 0 0 0\r\n"
                      "4 0 1 4 5\r\n4 1 2 3 4\r\n0 1\r\n");
  MeshAttributes a;
  const TriMesh mesh = read_mesh(dir / "q.ply", &a);
  EXPECT_EQ(mesh.n_vertices(), 6u);
  EXPECT_EQ(mesh.n_faces(), 4u);  // two quads, fan-triangulated
  double area = 0;
  for (auto f : mesh.faces()) area += mesh.calc_face_area(f);
  EXPECT_NEAR(area, 1.0, 1e-12);
  for (auto f : mesh.faces()) EXPECT_GT(mesh.normal(f)[2], 0.99);  // orientation kept
  ASSERT_EQ(a.colors.size(), 6u);
  EXPECT_EQ(a.colors[0], (std::array<std::uint8_t, 3>{255, 0, 0}));
  EXPECT_EQ(a.colors[4], (std::array<std::uint8_t, 3>{128, 128, 128}));
  EXPECT_TRUE(a.labels.empty());
}

/// A binary big-endian PLY of one triangle with uchar-counted int indices and int labels.
std::string big_endian_triangle(std::uint32_t face_list_length = 3) {
  std::string out =
      "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty int label\nelement face 1\n"
      "property list uint int vertex_indices\nend_header\n";
  auto put = [&](auto value) {
    char bytes[sizeof value];
    std::memcpy(bytes, &value, sizeof value);
    std::reverse(bytes, bytes + sizeof value);  // to big endian (the test machines are little)
    out.append(bytes, sizeof value);
  };
  const float xyz[3][3] = {{0, 0, 0}, {2, 0, 0}, {0, 3, 0}};
  for (int v = 0; v < 3; ++v) {
    for (float c : xyz[v]) put(c);
    put(std::int32_t{-5 + v});
  }
  put(face_list_length);
  for (std::int32_t i : {0, 1, 2}) put(i);
  return out;
}

TEST(MeshIo, BigEndianBinaryPly) {
  static_assert(std::endian::native == std::endian::little);
  TempDir dir;
  testing::write_text(dir / "be.ply", big_endian_triangle());
  MeshAttributes a;
  const TriMesh mesh = read_mesh(dir / "be.ply", &a);
  ASSERT_EQ(mesh.n_faces(), 1u);
  EXPECT_DOUBLE_EQ(mesh.calc_face_area(*mesh.faces().begin()), 3.0);
  EXPECT_EQ(a.labels, (std::vector<int>{-5, -4, -3}));
}

TEST(MeshIo, TruncationsOfABinaryPlyAreInputErrors) {
  TempDir dir;
  const TriMesh mesh = testing::icosphere(0);
  write_mesh(mesh, dir / "m.ply", attributes_for(mesh));
  const std::string bytes = testing::read_text(dir / "m.ply");
  // Every length through the header and the first vertices, then every 5th (file I/O per length).
  for (std::size_t n = 0; n < bytes.size(); n += n < 400 ? 1 : 5) {
    testing::write_text(dir / "t.ply", bytes.substr(0, n));
    try {
      read_mesh(dir / "t.ply");
      ADD_FAILURE() << "a prefix of " << n << " bytes was accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Input) << e.what();
      EXPECT_NE(std::string(e.what()).find("t.ply"), std::string::npos);
    }
  }
}

TEST(MeshIo, BadMeshesAreInputErrorsNamingTheFace) {
  TempDir dir;
  struct Case {
    std::string name, text;
    std::vector<std::string> parts;
  };
  const std::string quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  const std::vector<Case> cases = {
      {"range.obj", quad + "f 1 2 3\nf 1 3 5\n", {"face 1 (line 6)", "vertex index 4 is out of range"}},
      {"neg.obj", quad + "f 1 2 -5\n", {"face 0 (line 5)", "out of range"}},
      {"repeat.obj", quad + "f 1 2 2\n", {"face 0 (line 5)", "degenerate", "vertex 1 appears twice"}},
      {"short.obj", quad + "f 1 2\n", {"face 0 (line 5)", "degenerate"}},
      {"fin.obj", quad + "v 0 0 1\nf 1 2 3\nf 1 2 4\nf 2 1 5\n",
       {"face 1 (line 7)", "non-manifold", "edge 0-1"}},
      {"flip.obj", quad + "f 1 2 3\nf 1 3 4\nf 3 1 2\n", {"face 2 (line 7)", "non-manifold"}},
      {"token.obj", quad + "f 1 b 3\n", {"token.obj:5:", "'b'"}},
      {"nofaces.obj", quad, {"no faces"}},
      {"notply.ply", "solid cube\n", {"not a PLY file"}},
      {"noend.ply", "ply\nformat ascii 1.0\nelement vertex 1\n", {"no 'end_header'"}},
      {"badfmt.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n", {":2:", "unknown PLY format"}},
      {"huge.ply",
       "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
       "property float y\nproperty float z\nend_header\n0123456789",
       {"claims 4000000000 vertex elements", "10 bytes"}},
      {"hugelist.ply", big_endian_triangle(0x7fffffff), {"face 0", "a list of 2147483647 items"}},
      {"noxyz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float u\nend_header\n1\n",
       {"no x, y, z"}},
      {"asciibad.ply",
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
       "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
       "0 0 0\n1 0 0\n0 1 zz\n3 0 1 2\n",
       {"vertex 2", "'zz' is not a number"}},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    testing::write_text(dir / c.name, c.text);
    try {
      read_mesh(dir / c.name);
      ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Input) << e.what();
      EXPECT_NE(std::string(e.what()).find(c.name), std::string::npos) << e.what();
      for (const auto& p : c.parts) EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
    }
  }
  expect_error([&] { read_mesh(dir / "missing.ply"); }, ErrorKind::Input, {"missing.ply", "no such file"});
  expect_error([&] { read_mesh(dir / "m.stl"); }, ErrorKind::Usage, {"m.stl", "unknown mesh extension"});
}

TEST(MeshIo, WriterChecksAttributeSizesAndExtension) {
  TempDir dir;
  const TriMesh mesh = testing::icosphere(0);
  MeshAttributes a;
  a.labels = {1, 2, 3};
  expect_error([&] { write_mesh(mesh, dir / "m.ply", a); }, ErrorKind::Processing,
               {"3 labels for 12 vertices"});
  expect_error([&] { write_mesh(mesh, dir / "m.stl"); }, ErrorKind::Usage, {"unknown mesh extension"});
  EXPECT_TRUE(dir.files().empty());
}

TEST(MeshIo, DeletedElementsAreLeftOutAndIndicesCompacted) {
  TempDir dir;
  TriMesh mesh = testing::icosphere(1);
  const std::size_t faces = mesh.n_faces();
  mesh.delete_vertex(mesh.vertex_handle(0));  // deletes its 5 faces too
  write_mesh(mesh, dir / "d.ply");
  const TriMesh read = read_mesh(dir / "d.ply");
  EXPECT_EQ(read.n_vertices(), mesh.n_vertices() - 1);
  EXPECT_EQ(read.n_faces(), faces - 5);
}

TEST(MeshIo, RandomCorruptionsGiveAnInputErrorOrAValidMesh) {
  TempDir dir;
  const TriMesh mesh = testing::icosphere(0);
  write_mesh(mesh, dir / "m.ply", attributes_for(mesh));
  write_mesh(mesh, dir / "m.obj");
  const std::string files[2] = {testing::read_text(dir / "m.ply"), testing::read_text(dir / "m.obj")};
  std::mt19937 rng(9);
  for (int trial = 0; trial < 300; ++trial) {
    const std::string name = trial % 2 ? "c.obj" : "c.ply";
    testing::write_text(dir / name, testing::corrupt(files[trial % 2], rng));
    try {
      MeshAttributes a;
      const TriMesh m = read_mesh(dir / name, &a);
      EXPECT_GT(m.n_faces(), 0u);
      EXPECT_TRUE(a.labels.empty() || a.labels.size() == m.n_vertices());
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Input) << e.what();
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace sketchsurf
