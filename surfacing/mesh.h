#pragma once
// The one mesh type for geometry: an OpenMesh triangle mesh in double precision.

#include <Eigen/Core>
#include <vector>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

namespace sketchsurf {

struct MeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  VertexAttributes(OpenMesh::Attributes::Normal | OpenMesh::Attributes::Status);
  FaceAttributes(OpenMesh::Attributes::Normal | OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  HalfedgeAttributes(OpenMesh::Attributes::PrevHalfedge);
};

using TriMesh = OpenMesh::TriMesh_ArrayKernelT<MeshTraits>;

inline Eigen::Vector3d to_eigen(const OpenMesh::Vec3d& p) { return {p[0], p[1], p[2]}; }
inline OpenMesh::Vec3d to_openmesh(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

/// Vertex positions as a #V x 3 matrix (vertex i in row i).
Eigen::MatrixX3d vertex_matrix(const TriMesh& mesh);
/// Sets every vertex's position from row i of V (#V x 3): the inverse of vertex_matrix().
void set_vertex_matrix(TriMesh& mesh, const Eigen::MatrixX3d& V);
/// Triangle vertex indices as a #F x 3 matrix.
Eigen::MatrixX3i face_matrix(const TriMesh& mesh);
/// The area of triangle f of F (#F x 3) over positions V.
double triangle_area(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F, Eigen::Index f);
/// Unit vertex normals of the triangles F over positions V (#V x 3), each the sum of its triangles'
/// normals weighted by their areas; a zero row where they cancel or no triangle has area.
Eigen::MatrixX3d vertex_normals(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F);
/// Per vertex (0 .. vertices - 1): the lowest vertex index of its connected component through the
/// triangles of F, so equal values mean the same part (a vertex in no triangle is its own part).
std::vector<int> vertex_components(const Eigen::MatrixX3i& F, Eigen::Index vertices);
/// Builds a mesh from #V x 3 positions and #F x 3 triangles; throws Error (Processing) on a
/// triangle that OpenMesh cannot add (non-manifold or inconsistently oriented).
TriMesh mesh_from_matrices(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F);
/// Adds the vertices and faces of `part` to `mesh` (a separate component), in their order: the
/// vertex i of `part` becomes mesh.n_vertices() (before the call) + i.
void append_mesh(TriMesh& mesh, const TriMesh& part);

}  // namespace sketchsurf
