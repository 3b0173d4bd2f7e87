#include "surfacing/mesh.h"

#include <algorithm>
#include <numeric>

#include <Eigen/Geometry>

#include "surfacing/error.h"

namespace sketchsurf {

Eigen::MatrixX3d vertex_matrix(const TriMesh& mesh) {
  Eigen::MatrixX3d V(mesh.n_vertices(), 3);
  for (auto v : mesh.vertices()) V.row(v.idx()) = to_eigen(mesh.point(v)).transpose();
  return V;
}

void set_vertex_matrix(TriMesh& mesh, const Eigen::MatrixX3d& V) {
  for (auto v : mesh.vertices()) mesh.set_point(v, to_openmesh(V.row(v.idx()).transpose()));
}

std::vector<int> vertex_components(const Eigen::MatrixX3i& F, Eigen::Index vertices) {
  std::vector<int> parent(static_cast<std::size_t>(vertices));
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 1; k < 3; ++k) {
      const int a = find(F(f, 0)), b = find(F(f, k));
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  for (auto& p : parent) p = find(p);
  return parent;
}

Eigen::MatrixX3i face_matrix(const TriMesh& mesh) {
  Eigen::MatrixX3i F(mesh.n_faces(), 3);
  for (auto f : mesh.faces()) {
    int c = 0;
    for (auto v : f.vertices()) F(f.idx(), c++) = v.idx();
  }
  return F;
}

double triangle_area(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, Eigen::Index f) {
  const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
  return 0.5 * (b - a).cross(c - a).norm();
}

Eigen::MatrixX3d vertex_normals(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
  Eigen::MatrixX3d N = Eigen::MatrixX3d::Zero(V.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::RowVector3d n = (b - a).cross(c - a).transpose();  // length: twice the area
    for (int k = 0; k < 3; ++k) N.row(F(f, k)) += n;
  }
  for (Eigen::Index v = 0; v < N.rows(); ++v) {
    const double length = N.row(v).norm();
    if (length > 0.0) N.row(v) /= length;
  }
  return N;
}

TriMesh mesh_from_matrices(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
  TriMesh mesh;
  std::vector<TriMesh::VertexHandle> vh;
  vh.reserve(V.rows());
  for (Eigen::Index i = 0; i < V.rows(); ++i) vh.push_back(mesh.add_vertex(to_openmesh(V.row(i))));
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    for (int c = 0; c < 3; ++c) {
      if (F(f, c) < 0 || F(f, c) >= V.rows())
        throw Error::processing("triangle " + std::to_string(f) + " names vertex " +
                                std::to_string(F(f, c)) + " of " + std::to_string(V.rows()));
    }
    auto fh = mesh.add_face(vh[F(f, 0)], vh[F(f, 1)], vh[F(f, 2)]);
    if (!fh.is_valid())
      throw Error::processing("triangle " + std::to_string(f) +
                              " makes the mesh non-manifold or flips its orientation");
  }
  mesh.update_normals();
  return mesh;
}

void append_mesh(TriMesh& mesh, const TriMesh& part) {
  std::vector<TriMesh::VertexHandle> map;
  map.reserve(part.n_vertices());
  for (auto v : part.vertices()) map.push_back(mesh.add_vertex(part.point(v)));
  for (auto f : part.faces()) {
    std::vector<TriMesh::VertexHandle> corners;
    for (auto v : part.fv_range(f)) corners.push_back(map[v.idx()]);
    mesh.add_face(corners);
  }
}

}  // namespace sketchsurf
