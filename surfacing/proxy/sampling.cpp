#include "surfacing/proxy/sampling.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "surfacing/error.h"

namespace sketchsurf {

bool SamplingOptions::valid(std::string* why) const {
  auto fail = [&](const char* msg) {
    if (why) *why = msg;
    return false;
  };
  if (count < 4) return fail("sampling count must be at least 4");
  if (!(spacing > 0.0 && spacing < 1.0)) return fail("sampling spacing must be in (0, 1)");
  if (!(min_distance >= 0.0 && min_distance < 1.0))
    return fail("sampling min_distance must be in [0, 1)");
  return true;
}

Eigen::MatrixX3d sample_strokes(const Sketch& sketch, const SamplingOptions& options) {
  std::string why;
  if (!options.valid(&why)) throw Error::usage(why);

  BoundingBox box;
  for (const auto& s : sketch.strokes)
    if (!s.ignored)
      for (const auto& p : s.points) box.extend(p);
  if (box.empty()) throw Error::processing("the sketch has no stroke points to build a proxy from");
  const double diagonal = box.diagonal();
  const Eigen::Vector3d centre = 0.5 * (box.min + box.max);

  std::vector<Eigen::Vector3d> candidates;
  for (const auto& s : sketch.strokes) {
    if (s.ignored || s.points.empty()) continue;
    if (s.points.size() == 1 || diagonal == 0.0) {
      candidates.insert(candidates.end(), s.points.begin(), s.points.end());
      continue;
    }
    Stroke bare;  // geometry only: attributes are not needed for sampling
    bare.points = s.points;
    const Stroke dense = resample(bare, options.spacing * diagonal);
    candidates.insert(candidates.end(), dense.points.begin(), dense.points.end());
  }

  // Farthest-point sampling: nearest[i] = squared distance of candidate i to the chosen set.
  const std::size_t n = candidates.size();
  std::size_t next = 0;
  double far = -1.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double d = (candidates[i] - centre).squaredNorm();
    if (d > far) far = d, next = i;
  }
  std::vector<double> nearest(n, std::numeric_limits<double>::infinity());
  const double min_d2 = (options.min_distance * diagonal) * (options.min_distance * diagonal);
  std::vector<Eigen::Vector3d> chosen;
  chosen.reserve(std::min(n, options.count));
  while (chosen.size() < options.count) {
    const Eigen::Vector3d c = candidates[next];
    chosen.push_back(c);
    far = -1.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double d = std::min(nearest[i], (candidates[i] - c).squaredNorm());
      nearest[i] = d;
      if (d > far) far = d, next = i;
    }
    if (far <= min_d2 || far <= 0.0) break;
  }
  Eigen::MatrixX3d out(chosen.size(), 3);
  for (std::size_t i = 0; i < chosen.size(); ++i) out.row(i) = chosen[i].transpose();
  return out;
}

}  // namespace sketchsurf
