#include "surfacing/extract/mirror.h"

#include <cmath>

#include "surfacing/error.h"

namespace sketchsurf {

namespace {

/// Appends point i of `from` (position `p`) with its per-point attributes to `to`.
void append_point(const Stroke& from, std::size_t i, const Eigen::Vector3d& p, Stroke& to) {
  to.points.push_back(p);
  if (!from.orientations.empty()) to.orientations.push_back(from.orientations[i]);
  if (!from.pressures.empty()) to.pressures.push_back(from.pressures[i]);
  if (!from.timestamps_ms.empty()) to.timestamps_ms.push_back(from.timestamps_ms[i]);
}

Stroke empty_like(const Stroke& s) {
  Stroke piece = s;
  piece.points.clear();
  piece.orientations.clear();
  piece.pressures.clear();
  piece.timestamps_ms.clear();
  return piece;
}

Eigen::Vector3d onto_plane(const Eigen::Vector3d& p, const Plane& plane) {
  return p - plane.signed_distance(p) * plane.normal;
}

}  // namespace

ClippedMesh clip_to_half_space(const TriMesh& mesh, const Plane& plane, double snap) {
  const int nv = static_cast<int>(mesh.n_vertices());
  std::vector<double> sd(nv);
  std::vector<Eigen::Vector3d> points;
  ClippedMesh out;
  std::vector<int> new_index(nv, -1);
  for (auto v : mesh.vertices()) {
    Eigen::Vector3d p = to_eigen(mesh.point(v));
    double d = plane.signed_distance(p);
    if (std::abs(d) <= snap) {
      p = onto_plane(p, plane);
      d = 0.0;
    }
    sd[v.idx()] = d;
    if (d >= 0.0) {
      new_index[v.idx()] = static_cast<int>(points.size());
      points.push_back(p);
      out.source_vertex.push_back(v.idx());
      out.on_plane.push_back(d == 0.0);
    }
  }
  // One vertex on the plane per edge whose ends are strictly on opposite sides.
  std::vector<int> crossing(mesh.n_edges(), -1);
  for (auto e : mesh.edges()) {
    const int a = e.v0().idx(), b = e.v1().idx();
    if ((sd[a] > 0.0 && sd[b] < 0.0) || (sd[a] < 0.0 && sd[b] > 0.0)) {
      const double t = sd[a] / (sd[a] - sd[b]);
      const Eigen::Vector3d p =
          (1.0 - t) * to_eigen(mesh.point(e.v0())) + t * to_eigen(mesh.point(e.v1()));
      crossing[e.idx()] = static_cast<int>(points.size());
      points.push_back(onto_plane(p, plane));
      out.source_vertex.push_back(-1);
      out.on_plane.push_back(1);
    }
  }
  // Sutherland-Hodgman on each triangle, then a fan over the kept polygon (3 or 4 corners).
  std::vector<Eigen::Vector3i> faces;
  for (auto f : mesh.faces()) {
    std::vector<int> polygon;
    for (auto h : f.halfedges()) {
      const int a = h.from().idx();
      if (sd[a] >= 0.0) polygon.push_back(new_index[a]);
      if (crossing[h.edge().idx()] >= 0) polygon.push_back(crossing[h.edge().idx()]);
    }
    if (polygon.size() < 3) continue;
    bool all_on_plane = true;
    for (int i : polygon) all_on_plane = all_on_plane && out.on_plane[i];
    if (all_on_plane) continue;
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
      faces.emplace_back(polygon[0], polygon[k], polygon[k + 1]);
  }
  if (faces.empty())
    throw Error::processing("clipping the proxy at the mirror plane left nothing on the kept side; "
                            "check the plane's orientation (the kept side is where n.x + d >= 0)");
  // Drop vertices no kept face uses (the far side's vertices are already absent).
  std::vector<int> used(points.size(), -1);
  int count = 0;
  for (const auto& face : faces)
    for (int c = 0; c < 3; ++c)
      if (used[face[c]] < 0) used[face[c]] = count++;
  Eigen::MatrixX3d V(count, 3);
  std::vector<int> source(count);
  std::vector<std::uint8_t> on_plane(count);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (used[i] < 0) continue;
    V.row(used[i]) = points[i].transpose();
    source[used[i]] = out.source_vertex[i];
    on_plane[used[i]] = out.on_plane[i];
  }
  Eigen::MatrixX3i F(faces.size(), 3);
  for (std::size_t i = 0; i < faces.size(); ++i)
    for (int c = 0; c < 3; ++c) F(i, c) = used[faces[i][c]];
  out.mesh = mesh_from_matrices(V, F);
  out.source_vertex = std::move(source);
  out.on_plane = std::move(on_plane);
  return out;
}

Sketch half_sketch(const Sketch& sketch, const Plane& plane) {
  Sketch half = sketch;
  half.strokes.clear();
  for (const Stroke& s : sketch.strokes) {
    Stroke piece = empty_like(s);
    auto flush = [&] {
      if (piece.points.size() >= 2) half.strokes.push_back(piece);
      piece = empty_like(s);
    };
    for (std::size_t i = 0; i < s.points.size(); ++i) {
      const double d = plane.signed_distance(s.points[i]);
      if (i > 0) {
        const double d_prev = plane.signed_distance(s.points[i - 1]);
        if ((d_prev < 0.0) != (d < 0.0) && d_prev != 0.0 && d != 0.0) {
          // Crossing: the point on the plane closes (or opens) a piece, with the attributes of
          // the point on the kept side.
          const double t = d_prev / (d_prev - d);
          const Eigen::Vector3d x =
              onto_plane((1.0 - t) * s.points[i - 1] + t * s.points[i], plane);
          append_point(s, d >= 0.0 ? i : i - 1, x, piece);
          if (d < 0.0) flush();
        }
      }
      if (d >= 0.0) append_point(s, i, s.points[i], piece);
      else if (!piece.points.empty()) flush();
    }
    flush();
  }
  return half;
}

TriMesh mirror_and_weld(const TriMesh& half, const Plane& plane, double weld,
                        std::vector<int>* source_vertex) {
  const int n = static_cast<int>(half.n_vertices());
  std::vector<Eigen::Vector3d> points(n);
  std::vector<int> mirror(n, -1);
  std::vector<bool> welded(n, false);
  for (auto v : half.vertices()) {
    Eigen::Vector3d p = to_eigen(half.point(v));
    if (half.is_boundary(v) && std::abs(plane.signed_distance(p)) <= weld) {
      p = onto_plane(p, plane);
      welded[v.idx()] = true;
      mirror[v.idx()] = v.idx();
    }
    points[v.idx()] = p;
  }
  std::vector<int> source(n);
  for (int i = 0; i < n; ++i) source[i] = i;
  for (int i = 0; i < n; ++i) {
    if (welded[i]) continue;
    mirror[i] = static_cast<int>(points.size());
    points.push_back(plane.reflect(points[i]));
    source.push_back(i);
  }
  std::vector<Eigen::Vector3i> faces;
  for (auto f : half.faces()) {
    Eigen::Vector3i t;
    int c = 0;
    for (auto v : f.vertices()) t[c++] = v.idx();
    if (welded[t[0]] && welded[t[1]] && welded[t[2]]) continue;
    faces.push_back(t);
  }
  const std::size_t kept = faces.size();
  for (std::size_t i = 0; i < kept; ++i)
    faces.emplace_back(mirror[faces[i][0]], mirror[faces[i][2]], mirror[faces[i][1]]);
  Eigen::MatrixX3d V(points.size(), 3);
  for (std::size_t i = 0; i < points.size(); ++i) V.row(i) = points[i].transpose();
  Eigen::MatrixX3i F(faces.size(), 3);
  for (std::size_t i = 0; i < faces.size(); ++i) F.row(i) = faces[i].transpose();
  TriMesh out;
  try {
    out = mesh_from_matrices(V, F);
  } catch (const Error& e) {
    throw Error::processing(std::string("mirroring the half surface: ") + e.what() +
                            "; the half surface folds over the mirror plane");
  }
  if (source_vertex) *source_vertex = std::move(source);
  return out;
}

}  // namespace sketchsurf
