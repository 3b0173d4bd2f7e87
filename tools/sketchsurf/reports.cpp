#include "tools/sketchsurf/reports.h"

#include <sys/resource.h>

namespace sketchsurf::cli {

nlohmann::json models_json(const Segmentation& segmentation) {
  nlohmann::json models = nlohmann::json::array();
  std::vector<std::size_t> sizes(segmentation.models.size(), 0);
  for (int l : segmentation.labels) ++sizes[l];
  for (std::size_t i = 0; i < segmentation.models.size(); ++i) {
    const ImplicitModel& m = segmentation.models[i];
    models.push_back({{"label", i},
                      {"degree", m.degree},
                      {"vertices", sizes[i]},
                      {"center", {m.center.x(), m.center.y(), m.center.z()}},
                      {"scale", m.scale},
                      {"coefficients", std::vector<double>(m.coefficients.data(),
                                                           m.coefficients.data() + m.coefficients.size())}});
  }
  return models;
}

nlohmann::json checks_json(const ShapeChecks& c) {
  return {{"far_5", c.far_5},
          {"far_10", c.far_10},
          {"beyond", c.beyond},
          {"outside_box", c.outside_box},
          {"components", c.components},
          {"genus", c.genus},
          {"boundary_loops", c.boundary_loops},
          {"self_intersections", c.self_intersections},
          {"regions", c.regions},
          {"border_length", c.border_length},
          {"border_ratio", c.border_ratio},
          {"warnings", c.warnings}};
}

nlohmann::json decorations_json(const std::vector<Decoration>& decorations) {
  nlohmann::json out = nlohmann::json::array();
  for (const Decoration& d : decorations)
    out.push_back({{"id", d.id}, {"kind", decoration_kind_name(d.kind)}});
  return out;
}

nlohmann::json openings_json(const std::vector<Opening>& openings) {
  nlohmann::json out = nlohmann::json::array();
  for (const Opening& o : openings) {
    const Eigen::Vector3d& n = o.loop.plane.normal;
    const Eigen::Vector3d& c = o.loop.center;
    out.push_back({{"id", o.id},
                   {"normal", {n.x(), n.y(), n.z()}},
                   {"center", {c.x(), c.y(), c.z()}},
                   {"radius", o.loop.radius}});
  }
  return out;
}

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // Linux reports kilobytes
}

}  // namespace sketchsurf::cli
