#include "surfacing/segment/pearl.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <random>
#include <span>
#include <thread>
#include <unordered_map>

#include "surfacing/error.h"
#include "surfacing/parallel.h"
#include "surfacing/portable_math.h"
#include "surfacing/segment/expansion.h"
#include "surfacing/segment/spectral.h"

namespace sketchsurf {

namespace {

using Clock = std::chrono::steady_clock;
using V3 = Eigen::Vector3d;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// splitmix64: independent, well-mixed seeds for restart r and step i from one base seed.
std::uint64_t mix_seed(std::uint64_t seed, std::uint64_t salt) {
  std::uint64_t z = seed + 0x9e3779b97f4a7c15ULL * (salt + 1);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// Taubin distances can be infinite (f != 0 where grad f = 0); cap a point's squared distance at
// the squared diagonal (1 in normalised units) so graph-cut costs stay finite.
constexpr double kMaxDistance2 = 1.0;

// A model (normalised coordinates) with its squared distance to every associated point. Immutable
// once made, shared between restarts.
struct Candidate {
  ImplicitModel model;
  std::vector<double> dist2;    // #P
  std::vector<int> fitted_on;   // labelled-graph vertices (increasing) of a PEARL fit, else empty
};
using CandidatePtr = std::shared_ptr<const Candidate>;

std::uint64_t members_hash(int degree, const std::vector<int>& members) {
  std::uint64_t h = mix_seed(static_cast<std::uint64_t>(degree), members.size());
  for (int v : members) h = mix_seed(h, static_cast<std::uint64_t>(v));
  return h;
}

// The PEARL fits (steps 2 and 3) of one run by degree and labelled-graph vertices: a region that
// has not changed since an earlier iteration gets the identical fit, looked up instead of
// recomputed. Fits not asked for during an iteration are forgotten at its end.
class FitCache {
 public:
  CandidatePtr find(int degree, const std::vector<int>& members) {
    const auto it = entries_.find(members_hash(degree, members));
    if (it == entries_.end()) return nullptr;
    for (Entry& e : it->second)
      if (e.candidate->model.degree == degree && e.candidate->fitted_on == members) {
        e.used = true;
        return e.candidate;
      }
    return nullptr;
  }
  void insert(CandidatePtr c) {
    entries_[members_hash(c->model.degree, c->fitted_on)].push_back({std::move(c), true});
  }
  void end_iteration() {
    for (auto it = entries_.begin(); it != entries_.end();) {
      auto& list = it->second;
      std::erase_if(list, [](const Entry& e) { return !e.used; });
      for (Entry& e : list) e.used = false;
      it = list.empty() ? entries_.erase(it) : std::next(it);
    }
  }

 private:
  struct Entry {
    CandidatePtr candidate;
    bool used = false;
  };
  std::unordered_map<std::uint64_t, std::vector<Entry>> entries_;
};

// Scribble constraint (Eq. 10): the labelled-graph vertices that should take label `label`.
struct Constraint {
  std::vector<int> vertices;
  int label = -1;
};

// A labeling of the labelled graph and the candidate models its labels index.
struct RunState {
  std::vector<CandidatePtr> models;
  std::vector<int> labels;  // per labelled-graph vertex
  std::vector<Constraint> constraints;
};

struct RunResult {
  RunState state;
  double energy = 0.0;
  int iterations = 0;
  bool converged = false;
  std::vector<double> history;
};

// Progress of the PEARL runs, reported after every iteration of any run but only from the calling
// thread (callbacks need not be thread-safe). PEARL's iteration count is not known in advance (5-12
// on the real sketches), so a run counts 1 - 0.7^iterations until it finishes, then 1; the
// reported fraction never decreases. A cancellation seen by the caller stops every run at its next
// iteration.
class RunProgress {
 public:
  RunProgress(const Progress& progress, int runs)
      : progress_(progress), iterations_(runs), finished_(runs), caller_(std::this_thread::get_id()) {}
  void iteration_done(std::size_t run) {
    ++iterations_[run];
    report();
  }
  void run_done(std::size_t run) {
    finished_[run] = true;
    report();
  }
  bool stopped() const { return stop_.load(); }
  void stop() { stop_ = true; }

 private:
  void report() {
    if (std::this_thread::get_id() != caller_) return;
    double sum = 0.0;
    for (std::size_t r = 0; r < iterations_.size(); ++r)
      sum += finished_[r] ? 1.0 : 1.0 - portable::pow(0.7, iterations_[r].load());
    reported_ = std::max(reported_, std::min(sum / static_cast<double>(iterations_.size()), 1.0));
    try {
      progress_.update("segmentation", reported_);
    } catch (...) {
      stop();
      throw;
    }
  }

  const Progress& progress_;
  std::vector<std::atomic<int>> iterations_;
  std::vector<std::atomic<bool>> finished_;
  std::thread::id caller_;
  std::atomic<bool> stop_{false};
  double reported_ = 0.0;  // caller thread only
};

}  // namespace

bool SegmentOptions::valid(std::string* why) const {
  auto fail = [&](const std::string& m) {
    if (why) *why = m;
    return false;
  };
  auto positive = [](double x) { return x > 0 && std::isfinite(x); };
  auto non_negative = [](double x) { return x >= 0 && std::isfinite(x); };
  if (!positive(epsilon)) return fail("segment epsilon must be positive");
  if (!non_negative(w_smooth)) return fail("segment w_smooth must be >= 0");
  if (!non_negative(w_simp)) return fail("segment w_simp must be >= 0");
  if (!non_negative(mu)) return fail("segment mu must be >= 0");
  if (!non_negative(lambda)) return fail("segment lambda must be >= 0");
  if (!positive(init_boost)) return fail("segment init_boost must be positive");
  if (cluster_counts.empty()) return fail("segment cluster_counts must not be empty");
  for (int k : cluster_counts)
    if (k < 1) return fail("segment cluster_counts must be positive");
  if (max_degree < 1 || max_degree > kMaxImplicitDegree)
    return fail("segment max_degree must be in 1..4");
  if (merges_per_iteration < 0) return fail("segment merges_per_iteration must be >= 0");
  if (max_iterations < 1) return fail("segment max_iterations must be at least 1");
  if (!(min_gain >= 0.0 && min_gain < 1.0)) return fail("segment min_gain must be in [0, 1)");
  if (restarts < 1) return fail("segment restarts must be at least 1");
  if (!non_negative(tie)) return fail("segment tie must be >= 0");
  if (!positive(tie_distance)) return fail("segment tie_distance must be positive");
  if (!(tie_share >= 0.0 && tie_share < 1.0)) return fail("segment tie_share must be in [0, 1)");
  if (!non_negative(fold)) return fail("segment fold must be >= 0");
  if (!(fold_share >= 0.0 && fold_share < 1.0)) return fail("segment fold_share must be in [0, 1)");
  if (expansion_sweeps < 1) return fail("segment expansion_sweeps must be at least 1");
  if (!non_negative(penalty_factor)) return fail("segment penalty_factor must be >= 0");
  std::string sub;
  if (!association.valid(&sub)) return fail(sub);
  if (!simplification.valid(&sub)) return fail(sub);
  return true;
}

struct Segmenter::Impl {
  SegmentOptions options;
  V3 origin = V3::Zero();  // input = origin + unit * normalised
  double unit = 1.0;
  StrokeGraph graph;       // normalised
  SimplifiedGraph coarse;
  // Per labelled-graph vertex: the moments of its proxy vertices without stroke points (the normal
  // points of every fit, App. B), added up over a region instead of visited in each of its fits.
  std::vector<NormalMoments> normal_moments;
  double fidelity_scale = 0.0;  // 1 / (eps^2 N_p)
  double smooth_scale = 0.0;    // w_smooth / W, W the proxy's total edge weight
  FitOptions fit;
  FitOptions boosted_fit;
  std::vector<CandidatePtr> initial;
  SegmentationSummary base_summary;
  std::optional<RunState> current;

  // ---- models ----

  CandidatePtr make_candidate(ImplicitModel model, std::vector<int> fitted_on = {}) const {
    auto c = std::make_shared<Candidate>();
    c->fitted_on = std::move(fitted_on);
    c->dist2.resize(graph.points.rows());
    implicit_distances(model, graph.points, c->dist2.data());
    for (double& d : c->dist2) d = std::isfinite(d) ? std::min(d * d, kMaxDistance2) : kMaxDistance2;
    c->model = std::move(model);
    return c;
  }

  // Fits a model of `degree` to the labelled-graph vertices `members` (Eq. 6): the stroke points
  // of their proxy vertices, and the normals of those without stroke points, through their
  // moments (a vertex with stroke points is never merged, App. C: its points are its survivor's).
  // nullopt without stroke points.
  std::optional<ImplicitModel> fit_members(const std::vector<int>& members, int degree,
                                           const FitOptions& fit_options) const {
    NormalMoments normals;
    std::vector<int> points;
    for (int vc : members) {
      normals += normal_moments[vc];
      const auto pv = graph.points_of(coarse.coarse_to_fine[vc]);
      points.insert(points.end(), pv.begin(), pv.end());
    }
    return fit_points(std::move(points), normals, degree, fit_options);
  }

  // The same for the proxy vertices `fine` (scribbles).
  std::optional<ImplicitModel> fit_vertices(const std::vector<int>& fine, int degree,
                                            const FitOptions& fit_options) const {
    NormalMoments normals;
    std::vector<int> points;
    for (int v : fine) {
      const auto pv = graph.points_of(v);
      if (pv.empty()) normals.add(graph.positions.row(v), graph.normals.row(v));
      points.insert(points.end(), pv.begin(), pv.end());
    }
    return fit_points(std::move(points), normals, degree, fit_options);
  }

  // Fits the stroke points `points` (indices; a sample attached to several vertices counts once).
  std::optional<ImplicitModel> fit_points(std::vector<int> points, const NormalMoments& normals,
                                          int degree, const FitOptions& fit_options) const {
    std::sort(points.begin(), points.end());
    points.erase(std::unique(points.begin(), points.end()), points.end());
    if (points.empty()) return std::nullopt;
    Eigen::MatrixX3d P(points.size(), 3);
    for (std::size_t i = 0; i < points.size(); ++i) P.row(i) = graph.points.row(points[i]);
    return fit_implicit(degree, P, normals, fit_options);
  }

  // E_fidelity (unscaled) of the labelled-graph vertices `vertices` under a candidate.
  double fidelity_of(const Candidate& c, const std::vector<int>& coarse_vertices) const {
    double sum = 0.0;
    for (int vc : coarse_vertices)
      for (int p : graph.points_of(coarse.coarse_to_fine[vc])) sum += c.dist2[p];
    return sum;
  }

  // ---- the labeling problem ----

  LabelingProblem problem(const RunState& s) const {
    const int n = coarse.vertex_count, L = static_cast<int>(s.models.size());
    LabelingProblem pr;
    pr.data_cost = Eigen::MatrixXd::Zero(n, L);
    for (int vc = 0; vc < n; ++vc) {
      const auto pv = graph.points_of(coarse.coarse_to_fine[vc]);
      if (pv.empty()) continue;
      for (int a = 0; a < L; ++a) {
        double sum = 0.0;
        for (int p : pv) sum += s.models[a]->dist2[p];
        pr.data_cost(vc, a) = fidelity_scale * sum;
      }
    }
    // Eq. 10's rho = (10 eps)^2 is a squared distance: it goes through Eq. 2's normalisation
    // like the fidelity of a point 10 eps away from its model.
    const double penalty_distance = options.penalty_factor * options.epsilon;
    const double rho = penalty_distance * penalty_distance * fidelity_scale;
    for (const auto& c : s.constraints)
      for (int vc : c.vertices)
        for (int a = 0; a < L; ++a)
          if (a != c.label) pr.data_cost(vc, a) += rho;
    pr.edges = coarse.edges;
    pr.edge_weights.resize(coarse.weights.size());
    for (std::size_t e = 0; e < coarse.weights.size(); ++e)
      pr.edge_weights[e] = smooth_scale * coarse.weights[e];
    pr.label_cost.resize(L);
    for (int a = 0; a < L; ++a)
      pr.label_cost[a] = options.w_simp * s.models[a]->model.dimension() / 35.0;
    return pr;
  }

  // Drops the labels no vertex uses (Algorithm 1 after step (1)), keeping constraints attached.
  static void drop_unused(RunState& s) {
    std::vector<int> remap(s.models.size(), -1);
    std::vector<CandidatePtr> kept;
    for (int& l : s.labels) {
      if (remap[l] < 0) {
        remap[l] = static_cast<int>(kept.size());
        kept.push_back(s.models[l]);
      }
      l = remap[l];
    }
    s.models = std::move(kept);
    std::vector<Constraint> constraints;
    for (auto& c : s.constraints)
      if (c.label >= 0 && remap[c.label] >= 0) constraints.push_back({c.vertices, remap[c.label]});
    s.constraints = std::move(constraints);
  }

  // Labelled-graph vertices of each label.
  std::vector<std::vector<int>> coarse_members(const std::vector<int>& labels, int count) const {
    std::vector<std::vector<int>> members(count);
    for (int vc = 0; vc < coarse.vertex_count; ++vc) members[labels[vc]].push_back(vc);
    return members;
  }

  // The PEARL fit (options.mu, options.lambda) of `degree` to the labelled-graph vertices
  // `members` (increasing), through the run's cache; nullptr when they have no stroke point.
  CandidatePtr fit_region(const std::vector<int>& members, int degree, FitCache& cache) const {
    if (CandidatePtr c = cache.find(degree, members)) return c;
    auto model = fit_members(members, degree, fit);
    if (!model) return nullptr;
    CandidatePtr c = make_candidate(std::move(*model), members);
    cache.insert(c);
    return c;
  }

  // Step (2): refit every used model; keep the refit only if it lowers E_fidelity on its
  // vertices, else add it as a new candidate (§4.2). A model that is already the fit of its
  // region's vertices is left as it is (its refit is itself). Returns whether a model was replaced.
  bool refit(RunState& s, FitCache& cache) const {
    bool replaced = false;
    const int L = static_cast<int>(s.models.size());
    const auto members = coarse_members(s.labels, L);
    for (int a = 0; a < L; ++a) {
      CandidatePtr c = fit_region(members[a], s.models[a]->model.degree, cache);
      if (!c || c == s.models[a]) continue;
      if (fidelity_of(*c, members[a]) < fidelity_of(*s.models[a], members[a])) {
        s.models[a] = std::move(c);
        replaced = true;
      } else {
        s.models.push_back(std::move(c));
      }
    }
    return replaced;
  }

  // Step (3): lower-degree fits of every used model, and merges of the neighbouring label
  // pairs separated by the most edge weight (§4.2).
  void propose(RunState& s, int used, FitCache& cache) const {
    const auto members = coarse_members(s.labels, used);
    for (int a = 0; a < used; ++a) {
      const int d = s.models[a]->model.degree;
      const int lowest = options.all_lower_degrees ? 1 : std::max(1, d - 1);
      for (int lower = d - 1; lower >= lowest; --lower)
        if (CandidatePtr c = fit_region(members[a], lower, cache)) s.models.push_back(std::move(c));
    }
    std::map<std::pair<int, int>, double> between;
    for (std::size_t e = 0; e < coarse.edges.size(); ++e) {
      int a = s.labels[coarse.edges[e][0]], b = s.labels[coarse.edges[e][1]];
      if (a == b) continue;
      if (a > b) std::swap(a, b);
      between[{a, b}] += coarse.weights[e];
    }
    std::vector<std::pair<double, std::pair<int, int>>> pairs;
    for (const auto& [ab, w] : between) pairs.push_back({-w, ab});
    std::sort(pairs.begin(), pairs.end());
    const int merges = std::min<int>(options.merges_per_iteration, static_cast<int>(pairs.size()));
    for (int i = 0; i < merges; ++i) {
      const auto [a, b] = pairs[i].second;
      std::vector<int> both;
      std::merge(members[a].begin(), members[a].end(), members[b].begin(), members[b].end(),
                 std::back_inserter(both));
      const int degree = std::max(s.models[a]->model.degree, s.models[b]->model.degree);
      if (CandidatePtr c = fit_region(both, degree, cache)) s.models.push_back(std::move(c));
    }
  }

  // Algorithm 1 from step (1) on `s`, until the labeling is stable or the iteration cap.
  // Reports each iteration to progress as run `run`.
  //
  // When a step's expansion converged (no move of its labels improves the labeling) and refit
  // then replaces no model, the next step starts from that labeling with the same data costs for
  // every vertex's label, so the expansion of every label of the last step is the same move as
  // before and fails again: those labels are skipped until a move is accepted
  // (ExpansionOptions::known_to_fail; the same labels as trying them). Saved about 2% of the
  // moves with 10 expansion sweeps per step (chair 19,316 -> 19,014; 01-0-1 33,658 -> 32,990):
  // refit usually replaces some model.
  RunResult pearl(RunState s, std::uint64_t seed, RunProgress& progress, std::size_t run) const {
    RunResult r;
    FitCache cache;
    std::vector<CandidatePtr> failed;  // labels known to fail at s.labels (sorted; owned, so no
                                       // new candidate can reuse an address in the list)
    for (int it = 0; it < options.max_iterations; ++it) {
      if (progress.stopped()) throw Error(ErrorKind::Cancelled, "cancelled during segmentation");
      ExpansionOptions eo;
      eo.max_sweeps = options.expansion_sweeps;
      eo.seed = mix_seed(seed, static_cast<std::uint64_t>(it));
      if (!failed.empty()) {
        eo.known_to_fail.resize(s.models.size());
        for (std::size_t a = 0; a < s.models.size(); ++a)
          eo.known_to_fail[a] = std::binary_search(failed.begin(), failed.end(), s.models[a]);
      }
      const ExpansionSummary ex = alpha_expansion(problem(s), s.labels, eo);
      const bool stable = ex.labels == s.labels;
      s.labels = ex.labels;
      r.history.push_back(ex.energy);
      r.iterations = it + 1;
      failed.clear();
      if (ex.converged) failed = s.models;
      drop_unused(s);
      const int used = static_cast<int>(s.models.size());
      if (refit(s, cache)) failed.clear();
      std::sort(failed.begin(), failed.end());
      progress.iteration_done(run);
      const bool small_gain = it > 0 && r.history[it - 1] - ex.energy < options.min_gain * r.history[it - 1];
      if (stable || small_gain) {
        r.converged = true;
        break;
      }
      propose(s, used, cache);
      cache.end_iteration();
    }
    drop_unused(s);
    r.energy = labeling_energy(problem(s), s.labels);
    r.state = std::move(s);
    return r;
  }

  // ---- results ----

  // Share of the proxy's vertices that projecting onto their region's model moves farther than
  // `far` (normalised units; the final mesh's start: Newton steps along the gradient, each at most
  // kStep): how much of the proxy the models would move far (a fold across a face), not the detail
  // they correct.
  double departure(const RunState& s, double far) const {
    constexpr int kSteps = 5;
    constexpr double kStep = 0.02;
    const std::vector<int> fine = coarse.propagate(s.labels);
    std::size_t count = 0;
    for (std::size_t v = 0; v < fine.size(); ++v) {
      const ImplicitModel& model = s.models[fine[v]]->model;
      const Eigen::Vector3d start = graph.positions.row(static_cast<Eigen::Index>(v)).transpose();
      Eigen::Vector3d x = start;
      for (int k = 0; k < kSteps; ++k) {
        const Eigen::Vector3d g = model.gradient(x);
        Eigen::Vector3d dx = -(model.value(x) / g.squaredNorm()) * g;
        if (!dx.allFinite()) break;
        if (dx.norm() > kStep) dx *= kStep / dx.norm();
        x += dx;
      }
      count += (x - start).norm() > far;
    }
    return fine.empty() ? 0.0 : static_cast<double>(count) / static_cast<double>(fine.size());
  }

  ImplicitModel to_input_units(ImplicitModel m) const {
    m.center = origin + unit * m.center;
    m.scale = unit * m.scale;
    return m;
  }

  Segmentation result(const RunState& s) const {
    Segmentation out;
    const std::vector<int> fine = coarse.propagate(s.labels);
    std::vector<int> remap(s.models.size(), -1);
    out.labels.resize(fine.size());
    for (std::size_t v = 0; v < fine.size(); ++v) {
      int& r = remap[fine[v]];
      if (r < 0) {
        r = static_cast<int>(out.models.size());
        out.models.push_back(to_input_units(s.models[fine[v]]->model));
      }
      out.labels[v] = r;
    }
    // Eq. 1-4 on the proxy itself (the labelled graph may be coarser).
    SegmentEnergy& E = out.summary.energy;
    double fid = 0.0;
    for (int v = 0; v < graph.vertex_count(); ++v)
      for (int p : graph.points_of(v)) fid += s.models[fine[v]]->dist2[p];
    E.fidelity = fidelity_scale * fid;
    double cut = 0.0, W = 0.0;
    for (std::size_t e = 0; e < graph.edges.size(); ++e) {
      W += graph.weights[e];
      if (fine[graph.edges[e][0]] != fine[graph.edges[e][1]]) cut += graph.weights[e];
    }
    E.smoothness = W > 0 ? cut / W : 0.0;
    for (const auto& m : out.models) E.simplicity += m.dimension() / 35.0;
    E.total = E.fidelity + options.w_smooth * E.smoothness + options.w_simp * E.simplicity;
    return out;
  }

  Segmentation rerun_with(RunState s, const Progress& progress) {
    const auto start = Clock::now();
    progress.update("segmentation", 0.0);
    RunProgress runs(progress, 1);
    RunResult r = pearl(std::move(s), mix_seed(options.seed, 0xfeed), runs, 0);
    progress.update("segmentation", 1.0);
    Segmentation out = result(r.state);
    out.summary = finish_summary(out.summary.energy, r, 1, 0, {r.energy});
    out.summary.segmentation_s = seconds_since(start);
    current = std::move(r.state);
    return out;
  }

  SegmentationSummary finish_summary(const SegmentEnergy& energy, const RunResult& r, int runs,
                                     int best, std::vector<double> energies) const {
    SegmentationSummary summary = base_summary;
    summary.energy = energy;
    summary.iterations = r.iterations;
    summary.converged = r.converged;
    summary.restarts = runs;
    summary.best_restart = best;
    summary.restart_energies = std::move(energies);
    summary.energy_history = r.history;
    return summary;
  }

  // Labelled-graph vertices of proxy vertices, validated.
  std::vector<int> scribbled(const std::vector<int>& vertices) const {
    if (!current) throw Error::usage("scribbles need a segmentation: call run() first");
    if (vertices.empty()) throw Error::usage("the scribble covers no vertex");
    std::vector<int> out;
    for (int v : vertices) {
      if (v < 0 || v >= graph.vertex_count())
        throw Error::usage("scribbled vertex " + std::to_string(v) + " is not a proxy vertex (" +
                           std::to_string(graph.vertex_count()) + " vertices)");
      out.push_back(coarse.fine_to_coarse[v]);
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

  Segmentation add_region(const std::vector<int>& fine, const std::vector<int>& scribble,
                          const Progress& progress) {
    auto model = fit_vertices(fine, options.max_degree, fit);
    if (!model) throw Error::processing("the scribbled vertices have no stroke point to fit a surface to");
    RunState s = *current;
    s.models.push_back(make_candidate(std::move(*model)));
    s.constraints.push_back({scribble, static_cast<int>(s.models.size()) - 1});
    return rerun_with(std::move(s), progress);
  }
};

Segmenter::Segmenter(const Sketch& sketch, const TriMesh& proxy, const SegmentOptions& options,
                     const Progress& progress)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  std::string why;
  if (!options.valid(&why)) throw Error::usage(why);
  m.options = options;
  auto start = Clock::now();
  progress.update("association", 0.0);

  // Normalise: the sketch's box centred at the origin with a unit diagonal (METHOD.md).
  const BoundingBox box = sketch.bounding_box();
  if (box.empty() || !(box.diagonal() > 0) || !std::isfinite(box.diagonal()))
    throw Error::processing("the sketch has no extent to segment (empty or a single point)");
  m.origin = 0.5 * (box.min + box.max);
  m.unit = box.diagonal();
  Sketch normalised = sketch;
  for (auto& s : normalised.strokes)
    for (auto& p : s.points) p = (p - m.origin) / m.unit;
  TriMesh mesh = proxy;
  mesh.garbage_collection();
  if (mesh.n_vertices() != proxy.n_vertices())
    throw Error::usage("the proxy mesh has deleted elements: call garbage_collection() first");
  for (auto v : mesh.vertices())
    mesh.set_point(v, to_openmesh((to_eigen(mesh.point(v)) - m.origin) / m.unit));
  AssociationOptions ao = options.association;
  ao.threads = options.threads;
  m.graph = associate(normalised, mesh, ao);
  if (m.graph.association_count() == 0)
    throw Error::processing("no stroke could be associated with the proxy: is the proxy near the strokes?");
  m.coarse = options.simplify ? simplify_graph(std::move(mesh), m.graph, ao, options.simplification)
                              : identity_graph(m.graph);
  m.normal_moments.assign(m.coarse.vertex_count, NormalMoments());
  for (int v = 0; v < m.graph.vertex_count(); ++v)
    if (m.graph.points_of(v).empty())
      m.normal_moments[m.coarse.fine_to_coarse[v]].add(m.graph.positions.row(v).transpose(),
                                                       m.graph.normals.row(v).transpose());
  m.fidelity_scale = 1.0 / (options.epsilon * options.epsilon * m.graph.association_count());
  // W of Eq. 3 on the proxy, also on a coarser graph: a cut along strokes costs the same on both.
  double W = 0.0;
  for (double w : m.graph.weights) W += w;
  m.smooth_scale = W > 0 ? options.w_smooth / W : 0.0;
  m.fit.mu = options.mu;
  m.fit.lambda = options.lambda;
  m.fit.length_unit = 1.0;  // the unit diagonal, as in the paper
  m.boosted_fit = m.fit;
  m.boosted_fit.mu *= options.init_boost;
  m.boosted_fit.lambda *= options.init_boost;
  m.base_summary.association_s = seconds_since(start);
  m.base_summary.graph_vertices = m.coarse.vertex_count;
  m.base_summary.proxy_vertices = m.graph.vertex_count();
  m.base_summary.associated_points = m.graph.association_count();
  m.base_summary.crease_guides = m.graph.guides;
  progress.update("association", 1.0);

  // Initial models (§4.2): spectral clustering of the labelled graph for each k, one fit with
  // boosted regularisation per cluster that has stroke points.
  start = Clock::now();
  progress.update("initialisation", 0.0);
  // One eigen solve for the largest k; each k clusters a prefix of its eigenvectors.
  const auto& ks = options.cluster_counts;
  const int max_k = std::min(*std::max_element(ks.begin(), ks.end()), m.coarse.vertex_count);
  SpectralOptions so;
  so.threads = 1;  // the clusterings themselves run in parallel
  const SpectralClustering spectral(m.coarse.vertex_count, m.coarse.edges, m.coarse.weights,
                                    std::max(max_k, 1), so);
  progress.update("initialisation", 0.2);
  std::vector<std::vector<int>> clusters(ks.size());
  parallel_for(0, ks.size(), options.threads, [&](std::size_t i) {
    const int k = std::max(1, std::min(ks[i], m.coarse.vertex_count));
    clusters[i] = spectral.cluster(k, mix_seed(options.seed, 1000 + i));
  });
  progress.update("initialisation", 0.3);
  std::vector<std::pair<std::size_t, int>> jobs;  // (clustering, cluster)
  std::vector<std::vector<std::vector<int>>> members(ks.size());
  for (std::size_t i = 0; i < ks.size(); ++i) {
    const int k = *std::max_element(clusters[i].begin(), clusters[i].end()) + 1;
    members[i].resize(k);
    for (int vc = 0; vc < m.coarse.vertex_count; ++vc) members[i][clusters[i][vc]].push_back(vc);
    for (int c = 0; c < k; ++c) jobs.push_back({i, c});
  }
  std::vector<CandidatePtr> made(jobs.size());
  parallel_for(0, jobs.size(), options.threads, [&](std::size_t j) {
    auto model = m.fit_members(members[jobs[j].first][jobs[j].second], options.max_degree, m.boosted_fit);
    if (model) made[j] = m.make_candidate(std::move(*model));
  });
  for (auto& c : made)
    if (c) m.initial.push_back(std::move(c));
  if (m.initial.empty()) throw Error::processing("no initial surface model could be fitted to the strokes");
  m.base_summary.initial_models = static_cast<int>(m.initial.size());
  m.base_summary.init_s = seconds_since(start);
  progress.update("initialisation", 1.0);
}

Segmenter::~Segmenter() = default;
Segmenter::Segmenter(Segmenter&&) noexcept = default;
Segmenter& Segmenter::operator=(Segmenter&&) noexcept = default;

const StrokeGraph& Segmenter::association() const { return impl_->graph; }
const SimplifiedGraph& Segmenter::graph() const { return impl_->coarse; }

Segmentation Segmenter::run(const Progress& progress) {
  Impl& m = *impl_;
  const auto start = Clock::now();
  const int runs = m.options.restarts;
  std::vector<std::optional<RunResult>> results(runs);
  progress.update("segmentation", 0.0);
  RunProgress run_progress(progress, runs);
  // Runs take 5 to 12 iterations: workers take the next run as they finish (fixed chunks left one
  // thread idle for seconds); each run depends on its index only.
  parallel_dynamic(static_cast<std::size_t>(runs), m.options.threads, [&](std::size_t r) {
    const std::uint64_t seed = mix_seed(m.options.seed, r);
    RunState s;
    s.models = m.initial;
    // Algorithm 1 starts from a single label; each restart starts from a different one.
    const int first = r == 0 ? 0 : static_cast<int>(seed % m.initial.size());
    s.labels.assign(m.coarse.vertex_count, first);
    try {
      results[r] = m.pearl(std::move(s), seed, run_progress, r);
      run_progress.run_done(r);
    } catch (...) {
      run_progress.stop();
      throw;
    }
  });
  int best = 0;
  std::vector<double> energies(runs);
  for (int r = 0; r < runs; ++r) {
    energies[r] = results[r]->energy;
    if (energies[r] < energies[best]) best = r;
  }
  std::vector<double> departures;
  if (m.options.tie > 0.0 || m.options.fold > 0.0) {
    departures.resize(runs);
    parallel_for(0, departures.size(), m.options.threads, [&](std::size_t r) {
      departures[r] = m.departure(results[r]->state, m.options.tie_distance);
    });
    const double lowest = energies[best];
    // Of the runs within `window` of the lowest energy, the one with the fewest far vertices
    // replaces the kept run when it has fewer by more than `share`.
    const auto prefer_fewest_far = [&](double window, double share) {
      if (window <= 0.0) return;
      const double within = lowest * (1.0 + window);
      int fewest = best;
      for (int r = 0; r < runs; ++r)
        if (energies[r] <= within && departures[r] < departures[fewest]) fewest = r;
      if (departures[fewest] < departures[best] - share) best = fewest;
    };
    prefer_fewest_far(m.options.tie, m.options.tie_share);
    prefer_fewest_far(m.options.fold, m.options.fold_share);
  }
  Segmentation out = m.result(results[best]->state);
  out.summary = m.finish_summary(out.summary.energy, *results[best], runs, best, std::move(energies));
  out.summary.restart_departures = std::move(departures);
  out.summary.segmentation_s = seconds_since(start);
  m.current = std::move(results[best]->state);
  progress.update("segmentation", 1.0);
  return out;
}

Segmentation Segmenter::insert_region(const std::vector<int>& vertices, const Progress& progress) {
  Impl& m = *impl_;
  const std::vector<int> scribble = m.scribbled(vertices);
  return m.add_region(vertices, scribble, progress);
}

Segmentation Segmenter::merge_regions(const std::vector<int>& vertices, const Progress& progress) {
  Impl& m = *impl_;
  const std::vector<int> scribble = m.scribbled(vertices);
  // Every proxy vertex connected to a scribbled vertex through vertices of its label.
  const std::vector<int> labels = m.coarse.propagate(m.current->labels);
  std::vector<std::vector<int>> adjacency(m.graph.vertex_count());
  for (const auto& e : m.graph.edges)
    if (labels[e[0]] == labels[e[1]]) {
      adjacency[e[0]].push_back(e[1]);
      adjacency[e[1]].push_back(e[0]);
    }
  std::vector<char> seen(m.graph.vertex_count(), 0);
  std::vector<int> region, stack;
  for (int v : vertices)
    if (!seen[v]) seen[v] = 1, stack.push_back(v);
  while (!stack.empty()) {
    const int v = stack.back();
    stack.pop_back();
    region.push_back(v);
    for (int w : adjacency[v])
      if (!seen[w]) seen[w] = 1, stack.push_back(w);
  }
  std::sort(region.begin(), region.end());
  return m.add_region(region, scribble, progress);
}

Segmentation segment(const Sketch& sketch, const TriMesh& proxy, const SegmentOptions& options,
                     const Progress& progress) {
  Segmenter segmenter(sketch, proxy, options, progress);
  return segmenter.run(progress);
}

}  // namespace sketchsurf
