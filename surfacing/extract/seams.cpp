#include "surfacing/extract/seams.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "surfacing/error.h"
#include "surfacing/parallel.h"

namespace sketchsurf {

bool SeamOptions::valid(std::string* why) const {
  auto fail = [&](const char* what) {
    if (why) *why = what;
    return false;
  };
  if (!(edge_margin >= 0.0 && edge_margin < 1.0 / 3.0))
    return fail("seams.edge_margin must be in [0, 1/3)");
  if (samples < 2) return fail("seams.samples must be at least 2");
  return true;
}

namespace {

/// Squared Taubin distance, finite everywhere (a vanishing gradient gives a large value) so that
/// it can be compared and minimised.
double squared_distance(const ImplicitModel& model, const Eigen::Vector3d& x) {
  const double d = model.distance(x);
  return std::isfinite(d) ? d * d : std::numeric_limits<double>::max() / 8;
}

double cost(const std::vector<const ImplicitModel*>& models, const Eigen::Vector3d& x) {
  double c = 0.0;
  for (const ImplicitModel* m : models) c += squared_distance(*m, x);
  return c;
}

/// Where the surfaces are closest along the segment a-b: sampling, then golden-section search in
/// the bracket around the best sample.
Eigen::Vector3d place_on_edge(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              const std::vector<const ImplicitModel*>& models,
                              const SeamOptions& options) {
  const double lo = options.edge_margin, hi = 1.0 - options.edge_margin;
  auto at = [&](double t) { return Eigen::Vector3d((1.0 - t) * a + t * b); };
  auto f = [&](double t) { return cost(models, at(t)); };
  const int n = options.samples;
  const double step = (hi - lo) / (n - 1);
  int best = 0;
  double best_cost = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i) {
    const double c = f(lo + step * i);
    if (c < best_cost) {
      best_cost = c;
      best = i;
    }
  }
  double left = lo + step * std::max(0, best - 1), right = lo + step * std::min(n - 1, best + 1);
  const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = right - golden * (right - left), x2 = left + golden * (right - left);
  double f1 = f(x1), f2 = f(x2);
  for (int it = 0; it < 40 && right - left > 1e-9; ++it) {
    if (f1 <= f2) {
      right = x2;
      x2 = x1;
      f2 = f1;
      x1 = right - golden * (right - left);
      f1 = f(x1);
    } else {
      left = x1;
      x1 = x2;
      f1 = f2;
      x2 = left + golden * (right - left);
      f2 = f(x2);
    }
  }
  const double t = 0.5 * (left + right);
  return f(t) <= best_cost ? at(t) : at(lo + step * best);
}

/// Where the surfaces are closest inside the triangle: the best point of a barycentric grid whose
/// barycentric coordinates all stay >= margin.
Eigen::Vector3d place_in_triangle(const std::array<Eigen::Vector3d, 3>& corner,
                                  const std::vector<const ImplicitModel*>& models,
                                  const SeamOptions& options) {
  const int n = options.samples;
  const double m = options.edge_margin, span = 1.0 - 3.0 * m;
  Eigen::Vector3d best = (corner[0] + corner[1] + corner[2]) / 3.0;
  double best_cost = cost(models, best);
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      const double b0 = m + span * i / n, b1 = m + span * j / n, b2 = 1.0 - b0 - b1;
      const Eigen::Vector3d x = b0 * corner[0] + b1 * corner[1] + b2 * corner[2];
      const double c = cost(models, x);
      if (c < best_cost) {
        best_cost = c;
        best = x;
      }
    }
  return best;
}

}  // namespace

LabeledMesh insert_seams(const TriMesh& proxy, const std::vector<int>& labels,
                         const std::vector<ImplicitModel>& models, const SeamOptions& options) {
  std::string why;
  if (!options.valid(&why)) throw Error::usage(why);
  if (labels.size() != proxy.n_vertices())
    throw Error::usage("insert_seams: " + std::to_string(labels.size()) + " labels for " +
                       std::to_string(proxy.n_vertices()) + " proxy vertices");
  for (std::size_t v = 0; v < labels.size(); ++v)
    if (labels[v] < 0 || labels[v] >= static_cast<int>(models.size()))
      throw Error::usage("insert_seams: vertex " + std::to_string(v) + " has label " +
                         std::to_string(labels[v]) + " but there are " +
                         std::to_string(models.size()) + " models");

  std::vector<Eigen::Vector3d> points;
  LabeledMesh out;
  points.reserve(proxy.n_vertices());
  for (auto v : proxy.vertices()) {
    points.push_back(to_eigen(proxy.point(v)));
    out.labels.push_back({labels[v.idx()]});
    out.source_vertex.push_back(v.idx());
  }
  auto add_vertex = [&](const Eigen::Vector3d& p, std::vector<int> vertex_labels) {
    std::sort(vertex_labels.begin(), vertex_labels.end());
    points.push_back(p);
    out.labels.push_back(std::move(vertex_labels));
    out.source_vertex.push_back(-1);
    return static_cast<int>(points.size()) - 1;
  };
  auto models_of = [&](std::initializer_list<int> ls) {
    std::vector<const ImplicitModel*> ms;
    for (int l : ls) ms.push_back(&models[l]);
    return ms;
  };

  // One inserted vertex per edge whose ends have different labels.
  // Placed in parallel, added in edge order.
  std::vector<int> crossed;
  for (auto e : proxy.edges())
    if (labels[e.v0().idx()] != labels[e.v1().idx()]) crossed.push_back(e.idx());
  std::vector<Eigen::Vector3d> placed(crossed.size());
  parallel_for(0, crossed.size(), options.threads, [&](std::size_t i) {
    const auto e = proxy.edge_handle(crossed[i]);
    const int a = proxy.from_vertex_handle(proxy.halfedge_handle(e, 0)).idx();
    const int b = proxy.to_vertex_handle(proxy.halfedge_handle(e, 0)).idx();
    placed[i] = place_on_edge(points[a], points[b], models_of({labels[a], labels[b]}), options);
  });
  std::vector<int> edge_vertex(proxy.n_edges(), -1);
  for (std::size_t i = 0; i < crossed.size(); ++i) {
    const auto e = proxy.edge_handle(crossed[i]);
    const int a = proxy.from_vertex_handle(proxy.halfedge_handle(e, 0)).idx();
    const int b = proxy.to_vertex_handle(proxy.halfedge_handle(e, 0)).idx();
    edge_vertex[crossed[i]] = add_vertex(placed[i], {labels[a], labels[b]});
  }

  std::vector<Eigen::Vector3i> faces;
  faces.reserve(proxy.n_faces() * 2);
  for (auto f : proxy.faces()) {
    std::array<int, 3> c, mid;  // corners in orientation order; mid[i] on edge c[i] -> c[i+1]
    int k = 0;
    for (auto h : f.halfedges()) {
      c[k] = h.from().idx();
      mid[k] = edge_vertex[h.edge().idx()];
      ++k;
    }
    const int l0 = labels[c[0]], l1 = labels[c[1]], l2 = labels[c[2]];
    if (l0 == l1 && l1 == l2) {
      faces.emplace_back(c[0], c[1], c[2]);
    } else if (l0 != l1 && l1 != l2 && l0 != l2) {
      const int center = add_vertex(
          place_in_triangle({points[c[0]], points[c[1]], points[c[2]]}, models_of({l0, l1, l2}),
                            options),
          {l0, l1, l2});
      for (int i = 0; i < 3; ++i) {
        const int before = mid[(i + 2) % 3];  // on the edge arriving at corner i
        faces.emplace_back(c[i], mid[i], center);
        faces.emplace_back(c[i], center, before);
      }
    } else {
      // Rotate so that corner 0 is the odd one out: edges 0 (c0 -> c1) and 2 (c2 -> c0) are crossed.
      int odd = l1 == l2 ? 0 : (l0 == l2 ? 1 : 2);
      std::rotate(c.begin(), c.begin() + odd, c.end());
      std::rotate(mid.begin(), mid.begin() + odd, mid.end());
      const int m1 = mid[0], m2 = mid[2];
      faces.emplace_back(c[0], m1, m2);
      // Quad (m1, c1, c2, m2): split along its shorter diagonal.
      if ((points[m1] - points[c[2]]).squaredNorm() <= (points[c[1]] - points[m2]).squaredNorm()) {
        faces.emplace_back(m1, c[1], c[2]);
        faces.emplace_back(m1, c[2], m2);
      } else {
        faces.emplace_back(m1, c[1], m2);
        faces.emplace_back(c[1], c[2], m2);
      }
    }
  }

  Eigen::MatrixX3d V(points.size(), 3);
  for (std::size_t i = 0; i < points.size(); ++i) V.row(i) = points[i].transpose();
  Eigen::MatrixX3i F(faces.size(), 3);
  for (std::size_t i = 0; i < faces.size(); ++i) F.row(i) = faces[i].transpose();
  out.mesh = mesh_from_matrices(V, F);
  return out;
}

int face_region(const LabeledMesh& mesh, const Eigen::MatrixX3i& F, int f) {
  const auto& a = mesh.labels[F(f, 0)];
  for (int l : a) {
    const auto has = [&](int v) {
      const auto& b = mesh.labels[v];
      return std::find(b.begin(), b.end(), l) != b.end();
    };
    if (has(F(f, 1)) && has(F(f, 2))) return l;
  }
  return a.front();
}

}  // namespace sketchsurf
