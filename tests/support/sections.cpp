#include "tests/support/sections.h"

#include <cmath>
#include <utility>
#include <vector>

#include "surfacing/sketch/sketch.h"

namespace sketchsurf::testing {

std::size_t section_loops(const TriMesh& mesh, double height) {
  const auto above = [&](OpenMesh::VertexHandle v) { return mesh.point(v)[1] > height; };
  std::vector<int> root(mesh.n_faces());
  for (std::size_t i = 0; i < root.size(); ++i) root[i] = static_cast<int>(i);
  const auto find = [&](int f) {
    while (root[static_cast<std::size_t>(f)] != f)
      f = root[static_cast<std::size_t>(f)] = root[static_cast<std::size_t>(root[static_cast<std::size_t>(f)])];
    return f;
  };
  std::vector<char> cut(mesh.n_faces(), 0);
  for (const auto e : mesh.edges()) {
    const auto h = e.h0();
    if (above(h.from()) == above(h.to()) || !h.face().is_valid() || !h.opp().face().is_valid()) continue;
    cut[static_cast<std::size_t>(h.face().idx())] = cut[static_cast<std::size_t>(h.opp().face().idx())] = 1;
    root[static_cast<std::size_t>(find(h.face().idx()))] = find(h.opp().face().idx());
  }
  std::size_t loops = 0;
  for (std::size_t f = 0; f < root.size(); ++f) loops += cut[f] && find(static_cast<int>(f)) == static_cast<int>(f);
  return loops;
}

double section_width(const TriMesh& mesh, double height) {
  BoundingBox box;
  for (const auto e : mesh.edges()) {
    const Eigen::Vector3d a = to_eigen(mesh.point(e.v0())), b = to_eigen(mesh.point(e.v1()));
    if ((a.y() > height) == (b.y() > height)) continue;
    box.extend(a + (height - a.y()) / (b.y() - a.y()) * (b - a));
  }
  return box.diagonal();
}

double section_area(const TriMesh& mesh, double height) {
  double twice = 0.0;
  for (const auto f : mesh.faces()) {
    std::vector<Eigen::Vector3d> corners;
    for (const auto v : f.vertices()) corners.push_back(to_eigen(mesh.point(v)));
    std::vector<Eigen::Vector3d> crossings;
    for (std::size_t k = 0; k < corners.size(); ++k) {
      const Eigen::Vector3d &a = corners[k], &b = corners[(k + 1) % corners.size()];
      if ((a.y() > height) != (b.y() > height)) crossings.push_back(a + (height - a.y()) / (b.y() - a.y()) * (b - a));
    }
    if (crossings.size() != 2) continue;
    // The segment runs along the outward normal crossed with the plane's normal: each loop is
    // walked one way round, holes the other.
    const Eigen::Vector3d normal = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
    Eigen::Vector3d p = crossings[0], q = crossings[1];
    if ((q - p).dot(normal.cross(Eigen::Vector3d::UnitY())) < 0.0) std::swap(p, q);
    twice += p.z() * q.x() - p.x() * q.z();
  }
  return std::abs(0.5 * twice);
}

}  // namespace sketchsurf::testing
