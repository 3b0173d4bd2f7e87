#pragma once
// Final mesh optimisation (paper §4.3, Eq. 7-9, and App. D Eq. 13): move the seamed mesh onto the
// implicit surfaces of its regions while keeping it regular (our L-BFGS; Ceres' trust-region
// solvers for comparison).

#include <ceres/cost_function.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "surfacing/extract/seams.h"
#include "surfacing/progress.h"
#include "surfacing/segment/implicit.h"
#include "surfacing/sketch/sketch.h"

namespace sketchsurf {

/// How E_mesh is minimised. Measured with tests/bench/extract_bench (rounded cube, 2 threads,
/// shared 2-core machine) and on real segmentations (hat, 84k seamed vertices): on 11k vertices
/// Levenberg-Marquardt with sparse normal Cholesky (SuiteSparse) needs 12 iterations but 15 s of
/// CPU (the Laplacian's 2-ring fill-in makes each factorisation ~1 s), CGNR 62 s. L-BFGS on a
/// first-order function with precomputed Laplacian matrices (the paper's choice, §4.3) is the
/// default; the Laplacian terms make E_mesh stiff, so how it is started and scaled decides its
/// iteration count:
/// - started from the per-vertex projection alone and unscaled (the previous default), 500
///   iterations end far from converged: hat E_mesh 2.15 (NO_CONVERGENCE), 42.6k cube 0.0275;
/// - Jacobi scaling (y = x / sqrt(diag H)) halves the iterations to a given energy (hat: 4.49 ->
///   2.43 after 200 iterations from the same start);
/// - 5 local-global iterations after the projection (see local_global_iterations) start L-BFGS at
///   E_mesh 4.2 instead of 888 on the hat; then 150 iterations reach 1.69, 200 reach 1.48 (42.6k
///   cube: 0.0255 and 0.0216; without the local-global start 0.032 and 0.026);
/// - the projection residual with a hand-written gradient instead of Jets (perf on the hat: the
///   Jet evaluation was half of the L-BFGS time; same energies to all printed digits), and the
///   Laplacian products row-parallel.
/// What remains slow is the sliding of vertices along flat or gently curved surfaces that evens
/// out the graph Laplacian: on the cube it still moves vertices by 2-8% of an edge per 10
/// iterations at iteration 500, so a "vertices no longer move" test does not stop earlier than the
/// iteration cap, and max_iterations is the working stop: 300, the smallest of 200/250/300 at
/// which E_mesh ends below the previous default's on each of hat, chair, teapot, box and the
/// median stroke distance within 1% of it (teapot: E 0.0620 at 200, 0.0610 at 250 with median
/// distance +0.6%, 0.0601 and +0.2% at 300; previous 0.0612). Previous default -> this one, same
/// segmentations, process CPU on a loaded 2-core machine (load ~6.5: wall ~2x CPU):
/// hat (84k seamed vertices) E 2.149 -> 1.271, median distance 2.385e-3 -> 2.226e-3 (of the
/// diagonal), CPU 30.5 s -> 16.6 s; chair (25k) 0.1785 -> 0.1723, 3.200e-3 -> 3.181e-3, 9.0 -> 4.9 s;
/// teapot (20k) 0.0612 -> 0.0601, 3.081e-3 -> 3.086e-3, 6.8 -> 3.5 s; box (36k) 0.685 -> 0.603,
/// 1.697e-3 -> 1.709e-3, 9.0 -> 5.7 s. The largest stroke distance (one point) moved both ways
/// (hat 0.056 -> 0.079, chair 0.031 -> 0.042, box 0.0156 -> 0.0161, teapot 0.0413 -> 0.0411).
/// extract_bench (medians of 3, wall / main-thread CPU, same load): 42.6k cube 10.1 s / 5.0 s,
/// E 0.0275 -> 7.1 s / 2.8 s, E 0.0182; 11k cube 3.1 s / 1.2 s, E 0.0389 -> 2.4 s / 0.7 s,
/// E 0.0086; peak RSS 128 MB (was 114 MB); hat scratch process 223 MB (was 193 MB).
///
/// Session 3 (extraction alone on cached real segmentations; the 2-core machine shared at load
/// 3-6, so process CPU and main-thread CPU rather than wall: the main thread runs every serial
/// part and half of each parallel loop, so its CPU approximates the wall on an idle machine):
/// - what the iterations chase on real sketches is not only sliding: after 300 iterations the
///   top 1% of vertices hold 70-87% of E_project (hat, 01-0-1), up to 0.11-0.16 of the diagonal
///   from their own region's surface (zero sets away from the proxy, seams of surfaces that meet
///   far off). E_mesh keeps falling ~1% per 10 iterations up to 600 (hat 2.10 at 300, 1.54 at
///   600) while the stroke distances get no better (hat median 2.50e-3 at 100 iterations, 2.62e-3
///   at 300, 2.65e-3 at 600; p95 0.0173, 0.0197, 0.0214), so an earlier stop trades E_mesh for
///   stroke distance (01-0-1 at 200: E 2.07 instead of 1.32, median -6%): the cap stays 300;
/// - E_mesh at the cap is sensitive to rounding: changes that only reorder sums moved 01-0-1's
///   between 1.318 and 1.399, its p95 stroke distance by up to 2%;
/// - tried and dropped: preconditioned gradient steps d = A^-1 grad E (A the global step's
///   matrix, Armijo) every 20 or 50 L-BFGS iterations (hat E 2.41 / 2.18 instead of 2.10 at 300:
///   each step gains 1-3% and restarts the memory); 15 or 30 local-global iterations (E 5.04 /
///   4.74 after them instead of 4.70 after 5, at 2-4x the start's cost); L-BFGS rank 4 or 16
///   (E 2.19 / 2.01, rank 16 1.4x the time); H0 = (s.y / y.y) I instead of I (hat 2.06, 01-0-1
///   1.34 at 300, 2.28 / 2.10 at 200); an incomplete-Cholesky preconditioner (see GlobalStep);
/// - kept: E_project's derivatives from a differentiated table (detail::ModelDerivatives), one
///   block Jacobi-PCG pass per global step for all coordinates (detail::block_conjugate_gradients),
///   the Laplacian terms as one scalar matrix acting on the three coordinates, and our own
///   L-BFGS (optimize.cpp) with the same stopping tests, whose vector work runs on the worker
///   threads (Ceres' ran serially: 29% of a 01-0-1 extraction's CPU), and the per-vertex loops
///   around it on the threads too. Before (8f4f7a4) -> after, same segmentations, two runs each,
///   back to back: main-thread CPU hat (69.6k output vertices) 5.5-6.0 s -> 2.5-2.7 s, 01-0-1
///   (90.3k) 6.8-7.7 -> 3.7, chair (24.6k) 1.8-2.1 -> 1.0, teapot (19.8k) 1.3 -> 0.8-0.9, box
///   (36.4k) 2.3 -> 1.3-1.4; process CPU hat 8.7-9.7 -> 4.5-4.9, 01-0-1 11.1-12.5 -> 6.6, chair
///   2.9-3.5 -> 1.8, teapot 2.0-2.1 -> 1.3-1.5, box 3.6 -> 2.3-2.5. E_mesh hat 2.099 -> 2.043,
///   chair 0.2200 -> 0.2179, teapot 0.04708 -> 0.04703, box 0.4205 -> 0.4210, 01-0-1 1.367 ->
///   1.398; median stroke distance (of the diagonal) hat 2.620e-3 -> 2.617e-3, chair 3.612e-3 ->
///   3.610e-3, teapot 3.137e-3 -> 3.118e-3, box 1.168e-3 -> 1.158e-3, 01-0-1 3.674e-3 ->
///   3.677e-3; p95 hat 0.0197 -> 0.0208, chair 0.0190 -> 0.0194, teapot 0.0149 -> 0.0149, box
///   0.00652 -> 0.00649, 01-0-1 0.0280 -> 0.0282. extract_bench (same load): 42.6k cube 1.70 s ->
///   1.44 s wall (Ceres -> ours), E 0.01820 -> 0.01833; 11k cube 0.37 -> 0.53 s (noise), E
///   0.00863 -> 0.00941 (9% worse: our Armijo search takes other steps than Ceres' Wolfe
///   search; doubling accepted unit steps while the Wolfe curvature test fails made both cubes
///   worse, 0.00989 and 0.01849); peak RSS 118 MB. On the segmentations of the tree at 16:43
///   (segment room past 7098205: other regions, far lower E_mesh), before -> after: E_mesh hat
///   0.18346 -> 0.18379, chair 0.13627 -> 0.13625, 01-0-1 0.24894 -> 0.25062, teapot 0.067157
///   -> 0.067129, box 0.36253 -> 0.36299; median stroke distance hat 2.163e-3 -> 2.165e-3, chair 2.708e-3 ->
///   2.701e-3, 01-0-1 2.917e-3 -> 2.949e-3, teapot 2.481e-3 -> 2.473e-3, box 0.950e-3 ->
///   0.960e-3; p95 hat 0.01481 -> 0.01458, chair 0.01554 -> 0.01543, 01-0-1 0.01734 -> 0.01730,
///   teapot 0.01681 -> 0.01668, box 0.00431 -> 0.00436; extraction wall at load ~3: 01-0-1 7.8 s
///   -> 4.0-5.6 s, hat 5.3 -> 3.8-5.0 s (main-thread CPU 6.7 -> 3.4 s, 4.8 -> 2.3-3.1 s).
///
/// Session 4 (issue 4: the whole run under 10 s; extraction alone on the cached segmentations of
/// main bb0733f, load 3-9 on the shared 2-core machine, so main-thread CPU, medians of 3
/// interleaved runs):
/// - the stop. E_mesh still falls 0.2-0.55% per 10 iterations at the cap of 300 on hat, chair,
///   01-0-1, teapot and box, but the surface has settled long before: between the results after
///   150 and 300 iterations the vertex-to-surface distance is 2e-5 of the diagonal at the median
///   on 01-0-1 (the median stroke distance is 3e-3), 1.5e-3 at p95 (box 2.7e-4, hat 2.9e-4), and
///   the stroke distances do not improve (p95 01-0-1 0.0166 at 150, 0.0173 at 300; hat 0.0138,
///   0.0146). What the late iterations buy is evener triangles and the 1% of far vertices. So
///   L-BFGS also stops once E_mesh fell by less than stall_tolerance = 5% over the last stall_window = 50
///   iterations (0.1% per iteration; 10% stopped 01-0-1 at 140 iterations with E_mesh +19%, hat
///   +13%, box +17%: too much). Before -> after (with the next two items): iterations hat 300
///   -> 141, chair 157, 01-0-1 248, teapot 138, box 194; E_mesh hat 0.18379 -> 0.19355 (+5.3%),
///   chair 0.13625 -> 0.14359 (+5.4%), 01-0-1 0.25062 -> 0.25621 (+2.2%), teapot 0.06713 ->
///   0.07202 (+7.3%), box 0.36299 -> 0.38361 (+5.7%); median stroke distance -0.3%, +0.1%,
///   -0.4%, -2.2%, -0.3%; p95 -2.9%, -0.1%, -0.9%, -2.3%, +0.5%; between the two results the
///   vertex-to-surface distance is at most 1.2e-4 of the diagonal at the median (chair), 1.4e-3 at
///   p95 (chair, teapot), the smallest triangle angles (1st percentile) 1.1 -> 1.0 deg on 01-0-1,
///   25.4 -> 24.0 box, 8.1 -> 5.6 chair, 12.4 -> 13.5 teapot, 0.62 -> 0.65 hat. The E_mesh increase
///   is the price of the speed-up, paid in triangle evenness, not in distance to the strokes;
///   stall_window = 0 restores the previous stop;
/// - global_step_tolerance 1e-2 -> 3e-2: 01-0-1's five global steps take 342 conjugate-gradient
///   iterations instead of 450; alone, E_mesh -0.5% on hat, chair, 01-0-1 and box, +0.6% teapot,
///   median stroke distance within 1.2%, p95 within 1.5% but hat +2.6% (the rounding noise
///   above); 1e-1 moved 01-0-1's E_mesh +1.5% and teapot's -2.7%: not taken;
/// - ModelDerivatives' table evaluation unrolled per column count (4, 10, 20, 35) with
///   compile-time exponents and row counts, and taubin() reading the ten rows it uses: the same
///   operations in the same order (the same output bit for bit), 53 -> 44 ns per projection term
///   (01-0-1's terms, one thread, best of 7);
/// - main-thread CPU before -> after: hat 2.68 -> 1.68 s, chair 1.07 -> 0.73, 01-0-1 3.88 ->
///   2.91, teapot 0.80 -> 0.55, box 1.36 -> 1.02; process CPU 4.86 -> 3.07, 2.00 -> 1.32, 7.29 ->
///   5.30, 1.40 -> 0.96, 2.57 -> 1.88. extract_bench (rounded cubes, Previous300 -> Default):
///   the stall test does not act there (E_mesh still falls faster), 300 iterations both; E_mesh
///   11k 0.00941 -> 0.00828, 42.6k 0.01833 -> 0.01865 (the global-step tolerance), largest
///   distance to the cube 4.7e-4 -> 3.9e-4 and 6.0e-4 -> 4.2e-4 of the diagonal; time within the
///   noise (main-thread CPU 334 -> 303 ms, 983 -> 1039 ms); peak RSS 117 MB; all 14 `data`
///   surface tests pass;
/// - the loops of an optimisation (~25 per L-BFGS iteration, 3 per conjugate-gradient iteration,
///   ~7500 on 01-0-1) run on a WorkerTeam (parallel.h) whose threads wait on a condition
///   variable between loops, where parallel_for() starts and joins threads at every loop (~50 us
///   of CPU each: teapot's extraction took 0.70 s of CPU on one thread, 0.95 s on two). The same
///   chunks, so the same output bit for bit (all five sketches); after the changes above ->
///   with the team, interleaved, load 5-6: process CPU hat 3.30 -> 3.21 s, chair 1.33 -> 1.16,
///   01-0-1 6.66 -> 6.61, teapot 0.98 -> 0.80, box 2.16 -> 1.83; main-thread CPU 1.86 -> 1.81,
///   0.73 -> 0.65, 3.63 -> 3.61, 0.56 -> 0.45, 1.15 -> 1.02; wall 5.9 -> 5.0, 3.5 -> 2.1, 11.1 ->
///   10.9, 2.9 -> 1.3, 5.2 -> 3.0 s. (A first try, on the previous code at load ~3, had 01-0-1's
///   main-thread CPU 3.8-4.0 s instead of 3.1-3.4 s; at load 5-6 the team was ahead on 01-0-1,
///   6.2-6.3 s of process CPU instead of 6.5-6.8, and on all five sketches above);
/// - tried and dropped: two accumulators in the table evaluation (62 ns instead of 53: the
///   registers run out), one reciprocal instead of three divisions in taubin() (no gain), this
///   file compiled for AVX (no FMA, so the same output; 65-68 ns instead of 54), the unrolled
///   evaluation forced inline into taubin() (107 ns instead of 44); local_global_iterations = 3
///   with the stall test (01-0-1 stops at 280 iterations instead of 248, the same time; E_mesh
///   hat +0.9%, box -0.6%).
///
/// Session 5 (issue 4: 01-0-1's whole run under 10 s; extraction alone on the cached
/// segmentations of main ccd69cf, the machine shared with the lead's runs at load 1.6-4.5, so
/// process and main-thread CPU, interleaved runs, medians of 3). 01-0-1 (89.3k vertices) ran to
/// the cap (300 L-BFGS iterations, 363 evaluations): L-BFGS 3.4 s of its 4.5 s (evaluations 2.3,
/// of them the projection terms 1.8; vector work 1.1), local-global start 0.74 (its matrix 0.12
/// serial), seams 0.16. Kept, each with the same output bit for bit on hat, chair, 01-0-1,
/// teapot and box, and on a mirrored half sheet with seams and attraction targets (1-3 threads,
/// against the code before the session):
/// - the table evaluation's per-monomial step always inlined: GCC 12 had left its 1- and 4-row
///   instances out of line (24% of the extraction's perf samples), 01-0-1's terms 81 -> 35 ns;
/// - L-BFGS passes fused (Jacobi scaling of the gradient where it is assembled, trial point and
///   unscaled positions together, y.y and the largest gradient entry with s.y): 3 passes over
///   3n values fewer per iteration, one of them serial;
/// - the global step's matrix row by row on the team (detail::normal_matrix; 0.19 -> 0.11 s on
///   one thread, the same bits as Eigen's product, tested);
/// - base -> after, process CPU / main-thread CPU (s): 01-0-1 7.10 / 3.76 -> 4.79 / 2.58, hat
///   2.80 / 1.56 -> 2.14 / 1.20, chair 1.02 / 0.56 -> 0.94 / 0.52, teapot 0.79 / 0.44 -> 0.60 /
///   0.34, box 1.48 / 0.81 -> 1.15 / 0.63; 01-0-1 wall 4.5-4.6 -> 3.2-3.4 s at load ~1.6-2.3.
///   Quality unchanged (same bits): E_mesh 1.1542, 0.28738, 0.15246, 0.065991, 0.4803; median
///   stroke distance 3.09e-3, 1.98e-3, 2.79e-3, 2.41e-3, 0.64e-3, p95 0.0193, 0.0131, 0.0165,
///   0.0192, 0.0037 (of the diagonal); smallest angles (1st percentile, 01-0-1) 0.77 deg.
///   extract_bench (planes only, little to gain): E_mesh 0.00828 / 0.01865 as before, main-thread
///   CPU 175 / 797 ms at load ~4, peak RSS 116 MB.
/// Tried and dropped:
/// - workers spinning 50 us before sleeping between loops (WorkerTeam; ~8000 loops on 01-0-1):
///   with another process on one of the two cores, 01-0-1 took 15% more CPU and wall (the
///   spinning thread holds the core the other one needs); yielding instead of pausing while
///   spinning: the same wall at load ~4, CPU +8%. Not measurable on an idle machine during the
///   session, where the wake-ups it saves should matter most;
/// - projection terms and the Laplacian residuals in one team loop, S^T r in the gradient loop
///   (one loop and one 3n buffer fewer per evaluation): CPU 5.04 -> 5.13 s, not faster;
/// - build_energy's Laplacian terms per block of vertices on the team: the same time on one
///   thread, no difference at load 3 (0.04 s serial per call, two calls);
/// - taubin() compiled for AVX as a target clone: 36-38 ns instead of 34-36;
/// - an earlier stop on 01-0-1: 250 iterations E_mesh +6% (200: +19%), stroke distances within
///   1%, smallest angles as good (1st percentile 0.78 / 0.85 deg instead of 0.77): not taken.
/// Left (01-0-1): the projection terms (~25% of the CPU) and the two-loop recursion (~23%: 17
/// passes, 16 pair vectors of 2.1 MB, memory bound), the global steps' conjugate gradients
/// (~14%); serial: building the seamed OpenMesh mesh (0.08 s) and build_energy (2 x 0.04 s).
enum class MeshSolver {
  SparseCholesky,  ///< Levenberg-Marquardt, SPARSE_NORMAL_CHOLESKY (SuiteSparse)
  ConjugateGradients,  ///< Levenberg-Marquardt, CGNR with a Jacobi preconditioner
  Lbfgs,           ///< line search L-BFGS (paper §4.3; ours, Armijo backtracking, H0 = I)
};

/// Options of E_mesh = E_project + E_regularize + E_attract (Eq. 7-9, 13).
struct MeshEnergyOptions {
  double gamma_2d = 100.0;           ///< weight of the 2D graph Laplacian (Eq. 9)
  double gamma_1d = 500.0;           ///< weight of the 1D Laplacian along seams (Eq. 9)
  double smooth_angle = M_PI / 8.0;  ///< w_v = 1 when the region normals differ by less (rad, §4.3)
  double sharp_angle = M_PI / 3.0;   ///< w_v = 0 when they differ by more (rad, §4.3)
  double attract_weight = 100.0;     ///< multiplies E_attract (Eq. 13: 1)
  double plane_weight = 1.0e4;       ///< keeps mirror-plane vertices on the plane (ours; they are
                                     ///< snapped exactly onto it afterwards)
  int projection_steps = 5;          ///< Gauss-Newton steps moving each vertex onto its surfaces
                                     ///< before the solve, and Newton steps of each local step
                                     ///< (ours: a cheap start for L-BFGS)
  double max_projection_step = 0.02; ///< longest such step, fraction of the mesh's diagonal (ours)
  int local_global_iterations = 5;   ///< local-global iterations after the projection, 0 = none
                                     ///< (ours, see MeshSolver; each costs ~10 L-BFGS iterations)
  double local_global_tolerance = 1e-3;  ///< they stop early when no vertex moves more, fraction
                                         ///< of the mean edge length
  double global_step_tolerance = 3e-2;   ///< residual reduction of each global step's conjugate
                                         ///< gradients (ours, see MeshSolver)
  MeshSolver solver = MeshSolver::Lbfgs;  ///< see MeshSolver
  int lbfgs_rank = 8;                ///< L-BFGS memory (pairs kept; 20, Ceres' default, spent 40%
                                     ///< of the time in the two-loop recursion, measured)
  int max_iterations = 300;          ///< solver iterations (L-BFGS or trust-region): a cap; on
                                     ///< real sketches the stall test acts first, see MeshSolver
  double function_tolerance = 1e-8;  ///< relative cost decrease that stops the solver
  int stall_window = 50;             ///< L-BFGS also stops when E_mesh fell by less than
  double stall_tolerance = 0.05;     ///< stall_tolerance (relative) over the last stall_window
                                     ///< iterations; 0 = no such stop (ours, see MeshSolver)
  double gradient_tolerance = 1e-6;  ///< largest gradient entry that stops the solver, fraction of
                                     ///< the mesh's diagonal (the energy is in length^2, its
                                     ///< Jacobi-scaled gradient in length: about how far a vertex
                                     ///< still is from its optimum along well-conditioned directions)
  unsigned threads = 0;              ///< worker threads (0 = all); the result does not depend on it
  bool valid(std::string* why) const;
};

/// Where the vertices of an open boundary are pulled (Eq. 13): one target point per entry.
struct AttractTarget {
  int vertex = -1;                                ///< vertex of the seamed mesh
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< a boundary-stroke point, mesh units
};

/// Extra constraints of E_mesh: open boundaries and the mirror plane.
struct MeshConstraints {
  std::vector<AttractTarget> attract;  ///< E_attract targets (App. D)
  std::optional<Plane> plane;          ///< mirror plane, when the mesh is half of a symmetric one
  std::vector<int> plane_vertices;     ///< vertices that must stay on `plane` (its boundary there)
};

/// Energies of E_mesh's terms, each a plain sum of squares (mesh units squared) with its weight.
struct MeshEnergyTerms {
  double project = 0.0;        ///< E_project (Eq. 8)
  double regularize_2d = 0.0;  ///< gamma_2D sum w_v |Delta_2D v|^2 (Eq. 9)
  double regularize_1d = 0.0;  ///< gamma_1D sum |Delta_1D v|^2 over seams and open boundaries (Eq. 9)
  double attract = 0.0;        ///< E_attract (Eq. 13)
  double plane = 0.0;          ///< mirror-plane penalty
  double total() const { return project + regularize_2d + regularize_1d + attract + plane; }
};

/// What optimize_mesh() did (a digest of the solver's summary).
struct OptimizeSummary {
  MeshEnergyTerms initial, final;
  int iterations = 0;
  int local_global_iterations = 0;  ///< iterations of the local-global start made
  std::string termination;  ///< termination type and message (Ceres' words)
  std::string solver;       ///< minimizer and linear solver used
  bool usable = false;      ///< the solver reports a usable solution
  double seconds = 0.0;     ///< wall time of the start (projection, local-global) and the solve
};

/// w_v of Eq. 9 for a vertex between two regions whose (unoriented) normals make `angle` (rad):
/// 1 below smooth_angle, 0 above sharp_angle, linear in between.
double seam_weight(double angle, const MeshEnergyOptions& options);

/// w_v of Eq. 9 for every vertex: 1 for one label, 0 for three or more, seam_weight() of the angle
/// between the two implicit normals at the vertex's current position otherwise.
std::vector<double> regularization_weights(const LabeledMesh& mesh,
                                           const std::vector<ImplicitModel>& models,
                                           const MeshEnergyOptions& options);

/// Minimises E_mesh over the vertex positions of `mesh`, in place (Eq. 7-9, 13), starting from
/// each vertex moved onto its surfaces by projection_steps Gauss-Newton steps, then
/// local_global_iterations local-global iterations (see MeshSolver):
/// - E_project: each vertex, for each of its labels a, (1 / |labels|) dist_a(v)^2 with the Taubin
///   distance f_a / |grad f_a| (Eq. 5, 8);
/// - E_regularize: gamma_2D w_v |v - mean(1-ring)|^2 (graph Laplacian, Nealen et al. 2006) on
///   interior vertices; gamma_1D |v - (s1 + s2) / 2|^2 on seam vertices with exactly two seam
///   neighbours, and on open-boundary vertices without an attraction target along the boundary
///   (ours: the 2D Laplacian of a boundary vertex only shrinks the mesh, and the 1D one rounds the
///   corners that the boundary strokes draw); on mirror-plane vertices the 2D Laplacian restricted
///   to the plane, since their mirrored neighbours balance its normal part;
/// - E_attract: attract_weight |v - p|^2 per target (Eq. 13);
/// - plane_weight (n.v + d)^2 per plane vertex, then an exact snap onto the plane.
/// Labels index `models`. Throws Error (Usage) on invalid options or indices, Error (Cancelled)
/// through `progress`, Error (Processing) when the solver produces non-finite positions.
OptimizeSummary optimize_mesh(LabeledMesh& mesh, const std::vector<ImplicitModel>& models,
                              const MeshConstraints& constraints, const MeshEnergyOptions& options,
                              const Progress& progress = {});

namespace detail {

/// Eq. 8 residual of one vertex and one of its labels: sqrt(weight) f(x) / |grad f(x)|, the
/// signed Taubin distance. Signed (not |f|) so that the residual is smooth across the surface;
/// `gradient_floor` (f units per length) keeps it finite where grad f vanishes.
struct ProjectionResidual {
  const ImplicitModel* model = nullptr;
  double sqrt_weight = 1.0;
  double gradient_floor = 0.0;

  template <typename T>
  bool operator()(const T* x, T* residual) const {
    const T f = model->evaluate(x);
    T g[3];
    model->evaluate_gradient(x, g);
    using std::sqrt;
    const T norm = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2] + T(gradient_floor * gradient_floor));
    residual[0] = T(sqrt_weight) * f / norm;
    return true;
  }
  /// The model must outlive the cost function.
  static ceres::CostFunction* Create(const ImplicitModel& model, double weight, double gradient_floor);
};

/// f, its gradient and its Hessian (world units) of one ImplicitModel from one dense table: the
/// ten values (f, f_x, f_y, f_z, f_xx, f_yy, f_zz, f_xy, f_xz, f_yz) are C m(y), m the model's
/// monomials of the normalised coordinates y = (x - center) / scale and C its coefficients
/// differentiated term by term, in world units, built once per model. What the L-BFGS evaluation
/// and the local steps use: products of short dense columns that vectorise, skipping the blocks
/// that are zero (Hessian rows beyond degree 2, gradient rows beyond degree 3), instead of
/// differentiating each monomial at every call. perf on a hat extraction: the per-monomial
/// hand-written gradient (ProjectionResidual::value_and_gradient, now gone) took 35% of the CPU,
/// 12.8k samples; the table's evaluation and taubin() take 6.2k samples (same energies to 4
/// digits; the L-BFGS path is sensitive to rounding, 01-0-1's E_mesh moved 1.367 -> 1.399).
class ModelDerivatives {
 public:
  explicit ModelDerivatives(const ImplicitModel& model);
  /// f(x) and grad f(x) (3 values) at a world point.
  double value_and_gradient(const double* x, double* gradient) const;
  /// The signed Taubin residual sqrt_weight f / sqrt(|grad f|^2 + floor^2) of ProjectionResidual
  /// at x and its gradient (3 values): grad f / N - f (H grad f) / N^3.
  double taubin(const double* x, double sqrt_weight, double gradient_floor, double* gradient) const;

 private:
  static constexpr int kRows = 12;  // the ten values, padded for vector loads
  template <int Rows>
  void evaluate(const double* x, double* values) const;
  std::vector<std::array<double, kRows>> columns_;  // per monomial: its share of each value
  Eigen::Vector3d center_;
  double inverse_scale_ = 1.0;
  int needed_power_ = 0;  // highest power of a coordinate among the monomials
};

/// Eq. 9 residual of one vertex: sqrt(weight) P (x_0 - mean(x_1..x_k)), the uniform graph
/// Laplacian (Nealen et al. 2006) of the vertex x_0 with neighbours x_1..x_k (a 1-ring for
/// Delta_2D, the two seam neighbours for Delta_1D). P projects onto a plane (mirror-plane
/// vertices) or is the identity. Linear, so its Jacobian is constant and written out.
class LaplacianCost : public ceres::CostFunction {
 public:
  LaplacianCost(int neighbors, double weight, const Eigen::Matrix3d& projection);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;
  static ceres::CostFunction* Create(int neighbors, double weight,
                                     const Eigen::Matrix3d& projection = Eigen::Matrix3d::Identity());

 private:
  int neighbors_;
  Eigen::Matrix3d center_jacobian_;    // sqrt(weight) P
  Eigen::Matrix3d neighbor_jacobian_;  // -sqrt(weight) P / k
};

/// Eq. 13 residual: sqrt(weight) (x - p), a boundary vertex to one of its boundary-stroke points.
struct AttractResidual {
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  double sqrt_weight = 1.0;
  template <typename T>
  bool operator()(const T* x, T* residual) const {
    for (int i = 0; i < 3; ++i) residual[i] = T(sqrt_weight) * (x[i] - T(target[i]));
    return true;
  }
  static ceres::CostFunction* Create(const Eigen::Vector3d& target, double weight);
};

/// Mirror-plane residual: sqrt(weight) (n . x + d), the signed distance to the plane.
struct PlaneResidual {
  Plane plane;
  double sqrt_weight = 1.0;
  template <typename T>
  bool operator()(const T* x, T* residual) const {
    residual[0] = T(sqrt_weight) * (T(plane.normal.x()) * x[0] + T(plane.normal.y()) * x[1] +
                                     T(plane.normal.z()) * x[2] + T(plane.offset));
    return true;
  }
  static ceres::CostFunction* Create(const Plane& plane, double weight);
};

/// Jacobi-preconditioned conjugate gradients on A X = B for the K columns of B at once (A n x n
/// symmetric positive definite, `inverse_diagonal` = 1 / diag A, B and the result n x K stored
/// row by row: b[K i + j]); the global steps of the local-global start. Each iteration makes one
/// row-parallel pass over A for all the columns, where Eigen's ConjugateGradient, one column per
/// thread, passed over A per column and left one of two threads idle for three columns (19% of a
/// hat extraction, perf). Column j stops when |residual_j| <= tolerance |b_j| (as Eigen's) or
/// after 2n iterations; a column gives the same result as when solved alone. The sums run over
/// fixed chunks of rows, so the result does not depend on `threads`. Instantiated for K = 1, 2, 3.
template <int K>
std::vector<double> block_conjugate_gradients(const Eigen::SparseMatrix<double, Eigen::RowMajor>& A,
                                              const Eigen::VectorXd& inverse_diagonal,
                                              const std::vector<double>& B, double tolerance,
                                              unsigned threads);

using RowMajorMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;

/// A = (L2^T L2 + L1^T L1) + diag(d), n x n with n = d.size() (L2, L1: one row per Laplacian
/// term, n columns): the global steps' matrix, row by row on `threads` threads, with the same
/// operations in the same order as Eigen's serial conservative sparse product, sums and diagonal
/// update that built it before (the same bits; 0.1 s serial on 01-0-1 with those).
RowMajorMatrix normal_matrix(const Eigen::SparseMatrix<double>& L2, const Eigen::SparseMatrix<double>& L1,
                             const Eigen::VectorXd& d, unsigned threads);

}  // namespace detail

}  // namespace sketchsurf
