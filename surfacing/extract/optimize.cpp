#include "surfacing/extract/optimize.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <utility>

#include <Eigen/Dense>

#include "surfacing/closest_face.h"
#include "surfacing/error.h"
#include "surfacing/extract/energy.h"
#include "surfacing/extract/global_step.h"
#include "surfacing/lbfgs.h"
#include "surfacing/parallel.h"

namespace sketchsurf {


bool MeshEnergyOptions::valid(std::string* why) const {
  auto fail = [&](const char* what) {
    if (why) *why = what;
    return false;
  };
  if (!(gamma_2d >= 0.0)) return fail("extract.gamma_2d must be >= 0");
  if (!(gamma_1d >= 0.0)) return fail("extract.gamma_1d must be >= 0");
  if (!(smooth_angle >= 0.0 && smooth_angle < sharp_angle && sharp_angle <= M_PI / 2.0))
    return fail("extract angles must satisfy 0 <= smooth_angle < sharp_angle <= pi/2");
  if (!(attract_weight >= 0.0)) return fail("extract.attract_weight must be >= 0");
  if (!(plane_weight >= 0.0)) return fail("extract.plane_weight must be >= 0");
  if (max_iterations < 1) return fail("extract.max_iterations must be at least 1");
  if (local_global_iterations < 0) return fail("extract.local_global_iterations must be >= 0");
  if (!(local_global_tolerance > 0.0)) return fail("extract.local_global_tolerance must be > 0");
  if (!(global_step_tolerance > 0.0 && global_step_tolerance < 1.0))
    return fail("extract.global_step_tolerance must be in (0, 1)");
  if (!(function_tolerance > 0.0)) return fail("extract.function_tolerance must be > 0");
  if (stall_window < 0) return fail("extract.stall_window must be >= 0");
  if (!(stall_tolerance >= 0.0 && stall_tolerance < 1.0))
    return fail("extract.stall_tolerance must be in [0, 1)");
  if (!(gradient_tolerance > 0.0)) return fail("extract.gradient_tolerance must be > 0");
  if (lbfgs_rank < 1) return fail("extract.lbfgs_rank must be at least 1");
  if (projection_steps < 0) return fail("extract.projection_steps must be >= 0");
  if (!(max_projection_step > 0.0)) return fail("extract.max_projection_step must be > 0");
  if (!(trust_distance >= 0.0)) return fail("extract.trust_distance must be >= 0");
  if (!(box_margin >= 0.0)) return fail("extract.box_margin must be >= 0");
  return true;
}

namespace {

/// E_mesh in the variables y = x / s (Jacobi scaling: s = 1 / sqrt(Hessian diagonal)).
class ScaledFunction final : public detail::LbfgsFunction {
 public:
  ScaledFunction(const detail::MeshEnergyFunction& f, Eigen::VectorXd scale, const WorkerTeam& team)
      : f_(f), scale_(std::move(scale)), x_(scale_.size()), team_(team) {}
  Eigen::Index size() const override { return scale_.size(); }
  /// E_mesh and its gradient (in y) at y.
  bool evaluate(const double* y, double* cost, double* gradient) const override {
    detail::for_vector_chunks(size(), team_, [&](Eigen::Index lo, Eigen::Index count) {
      x_.segment(lo, count) = scale_.segment(lo, count).cwiseProduct(Eigen::Map<const Eigen::VectorXd>(y + lo, count));
    });
    return f_.evaluate(x_.data(), cost, gradient, scale_.data());
  }
  /// evaluate() at trial = y + step d, written to `trial` in the same pass as the positions.
  bool evaluate_step(const double* y, double step, const double* d, double* trial, double* cost,
                     double* gradient) const override {
    detail::for_vector_chunks(size(), team_, [&](Eigen::Index lo, Eigen::Index count) {
      for (Eigen::Index i = lo; i < lo + count; ++i) {
        trial[i] = y[i] + step * d[i];
        x_[i] = scale_[i] * trial[i];
      }
    });
    return f_.evaluate(x_.data(), cost, gradient, scale_.data());
  }

 private:
  const detail::MeshEnergyFunction& f_;
  Eigen::VectorXd scale_;
  mutable Eigen::VectorXd x_;  // buffer of the unscaled positions (a 2 MB allocation per call)
  const WorkerTeam& team_;
};

}  // namespace

std::vector<double> inside_offsets(const MeshConstraints& constraints, int n) {
  std::vector<double> offset(static_cast<std::size_t>(n), 0.0);
  for (int v : constraints.inside) offset[static_cast<std::size_t>(v)] = constraints.inside_gap;
  return offset;
}

void project_vertices(LabeledMesh& lm, const std::vector<ImplicitModel>& models, int steps,
                      double max_step, unsigned threads, const std::vector<char>& held,
                      const std::vector<double>& inside) {
  TriMesh& mesh = lm.mesh;
  parallel_for(0, mesh.n_vertices(), threads, [&](std::size_t i) {
    if (held[i]) return;
    const TriMesh::VertexHandle v(static_cast<int>(i));
    Eigen::Vector3d x = to_eigen(mesh.point(v));
    const auto& labels = lm.labels[i];
    const int k = static_cast<int>(labels.size());
    for (int step = 0; step < steps; ++step) {
      Eigen::MatrixXd J(k, 3);
      Eigen::VectorXd f(k);
      for (int a = 0; a < k; ++a) {
        f[a] = models[labels[a]].value(x);
        J.row(a) = models[labels[a]].gradient(x).transpose();
      }
      if (k == 1 && !inside.empty()) f[0] += inside[i] * J.row(0).norm();
      Eigen::MatrixXd JJt = J * J.transpose();
      const double damping = 1e-6 * JJt.trace() + std::numeric_limits<double>::min();
      JJt.diagonal().array() += damping;
      Eigen::Vector3d dx = -J.transpose() * JJt.ldlt().solve(f);
      if (!dx.allFinite()) break;
      if (dx.norm() > max_step) dx *= max_step / dx.norm();
      x += dx;
    }
    mesh.set_point(v, to_openmesh(x));
  });
}

namespace detail {

OptimizeSummary optimize_mesh_with(LabeledMesh& lm, const std::vector<ImplicitModel>& models,
                                   const MeshConstraints& constraints, const MeshEnergyOptions& options,
                                   const Progress& progress, const MeshMinimizer& minimize) {
  std::string why;
  if (!options.valid(&why)) throw Error::usage(why);
  TriMesh& mesh = lm.mesh;
  const int n = static_cast<int>(mesh.n_vertices());
  if (static_cast<int>(lm.labels.size()) != n)
    throw Error::usage("optimize_mesh: labels do not match the mesh's vertices");
  for (const auto& labels : lm.labels)
    for (int l : labels)
      if (l < 0 || l >= static_cast<int>(models.size()))
        throw Error::usage("optimize_mesh: label " + std::to_string(l) + " but " +
                           std::to_string(models.size()) + " models");
  auto check_vertex = [&](int v) {
    if (v < 0 || v >= n) throw Error::usage("optimize_mesh: constraint on vertex " + std::to_string(v));
  };
  for (const auto& t : constraints.attract) check_vertex(t.vertex);
  for (int v : constraints.plane_vertices) check_vertex(v);
  for (int v : constraints.held) check_vertex(v);
  for (int v : constraints.inside) check_vertex(v);
  if (!(constraints.inside_gap >= 0.0 && std::isfinite(constraints.inside_gap)))
    throw Error::usage("optimize_mesh: inside_gap must be finite and >= 0");
  if (!constraints.plane_vertices.empty() && !constraints.plane)
    throw Error::usage("optimize_mesh: plane vertices without a plane");

  // Length scale of the stopping test and of the start: the mesh's bounding-box diagonal.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (auto v : mesh.vertices()) {
    lo = lo.cwiseMin(to_eigen(mesh.point(v)));
    hi = hi.cwiseMax(to_eigen(mesh.point(v)));
  }
  const double size = n > 0 ? (hi - lo).norm() : 1.0;
  const unsigned threads = resolve_threads(options.threads);
  const WorkerTeam team(threads);
  const detail::MeshEnergy initial_energy = detail::build_energy(lm, models, constraints, options);
  std::vector<double> x(3 * static_cast<std::size_t>(n));
  auto load = [&] {
    for (auto v : mesh.vertices()) {
      const auto& p = mesh.point(v);
      for (int c = 0; c < 3; ++c) x[3 * v.idx() + c] = p[c];
    }
  };
  load();
  OptimizeSummary summary;
  summary.initial = detail::MeshEnergyFunction(initial_energy, n, team).terms(x.data());
  const auto start = std::chrono::steady_clock::now();
  const std::vector<double> proxy = x;
  // Vertices whose surfaces lie only farther from the strokes than where the proxy put them stay
  // there: what they would land on (a far branch of a zero set, a model extrapolated past its
  // strokes) is not what the strokes depict. So do vertices that would leave the strokes' grown
  // box from inside it (box_margin), and vertices far from the strokes that would leave a face
  // the proxy drew in by more than trust_distance (on_drawn_face). Tested after the first
  // projection, and once more after the solve (the solve can carry vertices there step by step);
  // a vertex held then makes a second solve from the proxy. A vertex that the solve leaves past
  // its flat region's drawn outline is held on the outline, the rim it spread past (outline.h);
  // tested after the solve only: after the first projection, vertices beside a box's edges lie
  // past their face's outline for a while and the solve brings them back.
  MeshConstraints trusted = constraints;
  std::optional<ClosestFaceTree> tree;
  if (options.trust_distance > 0.0 && constraints.strokes && constraints.strokes->segments.rows() > 0)
    tree.emplace(constraints.strokes->points, constraints.strokes->segments);
  const double reach = options.trust_distance * size;
  const auto outside_box = [&, margin = options.box_margin * size](const double* p) {
    if (!(options.box_margin > 0.0) || !constraints.strokes) return false;
    const BoundingBox& box = constraints.strokes->box;
    for (int c = 0; c < 3; ++c)
      if (p[c] < box.min[c] - margin || p[c] > box.max[c] + margin) return true;
    return false;
  };
  std::vector<char> held(static_cast<std::size_t>(n), 0);
  for (int v : constraints.held) held[static_cast<std::size_t>(v)] = 1;
  std::vector<char> on_face(static_cast<std::size_t>(n), 0);
  for (int v : constraints.on_drawn_face) on_face[static_cast<std::size_t>(v)] = 1;
  std::size_t outlined = 0, on_faces = 0;
  // Where each held vertex is held: the proxy, or its point of an outline.
  std::vector<Eigen::Vector3d> held_at(static_cast<std::size_t>(n));
  for (int v = 0; v < n; ++v)
    held_at[static_cast<std::size_t>(v)] = Eigen::Vector3d(proxy[3 * v], proxy[3 * v + 1], proxy[3 * v + 2]);
  const auto place_held = [&] {
    for (int v : trusted.held)
      mesh.set_point(TriMesh::VertexHandle(v), to_openmesh(held_at[static_cast<std::size_t>(v)]));
  };
  const bool any_outline = std::any_of(constraints.outlines.begin(), constraints.outlines.end(),
                                       [](const auto& o) { return !o.empty(); });
  const auto hold_far = [&](const std::vector<double>& at, bool solved) {
    if (!tree && !(options.box_margin > 0.0 && constraints.strokes) && !(solved && any_outline)) return false;
    const auto to_strokes = [&](const double* p) {
      const Eigen::Vector3d point(p[0], p[1], p[2]);
      Eigen::Vector3d q;
      return !tree || tree->closest_face(point, &q) < 0 ? 0.0 : (q - point).norm();
    };
    // 1: held at the proxy; 2: held on an outline; 3: held on a drawn face; at target[i].
    std::vector<char> far(static_cast<std::size_t>(n), 0);
    std::vector<Eigen::Vector3d> target(static_cast<std::size_t>(n));
    parallel_for(0, static_cast<std::size_t>(n), threads, [&](std::size_t i) {
      if (held[i]) return;
      const double* from = &proxy[3 * i];
      const Eigen::Vector3d to(at[3 * i], at[3 * i + 1], at[3 * i + 2]);
      const double moved = (to - Eigen::Vector3d(from[0], from[1], from[2])).norm();
      if (tree && moved > reach) {
        const double before = to_strokes(from);
        if (to_strokes(to.data()) > before + reach || (on_face[i] && before > reach)) {
          far[i] = on_face[i] ? 3 : 1;
          target[i] = Eigen::Vector3d(from[0], from[1], from[2]);
          return;
        }
      }
      if (outside_box(to.data()) && !outside_box(from)) {
        far[i] = 1;
        target[i] = Eigen::Vector3d(from[0], from[1], from[2]);
        return;
      }
      if (!solved) return;
      for (int label : lm.labels[i]) {
        if (static_cast<std::size_t>(label) >= constraints.outlines.size()) continue;
        for (const PlaneOutline& outline : constraints.outlines[label])
          if (const auto q = outline.pull_back(to, models[label].gradient(to), constraints.outline_margin)) {
            far[i] = 2;
            target[i] = *q;
            return;
          }
      }
    });
    bool any = false;
    for (int v = 0; v < n; ++v) {
      if (!far[static_cast<std::size_t>(v)]) continue;
      held[static_cast<std::size_t>(v)] = 1;
      trusted.held.push_back(v);
      trusted.attract.push_back({v, target[static_cast<std::size_t>(v)]});
      held_at[static_cast<std::size_t>(v)] = target[static_cast<std::size_t>(v)];
      outlined += far[static_cast<std::size_t>(v)] == 2;
      on_faces += far[static_cast<std::size_t>(v)] == 3;
      any = true;
    }
    return any;
  };
  for (int pass = 0; pass < 2; ++pass) {
    x = proxy;
    for (auto v : mesh.vertices())
      mesh.set_point(v, TriMesh::Point(proxy[3 * v.idx()], proxy[3 * v.idx() + 1], proxy[3 * v.idx() + 2]));
    place_held();
    load();
    if (options.projection_steps > 0) {
      project_vertices(lm, models, options.projection_steps, options.max_projection_step * size, threads, held,
                       inside_offsets(constraints, n));
      load();
      if (pass == 0 && hold_far(x, false)) {
        place_held();
        load();
      }
    }
    const detail::MeshEnergy energy = detail::build_energy(lm, models, trusted, options);
    if (options.local_global_iterations > 0) {
      double edges = 0.0;
      for (auto e : mesh.edges()) edges += mesh.calc_edge_length(e);
      const double mean_edge = mesh.n_edges() > 0 ? edges / mesh.n_edges() : size;
      summary.local_global_iterations = detail::local_global(
          energy, n, options.local_global_iterations, std::max(1, options.projection_steps),
          options.max_projection_step * size, options.local_global_tolerance * mean_edge,
          options.global_step_tolerance, team, x);
    }
    const detail::MeshEnergyFunction function(energy, n, team);
    minimize(energy, function, team, x, size, summary);
    if (pass == 1 || !hold_far(x, true)) break;
  }
  summary.outline_vertices = outlined;
  summary.held_vertices = trusted.held.size() - constraints.held.size() - outlined;
  summary.face_vertices = on_faces;
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  for (double value : x)
    if (!std::isfinite(value))
      throw Error::processing("the final mesh optimisation diverged (non-finite positions); "
                              "check that the proxy lies close to the strokes");
  std::vector<bool> on_plane(n, false);
  for (int v : constraints.plane_vertices) on_plane[v] = true;
  for (auto v : mesh.vertices()) {
    Eigen::Vector3d p(x[3 * v.idx()], x[3 * v.idx() + 1], x[3 * v.idx() + 2]);
    if (on_plane[v.idx()]) p -= constraints.plane->signed_distance(p) * constraints.plane->normal;
    mesh.set_point(v, to_openmesh(p));
  }
  mesh.update_normals();
  return summary;
}

}  // namespace detail

OptimizeSummary optimize_mesh(LabeledMesh& mesh, const std::vector<ImplicitModel>& models,
                              const MeshConstraints& constraints, const MeshEnergyOptions& options,
                              const Progress& progress) {
  auto lbfgs = [&](const detail::MeshEnergy&, const detail::MeshEnergyFunction& function, const WorkerTeam& team,
                   std::vector<double>& x, double size, OptimizeSummary& summary) {
    // Jacobi scaling: L-BFGS runs on y = x / s.
    const Eigen::VectorXd scale = function.hessian_diagonal().cwiseMax(1e-12).cwiseSqrt().cwiseInverse();
    Eigen::Map<Eigen::VectorXd> X(x.data(), static_cast<Eigen::Index>(x.size()));
    X.array() /= scale.array();
    const ScaledFunction scaled(function, scale, team);
    detail::LbfgsOptions lbfgs_options;
    lbfgs_options.rank = options.lbfgs_rank;
    lbfgs_options.max_iterations = options.max_iterations;
    lbfgs_options.function_tolerance = options.function_tolerance;
    lbfgs_options.gradient_tolerance = options.gradient_tolerance * size;
    lbfgs_options.stall_window = options.stall_window;
    lbfgs_options.stall_tolerance = options.stall_tolerance;
    const detail::LbfgsOutcome outcome =
        detail::minimize_lbfgs(scaled, x.data(), lbfgs_options, team, [&](int iteration) {
          progress.update("extract", std::min(1.0, double(iteration) / options.max_iterations));
        });
    X.array() *= scale.array();
    summary.final = function.terms(x.data());
    summary.iterations = outcome.iterations;
    summary.termination = outcome.termination;
    summary.solver = "LINE_SEARCH, LBFGS (ours, Armijo)";
    summary.usable = outcome.usable;
  };
  return detail::optimize_mesh_with(mesh, models, constraints, options, progress, lbfgs);
}

}  // namespace sketchsurf
