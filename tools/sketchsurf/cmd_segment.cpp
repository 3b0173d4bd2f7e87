// sketchsurf segment SKETCH --proxy MESH -o regions.ply [--report report.json] [--seed N]
// [--restarts N] [--epsilon F]: the proxy labelled into smooth regions (paper §4.1-4.2).


#include <array>
#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "surfacing/segment/pearl.h"
#include "surfacing/sketch/io/atomic_file.h"
#include "surfacing/sketch/io/mesh_io.h"
#include "tools/sketchsurf/commands.h"
#include "tools/sketchsurf/reports.h"
#include "tools/sketchsurf/run_files.h"

namespace sketchsurf::cli {

namespace {

struct SegmentCommandOptions {
  std::string sketch;
  std::string proxy;
  std::string output;
  std::string report;
  SegmentOptions segment;
};

// A distinct, saturated colour per region: hues spaced by the golden angle.
std::array<std::uint8_t, 3> region_color(int label) {
  const double h = std::fmod(label * 0.618033988749895, 1.0) * 6.0, s = 0.65, v = 0.95;
  const int i = static_cast<int>(h) % 6;
  const double f = h - std::floor(h), p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  const double rgb[6][3] = {{v, t, p}, {q, v, p}, {p, v, t}, {p, q, v}, {t, p, v}, {v, p, q}};
  return {static_cast<std::uint8_t>(std::lround(255 * rgb[i][0])),
          static_cast<std::uint8_t>(std::lround(255 * rgb[i][1])),
          static_cast<std::uint8_t>(std::lround(255 * rgb[i][2]))};
}

nlohmann::json report_json(const Segmentation& s, const SegmentOptions& o) {
  const SegmentationSummary& sum = s.summary;
  return {{"regions", s.models.size()},
          {"models", models_json(s)},
          {"energy", {{"fidelity", sum.energy.fidelity},
                      {"smoothness", sum.energy.smoothness},
                      {"simplicity", sum.energy.simplicity},
                      {"total", sum.energy.total}}},
          {"energy_history", sum.energy_history},
          {"iterations", sum.iterations},
          {"converged", sum.converged},
          {"restarts", sum.restarts},
          {"best_restart", sum.best_restart},
          {"restart_energies", sum.restart_energies},
          {"restart_departures", sum.restart_departures},
          {"initial_models", sum.initial_models},
          {"proxy_vertices", sum.proxy_vertices},
          {"graph_vertices", sum.graph_vertices},
          {"associated_points", sum.associated_points},
      {"crease_guides", sum.crease_guides},
          {"parameters", {{"epsilon", o.epsilon}, {"w_smooth", o.w_smooth}, {"w_simp", o.w_simp},
                          {"mu", o.mu}, {"lambda", o.lambda}, {"seed", o.seed},
                          {"simplify", o.simplify}}},
          {"timings", {{"association_s", sum.association_s},
                       {"init_s", sum.init_s},
                       {"segmentation_s", sum.segmentation_s}}},
          {"peak_rss_mb", peak_rss_mb()}};
}

void run_segment(const SegmentCommandOptions& opt, const GlobalOptions& global) {
  std::string why;
  if (!opt.segment.valid(&why)) throw Error::usage(why);
  RunFiles files;
  files.input(opt.sketch);
  files.input(opt.proxy);
  files.output("-o", opt.output, {".obj", ".ply", ".glb", ".gltf"});
  if (!opt.report.empty()) files.output("--report", opt.report);
  Sketch sketch = read_clean_sketch(opt.sketch, global);
  if (sketch.strokes.empty()) throw Error::input(opt.sketch, "no stroke left to segment");
  const TriMesh proxy = read_proxy_mesh(opt.proxy, sketch);
  if (global.verbose)
    std::cerr << "segment: epsilon " << opt.segment.epsilon << ", w_smooth " << opt.segment.w_smooth
              << ", w_simp " << opt.segment.w_simp << ", restarts " << opt.segment.restarts
              << ", seed " << opt.segment.seed << ", simplify " << opt.segment.simplify << "\n";

  const Segmentation s = segment(sketch, proxy, opt.segment, Progress(stderr_progress(global)));

  MeshAttributes attributes;
  attributes.labels = s.labels;
  for (int l : s.labels) attributes.colors.push_back(region_color(l));
  files.write(opt.output, [&](const auto& file) { write_mesh(proxy, file, attributes); });
  if (!opt.report.empty()) {
    const nlohmann::json j = report_json(s, opt.segment);
    files.write(opt.report, [&](const auto& file) {
      write_atomically(file, [&](std::ostream& out) { out << j.dump(2) << "\n"; });
    });
  }
  files.commit();
  if (!global.quiet)
    std::cerr << "segment: " << s.models.size() << " regions, energy " << s.summary.energy.total
              << ", " << s.summary.iterations << " iterations\n";
}

}  // namespace

void add_segment_command(CLI::App& app, const GlobalOptions& global) {
  auto opt = std::make_shared<SegmentCommandOptions>();
  auto* cmd = app.add_subcommand("segment", "Segment a proxy mesh into smooth regions fitting the strokes");
  cmd->add_option("SKETCH", opt->sketch, "Sketch (.tilt, .curves, .obj, .json)")->required();
  cmd->add_option("--proxy", opt->proxy, "Proxy surface mesh (.obj, .ply)")->required();
  cmd->add_option("-o,--output", opt->output, "Labelled proxy (.ply with per-vertex label and colour, .glb/.gltf, or .obj)")
      ->required();
  cmd->add_option("--report", opt->report, "Write energies, models and timings as JSON");
  cmd->add_option("--seed", opt->segment.seed, "Random seed")
      ->capture_default_str()
      ->check(whole_number(0, UINT64_MAX));
  cmd->add_option("--restarts", opt->segment.restarts, "Independent PEARL runs, lowest energy kept")
      ->capture_default_str()
      ->check(whole_number(1, 1000));
  cmd->add_option("--epsilon", opt->segment.epsilon,
                  "Fidelity tolerance, fraction of the bounding-box diagonal (Eq. 2)")
      ->capture_default_str()
      ->check(positive_number());
  cmd->add_option("--threads", opt->segment.threads, "Worker threads (0 = all)")
      ->capture_default_str()
      ->check(whole_number(0, kMaxThreads));
  cmd->callback([opt, &global] { run_segment(*opt, global); });
}

}  // namespace sketchsurf::cli
