#include "surfacing/lbfgs.h"

#include <algorithm>
#include <sstream>
#include <vector>

namespace sketchsurf::detail {

LbfgsOutcome minimize_lbfgs(const LbfgsFunction& f, double* x0, const LbfgsOptions& options, const WorkerTeam& team,
                            const std::function<void(int)>& on_iteration) {
  const int rank = options.rank;
  const Eigen::Index m = f.size();
  const std::size_t chunks = (static_cast<std::size_t>(m) + kVectorChunk - 1) / kVectorChunk;
  std::vector<double> partial(chunks), partial_yy(chunks), partial_max(chunks);
  // sum over chunks of body(lo, hi), each chunk on one thread, added in chunk order.
  auto reduce = [&](auto&& body) {
    team.chunks(static_cast<std::size_t>(m), kVectorChunk,
                [&](std::size_t c, Eigen::Index lo, Eigen::Index hi) { partial[c] = body(lo, hi); });
    double sum = 0.0;
    for (double p : partial) sum += p;
    return sum;
  };
  // Elementwise work (the same numbers whatever the threads) over the same chunks.
  auto for_chunks = [&](auto&& body) { for_vector_chunks(m, team, body); };
  // The iterate, written back to x0 however the minimisation ends.
  Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(x0, m);
  struct WriteBack {
    const Eigen::VectorXd& x;
    double* to;
    ~WriteBack() { std::copy(x.data(), x.data() + x.size(), to); }
  } write_back{x, x0};
  Eigen::VectorXd g(m), d(m), trial(m), trial_gradient(m);
  std::vector<Eigen::VectorXd> S(static_cast<std::size_t>(rank), Eigen::VectorXd(m)), Y = S;
  std::vector<double> rho(static_cast<std::size_t>(rank)), alpha(static_cast<std::size_t>(rank));
  int stored = 0, newest = -1;
  double gamma = 1.0;  // H0 = gamma I
  LbfgsOutcome out;
  double cost = 0.0;
  std::vector<double> costs;  // the cost after each iteration, 0 the start
  if (!f.evaluate(x.data(), &cost, g.data())) {
    out.usable = false;
    out.termination = "FAILURE: the cost is not finite at the start";
    return out;
  }
  costs.push_back(cost);
  // The largest gradient entry (of g; then of each accepted step's gradient, in the pass that
  // makes the new pair).
  for_chunks([&](Eigen::Index lo, Eigen::Index size) { partial_max[static_cast<std::size_t>(lo) / kVectorChunk] = g.segment(lo, size).cwiseAbs().maxCoeff(); });
  on_iteration(0);
  auto slot = [&](int age) { return static_cast<std::size_t>((newest - age + rank) % rank); };
  for (int it = 1; it <= options.max_iterations; ++it) {
    if (*std::max_element(partial_max.begin(), partial_max.end()) <= options.gradient_tolerance) {
      out.converged = true;
      out.termination = "CONVERGENCE: gradient tolerance reached";
      return out;
    }
    // Two-loop recursion: d = -H g, newest pair first, then back; each pass updates d with one
    // pair and computes the dot product the next pair needs.
    double dot = 0.0;
    if (stored > 0) dot = reduce([&](Eigen::Index lo, Eigen::Index hi) {
      d.segment(lo, hi - lo) = -g.segment(lo, hi - lo);
      return S[slot(0)].segment(lo, hi - lo).dot(d.segment(lo, hi - lo));
    });
    else d = -g;
    for (int age = 0; age < stored; ++age) {
      const std::size_t i = slot(age);
      alpha[i] = rho[i] * dot;
      const bool last = age + 1 == stored;
      dot = reduce([&](Eigen::Index lo, Eigen::Index hi) {
        auto seg = d.segment(lo, hi - lo);
        seg -= alpha[i] * Y[i].segment(lo, hi - lo);
        return last ? Y[i].segment(lo, hi - lo).dot(seg) : S[slot(age + 1)].segment(lo, hi - lo).dot(seg);
      });
    }
    if (stored > 0 && gamma != 1.0) {  // H0 = gamma I
      for_chunks([&](Eigen::Index lo, Eigen::Index size) { d.segment(lo, size) *= gamma; });
      dot *= gamma;
    }
    for (int age = stored - 1; age >= 0; --age) {
      const std::size_t i = slot(age);
      const double beta = rho[i] * dot;
      const bool last = age == 0;
      dot = reduce([&](Eigen::Index lo, Eigen::Index hi) {
        auto seg = d.segment(lo, hi - lo);
        seg += (alpha[i] - beta) * S[i].segment(lo, hi - lo);
        return last ? g.segment(lo, hi - lo).dot(seg) : Y[slot(age - 1)].segment(lo, hi - lo).dot(seg);
      });
    }
    double slope = stored > 0 ? dot : -g.squaredNorm();
    if (!(slope < 0.0)) {  // not a descent direction: forget the pairs, go down the gradient
      stored = 0;
      d = -g;
      slope = -g.squaredNorm();
    }
    // Armijo backtracking from the unit step, halving (or the minimiser of the quadratic through
    // the cost and slope at 0 and the trial cost, kept within [0.1, 0.5] of the step).
    double step = 1.0, trial_cost = 0.0;
    bool accepted = false;
    for (int search = 0; search < 40 && !accepted; ++search) {
      const bool finite = f.evaluate_step(x.data(), step, d.data(), trial.data(), &trial_cost, trial_gradient.data());
      if (finite && trial_cost <= cost + 1e-4 * step * slope) {
        accepted = true;
      } else {
        const double curvature = finite ? trial_cost - cost - slope * step : 0.0;
        const double quadratic = curvature > 0.0 ? -slope * step * step / (2.0 * curvature) : 0.5 * step;
        step = std::clamp(quadratic, 0.1 * step, 0.5 * step);
      }
    }
    if (!accepted) {
      out.termination = "FAILURE: no step along the L-BFGS direction lowers the cost";
      return out;
    }
    // The new pair (s, y) if it keeps H positive definite; y.y and the new gradient's largest
    // entry in the same pass.
    const std::size_t next = static_cast<std::size_t>((newest + 1) % rank);
    const double sy = reduce([&](Eigen::Index lo, Eigen::Index hi) {
      auto s = S[next].segment(lo, hi - lo);
      auto y = Y[next].segment(lo, hi - lo);
      s = trial.segment(lo, hi - lo) - x.segment(lo, hi - lo);
      y = trial_gradient.segment(lo, hi - lo) - g.segment(lo, hi - lo);
      const std::size_t c = static_cast<std::size_t>(lo) / kVectorChunk;
      partial_yy[c] = y.squaredNorm();
      partial_max[c] = trial_gradient.segment(lo, hi - lo).cwiseAbs().maxCoeff();
      return s.dot(y);
    });
    double yy = 0.0;
    for (double p : partial_yy) yy += p;
    if (sy > 1e-14 * yy) {
      newest = static_cast<int>(next);
      rho[next] = 1.0 / sy;
      if (options.scale_initial_hessian) gamma = sy / yy;
      stored = std::min(stored + 1, rank);
    } else if (stored == rank) {
      stored = rank - 1;  // the oldest pair's slot was overwritten
    }
    const double decrease = cost - trial_cost;
    x.swap(trial);
    g.swap(trial_gradient);
    const double previous = cost;
    cost = trial_cost;
    out.iterations = it;
    costs.push_back(cost);
    on_iteration(it);
    if (decrease <= options.function_tolerance * previous) {
      out.converged = true;
      out.termination = "CONVERGENCE: function tolerance reached";
      return out;
    }
    const int window = options.stall_window;
    if (window > 0 && it >= window && costs[it - window] - cost <= options.stall_tolerance * costs[it - window]) {
      out.converged = true;
      std::ostringstream message;
      message << "CONVERGENCE: the cost fell by less than " << 100.0 * options.stall_tolerance << "% over the last "
              << window << " iterations";
      out.termination = message.str();
      return out;
    }
  }
  out.termination = "NO_CONVERGENCE: maximum number of iterations reached";
  return out;
}

}  // namespace sketchsurf::detail
