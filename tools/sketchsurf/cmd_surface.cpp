// sketchsurf surface SKETCH [--proxy MESH] -o OUT.(obj|ply) [--report report.json]
// [--regions regions.ply] [--mirror x|y|z|a,b,c,d] [--boundary-strokes IDS] [--seed N]
// [--param NAME=VALUE]...:
// the piecewise-smooth surface of a sketch (the whole method, paper §4-5).


#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "surfacing/palette.h"
#include "surfacing/pipeline.h"
#include "surfacing/sketch/io/atomic_file.h"
#include "surfacing/sketch/io/mesh_io.h"
#include "tools/sketchsurf/commands.h"
#include "tools/sketchsurf/reports.h"
#include "tools/sketchsurf/run_files.h"

namespace sketchsurf::cli {

namespace {

struct SurfaceCommandOptions {
  std::string sketch;
  std::string proxy;
  std::string output;
  std::string report;
  std::string regions;
  std::string mirror;
  std::string boundary_strokes;
  std::vector<std::string> params;
  std::optional<std::uint64_t> seed;
  std::optional<unsigned> threads;
  bool keep_all_strokes = false;
  bool tubes = false;
  bool closed = false;
  bool force = false;
  bool with_strokes = false;
};

/// "x", "y", "z" (the plane through the origin with that normal) or "a,b,c,d" (a x + b y + c z +
/// d = 0; the kept half is where it is >= 0).
Plane parse_mirror(const std::string& text) {
  Plane plane;
  if (text == "x" || text == "y" || text == "z") {
    plane.normal = Eigen::Vector3d::Unit(text[0] - 'x');
    return plane;
  }
  std::vector<double> v;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    try {
      std::size_t used = 0;
      v.push_back(std::stod(item, &used));
      if (used != item.size()) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw Error::usage("--mirror: '" + item + "' is not a number; use x, y, z or a,b,c,d");
    }
  }
  const Eigen::Vector3d n = v.size() == 4 ? Eigen::Vector3d(v[0], v[1], v[2]) : Eigen::Vector3d::Zero();
  if (v.size() != 4 || !(n.norm() > 0.0) || !std::isfinite(v[3]))
    throw Error::usage("--mirror expects x, y, z or a,b,c,d with (a, b, c) != 0, got '" + text + "'");
  plane.normal = n / n.norm();
  plane.offset = v[3] / n.norm();
  return plane;
}

/// "3,5,9-12": stroke ids.
std::set<std::int64_t> parse_ids(const std::string& text) {
  std::set<std::int64_t> ids;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    try {
      const auto dash = item.find('-', 1);
      std::size_t used = 0;
      if (dash == std::string::npos) {
        ids.insert(std::stoll(item, &used));
        if (used != item.size()) throw std::invalid_argument(item);
      } else {
        const std::int64_t lo = std::stoll(item.substr(0, dash)), hi = std::stoll(item.substr(dash + 1));
        if (hi < lo || hi - lo > 1000000) throw std::invalid_argument(item);
        for (std::int64_t i = lo; i <= hi; ++i) ids.insert(i);
      }
    } catch (const std::exception&) {
      throw Error::usage("--boundary-strokes: '" + item + "' is not a stroke id or a range a-b");
    }
  }
  return ids;
}

nlohmann::json report_json(const SurfaceResult& r, const Params& p) {
  const SurfaceReport& rep = r.report;
  const SegmentationSummary& seg = rep.segmentation;
  const ExtractSummary& ex = rep.extraction;
  auto energy_terms = [](const MeshEnergyTerms& e) {
    return nlohmann::json{{"project", e.project},         {"regularize_2d", e.regularize_2d},
                          {"regularize_1d", e.regularize_1d}, {"attract", e.attract},
                          {"plane", e.plane},             {"total", e.total()}};
  };
  return {
      // The segmentation report (as `sketchsurf segment --report`) ...
      {"regions", r.segmentation.models.size()},
      {"models", models_json(r.segmentation)},
      {"energy", {{"fidelity", seg.energy.fidelity}, {"smoothness", seg.energy.smoothness},
                  {"simplicity", seg.energy.simplicity}, {"total", seg.energy.total}}},
      {"energy_history", seg.energy_history},
      {"iterations", seg.iterations},
      {"converged", seg.converged},
      {"restarts", seg.restarts},
      {"best_restart", seg.best_restart},
      {"restart_energies", seg.restart_energies},
      {"restart_departures", seg.restart_departures},
      {"initial_models", seg.initial_models},
      {"proxy_vertices", seg.proxy_vertices},
      {"graph_vertices", seg.graph_vertices},
      {"associated_points", seg.associated_points},
      {"crease_guides", seg.crease_guides},
      {"parameters", {{"epsilon", p.segment.epsilon}, {"w_smooth", p.segment.w_smooth},
                      {"w_simp", p.segment.w_simp}, {"mu", p.segment.mu}, {"lambda", p.segment.lambda},
                      {"seed", p.segment.seed}, {"simplify", p.segment.simplify},
                      {"gamma_2d", p.extract.energy.gamma_2d}, {"gamma_1d", p.extract.energy.gamma_1d},
                      {"attract_weight", p.extract.energy.attract_weight}}},
      // ... extended with the proxy, the final mesh and the fit to the strokes.
      {"sketch", {{"strokes", rep.strokes}, {"points", rep.points}, {"diagonal", rep.diagonal},
                  {"cleaning", rep.cleaning.messages}}},
      {"proxy", {{"user", rep.user_proxy}, {"vertices", r.proxy.n_vertices()}, {"faces", r.proxy.n_faces()},
                 {"genus", rep.proxy.topology.genus}, {"samples", rep.proxy.samples},
                 {"lambda", rep.proxy.lambda},
                 {"crossing_gap", rep.proxy.crossing_gap},
                 {"clean_windows", rep.proxy.clean_windows},
                 {"shared_misfit", rep.proxy.shared_misfit}, {"rounded", rep.proxy.rounded},
                 {"far_area", rep.proxy.far_area}, {"missed_strokes", rep.proxy.missed_strokes},
                 {"confine_radius", rep.proxy.confine_radius},
                 {"outline_cut", rep.proxy.outline_cut}, {"box_drawn_in", rep.proxy.box_drawn_in},
                 {"planes_drawn_in", rep.proxy.planes_drawn_in},
                 {"loft_sections", rep.proxy.loft_sections},
                 {"window_bumps", rep.proxy.windows}, {"bridges", rep.proxy.bridges},
                 {"necks_cut", rep.proxy.necks}, {"face_holes", rep.proxy.face_holes},
                 {"part_normals", rep.proxy.part_normals}}},
      {"extraction", {{"solver", ex.optimization.solver},
                      {"termination", ex.optimization.termination},
                      {"solver_iterations", ex.optimization.iterations},
                      {"usable", ex.optimization.usable},
                      {"initial_energy", energy_terms(ex.optimization.initial)},
                      {"final_energy", energy_terms(ex.optimization.final)},
                      {"seam_vertices", ex.seam_vertices},
                      {"corner_vertices", ex.corner_vertices},
                      {"held_vertices", ex.optimization.held_vertices},
                      {"outline_vertices", ex.optimization.outline_vertices},
                      {"face_vertices", ex.optimization.face_vertices},
                      {"regions_at_proxy", ex.smooth_fallback.kept},
                      {"regions_pulled_to_proxy", ex.smooth_fallback.pulled},
                      {"smooth_parts", ex.smooth_fallback.parts},
                      {"smooth_parts_at_proxy", ex.smooth_fallback.reverted},
                      {"back_side_vertices", ex.back_side_vertices},
                      {"unfold", {{"crossing_pairs", ex.unfold.crossing_pairs},
                                  {"left_pairs", ex.unfold.left_pairs},
                                  {"moved_vertices", ex.unfold.moved_vertices},
                                  {"skipped_vertices", ex.unfold.skipped_vertices},
                                  {"rounds", ex.unfold.rounds},
                                  {"refitted_regions", ex.unfold.refitted_regions},
                                  {"refit_degree", ex.unfold.refit_degree},
                                  {"held_regions", ex.unfold.held_regions},
                                  {"held_zone", ex.unfold.held_zone}}},
                      {"sharp_vertices", ex.sharp_vertices},
                      {"trimmed_faces", ex.trimmed_faces},
                      {"open", ex.open},
                      {"mirrored", ex.mirrored}}},
      {"mesh", {{"vertices", r.mesh.n_vertices()}, {"faces", r.mesh.n_faces()}}},
      {"stroke_distance", {{"median", rep.stroke_distance.median},
                           {"p95", rep.stroke_distance.p95},
                           {"max", rep.stroke_distance.max},
                           {"points", rep.stroke_distance.points}}},
      {"checks", checks_json(rep.checks)},
      {"decorations", decorations_json(rep.decorations)},
      {"tubes", rep.tubes},
      {"openings", openings_json(rep.openings)},
      {"opening_failure", rep.opening_failure},
      {"consolidation", {{"points", rep.consolidation.points},
                         {"strokes", rep.consolidation.strokes},
                         {"max_shift", rep.consolidation.max_shift}}},
      {"symmetry", rep.symmetry ? nlohmann::json{{"normal", {rep.symmetry->plane.normal.x(), rep.symmetry->plane.normal.y(),
                                                             rep.symmetry->plane.normal.z()}},
                                                 {"offset", rep.symmetry->plane.offset},
                                                 {"distance", rep.symmetry->distance},
                                                 {"half_ends", rep.symmetry->half_ends}}
                                : nlohmann::json()},
      {"timings", {{"prepare_s", rep.prepare_s},
                   {"proxy_s", rep.proxy_s},
                   {"association_s", seg.association_s},
                   {"init_s", seg.init_s},
                   {"segmentation_s", seg.segmentation_s},
                   {"extraction_s", rep.extraction_s},
                   {"checks_s", rep.checks_s},
                   {"total_s", rep.total_s}}},
      {"peak_rss_mb", peak_rss_mb()}};
}

void run_surface(const SurfaceCommandOptions& opt, const GlobalOptions& global) {
  RunFiles files;
  files.input(opt.sketch);
  files.input(opt.proxy);
  files.output("-o", opt.output, {".obj", ".ply", ".glb", ".gltf"});
  std::string extension = std::filesystem::path(opt.output).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (opt.with_strokes && extension != ".glb" && extension != ".gltf")
    throw Error::usage("--with-strokes: only a .glb or .gltf output (-o) carries the strokes");
  if (!opt.regions.empty()) files.output("--regions", opt.regions, {".obj", ".ply", ".glb", ".gltf"});
  if (!opt.report.empty()) files.output("--report", opt.report);
  Warnings warnings;
  Sketch sketch = read_sketch(opt.sketch, &warnings);
  print_warnings(global, opt.sketch, warnings);
  check_extent(sketch, opt.sketch);
  Params params;
  try {
    params.apply(sketch.params);
  } catch (const Error& e) {
    throw Error::input(opt.sketch, e.what());
  }
  const std::map<std::string, double> given = parse_params(opt.params);
  try {
    params.apply(given);
  } catch (const Error& e) {
    throw Error::usage(std::string("--param: ") + e.what());
  }
  if (opt.seed) params.segment.seed = *opt.seed;
  if (opt.keep_all_strokes) params.prepare.ignore_decorations = false;
  if (opt.tubes) params.prepare.decoration_tubes = true;
  if (opt.closed) params.prepare.open_rims = false;
  if (opt.force) params.checks.refuse_score = 0.0;
  if (opt.threads)
    params.segment.threads = params.proxy.threads = params.extract.energy.threads =
        params.extract.seams.threads = *opt.threads;
  if (!opt.mirror.empty()) sketch.mirror = parse_mirror(opt.mirror);
  if (!opt.boundary_strokes.empty()) {
    sketch.assign_ids();
    std::set<std::int64_t> ids = parse_ids(opt.boundary_strokes);
    for (Stroke& s : sketch.strokes)
      if (ids.erase(s.id)) s.boundary = true;
    if (!ids.empty())
      throw Error::usage("--boundary-strokes: the sketch has no stroke with id " + std::to_string(*ids.begin()) +
                         "; stroke ids are the file's, or 0, 1, 2... in file order");
  }
  std::optional<TriMesh> proxy;
  if (!opt.proxy.empty()) proxy = read_proxy_mesh(opt.proxy, sketch);
  if (global.verbose) {
    std::cerr << "surface: parameters";
    for (const auto& [k, v] : sketch.params) std::cerr << " " << k << "=" << v;
    for (const auto& [k, v] : given) std::cerr << " " << k << "=" << v << " (--param)";
    std::cerr << "; seed " << params.segment.seed << ", restarts " << params.segment.restarts
              << ", gamma_2d " << params.extract.energy.gamma_2d << ", gamma_1d "
              << params.extract.energy.gamma_1d << (sketch.mirror ? ", mirrored" : "") << "\n";
  }

  const SurfaceResult result = [&] {
    try {
      return Surfacer(params, stderr_progress(global)).run(sketch, proxy ? &*proxy : nullptr);
    } catch (const Error& e) {  // what is wrong with the sketch, said with its file name
      rethrow_naming(opt.sketch, e);
    }
  }();

  MeshAttributes attributes;
  attributes.labels = result.labels;
  attributes.sharp = result.sharp;
  for (int label : result.labels) attributes.colors.push_back(region_color(label));
  if (opt.with_strokes)
    for (const Stroke& stroke : sketch.strokes) attributes.strokes.push_back(stroke.points);
  files.write(opt.output, [&](const auto& file) { write_mesh(result.mesh, file, attributes); });
  if (!opt.regions.empty()) {
    MeshAttributes regions;
    regions.labels = result.segmentation.labels;
    files.write(opt.regions, [&](const auto& file) { write_mesh(result.proxy, file, regions); });
  }
  if (!opt.report.empty()) {
    const nlohmann::json j = report_json(result, params);
    files.write(opt.report, [&](const auto& file) {
      write_atomically(file, [&](std::ostream& out) { out << j.dump(2) << "\n"; });
    });
  }
  files.commit();
  note_decorations(global, opt.sketch, result.report.decorations, result.report.tubes,
                   "--keep-all-strokes keeps them, --tubes draws them as thin tubes");
  if (!global.quiet && !result.report.openings.empty()) {
    std::cerr << opt.sketch << ": note: opened the surface at " << result.report.openings.size()
              << " rim(s) with nothing drawn across or beyond them (stroke id";
    for (const Opening& o : result.report.openings) std::cerr << " " << o.id;
    std::cerr << "); --closed keeps the surface closed\n";
  }
  if (!global.quiet && !result.report.opening_failure.empty())
    std::cerr << opt.sketch << ": note: kept the surface closed at the rim(s) found in the strokes ("
              << result.report.opening_failure << "); mark the rim strokes with --boundary-strokes to "
              << "open it\n";
  if (!global.quiet && result.report.proxy.loft_sections > 0)
    std::cerr << opt.sketch << ": note: the strokes frame too little surface for VIPSS; the proxy was "
              << "lofted through " << result.report.proxy.loft_sections
              << " section strokes (--param proxy.loft_fit=0 keeps VIPSS's surface)\n";
  if (!global.quiet && result.report.symmetry) {
    // Four digits, round-off noise shown as 0: the plane as a user would type it.
    const auto num = [&](double v, double noise) {
      char text[32];
      std::snprintf(text, sizeof text, "%.4g", std::abs(v) < noise ? 0.0 : v);
      return std::string(text);
    };
    const Plane& m = result.report.symmetry->plane;
    const double tiny = 1e-6 * result.report.diagonal;
    const std::string plane = num(m.normal.x(), 1e-4) + "," + num(m.normal.y(), 1e-4) + "," +
                              num(m.normal.z(), 1e-4) + "," + num(m.offset, tiny);
    if (result.report.symmetry->half_ends > 0)
      std::cerr << opt.sketch << ": note: the strokes are one half of a symmetric object ("
                << result.report.symmetry->half_ends << " of them stop on the plane a,b,c,d = " << plane
                << "): surfaced with their mirror image; --param prepare.complete_half=0 surfaces them "
                << "as drawn\n";
    else
      std::cerr << opt.sketch << ": note: the strokes are mirror-symmetric (plane a,b,c,d = " << plane
                << "); --mirror " << plane << " surfaces one half and mirrors it\n";
  }
  if (!global.quiet)
    for (const std::string& warning : result.report.checks.warnings)
      std::cerr << opt.sketch << ": warning: " << warning << "\n";
  if (!global.quiet)
    std::cerr << "surface: " << result.mesh.n_vertices() << " vertices, "
              << result.segmentation.models.size() << " regions, median stroke distance "
              << 100.0 * result.report.stroke_distance.median << "% of the diagonal, "
              << result.report.total_s << " s\n";
}

}  // namespace

void add_surface_command(CLI::App& app, const GlobalOptions& global) {
  auto opt = std::make_shared<SurfaceCommandOptions>();
  auto* cmd = app.add_subcommand("surface", "Fit a piecewise-smooth surface to a sketch");
  cmd->add_option("SKETCH", opt->sketch, "Sketch (.tilt, .curves, .obj, .json)")->required();
  cmd->add_option("--proxy", opt->proxy,
                  "Proxy surface mesh (.obj, .ply), attracted to the strokes; default: automatic (VIPSS)");
  cmd->add_option("-o,--output", opt->output,
                  "Surface (.ply with per-vertex label and sharp flag, .glb/.gltf with creases and region colours, or .obj)")
      ->required();
  cmd->add_option("--report", opt->report, "Write energies, models, stroke distance and timings as JSON");
  cmd->add_option("--regions", opt->regions, "Write the segmented proxy (.ply with per-vertex label)");
  cmd->add_option("--mirror", opt->mirror,
                  "Symmetry plane: x, y, z or a,b,c,d (a x + b y + c z + d = 0); overrides the file's");
  cmd->add_option("--boundary-strokes", opt->boundary_strokes,
                  "Ids of strokes bounding an open surface, e.g. 3,5,9-12 (adds to the file's marks)");
  cmd->add_option("--param", opt->params,
                  "NAME=VALUE: set a pipeline parameter by its dotted name (proxy.lambda, "
                  "segment.epsilon, ...; an unknown name lists them all), over the sketch file's "
                  "own; the options below win over both. Repeatable")
      ->allow_extra_args(false);
  cmd->add_option("--seed", opt->seed, "Random seed of the segmentation")
      ->check(whole_number(0, UINT64_MAX));
  cmd->add_option("--threads", opt->threads, "Worker threads (0 = all); never changes the result")
      ->check(whole_number(0, kMaxThreads));
  auto* keep_all = cmd->add_flag("--keep-all-strokes", opt->keep_all_strokes,
                                 "Surface every stroke, also those that seem to depict no surface (a "
                                 "dot apart, a stroke hanging by one end)");
  cmd->add_flag("--tubes", opt->tubes,
                "Draw the strokes that seem to depict no surface as thin closed tubes apart from the "
                "surface (as thick as their brush, else 0.4% of the diagonal), instead of leaving them "
                "out")
      ->excludes(keep_all);
  cmd->add_flag("--closed", opt->closed,
                "Keep the surface closed: do not open it at rims found in the strokes (a closed loop "
                "with nothing drawn across or beyond it, such as a cup's top)");
  cmd->add_flag("--force", opt->force,
                "Write the surface even when the strokes do not seem to depict one (a hatching, "
                "writing or painterly scene: exit 4 otherwise)");
  cmd->add_flag("--with-strokes", opt->with_strokes,
                "In a .glb/.gltf output, also the strokes, as a second mesh of line strips");
  cmd->callback([opt, &global] { run_surface(*opt, global); });
}

}  // namespace sketchsurf::cli
