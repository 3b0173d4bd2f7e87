#include "surfacing/extract/optimize.h"

#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <memory>

#include "surfacing/error.h"
#include "surfacing/extract/energy.h"
#include "surfacing/extract/global_step.h"
#include "surfacing/extract/seams.h"
#include "surfacing/extract/trust_region.h"
#include "tests/support/shapes.h"
#include "tests/unit/extract/fixtures.h"

namespace sketchsurf {
namespace {

using testing::plane_model;

/// Runs ceres::GradientChecker on `cost` at the given parameter blocks.
void expect_jacobians_match(const ceres::CostFunction& cost, const std::vector<std::vector<double>>& blocks) {
  std::vector<const double*> params;
  for (const auto& b : blocks) params.push_back(b.data());
  ceres::NumericDiffOptions numeric;
  ceres::GradientChecker checker(&cost, static_cast<const std::vector<const ceres::Manifold*>*>(nullptr),
                                 numeric);
  ceres::GradientChecker::ProbeResults results;
  EXPECT_TRUE(checker.Probe(params.data(), 1e-7, &results)) << results.error_log;
}

ImplicitModel cubic_model() {
  ImplicitModel m;
  m.degree = 3;
  m.coefficients.resize(monomial_count(3));
  for (int k = 0; k < m.coefficients.size(); ++k) m.coefficients[k] = std::sin(1.7 * k + 0.3);
  m.center = Eigen::Vector3d(0.1, -0.2, 0.3);
  m.scale = 0.7;
  return m;
}

/// The unit sphere x^2 + y^2 + z^2 - 1 as a quadric.
TEST(MeshEnergyTerms, JacobiansMatchNumericDerivatives) {
  const ImplicitModel model = cubic_model();
  std::unique_ptr<ceres::CostFunction> project(detail::make_projection_cost(model, 0.5, 1e-6));
  expect_jacobians_match(*project, {{0.3, 0.1, -0.4}});
  expect_jacobians_match(*project, {{-0.8, 0.6, 0.2}});

  std::unique_ptr<ceres::CostFunction> laplacian(detail::LaplacianCost::Create(5, 100.0));
  expect_jacobians_match(*laplacian, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0.2, 0}, {0, -1, 0.3}, {0.5, 0.5, 1}});
  Eigen::Matrix3d in_plane = Eigen::Matrix3d::Identity() - Eigen::Vector3d::UnitX() * Eigen::Vector3d::UnitX().transpose();
  std::unique_ptr<ceres::CostFunction> planar(detail::LaplacianCost::Create(2, 500.0, in_plane));
  expect_jacobians_match(*planar, {{0, 0, 0}, {1, 0.3, 0}, {0.2, 1, -0.4}});

  std::unique_ptr<ceres::CostFunction> attract(detail::AttractResidual::Create({0.1, 0.2, 0.3}, 2.0));
  expect_jacobians_match(*attract, {{0.5, -0.5, 1.0}});
  Plane plane;
  plane.normal = Eigen::Vector3d(1, 2, 2).normalized();
  plane.offset = 0.25;
  std::unique_ptr<ceres::CostFunction> on_plane(detail::PlaneResidual::Create(plane, 1e4));
  expect_jacobians_match(*on_plane, {{0.5, -0.5, 1.0}});
}

TEST(MeshEnergyTerms, ProjectionResidualIsTheSignedTaubinDistance) {
  const ImplicitModel model = cubic_model();
  const detail::ProjectionResidual r{&model, 2.0, 0.0};
  const Eigen::Vector3d x(0.3, 0.1, -0.4);
  double value = 0.0;
  r(x.data(), &value);
  EXPECT_NEAR(std::abs(value), 2.0 * model.distance(x), 1e-12);
}

TEST(MeshEnergyTerms, DifferentiatedTableMatchesTheModelAndTheJets) {
  // Degree 3 and 4 (Hessian terms of every kind), off-centre and scaled, with and without a
  // gradient floor: the table's f and grad f against ImplicitModel, its Taubin residual and
  // gradient against the Jets of ProjectionResidual.
  ImplicitModel quartic = cubic_model();
  quartic.degree = 4;
  quartic.coefficients.resize(monomial_count(4));
  for (int k = 0; k < quartic.coefficients.size(); ++k) quartic.coefficients[k] = std::cos(0.9 * k + 0.2);
  quartic.center = Eigen::Vector3d(0.2, -0.3, 0.1);
  quartic.scale = 1.7;
  const ImplicitModel cubic = cubic_model();
  for (const ImplicitModel* model : {&cubic, static_cast<const ImplicitModel*>(&quartic)}) {
    const ImplicitModel& m = *model;
    const detail::ModelDerivatives table(m);
    for (double floor : {0.0, 0.3}) {
      std::unique_ptr<ceres::CostFunction> jets(detail::make_projection_cost(m, 0.5, floor));
      for (const Eigen::Vector3d& x : {Eigen::Vector3d(0.3, 0.1, -0.4), Eigen::Vector3d(-0.8, 0.6, 0.2),
                                      Eigen::Vector3d(1.5, -0.7, 0.9)}) {
        Eigen::Vector3d g;
        EXPECT_NEAR(table.value_and_gradient(x.data(), g.data()), m.value(x), 1e-12 * (1.0 + std::abs(m.value(x))));
        EXPECT_LT((g - m.gradient(x)).norm(), 1e-12 * (1.0 + g.norm()));
        Eigen::Vector3d gradient, expected_gradient;
        const double value = table.taubin(x.data(), std::sqrt(0.5), floor, gradient.data());
        double expected = 0.0;
        const double* params[] = {x.data()};
        double* jacobians[] = {expected_gradient.data()};
        ASSERT_TRUE(jets->Evaluate(params, &expected, jacobians));
        EXPECT_NEAR(value, expected, 1e-12 * (1.0 + std::abs(expected)));
        EXPECT_LT((gradient - expected_gradient).norm(), 1e-10 * (1.0 + expected_gradient.norm()))
            << gradient.transpose() << " vs " << expected_gradient.transpose();
      }
    }
  }
}

TEST(MeshEnergyTerms, LaplacianOfAnAverageIsZero) {
  std::unique_ptr<ceres::CostFunction> laplacian(detail::LaplacianCost::Create(3, 100.0));
  const double center[3] = {1.0 / 3, 1.0 / 3, 1.0 / 3};
  const double a[3] = {1, 0, 0}, b[3] = {0, 1, 0}, c[3] = {0, 0, 1};
  const double* params[] = {center, a, b, c};
  double r[3];
  laplacian->Evaluate(params, r, nullptr);
  EXPECT_NEAR(Eigen::Vector3d(r[0], r[1], r[2]).norm(), 0.0, 1e-14);
}

TEST(SeamWeight, FollowsThePaperRamp) {
  MeshEnergyOptions o;
  EXPECT_EQ(seam_weight(0.0, o), 1.0);
  EXPECT_EQ(seam_weight(M_PI / 8, o), 1.0);
  EXPECT_EQ(seam_weight(M_PI / 3, o), 0.0);
  EXPECT_EQ(seam_weight(M_PI / 2, o), 0.0);
  const double mid = 0.5 * (M_PI / 8 + M_PI / 3);
  EXPECT_NEAR(seam_weight(mid, o), 0.5, 1e-12);
}

TEST(RegularizationWeights, DependOnTheAngleBetweenRegions) {
  // A strip of two triangles: vertex 0 and 1 are seam vertices between models 0 and 1.
  Eigen::MatrixX3d V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, -1, 0;
  Eigen::MatrixX3i F(2, 3);
  F << 0, 1, 2, 1, 0, 3;
  LabeledMesh m{mesh_from_matrices(V, F), {{0, 1}, {0, 2}, {0}, {0, 1, 2}}, {-1, -1, 2, -1}};
  const std::vector<ImplicitModel> models{plane_model({0, 0, 1}, 0),
                                          plane_model(Eigen::Vector3d(0, std::sin(0.1), -std::cos(0.1)), 0),
                                          plane_model({0, 1, 0}, 0)};
  const std::vector<double> w = regularization_weights(m, models, {});
  EXPECT_EQ(w[0], 1.0);  // 0.1 rad < pi/8, and the sign of a model does not matter
  EXPECT_EQ(w[1], 0.0);  // 90 degrees
  EXPECT_EQ(w[2], 1.0);  // one region
  EXPECT_EQ(w[3], 0.0);  // three regions
}

TEST(OptimizeMesh, ProjectsANoisySphereOntoItsModel) {
  const ImplicitModel sphere = testing::sphere_model();
  TriMesh mesh = testing::icosphere(4, 1.0);
  // Push every vertex off the sphere by up to 5%.
  int i = 0;
  for (auto v : mesh.vertices()) {
    const double s = 1.0 + 0.05 * std::sin(12.9898 * i++);
    mesh.set_point(v, mesh.point(v) * s);
  }
  LabeledMesh m{mesh, std::vector<std::vector<int>>(mesh.n_vertices(), {0}),
                std::vector<int>(mesh.n_vertices(), 0)};
  const OptimizeSummary s = optimize_mesh(m, {sphere}, {}, {});
  EXPECT_TRUE(s.usable) << s.termination;
  EXPECT_LT(s.final.total(), 0.2 * s.initial.total());
  EXPECT_LT(s.final.project, 0.2 * s.initial.project);
  // The graph Laplacian of a curved mesh is not zero, and shrinking the mesh by s scales it by s:
  // the minimum of E_mesh lies inside the sphere by about gamma_2D |Delta v|^2 / R, which falls
  // as (edge / R)^4: 1.7% of R at 3 subdivisions (edge/R ~ 0.11), 0.45% at 4.
  double worst = 0.0;
  for (auto v : m.mesh.vertices()) worst = std::max(worst, std::abs(to_eigen(m.mesh.point(v)).norm() - 1.0));
  EXPECT_LT(worst, 6e-3);
}

TEST(OptimizeMesh, KeepsPlaneVerticesOnThePlaneAndAttractsTargets) {
  // The constraint plumbing alone: no regularisation, a plane model z = 0 compatible with both.
  Eigen::MatrixX3d V(4, 3);
  V << 0, 0, 0.1, 1, 0, -0.1, 0.5, 1, 0.05, 0.5, -1, 0.0;
  Eigen::MatrixX3i F(2, 3);
  F << 0, 1, 2, 1, 0, 3;
  LabeledMesh m{mesh_from_matrices(V, F), {{0}, {0}, {0}, {0}}, {0, 1, 2, 3}};
  MeshConstraints c;
  Plane plane;  // x = 0
  c.plane = plane;
  c.plane_vertices = {0};
  c.attract = {{2, Eigen::Vector3d(0.5, 1.2, 0.0)}};
  MeshEnergyOptions o;
  o.gamma_1d = o.gamma_2d = 0.0;
  const OptimizeSummary s = optimize_mesh(m, {plane_model({0, 0, 1}, 0)}, c, o);
  EXPECT_TRUE(s.usable);
  EXPECT_EQ(m.mesh.point(TriMesh::VertexHandle(0))[0], 0.0);
  for (auto v : m.mesh.vertices()) EXPECT_NEAR(m.mesh.point(v)[2], 0.0, 1e-6);
  EXPECT_NEAR((to_eigen(m.mesh.point(TriMesh::VertexHandle(2))) - Eigen::Vector3d(0.5, 1.2, 0)).norm(), 0.0, 1e-6);
  EXPECT_GT(s.initial.attract, 0.0);
  EXPECT_LT(s.final.total(), 1e-10);
}

TEST(OptimizeMesh, HeldVerticesStayAtTheirTargetsAndTheRestIsProjected) {
  // A sphere of radius 1.05 over the model of radius 1: the half x > 0 is held at the start
  // (what a region kept at the proxy gets), the rest is projected.
  const ImplicitModel sphere = testing::sphere_model();
  LabeledMesh m{testing::icosphere(4, 1.05), {}, {}};
  m.labels.assign(m.mesh.n_vertices(), {0});
  m.source_vertex.assign(m.mesh.n_vertices(), -1);
  MeshConstraints c;
  for (auto v : m.mesh.vertices())
    if (m.mesh.point(v)[0] > 0.0) {
      c.held.push_back(v.idx());
      c.attract.push_back({v.idx(), to_eigen(m.mesh.point(v))});
    }
  const OptimizeSummary s = optimize_mesh(m, {sphere}, c, {});
  EXPECT_TRUE(s.usable) << s.termination;
  EXPECT_EQ(s.held_vertices, 0u) << "held by the caller, not by trust_distance";
  for (auto v : m.mesh.vertices()) {
    const Eigen::Vector3d p = to_eigen(m.mesh.point(v));
    if (p.x() > 0.5) {
      EXPECT_NEAR(p.norm(), 1.05, 0.01) << "held vertex " << v.idx();
    } else if (p.x() < -0.5) {
      EXPECT_NEAR(p.norm(), 1.0, 0.01) << "projected vertex " << v.idx();
    }
  }
}

TEST(OptimizeMesh, VerticesStayInsideTheStrokesGrownBox) {
  // A proxy squashed to z in [-0.9, 0.9], drawn only along its equator and two rings at
  // z = +-0.85, over the unit sphere as model: projection would carry the poles to z = +-1,
  // past the strokes' box (z within 0.85) grown by box_margin. The rings are 0.33 from the
  // poles either way, so the distance to the strokes alone (trust_distance) does not hold them.
  const ImplicitModel sphere = testing::sphere_model();
  TriMesh proxy = testing::icosphere(4, 1.0);
  for (auto v : proxy.vertices()) proxy.point(v)[2] *= 0.9;
  Sketch sketch;
  for (double z : {-0.85, 0.0, 0.85})
    sketch.strokes.push_back(testing::horizontal_ring(std::sqrt(1.0 - (z / 0.9) * (z / 0.9)), z));
  MeshConstraints c;
  c.strokes = stroke_segments(sketch, false);
  auto top = [&](double margin, std::size_t* held, double trust = MeshEnergyOptions{}.trust_distance) {
    LabeledMesh m{proxy, std::vector<std::vector<int>>(proxy.n_vertices(), {0}),
                  std::vector<int>(proxy.n_vertices(), -1)};
    MeshEnergyOptions o;
    o.box_margin = margin;
    o.trust_distance = trust;
    const OptimizeSummary s = optimize_mesh(m, {sphere}, c, o);
    EXPECT_TRUE(s.usable) << s.termination;
    *held = s.held_vertices;
    double z = 0.0;
    for (auto v : m.mesh.vertices()) z = std::max(z, std::abs(m.mesh.point(v)[2]));
    for (auto v : m.mesh.vertices()) {
      if (std::abs(m.mesh.point(v)[2]) < 0.3) {
        EXPECT_NEAR(to_eigen(m.mesh.point(v)).norm(), 1.0, 0.01) << "projected vertex " << v.idx();
      }
    }
    return z;
  };
  std::size_t held = 0;
  EXPECT_GT(top(0.0, &held), 0.97) << "without the box test the poles reach the model";
  EXPECT_EQ(held, 0u);
  const double margin = 0.02 * std::sqrt(2.0 * 2.0 + 2.0 * 2.0 + 1.8 * 1.8);  // of the mesh's diagonal
  EXPECT_LT(top(0.02, &held), 0.85 + margin + 0.01);
  EXPECT_GT(held, 0u);
  EXPECT_LT(top(0.02, &held, 0.0), 0.85 + margin + 0.01) << "the box test alone, no trust distance";
  EXPECT_GT(held, 0u);
}

TEST(OptimizeMesh, AFaceDrawnInStaysFlatWhereAModelWouldDentIt) {
  // A sphere cut flat at z = 0.6 (a face drawn in: a disc of radius 0.8), drawn along its rim
  // and its equator. The model, a unit sphere centred at z = 1.2, passes through the rim and dips
  // to z = 0.2 under the disc's middle: the projection would dent the face by 0.4, a move that
  // brings the disc's middle no farther from the strokes (0.80 -> 0.89) than the trust distance
  // (0.1), inside the strokes' box. Marked as on a drawn face, the disc's vertices stay on it.
  const ImplicitModel dent = testing::sphere_model(Eigen::Vector3d(0.0, 0.0, 1.2));
  TriMesh proxy = testing::icosphere(4, 1.0);
  for (auto v : proxy.vertices()) proxy.point(v)[2] = std::min(proxy.point(v)[2], 0.6);
  Sketch sketch;
  sketch.strokes = {testing::horizontal_ring(0.8, 0.6), testing::horizontal_ring(1.0, 0.0)};
  const auto middle = [&](bool marked, std::size_t* on_face) {
    LabeledMesh m{proxy, std::vector<std::vector<int>>(proxy.n_vertices(), {0}),
                  std::vector<int>(proxy.n_vertices(), -1)};
    MeshConstraints c;
    c.strokes = stroke_segments(sketch, false);
    if (marked)
      for (auto v : proxy.vertices())
        if (proxy.point(v)[2] == 0.6) c.on_drawn_face.push_back(v.idx());
    const OptimizeSummary s = optimize_mesh(m, {dent}, c, {});
    EXPECT_TRUE(s.usable) << s.termination;
    *on_face = s.face_vertices;
    double lowest = std::numeric_limits<double>::infinity();
    for (auto v : proxy.vertices())
      if (std::hypot(proxy.point(v)[0], proxy.point(v)[1]) < 0.2 && proxy.point(v)[2] == 0.6)
        lowest = std::min<double>(lowest, m.mesh.point(v)[2]);
    return lowest;
  };
  std::size_t on_face = 0;
  EXPECT_LT(middle(false, &on_face), 0.4) << "unmarked, the face is dented";
  EXPECT_EQ(on_face, 0u);
  EXPECT_NEAR(middle(true, &on_face), 0.6, 0.01);
  EXPECT_GT(on_face, 0u);
}

TEST(OptimizeMesh, SameResultWhateverTheThreadCount) {
  const Eigen::Vector3d half(0.5, 0.5, 0.5);
  const TriMesh proxy = testing::rounded_box_mesh(3, half, 0.1);
  const auto models = testing::box_models(half);
  const LabeledMesh seamed = insert_seams(proxy, testing::box_labels(proxy, half), models);
  std::vector<TriMesh> results;
  for (unsigned threads : {1u, 2u, 3u}) {
    LabeledMesh m = seamed;
    MeshEnergyOptions o;
    o.threads = threads;
    optimize_mesh(m, models, {}, o);
    results.push_back(m.mesh);
  }
  for (std::size_t r = 1; r < results.size(); ++r)
    for (auto v : results[0].vertices())
      ASSERT_EQ(results[0].point(v), results[r].point(v)) << "threads differ at vertex " << v.idx();
}

TEST(OptimizeMesh, LbfgsAndSparseCholeskyReachTheSameSurface) {
  const Eigen::Vector3d half(0.5, 0.5, 0.5);
  const TriMesh proxy = testing::rounded_box_mesh(3, half, 0.1);
  const auto models = testing::box_models(half);
  const LabeledMesh seamed = insert_seams(proxy, testing::box_labels(proxy, half), models);
  double worst = 0.0;
  for (bool trust_region : {false, true}) {
    LabeledMesh m = seamed;
    const MeshEnergyOptions o;
    const OptimizeSummary s = trust_region
        ? optimize_mesh_trust_region(m, models, {}, o, TrustRegionSolver::SparseCholesky)
        : optimize_mesh(m, models, {}, o);
    EXPECT_TRUE(s.usable) << s.solver << ": " << s.termination;
    EXPECT_LT(s.final.total(), 1e-3 * s.initial.total()) << s.solver;
    for (auto v : m.mesh.vertices()) worst = std::max(worst, testing::box_distance(to_eigen(m.mesh.point(v)), half));
  }
  EXPECT_LT(worst, 0.003 * 2 * half.norm());
}

TEST(OptimizeMesh, LocalGlobalStartLowersTheEnergyOfTheFirstIterations) {
  const Eigen::Vector3d half(0.5, 0.5, 0.5);
  const TriMesh proxy = testing::rounded_box_mesh(3, half, 0.1);
  const auto models = testing::box_models(half);
  const LabeledMesh seamed = insert_seams(proxy, testing::box_labels(proxy, half), models);
  double energy[2];
  for (int with : {0, 1}) {
    LabeledMesh m = seamed;
    MeshEnergyOptions o;
    o.local_global_iterations = with ? 5 : 0;
    o.max_iterations = 1;
    const OptimizeSummary s = optimize_mesh(m, models, {}, o);
    EXPECT_EQ(s.local_global_iterations > 0, with == 1);
    energy[with] = s.final.total();
  }
  EXPECT_LT(energy[1], 0.5 * energy[0]);
}

TEST(OptimizeMesh, StopsWhenTheEnergyFallsLessThanTheStallToleranceOverTheWindow) {
  const Eigen::Vector3d half(0.5, 0.5, 0.5);
  const TriMesh proxy = testing::rounded_box_mesh(3, half, 0.1);
  const auto models = testing::box_models(half);
  const LabeledMesh seamed = insert_seams(proxy, testing::box_labels(proxy, half), models);
  MeshEnergyOptions o;
  o.stall_window = 10;
  o.stall_tolerance = 0.05;
  o.function_tolerance = 1e-15;
  o.gradient_tolerance = 1e-15;
  LabeledMesh stopped = seamed;
  const OptimizeSummary s = optimize_mesh(stopped, models, {}, o);
  EXPECT_TRUE(s.usable);
  ASSERT_NE(s.termination.find("fell by less than"), std::string::npos) << s.termination;
  ASSERT_GT(s.iterations, o.stall_window);
  ASSERT_LT(s.iterations, o.max_iterations);
  // The same run capped `window` iterations earlier follows the same path: E_mesh fell by at most
  // 5% since then, and by more than 5% over the window ending one iteration before.
  auto capped = [&](int iterations) {
    LabeledMesh m = seamed;
    MeshEnergyOptions c = o;
    c.stall_window = 0;
    c.max_iterations = iterations;
    return optimize_mesh(m, models, {}, c).final.total();
  };
  EXPECT_GE(s.final.total(), 0.95 * capped(s.iterations - o.stall_window));
  EXPECT_LT(capped(s.iterations - 1), 0.95 * capped(s.iterations - 1 - o.stall_window));
  // Without the stall test, the solve goes on to the cap and lowers E_mesh further.
  LabeledMesh full = seamed;
  o.stall_window = 0;
  const OptimizeSummary all = optimize_mesh(full, models, {}, o);
  EXPECT_GT(all.iterations, s.iterations);
  EXPECT_LT(all.final.total(), s.final.total());
}

TEST(OptimizeMesh, RejectsBadInput) {
  TriMesh mesh = testing::icosphere(1);
  LabeledMesh m{mesh, std::vector<std::vector<int>>(mesh.n_vertices(), {1}), std::vector<int>(mesh.n_vertices(), 0)};
  EXPECT_THROW(optimize_mesh(m, {plane_model({0, 0, 1}, 0)}, {}, {}), Error);
  MeshEnergyOptions bad;
  bad.sharp_angle = 0.1;
  m.labels.assign(mesh.n_vertices(), {0});
  EXPECT_THROW(optimize_mesh(m, {plane_model({0, 0, 1}, 0)}, {}, bad), Error);
  MeshEnergyOptions stall;
  stall.stall_tolerance = 1.0;
  EXPECT_THROW(optimize_mesh(m, {plane_model({0, 0, 1}, 0)}, {}, stall), Error);
  stall.stall_tolerance = 0.05;
  stall.stall_window = -1;
  EXPECT_THROW(optimize_mesh(m, {plane_model({0, 0, 1}, 0)}, {}, stall), Error);
}

TEST(NormalMatrix, IsLTransposeLPlusTheDiagonalBitForBitWhateverTheThreadCount) {
  // The uniform Laplacian rows of a 90 x 100 grid (9000 vertices: three row blocks), weighted,
  // some empty, a few with a repeated vertex; 1D rows along one grid line.
  const int w = 90, h = 100, n = w * h;
  std::vector<Eigen::Triplet<double>> rows_2d, rows_1d;
  for (int v = 0; v < n; ++v) {
    if (v % 17 == 5) continue;
    const int x = v % w, y = v / w;
    std::vector<int> ring;
    if (x > 0) ring.push_back(v - 1);
    if (x + 1 < w) ring.push_back(v + 1);
    if (y > 0) ring.push_back(v - w);
    if (y + 1 < h) ring.push_back(v + w);
    if (v % 101 == 3) ring.push_back(ring.front());
    const double s = std::sqrt(100.0 * (0.5 + 0.5 * std::sin(0.37 * v)));
    rows_2d.emplace_back(v, v, s);
    for (int u : ring) rows_2d.emplace_back(v, u, -s / static_cast<double>(ring.size()));
  }
  for (int x = 1; x + 1 < w; ++x) {
    const int v = 40 * w + x;
    rows_1d.emplace_back(v, v, std::sqrt(500.0));
    for (int u : {v - 1, v + 1}) rows_1d.emplace_back(v, u, -std::sqrt(500.0) / 2.0);
  }
  Eigen::SparseMatrix<double> L2(n, n), L1(n, n);
  L2.setFromTriplets(rows_2d.begin(), rows_2d.end());
  L1.setFromTriplets(rows_1d.begin(), rows_1d.end());
  Eigen::VectorXd d(n);
  for (int v = 0; v < n; ++v) d[v] = 1.0 / (1 + v % 3);
  Eigen::SparseMatrix<double> expected = L2.transpose() * L2 + L1.transpose() * L1;
  expected += Eigen::SparseMatrix<double>(d.asDiagonal());
  const detail::RowMajorMatrix rows(expected);
  for (unsigned threads : {1u, 2u, 3u}) {
    const detail::RowMajorMatrix A = detail::normal_matrix(L2, L1, d, threads);
    ASSERT_EQ(A.rows(), n);
    ASSERT_EQ(A.nonZeros(), rows.nonZeros()) << threads << " threads";
    for (int r = 0; r <= n; ++r) ASSERT_EQ(A.outerIndexPtr()[r], rows.outerIndexPtr()[r]) << "row " << r;
    for (Eigen::Index k = 0; k < A.nonZeros(); ++k) {
      ASSERT_EQ(A.innerIndexPtr()[k], rows.innerIndexPtr()[k]) << "entry " << k;
      ASSERT_EQ(A.valuePtr()[k], rows.valuePtr()[k]) << "entry " << k << ", " << threads << " threads";
    }
  }
}

TEST(BlockConjugateGradients, SolvesEachColumnAsIfAloneWhateverTheThreadCount) {
  // A = 100 L^T L + D for the graph Laplacian L of a 600-vertex path: stiff and SPD, with the
  // 2-ring pattern of the global step's matrix (condition ~1e4).
  const int n = 600;
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < n; ++i) {
    const std::vector<int> neighbours = i == 0 ? std::vector<int>{1}
                                        : i == n - 1 ? std::vector<int>{n - 2}
                                                     : std::vector<int>{i - 1, i + 1};
    entries.emplace_back(i, i, 1.0);
    for (int j : neighbours) entries.emplace_back(i, j, -1.0 / neighbours.size());
  }
  Eigen::SparseMatrix<double> L(n, n);
  L.setFromTriplets(entries.begin(), entries.end());
  Eigen::SparseMatrix<double> A = 100.0 * Eigen::SparseMatrix<double>(L.transpose() * L);
  for (int i = 0; i < n; ++i) A.coeffRef(i, i) += 0.05 + 0.01 * (i % 7);
  const Eigen::SparseMatrix<double, Eigen::RowMajor> R(A);
  const Eigen::VectorXd inverse_diagonal = A.diagonal().cwiseInverse();
  Eigen::MatrixXd B(n, 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < 3; ++j) B(i, j) = std::sin(0.05 * i * (j + 1) + j) + (j == 2 ? 0.3 : 0.0);
  auto packed = [&](std::initializer_list<int> columns) {
    std::vector<double> b;
    for (int i = 0; i < n; ++i)
      for (int j : columns) b.push_back(B(i, j));
    return b;
  };
  const Eigen::MatrixXd expected = Eigen::MatrixXd(A).ldlt().solve(B);
  const std::vector<double> X = detail::block_conjugate_gradients<3>(R, inverse_diagonal, packed({0, 1, 2}), 1e-10, 2);
  for (int j = 0; j < 3; ++j) {
    Eigen::VectorXd x(n);
    for (int i = 0; i < n; ++i) x[i] = X[3 * i + j];
    EXPECT_LT((x - expected.col(j)).norm(), 1e-5 * expected.col(j).norm()) << "column " << j;
    // The same column solved alone: the same numbers.
    const std::vector<double> alone = detail::block_conjugate_gradients<1>(R, inverse_diagonal, packed({j}), 1e-10, 2);
    for (int i = 0; i < n; ++i) ASSERT_EQ(alone[i], X[3 * i + j]) << "column " << j << " row " << i;
  }
  const std::vector<double> pair = detail::block_conjugate_gradients<2>(R, inverse_diagonal, packed({1, 2}), 1e-10, 2);
  for (int i = 0; i < n; ++i) ASSERT_EQ(pair[2 * i + 1], X[3 * i + 2]);
  for (unsigned threads : {1u, 3u})
    EXPECT_EQ(detail::block_conjugate_gradients<3>(R, inverse_diagonal, packed({0, 1, 2}), 1e-10, threads), X)
        << threads << " threads";
  // A loose tolerance stops early with the residual it promises.
  const std::vector<double> loose = detail::block_conjugate_gradients<1>(R, inverse_diagonal, packed({0}), 1e-2, 2);
  const Eigen::VectorXd residual = B.col(0) - A * Eigen::Map<const Eigen::VectorXd>(loose.data(), n);
  EXPECT_LE(residual.norm(), 1e-2 * B.col(0).norm());
  EXPECT_GT((Eigen::Map<const Eigen::VectorXd>(loose.data(), n) - expected.col(0)).norm(), 0.0);
}

/// A k x k grid in x, y in [0, 1], bumped in z, cut by the mirror plane x = 0: its left column
/// (vertices j k) is on the plane, slightly off it in x. One label, the plane z = 0.
struct HalfSheet {
  Eigen::MatrixX3d V;
  Eigen::MatrixX3i F;
  LabeledMesh mesh;
  MeshConstraints constraints;
};

HalfSheet half_sheet(int k) {
  HalfSheet h;
  h.V.resize(k * k, 3);
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i)
      h.V.row(j * k + i) << (i == 0 ? 0.01 * std::sin(3.0 * j) : i / (k - 1.0)), j / (k - 1.0),
          0.05 * std::sin(1.3 * i + 2.1 * j);
  h.F.resize(2 * (k - 1) * (k - 1), 3);
  int f = 0;
  for (int j = 0; j + 1 < k; ++j)
    for (int i = 0; i + 1 < k; ++i) {
      const int a = j * k + i;
      h.F.row(f++) << a, a + 1, a + k + 1;
      h.F.row(f++) << a, a + k + 1, a + k;
    }
  h.mesh = {mesh_from_matrices(h.V, h.F), std::vector<std::vector<int>>(k * k, {0}), std::vector<int>(k * k, 0)};
  h.constraints.plane = Plane{};  // x = 0
  for (int j = 0; j < k; ++j) h.constraints.plane_vertices.push_back(j * k);
  return h;
}

TEST(OptimizeMesh, ReportsEachTermOfAHalfSheetOnAMirrorPlane) {
  // Every kind of Laplacian term (2D, 2D restricted to the plane, 1D along the open boundary),
  // the plane penalty and E_project, against hand sums.
  const int k = 5;
  HalfSheet sheet = half_sheet(k);
  const Eigen::MatrixX3d& V = sheet.V;
  const Eigen::MatrixX3i& F = sheet.F;
  LabeledMesh& m = sheet.mesh;
  const MeshConstraints& c = sheet.constraints;
  MeshEnergyOptions o;
  o.max_iterations = 1;
  const OptimizeSummary s = optimize_mesh(m, {plane_model({0, 0, 1}, 0)}, c, o);

  const TriMesh grid = mesh_from_matrices(V, F);
  double project = 0.0, laplacian_2d = 0.0, laplacian_1d = 0.0, plane = 0.0;
  for (auto v : grid.vertices()) {
    const Eigen::Vector3d p = V.row(v.idx()).transpose();
    project += p.z() * p.z();
    Eigen::Vector3d ring = Eigen::Vector3d::Zero(), rim = Eigen::Vector3d::Zero();
    int ring_count = 0, rim_count = 0;
    for (auto h : v.outgoing_halfedges()) {
      const Eigen::Vector3d q = V.row(h.to().idx()).transpose();
      ring += q;
      ++ring_count;
      if (h.is_boundary() || h.opp().is_boundary()) {
        rim += q;
        ++rim_count;
      }
    }
    const Eigen::Vector3d delta = p - ring / ring_count;
    if (v.idx() % k == 0) {  // on the plane: the in-plane part of Delta_2D, and the penalty
      laplacian_2d += o.gamma_2d * delta.tail<2>().squaredNorm();
      plane += o.plane_weight * p.x() * p.x();
    } else if (grid.is_boundary(v)) {
      ASSERT_EQ(rim_count, 2);
      laplacian_1d += o.gamma_1d * (p - rim / rim_count).squaredNorm();
    } else {
      laplacian_2d += o.gamma_2d * delta.squaredNorm();
    }
  }
  // The projection's gradient floor (1e-3 of the model's gradient) shrinks E_project by 1e-6.
  EXPECT_NEAR(s.initial.project, project, 2e-6 * project);
  EXPECT_NEAR(s.initial.regularize_2d, laplacian_2d, 1e-12 * laplacian_2d);
  EXPECT_NEAR(s.initial.regularize_1d, laplacian_1d, 1e-12 * laplacian_1d);
  EXPECT_NEAR(s.initial.plane, plane, 1e-12 * plane);
  EXPECT_GT(laplacian_2d * laplacian_1d * plane, 0.0);
  EXPECT_LT(s.final.total(), s.initial.total());
}

TEST(OptimizeMesh, SameResultWhateverTheThreadCountOnAMirrorPlane) {
  // 6400 vertices: the L-BFGS vectors span two chunks, the global steps' systems four, and the
  // plane splits them into a two-column and a one-column system.
  const HalfSheet sheet = half_sheet(80);
  std::vector<TriMesh> results;
  for (unsigned threads : {1u, 2u, 3u}) {
    LabeledMesh m = sheet.mesh;
    MeshEnergyOptions o;
    o.threads = threads;
    o.max_iterations = 60;
    optimize_mesh(m, {plane_model({0, 0, 1}, 0)}, sheet.constraints, o);
    results.push_back(m.mesh);
  }
  for (std::size_t r = 1; r < results.size(); ++r)
    for (auto v : results[0].vertices())
      ASSERT_EQ(results[0].point(v), results[r].point(v)) << "threads differ at vertex " << v.idx();
}

TEST(OptimizeMesh, CancelsThroughProgress) {
  TriMesh mesh = testing::icosphere(2);
  LabeledMesh m{mesh, std::vector<std::vector<int>>(mesh.n_vertices(), {0}), std::vector<int>(mesh.n_vertices(), 0)};
  const Progress cancel([](std::string_view, double) { return false; });
  try {
    optimize_mesh(m, {plane_model({0, 0, 1}, 0)}, {}, {}, cancel);
    FAIL() << "not cancelled";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Cancelled);
  }
}

}  // namespace
}  // namespace sketchsurf
