// sketchsurf proxy SKETCH -o proxy.(obj|ply) [--points N] [--lambda F] [--edge F] [--from MESH]
// [--param proxy.NAME=VALUE]... [--report report.json]: the proxy surface (paper §5 "Proxy
// creation"), automatic (VIPSS) or a user mesh attracted to the strokes.


#include <iostream>
#include <memory>
#include <optional>
#include <nlohmann/json.hpp>

#include "surfacing/pipeline.h"
#include "surfacing/proxy/proxy.h"
#include "surfacing/sketch/io/atomic_file.h"
#include "surfacing/sketch/io/mesh_io.h"
#include "tools/sketchsurf/commands.h"
#include "tools/sketchsurf/reports.h"
#include "tools/sketchsurf/run_files.h"

namespace sketchsurf::cli {

namespace {

struct ProxyCommandOptions {
  std::string sketch;
  std::string output;
  std::string from;
  std::string report;
  std::vector<std::string> params;
  bool keep_all_strokes = false;
  ProxyOptions proxy;
};

nlohmann::json report_json(const ProxyReport& r, const SurfaceReport& prepared,
                           const ProxyCommandOptions& opt) {
  nlohmann::json j = {
      {"mode", opt.from.empty() ? "vipss" : "attract"},
      {"decorations", decorations_json(prepared.decorations)},
      {"samples", r.samples},
      {"vertices", r.vertices},
      {"faces", r.faces},
      {"components", r.topology.components},
      {"genus", r.topology.genus},
      {"euler_characteristic", r.topology.euler},
      {"boundary_loops", r.topology.boundary_loops},
      {"parameters", {{"points", opt.proxy.points}, {"lambda", opt.proxy.lambda},
                      {"edge", opt.proxy.edge}, {"cell", opt.proxy.cell}}},
      {"timings", {{"sampling_s", r.sampling_seconds}, {"vipss_s", r.vipss_seconds},
                   {"polygonize_s", r.polygonize_seconds}, {"remesh_s", r.remesh_seconds},
                   {"attract_s", r.attract_seconds}, {"total_s", r.total_seconds}}},
      {"peak_rss_mb", peak_rss_mb()}};
  if (opt.from.empty())
    j["vipss"] = {{"initial_energy", r.vipss.initial_energy},
                  {"final_energy", r.vipss.final_energy},
                  {"lanczos_products", r.vipss.eigen_matvecs},
                  {"lbfgs_iterations", r.vipss.lbfgs_iterations},
                  {"start", r.vipss.start == 0 ? "eigenvector" : "ellipsoid"},
                  {"closed_in_box", r.vipss.closed},
                  {"lambda", r.lambda},
                  {"crossing_gap", r.crossing_gap},
                  {"clean_windows", r.clean_windows},
                  {"shared_misfit", r.shared_misfit},
                  {"rounded", r.rounded},
                  {"solves", r.vipss_solves},
                  {"far_area", r.far_area},
                  {"missed_strokes", r.missed_strokes},
                  {"outline_cut", r.outline_cut},
                  {"box_drawn_in", r.box_drawn_in},
                  {"planes_drawn_in", r.planes_drawn_in},
                  {"loft_sections", r.loft_sections},
                  {"window_bumps", r.windows},
                  {"bridges", r.bridges},
                  {"necks_cut", r.necks},
                  {"face_holes", r.face_holes},
                  {"part_normals", r.part_normals},
                  {"confine_radius", r.confine_radius},
                  {"termination", r.vipss.termination},
                  {"evaluations", r.evaluations}};
  if (r.anchors > 0)
    j["attraction"] = {{"anchors", r.anchors},
                       {"median_distance_before", r.median_distance_before},
                       {"median_distance_after", r.median_distance_after}};
  return j;
}

// The proxy options with the --param assignments applied over them: proxy.* names only.
ProxyOptions with_params(const ProxyCommandOptions& opt) {
  const std::map<std::string, double> given = parse_params(opt.params);
  for (const auto& [name, value] : given)
    if (name.rfind("proxy.", 0) != 0)
      throw Error::usage("--param: the proxy command takes proxy.* parameters only, got '" + name + "'");
  Params params;
  params.proxy = opt.proxy;
  try {
    params.apply(given);
  } catch (const Error& e) {
    throw Error::usage(std::string("--param: ") + e.what());
  }
  return params.proxy;
}

void run_proxy(const ProxyCommandOptions& given, const GlobalOptions& global) {
  ProxyCommandOptions opt = given;
  opt.proxy = with_params(given);
  std::string why;
  if (!opt.proxy.valid(&why)) throw Error::usage(why);
  RunFiles files;
  files.input(opt.sketch);
  files.input(opt.from);
  files.output("-o", opt.output, {".obj", ".ply"});
  if (!opt.report.empty()) files.output("--report", opt.report);
  Sketch sketch = read_clean_sketch(opt.sketch, global);
  // The strokes as the surface command hands them to the proxy (resampled, decorations ignored,
  // ...): the same proxy as `sketchsurf surface` builds with these options. Scribbled ink is
  // the surface command's to refuse.
  Params params;
  params.proxy = opt.proxy;
  params.prepare.ignore_decorations = !opt.keep_all_strokes;
  SurfaceReport prepared;
  try {
    sketch = Surfacer(params).prepare(sketch, false, prepared);
  } catch (const Error& e) {
    rethrow_naming(opt.sketch, e);
  }
  if (global.verbose)
    std::cerr << "proxy: points " << opt.proxy.points << ", lambda " << opt.proxy.lambda
              << ", edge " << opt.proxy.edge << ", cell " << opt.proxy.cell << ", threads "
              << opt.proxy.threads << (opt.from.empty() ? "" : ", from " + opt.from) << "\n";

  const Progress progress(stderr_progress(global));
  ProxyReport report;
  TriMesh mesh;
  std::optional<TriMesh> from;  // a bad --from mesh is an error naming that file
  if (!opt.from.empty()) from = read_proxy_mesh(opt.from, sketch);
  try {
    mesh = from ? attract_proxy(*from, sketch, opt.proxy, progress, &report)
                : make_proxy(sketch, opt.proxy, progress, &report);
  } catch (const Error& e) {
    rethrow_naming(opt.sketch, e);
  }
  files.write(opt.output, [&](const auto& file) { write_mesh(mesh, file); });
  if (!opt.report.empty()) {
    const nlohmann::json j = report_json(report, prepared, opt);
    files.write(opt.report, [&](const auto& file) {
      write_atomically(file, [&](std::ostream& out) { out << j.dump(2) << "\n"; });
    });
  }
  files.commit();
  note_decorations(global, opt.sketch, prepared.decorations, 0, "--keep-all-strokes keeps them");
  if (!global.quiet)
    std::cerr << "proxy: " << report.vertices << " vertices, " << report.faces << " faces, "
              << report.topology.components << " component(s), genus " << report.topology.genus
              << (report.loft_sections > 0
                      ? ", lofted through " + std::to_string(report.loft_sections) + " section strokes"
                      : std::string())
              << ", " << report.total_seconds << " s\n";
}

}  // namespace

void add_proxy_command(CLI::App& app, const GlobalOptions& global) {
  auto opt = std::make_shared<ProxyCommandOptions>();
  auto* cmd = app.add_subcommand("proxy", "Build the proxy surface: VIPSS on the strokes, or "
                                          "attract a rough user mesh (--from) to them");
  cmd->add_option("SKETCH", opt->sketch, "Sketch (.tilt, .curves, .obj, .json)")->required();
  cmd->add_option("-o,--output", opt->output, "Proxy mesh (.obj or .ply)")->required();
  cmd->add_option("--points", opt->proxy.points,
                  "VIPSS sample points (a clean curve network's first solve: at least "
                  "proxy.clean_points)")
      ->capture_default_str()
      ->check(whole_number(10, 20000));
  cmd->add_option("--lambda", opt->proxy.lambda,
                  "VIPSS smoothing, 0 = interpolate the samples (default: chosen per sketch)")
      ->check(non_negative_number());
  cmd->add_option("--edge", opt->proxy.edge, "Target edge length, fraction of the bbox diagonal")
      ->capture_default_str()
      ->check(positive_number());
  cmd->add_option("--from", opt->from, "Rough user proxy (.obj, .ply) to attract to the strokes")
      ->check(CLI::ExistingFile);
  cmd->add_flag("--attract", opt->proxy.attract_vipss,
                "Attract the VIPSS surface to the strokes too (flattens it between strokes: for "
                "sharp, planar sketches)")
      ->excludes("--from");
  cmd->add_option("--param", opt->params,
                  "NAME=VALUE: set a proxy parameter by its dotted name (proxy.confine_radius, "
                  "proxy.window_value, ...; an unknown name lists them all), applied after the "
                  "options above. Repeatable")
      ->allow_extra_args(false);
  cmd->add_option("--report", opt->report, "Write counts, genus and per-stage timings as JSON");
  cmd->add_flag("--keep-all-strokes", opt->keep_all_strokes,
                "Fit every stroke, also those that seem to depict no surface (a dot apart, a stroke "
                "hanging by one end); by default they are left out, as the surface command does");
  cmd->add_option("--threads", opt->proxy.threads, "Worker threads (0 = all)")
      ->capture_default_str()
      ->check(whole_number(0, kMaxThreads));
  cmd->callback([opt, &global] { run_proxy(*opt, global); });
}

}  // namespace sketchsurf::cli
