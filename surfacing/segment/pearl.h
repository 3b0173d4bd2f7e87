#pragma once
// Segmentation of the proxy into regions, one implicit polynomial per region: the energy of
// Eq. 1-4 minimised by PEARL (paper §4.2, Algorithm 1) from spectral-clustering initial models,
// with restarts, and the scribble constraints of §5 (Eq. 10).

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "surfacing/mesh.h"
#include "surfacing/progress.h"
#include "surfacing/segment/association.h"
#include "surfacing/segment/implicit.h"
#include "surfacing/segment/simplify.h"
#include "surfacing/sketch/sketch.h"

namespace sketchsurf {

/// Every tunable of the segmentation, with the paper's defaults. Lengths are fractions of the
/// sketch's bounding-box diagonal: the work happens in coordinates where that diagonal is 1.
struct SegmentOptions {
  double epsilon = 0.01;      ///< eps of E_fidelity, fraction of the diagonal (Eq. 2)
  double w_smooth = 5.0;      ///< weight of E_smoothness (Eq. 1, 3; the paper has 10, which keeps
                              ///< curved models wrapped round thin faces drawn only by their rims)
  double w_simp = 0.01;       ///< weight of E_simplicity (Eq. 1, 4)
  double mu = 0.1;            ///< proxy-normal alignment weight of the fit (Eq. 6)
  double lambda = 1.0;        ///< L2 regularisation of the fit (Eq. 6, App. B)
  double init_boost = 10.0;   ///< mu and lambda multiplier for the initial fits (§4.2)
  std::vector<int> cluster_counts{20, 30, 40, 50};  ///< spectral clusterings k (§4.2)
  int max_degree = 4;         ///< degree of the initial fits, highest degree (§4.2: d <= 4)
  int merges_per_iteration = 3;  ///< merge proposals per PEARL iteration (§4.2)
  bool all_lower_degrees = true;  ///< propose fits of every degree below d, not only d - 1 (§4.2
                                  ///< has d - 1; ours: that ladder stalls on a plane whose degree-3
                                  ///< fit is worse than its degree-4 and degree-1 fits)
  int max_iterations = 30;    ///< cap on PEARL iterations (public implementation)
  double min_gain = 0.003;    ///< a run also stops after a step that lowered the energy by less
                              ///< than this fraction (0: only at a stable labeling or the cap).
                              ///< The last steps of a run move a few vertices each: against 0 on
                              ///< 9 real sketches x 3 seeds, 10 restarts: 0.74-0.99x the CPU
                              ///< (01-0-1 0.76, Dungeon_Chest 0.74), mean energy -0.4% to +0.2%,
                              ///< best of 10 within +0.16%; 0.001: 0.81-1.0x; 0.01: 0.62-0.93x
                              ///< but up to +1.3% (mean) and +2.6% (best)
  int restarts = 10;          ///< independent runs, lowest energy kept (§4.2, Fig. 7)
  double tie = 0.01;          ///< runs whose energy is within this fraction of the lowest are
                              ///< equally good explanations of the strokes, but can differ in
                              ///< shape between them: a shield's back drawn by its rim and one
                              ///< meridian is a quartic folding across the face in the lowest run
                              ///< and a smooth cap in another just above it. Of those runs, the
                              ///< one whose models would move the fewest proxy vertices farther
                              ///< than tie_distance (projected as the final mesh starts) is kept,
                              ///< when that share is lower by more than tie_share than the lowest
                              ///< run's (ours; 0 = the lowest energy only)
  double tie_distance = 0.03; ///< fraction of the diagonal (the final mesh's trust distance)
  double tie_share = 0.01;    ///< fraction of the proxy's vertices
  double fold = 0.1;          ///< a wider window for a fold: of the runs within this fraction of
                              ///< the lowest energy, the one with the fewest far vertices is kept
                              ///< when the run the tie rule kept has more by over fold_share. A
                              ///< model folding across a face moves a third of the proxy far, in a
                              ///< run a few percent below a smooth one (ours; 0 = off)
  double fold_share = 0.15;   ///< fraction of the proxy's vertices
  std::uint64_t seed = 123;   ///< base seed; restart r uses a seed derived from it and r
  unsigned threads = 0;       ///< worker threads (0 = all); results do not depend on it
  int expansion_sweeps = 1;   ///< alpha-expansion passes over the labels per PEARL step (1).
                              ///< One pass, then refit and propose: PEARL only needs each step
                              ///< to lower the energy, and a run still ends at a labeling that no
                              ///< expansion improves (a step that accepts no move is its last).
                              ///< Against 10 (passes until none is accepted; 3 on average, the
                              ///< last one rejecting every move) on 8 real sketches x 6 seeds, 10
                              ///< restarts: 0.56-0.67x the CPU, mean energy per sketch -3.4% to
                              ///< +1.4% (all 48: -0.5%; lower in 26), within the seed-to-seed
                              ///< spread (3-10%). 2 passes: 0.73-0.90x, no lower energy
  double penalty_factor = 10.0;  ///< scribble penalty rho = (penalty_factor * epsilon)^2 (Eq. 10),
                                 ///< a squared distance, normalised like E_fidelity (Eq. 2)
  bool simplify = true;       ///< label a coarsened graph (App. C) and propagate back
  AssociationOptions association;   ///< stroke-to-proxy association (App. A)
  SimplifyOptions simplification;   ///< graph simplification (App. C)
  bool valid(std::string* why) const;
};

/// The energy of Eq. 1 split into its terms (unweighted), for a labeling of the proxy.
struct SegmentEnergy {
  double fidelity = 0.0;    ///< Eq. 2
  double smoothness = 0.0;  ///< Eq. 3 on the proxy's edges
  double simplicity = 0.0;  ///< Eq. 4
  double total = 0.0;       ///< Eq. 1: fidelity + w_smooth smoothness + w_simp simplicity
};

/// What a segmentation run did.
struct SegmentationSummary {
  SegmentEnergy energy;          ///< of the returned labeling, on the proxy
  int iterations = 0;            ///< PEARL iterations of the kept run
  bool converged = false;        ///< the kept run stopped because its labeling was stable or its
                                 ///< last step gained less than min_gain (not at the cap)
  int restarts = 0;              ///< runs made
  int best_restart = 0;          ///< index of the kept run
  std::vector<double> restart_energies;  ///< total energy (on the labelled graph) of each run
  std::vector<double> restart_departures;  ///< with options.tie > 0, per run: share of the
                                           ///< proxy's vertices that projecting onto their
                                           ///< region's model moves farther than tie_distance
  std::vector<double> energy_history;    ///< kept run: total energy after each step (1)
  int initial_models = 0;        ///< models proposed by the initialisation
  int graph_vertices = 0;        ///< vertices of the labelled (simplified) graph
  int proxy_vertices = 0;
  std::size_t associated_points = 0;  ///< N_p of Eq. 2
  std::size_t crease_guides = 0;      ///< creases joined from stroke corners (crease_guides.h)
  double association_s = 0.0;    ///< wall time: association and graph simplification
  double init_s = 0.0;           ///< wall time: spectral clustering and initial fits
  double segmentation_s = 0.0;   ///< wall time: PEARL runs (all restarts) or the scribble re-run
};

/// A labeling of the proxy's vertices and one model per label.
struct Segmentation {
  std::vector<int> labels;            ///< per proxy vertex, index into models
  std::vector<ImplicitModel> models;  ///< one per label in use (labels are compacted 0..k-1), input units
  SegmentationSummary summary;
};

/// Segmentation state kept between runs, so that scribbles re-run PEARL from step (1) without
/// re-associating the strokes or re-initialising (§5 "User control").
class Segmenter {
 public:
  /// Normalises the inputs (unit diagonal), associates the strokes with the proxy (App. A),
  /// simplifies the graph (App. C) and fits the initial models (§4.2). `proxy` must not hold
  /// deleted elements (its vertex indices are those of the labels). Throws Error (Usage) for
  /// invalid options or a proxy with deleted elements, Error (Processing) when the sketch has no
  /// usable stroke or the proxy no triangle, Error (Cancelled) through `progress`.
  Segmenter(const Sketch& sketch, const TriMesh& proxy, const SegmentOptions& options = {},
            const Progress& progress = {});
  ~Segmenter();
  Segmenter(Segmenter&&) noexcept;
  Segmenter& operator=(Segmenter&&) noexcept;

  /// Runs PEARL options.restarts times in parallel from the initial models, keeps the run of
  /// lowest energy (or, of the runs within options.tie of it, the one whose models would move the
  /// fewest proxy vertices far) and returns it. Deterministic for the seed whatever the thread
  /// count.
  Segmentation run(const Progress& progress = {});

  /// Scribble "insert a region" (§5): fits a new model to the stroke points of `vertices` (proxy
  /// vertex indices), penalises every other label on them with rho (Eq. 10) and re-runs PEARL
  /// from step (1) on the current result. Requires a previous run(). Throws Error (Usage) for an
  /// empty or out-of-range vertex set or no previous run, Error (Processing) when the scribbled
  /// vertices have no stroke point.
  Segmentation insert_region(const std::vector<int>& vertices, const Progress& progress = {});
  /// Scribble "merge regions" (§5): fits a new model to the stroke points of every vertex that
  /// shares a label with a scribbled vertex and is connected to it within that label, penalises
  /// other labels on the scribbled vertices (Eq. 10), re-runs PEARL from step (1).
  Segmentation merge_regions(const std::vector<int>& vertices, const Progress& progress = {});

  /// The association on normalised coordinates (unit diagonal, centred on the sketch's box).
  const StrokeGraph& association() const;
  /// The labelled graph (the proxy's when options.simplify is off).
  const SimplifiedGraph& graph() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// One-shot segmentation: Segmenter(sketch, proxy, options, progress).run(progress).
Segmentation segment(const Sketch& sketch, const TriMesh& proxy, const SegmentOptions& options = {},
                     const Progress& progress = {});

}  // namespace sketchsurf
