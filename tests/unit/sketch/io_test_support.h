#pragma once
// Helpers for the sketch-format tests: a scratch directory, a sketch with every attribute set to
// awkward values, a cube mesh with sharp edges, and exact comparisons.

#include <gtest/gtest.h>

#include <bit>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "surfacing/error.h"
#include "surfacing/mesh.h"
#include "surfacing/sketch/sketch.h"

namespace sketchsurf::testing {

/// A fresh directory under the system temp dir, removed with everything in it at scope exit.
class TempDir {
 public:
  TempDir() {
    std::random_device rd;
    path_ = std::filesystem::temp_directory_path() /
            ("sketchsurf-test-" + std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
  const std::filesystem::path& path() const { return path_; }
  /// Names of the files in the directory, sorted.
  std::vector<std::string> files() const {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(path_))
      names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  std::filesystem::path path_;
};

inline void write_text(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
}

inline std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A unit cube of 12 triangles, every edge of its squares a 90-degree crease.
inline TriMesh cube_mesh() {
  TriMesh mesh;
  std::vector<TriMesh::VertexHandle> v;
  for (int i = 0; i < 8; ++i) v.push_back(mesh.add_vertex(TriMesh::Point(i & 1, (i >> 1) & 1, (i >> 2) & 1)));
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    mesh.add_face(v[q[0]], v[q[1]], v[q[2]]);
    mesh.add_face(v[q[0]], v[q[2]], v[q[3]]);
  }
  return mesh;
}

/// True when both doubles have the same bits (so -0.0 != 0.0).
inline bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}
inline bool same_bits(float a, float b) {
  return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b);
}

/// A sketch with every attribute of every stroke set, to values that are hard to print: full
/// 53-bit mantissas, negative zero, subnormals, huge and tiny magnitudes, quotes and unicode.
inline Sketch sketch_with_every_attribute(unsigned seed, int strokes = 5, int points = 7) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_real_distribution<float> uf(0.0f, 1.0f);
  Sketch sketch;
  sketch.units = "m";
  sketch.provenance = "test \"sketch\"\nwith a newline, a tab\t and unicode: é ∑";
  sketch.mirror = Plane{Eigen::Vector3d(0.6, 0.0, 0.8), -0.125};
  sketch.params = {{"segment.epsilon", 0.01}, {"segment.lambda", 1.0 / 3.0},
                   {"proxy.vipss.lambda", 0.0}, {"top", -2.5e-300}};
  for (int s = 0; s < strokes; ++s) {
    Stroke st;
    for (int i = 0; i < points; ++i) {
      st.points.emplace_back(u(rng), u(rng) * 1e3, u(rng) * 1e-7);
      Eigen::Quaterniond q(u(rng), u(rng), u(rng), u(rng));
      st.orientations.push_back(q.normalized());
      st.pressures.push_back(uf(rng));
      st.timestamps_ms.push_back(static_cast<std::uint32_t>(rng()));
    }
    st.points[0] = Eigen::Vector3d(-0.0, 4.9e-324, 1.7976931348623157e308);
    st.pressures[0] = -0.0f;
    st.pressures[1] = 1.4e-45f;  // the smallest subnormal float
    st.timestamps_ms[0] = 0xffffffffu;
    st.width = u(rng) + 1.0;
    st.color = {uf(rng), uf(rng), uf(rng), 1.0f / 3.0f};
    st.brush = s % 2 ? "{89d104cd-d012-426b-b5b3-bbaee63ac43c}" : "a \"quoted\\brush\"";
    st.id = 1000 - s * 7;
    st.layer = static_cast<std::uint32_t>(s);
    st.boundary = s % 2 == 0;
    st.ignored = s % 3 == 1;
    sketch.strokes.push_back(st);
  }
  return sketch;
}

/// Expects both sketches to be identical, bit for bit, in every attribute.
inline void expect_identical(const Sketch& a, const Sketch& b) {
  EXPECT_EQ(a.units, b.units);
  EXPECT_EQ(a.provenance, b.provenance);
  EXPECT_EQ(a.params, b.params);
  ASSERT_EQ(a.mirror.has_value(), b.mirror.has_value());
  if (a.mirror) {
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(same_bits(a.mirror->normal[c], b.mirror->normal[c]));
    EXPECT_TRUE(same_bits(a.mirror->offset, b.mirror->offset));
  }
  ASSERT_EQ(a.strokes.size(), b.strokes.size());
  for (std::size_t s = 0; s < a.strokes.size(); ++s) {
    SCOPED_TRACE("stroke " + std::to_string(s));
    const Stroke& x = a.strokes[s];
    const Stroke& y = b.strokes[s];
    ASSERT_EQ(x.points.size(), y.points.size());
    ASSERT_EQ(x.orientations.size(), y.orientations.size());
    ASSERT_EQ(x.pressures.size(), y.pressures.size());
    EXPECT_EQ(x.timestamps_ms, y.timestamps_ms);
    for (std::size_t i = 0; i < x.points.size(); ++i)
      for (int c = 0; c < 3; ++c)
        EXPECT_TRUE(same_bits(x.points[i][c], y.points[i][c])) << "point " << i << "[" << c << "]";
    for (std::size_t i = 0; i < x.orientations.size(); ++i)
      for (int c = 0; c < 4; ++c)
        EXPECT_TRUE(same_bits(x.orientations[i].coeffs()[c], y.orientations[i].coeffs()[c]));
    for (std::size_t i = 0; i < x.pressures.size(); ++i)
      EXPECT_TRUE(same_bits(x.pressures[i], y.pressures[i])) << "pressure " << i;
    EXPECT_TRUE(same_bits(x.width, y.width));
    for (int c = 0; c < 4; ++c) EXPECT_TRUE(same_bits(x.color[c], y.color[c])) << "colour " << c;
    EXPECT_EQ(x.brush, y.brush);
    EXPECT_EQ(x.id, y.id);
    EXPECT_EQ(x.layer, y.layer);
    EXPECT_EQ(x.boundary, y.boundary);
    EXPECT_EQ(x.ignored, y.ignored);
  }
}

/// Expects the same strokes with the same points (to `tolerance`), attributes aside.
inline void expect_same_points(const Sketch& a, const Sketch& b, double tolerance) {
  ASSERT_EQ(a.strokes.size(), b.strokes.size());
  for (std::size_t s = 0; s < a.strokes.size(); ++s) {
    ASSERT_EQ(a.strokes[s].points.size(), b.strokes[s].points.size()) << "stroke " << s;
    for (std::size_t i = 0; i < a.strokes[s].points.size(); ++i)
      ASSERT_LE((a.strokes[s].points[i] - b.strokes[s].points[i]).norm(), tolerance)
          << "stroke " << s << " point " << i;
  }
}

/// `text` with 1 to 3 seeded random edits (replace, delete a few bytes, insert), biased towards
/// bytes that matter to the text formats.
inline std::string corrupt(const std::string& text, std::mt19937& rng) {
  static const std::string special = "{}[]\",:-.0123456789eE \tfnvl/\n\r\x80\xff";
  std::string bad = text;
  const int edits = 1 + static_cast<int>(rng() % 3);
  for (int e = 0; e < edits && !bad.empty(); ++e) {
    const std::size_t at = rng() % bad.size();
    const char c = rng() % 2 ? special[rng() % special.size()] : static_cast<char>(rng());
    switch (rng() % 3) {
      case 0: bad[at] = c; break;
      case 1: bad.erase(at, 1 + rng() % 8); break;
      default: bad.insert(bad.begin() + static_cast<std::ptrdiff_t>(at), c); break;
    }
  }
  return bad;
}

/// Runs `f`, expecting an Error of kind `kind` whose message contains every one of `parts`.
template <typename F>
void expect_error(F&& f, ErrorKind kind, std::initializer_list<std::string> parts) {
  try {
    f();
    ADD_FAILURE() << "no error thrown";
  } catch (const Error& e) {
    EXPECT_EQ(static_cast<int>(e.kind()), static_cast<int>(kind)) << e.what();
    for (const auto& p : parts)
      EXPECT_NE(std::string(e.what()).find(p), std::string::npos)
          << "message \"" << e.what() << "\" lacks \"" << p << "\"";
  }
}

}  // namespace sketchsurf::testing
