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
#include "surfacing/sketch/io/split_normals.h"

namespace sketchsurf::io_detail {

namespace {

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

/// The strokes as a second mesh, "strokes": one LINE_STRIP primitive per polyline of at least two
/// points (all points in one buffer view, an accessor each), drawn in a dark grey. Returns the
/// mesh index, or -1 when no polyline has two points.
int add_strokes(tinygltf::Model& model, const std::vector<std::vector<Eigen::Vector3d>>& strokes) {
  std::vector<float> points;
  for (const auto& stroke : strokes)
    if (stroke.size() >= 2)
      for (const Eigen::Vector3d& p : stroke)
        for (int c = 0; c < 3; ++c) points.push_back(static_cast<float>(p[c]));
  if (points.empty()) return -1;
  const int view = add_view(model, points, TINYGLTF_TARGET_ARRAY_BUFFER);
  model.bufferViews[view].byteStride = 3 * sizeof(float);  // required: the accessors share the view
  tinygltf::Material material;
  material.name = "strokes";
  material.pbrMetallicRoughness.baseColorFactor = {0.1, 0.1, 0.1, 1.0};
  material.pbrMetallicRoughness.metallicFactor = 0.0;
  model.materials.push_back(material);
  tinygltf::Mesh mesh;
  mesh.name = "strokes";
  std::size_t first = 0;  // first point of the stroke in `points`
  for (const auto& stroke : strokes) {
    if (stroke.size() < 2) continue;
    tinygltf::Accessor accessor;
    accessor.bufferView = view;
    accessor.byteOffset = first * 3 * sizeof(float);
    accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    accessor.type = TINYGLTF_TYPE_VEC3;
    accessor.count = stroke.size();
    accessor.minValues.assign(3, std::numeric_limits<double>::infinity());
    accessor.maxValues.assign(3, -std::numeric_limits<double>::infinity());
    for (std::size_t i = first; i < first + stroke.size(); ++i)
      for (int c = 0; c < 3; ++c) {
        accessor.minValues[c] = std::min<double>(accessor.minValues[c], points[3 * i + c]);
        accessor.maxValues[c] = std::max<double>(accessor.maxValues[c], points[3 * i + c]);
      }
    model.accessors.push_back(accessor);
    tinygltf::Primitive primitive;
    primitive.mode = TINYGLTF_MODE_LINE_STRIP;
    primitive.attributes["POSITION"] = static_cast<int>(model.accessors.size()) - 1;
    primitive.material = static_cast<int>(model.materials.size()) - 1;
    mesh.primitives.push_back(primitive);
    first += stroke.size();
  }
  model.meshes.push_back(mesh);
  return static_cast<int>(model.meshes.size()) - 1;
}

}  // namespace

void write_gltf_mesh(const TriMesh& mesh, const std::filesystem::path& file, const MeshAttributes& a,
                     bool binary) {
  const SplitNormals split = split_normals(mesh, a.sharp);
  const std::vector<std::uint32_t>& index = split.corner_vertex;
  const std::size_t corners = index.size();

  std::vector<float> positions, normals, colors, labels;
  for (std::size_t o = 0; o < split.source.size(); ++o) {
    const int v = split.source[o];
    const auto& p = mesh.point(TriMesh::VertexHandle(v));
    const Eigen::Vector3d& n = split.normals[o];
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
  }
  node.name = "surface";
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  if (const int strokes = add_strokes(model, a.strokes); strokes >= 0) {
    tinygltf::Node strokes_node;
    strokes_node.name = "strokes";
    strokes_node.mesh = strokes;
    model.nodes.push_back(strokes_node);
    scene.nodes.push_back(1);
  }
  if (model.buffers[0].data.empty()) model.buffers.clear();
  model.scenes.push_back(scene);
  model.defaultScene = 0;

  write_atomically(file, [&](std::ostream& out) {
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&model, out, /*prettyPrint=*/!binary, /*writeBinary=*/binary))
      throw Error::processing("the glTF writer failed");
  });
}

}  // namespace sketchsurf::io_detail
