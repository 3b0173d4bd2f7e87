#pragma once
// Limited-memory BFGS on a function of many variables whose vector work runs on a WorkerTeam:
// the solve of optimize_mesh() (extract) and of the VIPSS normals (proxy). Internal to the
// library: neither room's public header exposes it.

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <string>

#include "surfacing/parallel.h"

namespace sketchsurf::detail {

/// Chunk length of the L-BFGS vector work: fixed, so its sums do not depend on the thread count.
constexpr std::size_t kVectorChunk = 16384;

/// body(lo, size) over the kVectorChunk-long chunks of [0, n), on the team's threads.
template <class Body>
void for_vector_chunks(Eigen::Index n, const WorkerTeam& team, Body&& body) {
  team.chunks(static_cast<std::size_t>(n), kVectorChunk,
              [&](std::size_t, Eigen::Index lo, Eigen::Index hi) { body(lo, hi - lo); });
}

/// What minimize_lbfgs() minimises: a cost with its gradient.
class LbfgsFunction {
 public:
  virtual ~LbfgsFunction() = default;
  /// Number of variables.
  virtual Eigen::Index size() const = 0;
  /// The cost and its gradient at y; false when the cost is not finite.
  virtual bool evaluate(const double* y, double* cost, double* gradient) const = 0;
  /// evaluate() at trial = y + step d, written to `trial` (size() values) in the same pass: the
  /// line search's trial point costs no pass of its own.
  virtual bool evaluate_step(const double* y, double step, const double* d, double* trial, double* cost,
                             double* gradient) const = 0;
};

/// When minimize_lbfgs() stops, and its memory.
struct LbfgsOptions {
  int rank = 8;                       ///< (s, y) pairs kept
  bool scale_initial_hessian = false; ///< H0 = (s.y / y.y) I of the newest pair (Nocedal and
                                      ///< Wright Eq. 7.20) instead of I: for variables the
                                      ///< caller cannot scale beforehand
  int max_iterations = 300;           ///< iteration cap
  double function_tolerance = 1e-8;   ///< relative cost decrease of one iteration that stops it
  double gradient_tolerance = 1e-6;   ///< largest gradient entry that stops it (absolute)
  int stall_window = 50;              ///< also stops when the cost fell by less than
  double stall_tolerance = 0.05;      ///< stall_tolerance (relative) over the last stall_window
                                      ///< iterations; 0 = no such stop
};

/// What minimize_lbfgs() did.
struct LbfgsOutcome {
  int iterations = 0;
  bool converged = false;  ///< a tolerance was met (else the iteration cap or a failed line search)
  bool usable = true;      ///< x holds finite values with the lowest cost found
  std::string termination;  ///< in Ceres' words: CONVERGENCE, NO_CONVERGENCE or FAILURE, and why
};

/// Limited-memory BFGS (Nocedal and Wright 2006, Alg. 7.4-7.5) with H0 = I (the caller scales
/// the variables, e.g. Jacobi; or the scaled identity, scale_initial_hessian) and a backtracking
/// Armijo line search from the unit step. What Ceres' GradientProblemSolver does with LBFGS and
/// its Wolfe search, but the vector operations run over fixed chunks of the variables on the
/// team's threads (the sums in a fixed order: the result does not depend on the thread count),
/// the two-loop recursion fusing each update with the next dot product. Stops as Ceres does
/// (largest gradient entry <= gradient_tolerance, relative cost decrease <= function_tolerance,
/// or max_iterations), or on the stall test. x0 (f.size() values) is the start and receives the
/// lowest-cost iterate however it ends. `on_iteration(i)` runs after iteration i (0: the start)
/// and may throw to stop.
LbfgsOutcome minimize_lbfgs(const LbfgsFunction& f, double* x0, const LbfgsOptions& options, const WorkerTeam& team,
                            const std::function<void(int)>& on_iteration);

}  // namespace sketchsurf::detail
