#include "surfacing/sketch/io/mesh_io.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <sstream>

#include "surfacing/error.h"
#include "surfacing/sketch/io/atomic_file.h"
#include "surfacing/sketch/io/gltf_io.h"
#include "surfacing/sketch/io/split_normals.h"
#include "surfacing/sketch/io/text_io.h"

namespace sketchsurf {

using io_detail::lower_extension;

namespace {

/// Polygons as read from a file, before they become a TriMesh.
struct PolygonSoup {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::size_t> starts{0};     // polygon p is indices[starts[p] .. starts[p+1])
  std::vector<std::int64_t> indices;      // 0-based, not yet range-checked
  std::vector<std::size_t> lines;         // OBJ: line of each polygon (empty for PLY)
  MeshAttributes attributes;

  std::size_t polygon_count() const { return starts.size() - 1; }
  void end_polygon() { starts.push_back(indices.size()); }
};

std::string face_name(const PolygonSoup& soup, std::size_t p) {
  std::string name = "face " + std::to_string(p);
  if (!soup.lines.empty()) name += " (line " + std::to_string(soup.lines[p]) + ")";
  return name;
}

/// Why OpenMesh refused triangle (a, b, c): an edge already used in this direction, or a vertex
/// whose fan is already closed.
std::string why_not_manifold(const TriMesh& mesh, const TriMesh::VertexHandle (&v)[3]) {
  for (int k = 0; k < 3; ++k) {
    const auto h = mesh.find_halfedge(v[k], v[(k + 1) % 3]);
    if (h.is_valid() && !mesh.is_boundary(h))
      return "edge " + std::to_string(v[k].idx()) + "-" + std::to_string(v[(k + 1) % 3].idx()) +
             " already has a face on this side (more than two faces at an edge, or the "
             "orientation flips)";
  }
  return "it makes a vertex non-manifold (two fans touching at one vertex)";
}

/// Fan-triangulates the polygons into a TriMesh; throws Error (Input) naming the face.
TriMesh build_mesh(const PolygonSoup& soup, const std::filesystem::path& file) {
  if (soup.polygon_count() == 0) throw Error::input(file, "no faces: not a triangle mesh");
  TriMesh mesh;
  mesh.reserve(soup.points.size(), soup.indices.size(), soup.indices.size());
  for (const auto& p : soup.points) mesh.add_vertex(to_openmesh(p));
  const auto n = static_cast<std::int64_t>(soup.points.size());
  std::vector<std::int64_t> sorted;
  for (std::size_t p = 0; p < soup.polygon_count(); ++p) {
    const std::size_t begin = soup.starts[p], end = soup.starts[p + 1];
    if (end - begin < 3)
      throw Error::input(file, face_name(soup, p) + ": degenerate, a face needs 3 vertices");
    for (std::size_t i = begin; i < end; ++i) {
      if (soup.indices[i] < 0 || soup.indices[i] >= n)
        throw Error::input(file, face_name(soup, p) + ": vertex index " +
                                     std::to_string(soup.indices[i]) + " is out of range (" +
                                     std::to_string(n) + " vertices)");
    }
    // A repeated vertex makes a face degenerate (sorted copy: a face may have many vertices).
    sorted.assign(soup.indices.begin() + begin, soup.indices.begin() + end);
    std::sort(sorted.begin(), sorted.end());
    if (const auto twice = std::adjacent_find(sorted.begin(), sorted.end()); twice != sorted.end())
      throw Error::input(file, face_name(soup, p) + ": degenerate, vertex " +
                                   std::to_string(*twice) + " appears twice");
    for (std::size_t i = begin + 1; i + 1 < end; ++i) {
      const TriMesh::VertexHandle v[3] = {
          TriMesh::VertexHandle(static_cast<int>(soup.indices[begin])),
          TriMesh::VertexHandle(static_cast<int>(soup.indices[i])),
          TriMesh::VertexHandle(static_cast<int>(soup.indices[i + 1]))};
      if (!mesh.add_face(v[0], v[1], v[2]).is_valid())
        throw Error::input(file, face_name(soup, p) + ": non-manifold: " + why_not_manifold(mesh, v));
    }
  }
  mesh.update_normals();
  return mesh;
}

// ---------------------------------------------------------------------------------------------
// OBJ

PolygonSoup read_obj_soup(const std::filesystem::path& file, bool want_colors) {
  const std::string text = io_detail::read_file(file);
  io_detail::check_not_empty(text, file);
  io_detail::LineReader lines(text, file);
  std::vector<std::string_view> tokens;
  PolygonSoup soup;
  std::vector<std::array<std::uint8_t, 3>> colors;
  bool all_colored = true;
  std::string_view line;
  while (lines.next(line)) {
    io_detail::split_tokens(line, tokens);
    if (tokens.empty()) continue;
    if (tokens[0] == "v") {
      if (tokens.size() < 4)
        throw Error::input_at_line(file, lines.line_number(), "a vertex needs 3 coordinates");
      double values[6] = {0, 0, 0, 0, 0, 0};
      const std::size_t count = std::min<std::size_t>(tokens.size() - 1, 6);
      for (std::size_t c = 0; c < count; ++c) {
        const auto d = io_detail::parse_double(tokens[c + 1]);
        if (!d)
          throw Error::input_at_line(file, lines.line_number(),
                                     io_detail::excerpt(tokens[c + 1]) + " is not a number");
        values[c] = *d;
      }
      soup.points.emplace_back(values[0], values[1], values[2]);
      // `v x y z r g b`, colours in [0, 1]; `v x y z w` has no colour.
      all_colored = all_colored && count == 6;
      if (want_colors && all_colored) {
        std::array<std::uint8_t, 3> rgb;
        for (int c = 0; c < 3; ++c)
          rgb[c] = static_cast<std::uint8_t>(std::lround(std::clamp(values[3 + c], 0.0, 1.0) * 255));
        colors.push_back(rgb);
      }
    } else if (tokens[0] == "f") {
      for (std::size_t k = 1; k < tokens.size(); ++k) {
        const std::string_view token = tokens[k].substr(0, tokens[k].find('/'));
        const auto i = io_detail::parse_int(token);
        if (!i || *i == 0)
          throw Error::input_at_line(file, lines.line_number(),
                                     io_detail::excerpt(tokens[k]) + " is not a vertex index");
        // 1-based; negative counts back from the last vertex read so far.
        soup.indices.push_back(*i > 0 ? *i - 1 : static_cast<std::int64_t>(soup.points.size()) + *i);
      }
      soup.end_polygon();
      soup.lines.push_back(lines.line_number());
    }
    // Everything else (vn, vt, l, o, g, s, usemtl, comments) has no bearing on the triangles.
  }
  if (want_colors && all_colored && !soup.points.empty()) soup.attributes.colors = std::move(colors);
  return soup;
}

void append_vec(std::string& text, const char* tag, const OpenMesh::Vec3d& p) {
  text += tag;
  for (int c = 0; c < 3; ++c) {
    text += ' ';
    io_detail::append_number(text, p[c]);
  }
}

// ---------------------------------------------------------------------------------------------
// PLY

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

std::optional<PlyType> ply_type(std::string_view name) {
  if (name == "char" || name == "int8") return PlyType::Int8;
  if (name == "uchar" || name == "uint8") return PlyType::UInt8;
  if (name == "short" || name == "int16") return PlyType::Int16;
  if (name == "ushort" || name == "uint16") return PlyType::UInt16;
  if (name == "int" || name == "int32") return PlyType::Int32;
  if (name == "uint" || name == "uint32") return PlyType::UInt32;
  if (name == "float" || name == "float32") return PlyType::Float32;
  if (name == "double" || name == "float64") return PlyType::Float64;
  return std::nullopt;
}

std::size_t type_size(PlyType t) {
  switch (t) {
    case PlyType::Int8:
    case PlyType::UInt8: return 1;
    case PlyType::Int16:
    case PlyType::UInt16: return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32: return 4;
    case PlyType::Float64: return 8;
  }
  return 1;
}

struct PlyProperty {
  std::string name;
  PlyType type;
  bool list = false;
  PlyType count_type = PlyType::UInt8;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

enum class PlyFormat { Ascii, BinaryLittle, BinaryBig };

/// Reads PLY scalars from the data section, in ASCII or binary of either byte order.
class PlyData {
 public:
  PlyData(std::string_view data, std::size_t offset, PlyFormat format,
          const std::filesystem::path& file)
      : data_(data), pos_(offset), format_(format), file_(file) {}

  std::size_t left() const { return data_.size() - pos_; }
  std::size_t offset() const { return pos_; }
  bool ascii() const { return format_ == PlyFormat::Ascii; }

  /// Names the record being read, for error messages ("vertex 17").
  void set_record(const std::string* element, std::uint64_t index) {
    element_ = element;
    record_ = index;
  }

  /// The next scalar of the current record.
  double read(PlyType type) { return ascii() ? read_ascii(type) : read_binary(type); }

 private:
  std::string what() const {
    return element_ ? *element_ + " " + std::to_string(record_) : std::string("data");
  }

  double read_ascii(PlyType type) {
    while (pos_ < data_.size() && std::isspace(static_cast<unsigned char>(data_[pos_]))) ++pos_;
    const std::size_t start = pos_;
    while (pos_ < data_.size() && !std::isspace(static_cast<unsigned char>(data_[pos_]))) ++pos_;
    if (start == pos_)
      throw Error::input_at_byte(file_, start, "truncated: the file ends inside " + what());
    const std::string_view token = data_.substr(start, pos_ - start);
    const bool integral = type != PlyType::Float32 && type != PlyType::Float64;
    if (integral) {
      const auto i = io_detail::parse_int(token);
      if (!i)
        throw Error::input_at_byte(file_, start,
                                   what() + ": " + io_detail::excerpt(token) + " is not an integer");
      return static_cast<double>(*i);
    }
    const auto d = io_detail::parse_double(token);
    if (!d)
      throw Error::input_at_byte(file_, start,
                                 what() + ": " + io_detail::excerpt(token) + " is not a number");
    return *d;
  }

  double read_binary(PlyType type) {
    const std::size_t size = type_size(type);
    if (left() < size)
      throw Error::input_at_byte(file_, pos_, "truncated: the file ends inside " + what());
    unsigned char bytes[8];
    std::memcpy(bytes, data_.data() + pos_, size);
    pos_ += size;
    const bool file_little = format_ == PlyFormat::BinaryLittle;
    if (file_little != (std::endian::native == std::endian::little)) std::reverse(bytes, bytes + size);
    auto as = [&](auto value) {
      std::memcpy(&value, bytes, sizeof value);
      return static_cast<double>(value);
    };
    switch (type) {
      case PlyType::Int8: return as(std::int8_t{});
      case PlyType::UInt8: return as(std::uint8_t{});
      case PlyType::Int16: return as(std::int16_t{});
      case PlyType::UInt16: return as(std::uint16_t{});
      case PlyType::Int32: return as(std::int32_t{});
      case PlyType::UInt32: return as(std::uint32_t{});
      case PlyType::Float32: return as(float{});
      case PlyType::Float64: return as(double{});
    }
    return 0.0;
  }

  std::string_view data_;
  std::size_t pos_;
  PlyFormat format_;
  const std::filesystem::path& file_;
  const std::string* element_ = nullptr;
  std::uint64_t record_ = 0;
};

/// Parses the header; returns the offset of the first data byte.
std::size_t read_ply_header(std::string_view text, const std::filesystem::path& file,
                            PlyFormat& format, std::vector<PlyElement>& elements) {
  io_detail::LineReader lines(text, file);
  std::vector<std::string_view> tokens;
  std::string_view line;
  if (!lines.next(line) || line != "ply") throw Error::input(file, "not a PLY file (no 'ply' magic)");
  bool have_format = false;
  while (true) {
    if (!lines.next(line)) throw Error::input(file, "truncated header: no 'end_header'");
    const std::size_t at = lines.line_number();
    io_detail::split_tokens(line, tokens);
    if (tokens.empty() || tokens[0] == "comment" || tokens[0] == "obj_info") continue;
    if (tokens[0] == "end_header") break;
    if (tokens[0] == "format") {
      if (tokens.size() != 3 || tokens[2] != "1.0")
        throw Error::input_at_line(file, at, "expected 'format <ascii|binary_*> 1.0'");
      if (tokens[1] == "ascii") format = PlyFormat::Ascii;
      else if (tokens[1] == "binary_little_endian") format = PlyFormat::BinaryLittle;
      else if (tokens[1] == "binary_big_endian") format = PlyFormat::BinaryBig;
      else throw Error::input_at_line(file, at, "unknown PLY format " + io_detail::excerpt(tokens[1]));
      have_format = true;
    } else if (tokens[0] == "element") {
      const auto count = tokens.size() == 3 ? io_detail::parse_int(tokens[2]) : std::nullopt;
      if (!count || *count < 0) throw Error::input_at_line(file, at, "expected 'element NAME COUNT'");
      elements.push_back({std::string(tokens[1]), static_cast<std::uint64_t>(*count), {}});
    } else if (tokens[0] == "property") {
      if (elements.empty()) throw Error::input_at_line(file, at, "a property before any element");
      PlyProperty property;
      if (tokens.size() == 5 && tokens[1] == "list") {
        const auto count_type = ply_type(tokens[2]);
        const auto item_type = ply_type(tokens[3]);
        if (!count_type || !item_type || *count_type == PlyType::Float32 ||
            *count_type == PlyType::Float64)
          throw Error::input_at_line(file, at, "bad list property types");
        property = {std::string(tokens[4]), *item_type, true, *count_type};
      } else if (tokens.size() == 3) {
        const auto type = ply_type(tokens[1]);
        if (!type)
          throw Error::input_at_line(file, at, "unknown property type " + io_detail::excerpt(tokens[1]));
        property = {std::string(tokens[2]), *type};
      } else {
        throw Error::input_at_line(file, at, "expected 'property TYPE NAME' or 'property list ...'");
      }
      elements.back().properties.push_back(property);
    } else {
      throw Error::input_at_line(file, at, "unknown header line " + io_detail::excerpt(line));
    }
  }
  if (!have_format) throw Error::input(file, "the PLY header has no 'format' line");
  return text.size() - lines.bytes_left();
}

PolygonSoup read_ply_soup(const std::filesystem::path& file, bool want_attributes) {
  const std::string text = io_detail::read_file(file);
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
  const std::size_t data_start = read_ply_header(text, file, format, elements);
  PlyData data(text, data_start, format, file);

  PolygonSoup soup;
  bool have_vertices = false;
  for (const PlyElement& element : elements) {
    // The smallest a record can be: every scalar and list count present (lists empty), and in
    // ASCII one character plus a separator per value. Refuses absurd counts before allocating.
    std::size_t min_record = 0;
    for (const auto& p : element.properties)
      min_record += data.ascii() ? 2 : type_size(p.list ? p.count_type : p.type);
    if (min_record == 0) continue;  // no properties, no data
    if (element.count > (data.left() + 1) / min_record)
      throw Error::input_at_byte(file, data.offset(),
                                 "the header claims " + std::to_string(element.count) + " " +
                                     element.name + " elements but only " +
                                     std::to_string(data.left()) + " bytes of data remain");
    const bool is_vertex = element.name == "vertex";
    const bool is_face = element.name == "face";
    const bool is_edge = element.name == "edge" && want_attributes;
    // Which property feeds what (-1 = none).
    int xyz[3] = {-1, -1, -1}, rgb[3] = {-1, -1, -1}, label = -1, sharp = -1, face_list = -1;
    int ends[2] = {-1, -1};
    double edge[3] = {0, 0, 0};  // vertex1, vertex2, sharp of the edge being read
    for (std::size_t k = 0; k < element.properties.size(); ++k) {
      const auto& p = element.properties[k];
      const int ki = static_cast<int>(k);
      if (is_vertex && !p.list) {
        if (p.name == "x") xyz[0] = ki;
        if (p.name == "y") xyz[1] = ki;
        if (p.name == "z") xyz[2] = ki;
        if (p.name == "red") rgb[0] = ki;
        if (p.name == "green") rgb[1] = ki;
        if (p.name == "blue") rgb[2] = ki;
        if (p.name == "label") label = ki;
        if (p.name == "sharp") sharp = ki;
      }
      if (is_face && p.list && (p.name == "vertex_indices" || p.name == "vertex_index"))
        face_list = ki;
      if (is_edge && !p.list) {
        if (p.name == "vertex1") ends[0] = ki;
        if (p.name == "vertex2") ends[1] = ki;
        if (p.name == "sharp") sharp = ki;
      }
    }
    const bool sharp_edges = is_edge && ends[0] >= 0 && ends[1] >= 0 && sharp >= 0;
    if (is_vertex) {
      if (have_vertices) throw Error::input(file, "more than one vertex element");
      if (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0)
        throw Error::input(file, "the vertex element has no x, y, z properties");
      have_vertices = true;
      soup.points.resize(element.count);
    }
    if (is_face && face_list < 0)
      throw Error::input(file, "the face element has no vertex_indices list");
    const bool colors = is_vertex && want_attributes && rgb[0] >= 0 && rgb[1] >= 0 && rgb[2] >= 0;
    if (colors) soup.attributes.colors.resize(element.count);
    if (is_vertex && want_attributes && label >= 0) soup.attributes.labels.resize(element.count);
    if (is_vertex && want_attributes && sharp >= 0) soup.attributes.sharp.resize(element.count);

    for (std::uint64_t r = 0; r < element.count; ++r) {
      data.set_record(&element.name, r);
      for (std::size_t k = 0; k < element.properties.size(); ++k) {
        const PlyProperty& p = element.properties[k];
        const int ki = static_cast<int>(k);
        if (p.list) {
          const double length = data.read(p.count_type);
          const std::size_t item = data.ascii() ? 2 : type_size(p.type);
          // Integral (the header refuses float counts): int64 holds it, negative ones included.
          if (length < 0 || length > static_cast<double>(data.left() / item + 1))
            throw Error::input_at_byte(file, data.offset(),
                                       element.name + " " + std::to_string(r) + ": a list of " +
                                           std::to_string(static_cast<std::int64_t>(length)) +
                                           (length < 0 ? " items is impossible"
                                                       : " items runs past the end of the file"));
          const auto n = static_cast<std::size_t>(length);
          for (std::size_t i = 0; i < n; ++i) {
            const double value = data.read(p.type);
            if (ki != face_list) continue;
            // Float index types are allowed, but only whole numbers that an index can hold.
            if (!(std::abs(value) <= 0x1p53) || value != std::trunc(value)) {
              std::ostringstream number;
              number << value;
              throw Error::input_at_byte(file, data.offset(),
                                         element.name + " " + std::to_string(r) + ": " + number.str() +
                                             " is not a vertex index");
            }
            soup.indices.push_back(static_cast<std::int64_t>(value));
          }
          if (ki == face_list) soup.end_polygon();
          continue;
        }
        const double value = data.read(p.type);
        if (sharp_edges) {
          for (int c = 0; c < 2; ++c)
            if (ki == ends[c]) edge[c] = value;
          if (ki == sharp) edge[2] = value;
        }
        if (!is_vertex) continue;
        for (int c = 0; c < 3; ++c)
          if (ki == xyz[c]) soup.points[r][c] = value;
        if (colors)
          for (int c = 0; c < 3; ++c)
            if (ki == rgb[c]) {
              // Floating-point colours are in [0, 1], integer ones in [0, 255].
              const bool unit = p.type == PlyType::Float32 || p.type == PlyType::Float64;
              soup.attributes.colors[r][c] = static_cast<std::uint8_t>(
                  std::lround(std::clamp(unit ? value * 255.0 : value, 0.0, 255.0)));
            }
        if (ki == label && want_attributes) {
          if (!(std::abs(value) <= std::numeric_limits<int>::max()))
            throw Error::input(file, "vertex " + std::to_string(r) + ": label out of range");
          soup.attributes.labels[r] = static_cast<int>(value);
        }
        if (ki == sharp && want_attributes) soup.attributes.sharp[r] = value != 0.0;
      }
      if (sharp_edges && edge[2] != 0.0) {
        for (int c = 0; c < 2; ++c)
          if (!(edge[c] >= 0 && edge[c] < static_cast<double>(soup.points.size())))
            throw Error::input(file, "edge " + std::to_string(r) + ": vertex index " +
                                         std::to_string(edge[c]) + " is out of range (" +
                                         std::to_string(soup.points.size()) + " vertices)");
        soup.attributes.sharp_edges.push_back({static_cast<int>(edge[0]), static_cast<int>(edge[1])});
      }
    }
  }
  if (!have_vertices) throw Error::input(file, "no vertex element: not a mesh");
  for (std::size_t v = 0; v < soup.points.size(); ++v)
    if (!soup.points[v].allFinite())
      throw Error::input(file, "vertex " + std::to_string(v) + ": the position is NaN or infinite");
  return soup;
}

template <typename T>
void put(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) std::reverse(bytes, bytes + sizeof(T));
  out.append(bytes, sizeof(T));
}

void check_attributes(const TriMesh& mesh, const MeshAttributes& a, const std::filesystem::path& file) {
  auto check = [&](std::size_t size, const char* what) {
    if (size != 0 && size != mesh.n_vertices())
      throw Error::processing(file.string() + ": " + std::to_string(size) + " " + what + " for " +
                              std::to_string(mesh.n_vertices()) + " vertices");
  };
  check(a.labels.size(), "labels");
  check(a.colors.size(), "colours");
  check(a.sharp.size(), "sharp flags");
}

/// New consecutive indices of the mesh's live vertices (deleted ones get -1).
std::vector<int> live_vertex_indices(const TriMesh& mesh, std::size_t& count) {
  std::vector<int> index(mesh.n_vertices(), -1);
  count = 0;
  for (auto v : mesh.vertices()) index[v.idx()] = static_cast<int>(count++);
  return index;
}

/// The region of each live face (mesh order): the label two or three of its vertices share,
/// else the smallest of the three.
std::vector<int> face_labels(const TriMesh& mesh, const std::vector<int>& labels) {
  std::vector<int> out;
  for (auto f : mesh.faces()) {
    std::array<int, 3> l{};
    int k = 0;
    for (auto v : f.vertices()) l[k++ % 3] = labels[v.idx()];
    out.push_back(l[1] == l[2] ? l[1] : l[0] == l[1] || l[0] == l[2] ? l[0] : std::min({l[0], l[1], l[2]}));
  }
  return out;
}

void write_obj_mesh(const TriMesh& mesh, const std::filesystem::path& file, const MeshAttributes& a) {
  std::size_t count = 0;
  const std::vector<int> index = live_vertex_indices(mesh, count);
  const io_detail::SplitNormals normals = io_detail::split_normals(mesh, a.sharp);
  // Faces in region order, one group per region; without labels one group in mesh order.
  std::vector<std::size_t> order(normals.corner_vertex.size() / 3);
  std::iota(order.begin(), order.end(), 0);
  std::vector<int> region;
  if (!a.labels.empty()) {
    region = face_labels(mesh, a.labels);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return region[x] < region[y]; });
  }
  std::vector<int> corners;  // mesh vertex of each corner, faces in mesh order
  for (auto f : mesh.faces())
    for (auto v : f.vertices()) corners.push_back(v.idx());
  write_atomically(file, [&](std::ostream& out) {
    std::string text = "# sketchsurf mesh: " + std::to_string(count) + " vertices, " +
                       std::to_string(order.size()) + " faces; normals split along creases" +
                       (region.empty() ? "" : ", one group per region") + "\n";
    for (auto v : mesh.vertices()) {
      append_vec(text, "v", mesh.point(v));
      if (!a.colors.empty())
        for (int c = 0; c < 3; ++c) {
          text += ' ';
          io_detail::append_number(text, static_cast<float>(a.colors[v.idx()][c] / 255.0));
        }
      text += '\n';
    }
    for (const Eigen::Vector3d& n : normals.normals) {
      append_vec(text, "vn", OpenMesh::Vec3d(n.x(), n.y(), n.z()));
      text += '\n';
    }
    for (std::size_t i = 0; i < order.size(); ++i) {
      const std::size_t f = order[i];
      if (!region.empty() && (i == 0 || region[f] != region[order[i - 1]]))
        text += "g region_" + std::to_string(region[f]) + "\n";
      text += 'f';
      for (std::size_t c = 3 * f; c < 3 * f + 3; ++c)
        text += ' ' + std::to_string(index[corners[c]] + 1) + "//" +
                std::to_string(normals.corner_vertex[c] + 1);
      text += '\n';
      if (text.size() > (1u << 20)) {
        out.write(text.data(), static_cast<std::streamsize>(text.size()));
        text.clear();
      }
    }
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
  });
}

void write_ply_mesh(const TriMesh& mesh, const std::filesystem::path& file, const MeshAttributes& a) {
  std::size_t count = 0;
  const std::vector<int> index = live_vertex_indices(mesh, count);
  std::size_t faces = 0;
  for ([[maybe_unused]] auto f : mesh.faces()) ++faces;
  std::string header = "ply\nformat binary_little_endian 1.0\ncomment written by sketchsurf\n";
  header += "element vertex " + std::to_string(count) + "\n";
  header += "property double x\nproperty double y\nproperty double z\n";
  if (!a.labels.empty()) header += "property int label\n";
  if (!a.colors.empty()) header += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  if (!a.sharp.empty()) header += "property uchar sharp\n";
  header += "element face " + std::to_string(faces) + "\n";
  header += "property list uchar int vertex_indices\n";
  // With sharp flags, the creases per edge too: a vertex flag cannot say which of its edges is
  // sharp.
  std::vector<std::uint8_t> crease;
  if (!a.sharp.empty()) {
    crease = io_detail::crease_edges(mesh, a.sharp);
    std::size_t edges = 0;
    for ([[maybe_unused]] auto e : mesh.edges()) ++edges;
    header += "element edge " + std::to_string(edges) +
              "\nproperty int vertex1\nproperty int vertex2\nproperty uchar sharp\n";
  }
  header += "end_header\n";
  write_atomically(file, [&](std::ostream& out) {
    std::string bytes = header;
    for (auto v : mesh.vertices()) {
      const auto& p = mesh.point(v);
      for (int c = 0; c < 3; ++c) put<double>(bytes, p[c]);
      if (!a.labels.empty()) put<std::int32_t>(bytes, a.labels[v.idx()]);
      if (!a.colors.empty()) bytes.append(reinterpret_cast<const char*>(a.colors[v.idx()].data()), 3);
      if (!a.sharp.empty()) put<std::uint8_t>(bytes, a.sharp[v.idx()]);
    }
    for (auto f : mesh.faces()) {
      put<std::uint8_t>(bytes, 3);
      for (auto v : f.vertices()) put<std::int32_t>(bytes, index[v.idx()]);
      if (bytes.size() > (1u << 20)) {
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        bytes.clear();
      }
    }
    if (!crease.empty())
      for (auto e : mesh.edges()) {
        put<std::int32_t>(bytes, index[e.v0().idx()]);
        put<std::int32_t>(bytes, index[e.v1().idx()]);
        put<std::uint8_t>(bytes, crease[e.idx()]);
      }
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  });
}

}  // namespace

void write_mesh(const TriMesh& mesh, const std::filesystem::path& file,
                const MeshAttributes& attributes) {
  const std::string ext = lower_extension(file);
  if (ext != ".obj" && ext != ".ply" && ext != ".glb" && ext != ".gltf")
    throw Error::usage(file.string() + ": unknown mesh extension '" + ext +
                       "' (writable: .obj, .ply, .glb, .gltf)");
  check_attributes(mesh, attributes, file);
  if (ext == ".obj") write_obj_mesh(mesh, file, attributes);
  else if (ext == ".ply") write_ply_mesh(mesh, file, attributes);
  else io_detail::write_gltf_mesh(mesh, file, attributes, ext == ".glb");
}

TriMesh read_mesh(const std::filesystem::path& file, MeshAttributes* attributes) {
  const std::string ext = lower_extension(file);
  if (ext != ".obj" && ext != ".ply")
    throw Error::usage(file.string() + ": unknown mesh extension '" + ext + "' (readable: .obj, .ply)");
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw Error::input(file, "no such file");
  PolygonSoup soup = ext == ".obj" ? read_obj_soup(file, attributes != nullptr)
                                   : read_ply_soup(file, attributes != nullptr);
  if (soup.points.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw Error::input(file, "too many vertices");
  TriMesh mesh = build_mesh(soup, file);
  if (attributes) *attributes = std::move(soup.attributes);
  return mesh;
}

}  // namespace sketchsurf
