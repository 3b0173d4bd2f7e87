#pragma once
// Final mesh optimisation (paper §4.3, Eq. 7-9, and App. D Eq. 13): move the seamed mesh onto the
// implicit surfaces of its regions while keeping it regular.
//
// How E_mesh is minimised (the paper's choice, §4.3: a first-order method with precomputed
// matrices for the quadratic terms): each vertex is first projected onto its surfaces, then a few
// local-global iterations (global_step.h) spread that move over the mesh, then a Jacobi-scaled
// L-BFGS (lbfgs.h) on E_mesh (energy.h) does the rest. The Laplacian terms make E_mesh stiff: the
// start decides the iteration count, and the stall test (stall_window, stall_tolerance) stops once
// the surface has settled, long before the energy stops falling. Trust-region solvers with sparse
// factorisations (Ceres) are kept for comparison outside the library (trust_region.h, tests and
// benchmarks only). The measurements behind every default are in docs/performance.md.

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "surfacing/extract/outline.h"
#include "surfacing/extract/seams.h"
#include "surfacing/progress.h"
#include "surfacing/segment/implicit.h"
#include "surfacing/sketch/sketch.h"
#include "surfacing/sketch/stroke_segments.h"

namespace sketchsurf {

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
  double trust_distance = 0.03;      ///< a vertex that those steps would take farther than this
                                     ///< away from the strokes (fraction of the mesh's diagonal)
                                     ///< has no surface of its regions near it (a far branch of the
                                     ///< zero set, a model extrapolated past its strokes): it stays
                                     ///< with the proxy, held at its start by E_attract instead of
                                     ///< projected; 0 = no limit (ours; the Surfacer sets 0 with a
                                     ///< user's proxy, rough by design)
  double box_margin = 0.02;          ///< a vertex that those steps would take outside the strokes'
                                     ///< bounding box grown by this (fraction of the mesh's
                                     ///< diagonal), from inside it, also stays with the proxy: no
                                     ///< stroke asks for surface there (an undrawn back that a
                                     ///< region's model bulges past the sketch); 0 = no such test
                                     ///< (ours; the Surfacer sets 0 with a user's proxy)
  int local_global_iterations = 5;   ///< local-global iterations after the projection, 0 = none
                                     ///< (ours; each costs ~10 L-BFGS iterations)
  double local_global_tolerance = 1e-3;  ///< they stop early when no vertex moves more, fraction
                                         ///< of the mean edge length
  double global_step_tolerance = 3e-2;   ///< residual reduction of each global step's conjugate
                                         ///< gradients (ours)
  int lbfgs_rank = 8;                ///< L-BFGS memory (pairs kept; 20, Ceres' default, spends 40%
                                     ///< of the time in the two-loop recursion)
  int max_iterations = 300;          ///< solver iterations (L-BFGS or trust-region): a cap; on
                                     ///< real sketches the stall test acts first
  double function_tolerance = 1e-8;  ///< relative cost decrease that stops the solver
  int stall_window = 50;             ///< L-BFGS also stops when E_mesh fell by less than
  double stall_tolerance = 0.05;     ///< stall_tolerance (relative) over the last stall_window
                                     ///< iterations; 0 = no such stop (ours)
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
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< a boundary-stroke point or the vertex's
                                                  ///< proxy position, mesh units
  double weight = 1.0;                            ///< share of attract_weight for this target
};

/// Extra constraints of E_mesh: open boundaries and the mirror plane.
struct MeshConstraints {
  std::vector<AttractTarget> attract;  ///< E_attract targets (App. D)
  std::optional<Plane> plane;          ///< mirror plane, when the mesh is half of a symmetric one
  std::vector<int> plane_vertices;     ///< vertices that must stay on `plane` (its boundary there)
  std::vector<int> held;               ///< vertices with no E_project term, not projected at the
                                       ///< start either (each also needs an `attract` target, or
                                       ///< only the Laplacian places it)
  std::vector<int> inside;             ///< single-label vertices projected onto the level set
                                       ///< `inside_gap` inside their model's zero set instead of
                                       ///< the zero set: a thin part's far side (back_sides.h)
  double inside_gap = 0.0;             ///< mesh units
  std::optional<StrokeSegments> strokes;  ///< the strokes, for trust_distance (none: no limit)
  std::vector<std::vector<PlaneOutline>> outlines;  ///< per model, or empty: a flat region's
                                                    ///< drawn outlines (outline.h); a vertex that
                                                    ///< the solve leaves farther than
                                                    ///< outline_margin outside one is held at its
                                                    ///< closest point of the outline instead
  double outline_margin = 0.0;         ///< mesh units
  std::vector<int> on_drawn_face;      ///< vertices on a face the proxy drew in where the strokes
                                       ///< draw one (ProxyReport::drawn_faces): flat, bounded by
                                       ///< its strokes. One farther than trust_distance from the
                                       ///< strokes that those steps would take farther than that
                                       ///< off the face stays there: a region's model that bulges
                                       ///< into or out of a face with no stroke on it is
                                       ///< extrapolated from the strokes round it
};

/// Moves each vertex onto the intersection of its labels' surfaces by damped Gauss-Newton steps
/// (least-norm dx with f_i + grad f_i . dx = 0), each step at most `max_step` long: the start of
/// optimize_mesh(), which leaves L-BFGS mostly the regularisation to do. Vertices marked `held`
/// (one entry per vertex) stay. `inside` (one entry per vertex, or empty: all 0): a single-label
/// vertex's target is the level set that far inside its model's zero set (Taubin distance).
/// The result does not depend on `threads`.
void project_vertices(LabeledMesh& lm, const std::vector<ImplicitModel>& models, int steps,
                      double max_step, unsigned threads, const std::vector<char>& held,
                      const std::vector<double>& inside = {});

/// Per vertex (n of them): constraints.inside_gap for the vertices of constraints.inside, else 0.
std::vector<double> inside_offsets(const MeshConstraints& constraints, int n);

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
  std::size_t held_vertices = 0;    ///< vertices kept with the proxy (trust_distance)
  std::size_t outline_vertices = 0; ///< vertices held on a flat region's drawn outline
  std::size_t face_vertices = 0;    ///< vertices held on a face drawn in (on_drawn_face; also
                                    ///< counted in held_vertices)
  std::string termination;  ///< termination type and message (in Ceres' words: CONVERGENCE, ...)
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
/// local_global_iterations local-global iterations, then L-BFGS:
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

class WorkerTeam;

namespace detail {

struct MeshEnergy;
class MeshEnergyFunction;

/// Minimises E_mesh from the start x (3n values, in place; `size` the mesh's bounding-box
/// diagonal) and fills summary's final, iterations, termination, solver and usable.
using MeshMinimizer = std::function<void(const MeshEnergy& energy, const MeshEnergyFunction& function,
                                         const WorkerTeam& team, std::vector<double>& x, double size,
                                         OptimizeSummary& summary)>;

/// optimize_mesh() with another minimiser after the same start (checks, projection,
/// local-global iterations) and the same end (non-finite check, plane snap): what lets the
/// trust-region comparison (trust_region.h) live outside the library.
OptimizeSummary optimize_mesh_with(LabeledMesh& mesh, const std::vector<ImplicitModel>& models,
                                   const MeshConstraints& constraints, const MeshEnergyOptions& options,
                                   const Progress& progress, const MeshMinimizer& minimize);

}  // namespace detail

}  // namespace sketchsurf
