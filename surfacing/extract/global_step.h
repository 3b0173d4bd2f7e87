#pragma once
// The local-global start of optimize_mesh() (after projective dynamics, Bouaziz et al. 2014) and
// the sparse linear algebra of its global steps. Private to the extract room.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "surfacing/extract/energy.h"
#include "surfacing/parallel.h"

namespace sketchsurf::detail {

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

/// A = (L2^T L2 + L1^T L1) + diag(d), n x n with n = d.size() (L2, L1: one row per Laplacian
/// term, n columns): the global steps' matrix, row by row on `threads` threads, with the same
/// operations in the same order as Eigen's serial conservative sparse product, sums and diagonal
/// update (the same bits, tested), where those run on one thread.
RowMajorMatrix normal_matrix(const Eigen::SparseMatrix<double>& L2, const Eigen::SparseMatrix<double>& L1,
                             const Eigen::VectorXd& d, unsigned threads);

/// Local-global start: E_project's distance to Z(f_a) is the distance to the closest point of
/// Z(f_a), so alternately moving each vertex's points onto its surfaces (local step: Newton steps
/// along the gradient, each at most `max_step` long, in parallel) and minimising over the
/// vertices with the points fixed (global step: a sparse SPD solve per coordinate) lowers E_mesh.
/// Global steps spread a change over the whole mesh where L-BFGS needs hundreds of iterations
/// (the Laplacian terms make E_mesh stiff); the sliding of vertices along the surfaces stays slow
/// in both, and the L-BFGS solve does it. x: 3n positions, in place. Runs `iterations` times or
/// until no vertex moves more than `tolerance` (mesh units); each global step's conjugate
/// gradients stop at the relative residual `solve_tolerance`. Returns the iterations made.
int local_global(const MeshEnergy& energy, int n, int iterations, int projection_steps, double max_step,
                 double tolerance, double solve_tolerance, const WorkerTeam& team, std::vector<double>& x);

}  // namespace sketchsurf::detail
