#include "surfacing/sketch/io/gltf_io.h"

#include <tiny_gltf.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>
#include <vector>

#include "surfacing/error.h"
#include "surfacing/palette.h"
#include "surfacing/sketch/io/atomic_file.h"

namespace sketchsurf::io_detail {

namespace {

/// Union-find over the face corners: the corners of one vertex that share a smooth side.
class CornerSets {
 public:
  explicit CornerSets(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  std::size_t find(std::size_t c) {
    while (parent_[c] != c) c = parent_[c] = parent_[parent_[c]];
    return c;
  }
  /// The smaller root wins, so the sets do not depend on the order of the unions.
  void join(std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<std::size_t> parent_;
};

/// The triangles of the mesh with their vertices, unit normals and corner angles.
struct Triangles {
  std::vector<int> slot;                      // per mesh face index: its triangle, -1 if none
  std::vector<std::array<int, 3>> vertices;   // mesh vertex indices
  std::vector<Eigen::Vector3d> normals;       // zero for a degenerate triangle
  std::vector<std::array<double, 3>> angles;  // at each corner (rad)
};

Triangles triangles(const TriMesh& mesh) {
  Triangles t;
  t.slot.assign(mesh.n_faces(), -1);
  for (auto f : mesh.faces()) {
    std::array<int, 3> v{};
    int k = 0;
    for (auto u : f.vertices()) {
      if (k == 3) throw Error::processing("glTF output: a face with more than three vertices");
      v[k++] = u.idx();
    }
    if (k != 3) throw Error::processing("glTF output: a face with fewer than three vertices");
    std::array<Eigen::Vector3d, 3> p;
    for (int i = 0; i < 3; ++i) p[i] = to_eigen(mesh.point(TriMesh::VertexHandle(v[i])));
    Eigen::Vector3d n = (p[1] - p[0]).cross(p[2] - p[0]);
    n = n.norm() > 0.0 && n.allFinite() ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::Zero();
    std::array<double, 3> angle{};
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d a = p[(i + 1) % 3] - p[i], b = p[(i + 2) % 3] - p[i];
      const double value = std::atan2(a.cross(b).norm(), a.dot(b));
      angle[i] = std::isfinite(value) ? value : 0.0;
    }
    t.slot[f.idx()] = static_cast<int>(t.vertices.size());
    t.vertices.push_back(v);
    t.normals.push_back(n);
    t.angles.push_back(angle);
  }
  return t;
}

/// Corner index (3 triangle + k) of mesh vertex v in triangle i.
std::size_t corner(const Triangles& t, int i, int v) {
  for (int k = 0; k < 3; ++k)
    if (t.vertices[i][k] == v) return 3 * static_cast<std::size_t>(i) + k;
  throw Error::processing("glTF output: inconsistent mesh connectivity");
}

/// Appends `values` to the buffer as a new buffer view (4-byte aligned) and returns its index.
template <typename T>
int add_view(tinygltf::Model& model, const std::vector<T>& values, int target) {
  auto& data = model.buffers[0].data;
  data.resize((data.size() + 3) / 4 * 4, 0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = data.size();
  view.byteLength = values.size() * sizeof(T);
  view.target = target;
  const auto* bytes = reinterpret_cast<const unsigned char*>(values.data());
  data.insert(data.end(), bytes, bytes + view.byteLength);
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size()) - 1;
}

/// A float accessor of `components` (1 or 3) per element over a new view of `values`.
int add_float_accessor(tinygltf::Model& model, const std::vector<float>& values, int components,
                       bool with_bounds) {
  tinygltf::Accessor accessor;
  accessor.bufferView = add_view(model, values, TINYGLTF_TARGET_ARRAY_BUFFER);
  accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  accessor.type = components == 3 ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_SCALAR;
  accessor.count = values.size() / components;
  if (with_bounds) {  // required for POSITION
    accessor.minValues.assign(components, std::numeric_limits<double>::infinity());
    accessor.maxValues.assign(components, -std::numeric_limits<double>::infinity());
    for (std::size_t i = 0; i < values.size(); ++i) {
      const std::size_t c = i % components;
      accessor.minValues[c] = std::min<double>(accessor.minValues[c], values[i]);
      accessor.maxValues[c] = std::max<double>(accessor.maxValues[c], values[i]);
    }
  }
  model.accessors.push_back(accessor);
  return static_cast<int>(model.accessors.size()) - 1;
}

}  // namespace

void write_gltf_mesh(const TriMesh& mesh, const std::filesystem::path& file, const MeshAttributes& a,
                     bool binary) {
  const Triangles t = triangles(mesh);
  const std::size_t corners = 3 * t.vertices.size();

  // The corners of a vertex on the two sides of an edge share an output vertex unless the edge
  // is a crease (or a border: then they are not on two sides of it).
  const double crease = std::cos(kGltfCreaseAngle * M_PI / 180.0);
  const double sharp_crease = std::cos(kGltfSharpCreaseAngle * M_PI / 180.0);
  CornerSets sets(corners);
  for (auto e : mesh.edges()) {
    if (e.is_boundary()) continue;
    const int f0 = t.slot[e.h0().face().idx()], f1 = t.slot[e.h1().face().idx()];
    if (f0 < 0 || f1 < 0) continue;
    const int u = e.v0().idx(), v = e.v1().idx();
    const bool sharp = !a.sharp.empty() && a.sharp[u] && a.sharp[v];
    const double cosine = t.normals[f0].dot(t.normals[f1]);
    const bool degenerate = t.normals[f0].isZero(0.0) || t.normals[f1].isZero(0.0);
    if (!degenerate && cosine < (sharp ? sharp_crease : crease)) continue;
    for (int w : {u, v}) sets.join(corner(t, f0, w), corner(t, f1, w));
  }

  // One output vertex per set, numbered in corner order.
  std::vector<std::uint32_t> index(corners);
  std::vector<std::size_t> output(corners, std::numeric_limits<std::size_t>::max());
  std::vector<int> source;                // mesh vertex of each output vertex
  std::vector<Eigen::Vector3d> normal;    // angle-weighted sums
  std::vector<Eigen::Vector3d> fallback;  // a face normal, for a sum that cancels out
  for (std::size_t c = 0; c < corners; ++c) {
    const std::size_t root = sets.find(c);
    if (output[root] == std::numeric_limits<std::size_t>::max()) {
      output[root] = source.size();
      source.push_back(t.vertices[c / 3][c % 3]);
      normal.emplace_back(Eigen::Vector3d::Zero());
      fallback.emplace_back(Eigen::Vector3d::UnitZ());
    }
    const std::size_t o = output[root];
    index[c] = static_cast<std::uint32_t>(o);
    normal[o] += t.angles[c / 3][c % 3] * t.normals[c / 3];
    if (!t.normals[c / 3].isZero(0.0)) fallback[o] = t.normals[c / 3];
  }

  std::vector<float> positions, normals, colors, labels;
  for (std::size_t o = 0; o < source.size(); ++o) {
    const int v = source[o];
    const auto& p = mesh.point(TriMesh::VertexHandle(v));
    const Eigen::Vector3d n = normal[o].norm() > 0.0 ? Eigen::Vector3d(normal[o].normalized()) : fallback[o];
    for (int c = 0; c < 3; ++c) {
      positions.push_back(static_cast<float>(p[c]));
      normals.push_back(static_cast<float>(n[c]));
    }
    if (!a.colors.empty() || !a.labels.empty()) {
      const Rgb8 rgb = !a.colors.empty() ? a.colors[v] : region_color(a.labels[v]);
      for (int c = 0; c < 3; ++c) colors.push_back(static_cast<float>(rgb[c] / 255.0));
    }
    if (!a.labels.empty()) labels.push_back(static_cast<float>(a.labels[v]));
  }

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "sketchsurf";
  model.buffers.emplace_back();
  tinygltf::Node node;
  if (corners > 0) {
    tinygltf::Primitive primitive;
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    tinygltf::Accessor indices;
    indices.bufferView = add_view(model, index, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    indices.type = TINYGLTF_TYPE_SCALAR;
    indices.count = index.size();
    model.accessors.push_back(indices);
    primitive.indices = static_cast<int>(model.accessors.size()) - 1;
    primitive.attributes["POSITION"] = add_float_accessor(model, positions, 3, true);
    primitive.attributes["NORMAL"] = add_float_accessor(model, normals, 3, false);
    if (!colors.empty()) primitive.attributes["COLOR_0"] = add_float_accessor(model, colors, 3, false);
    if (!labels.empty()) primitive.attributes["_LABEL"] = add_float_accessor(model, labels, 1, false);
    // Vertex colours are multiplied by the base colour: white, not metallic, both sides lit
    // (open surfaces are seen from both sides).
    tinygltf::Material material;
    material.name = "sketchsurf";
    material.pbrMetallicRoughness.metallicFactor = 0.0;
    material.pbrMetallicRoughness.roughnessFactor = 0.8;
    material.doubleSided = true;
    model.materials.push_back(material);
    primitive.material = 0;
    tinygltf::Mesh gltf_mesh;
    gltf_mesh.name = "surface";
    gltf_mesh.primitives.push_back(primitive);
    model.meshes.push_back(gltf_mesh);
    node.mesh = 0;
  } else {
    model.buffers.clear();
  }
  node.name = "surface";
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  model.scenes.push_back(scene);
  model.defaultScene = 0;

  write_atomically(file, [&](std::ostream& out) {
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&model, out, /*prettyPrint=*/!binary, /*writeBinary=*/binary))
      throw Error::processing("the glTF writer failed");
  });
}

}  // namespace sketchsurf::io_detail
