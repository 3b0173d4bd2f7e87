// sketchsurf eval RESULT --truth TRUE [--sketch SKETCH] [--json R] [--deviation D.ply] [--png P]:
// a surface measured against its ground truth (accuracy, completeness, creases).

#include <cstdio>
#include <iostream>
#include <memory>

#include "surfacing/error.h"
#include "surfacing/quality/checks.h"
#include "surfacing/quality/eval.h"
#include "surfacing/sketch/io/atomic_file.h"
#include "surfacing/sketch/io/mesh_io.h"
#include "tools/sketchsurf/commands.h"
#include "tools/sketchsurf/reports.h"
#include "tools/sketchsurf/run_files.h"
#ifdef SKETCHSURF_HAVE_ENGINE
#include "engine/render/headless.h"
#endif

namespace sketchsurf::cli {

namespace {

struct EvalCommandOptions {
  std::string result, truth, sketch, json, deviation, png;
  double scale = 0.02;
  EvalOptions eval;
};

nlohmann::json stats_json(const DistanceStats& s) {
  return {{"mean", s.mean}, {"median", s.median}, {"p95", s.p95}, {"p99", s.p99}, {"max", s.max},
          {"samples", s.count}};
}

std::string line(const char* what, const DistanceStats& s, double scale, const char* unit) {
  char text[256];
  std::snprintf(text, sizeof text, "%-13s median %.4g%s, p95 %.4g%s, p99 %.4g%s, max %.4g%s", what,
                scale * s.median, unit, scale * s.p95, unit, scale * s.p99, unit, scale * s.max, unit);
  return text;
}

void run_eval(const EvalCommandOptions& opt, const GlobalOptions& global) {
  std::string why;
  if (!opt.eval.valid(&why)) throw Error::usage(why);
#ifndef SKETCHSURF_HAVE_ENGINE
  if (!opt.png.empty()) throw Error::usage("--png: this build has no renderer (configure with SKETCHSURF_ENGINE=ON)");
#endif
  RunFiles files;
  files.input(opt.result);
  files.input(opt.truth);
  if (!opt.sketch.empty()) files.input(opt.sketch);
  if (!opt.png.empty()) files.output("--png", opt.png, {".png"});
  if (!opt.deviation.empty()) files.output("--deviation", opt.deviation, {".ply", ".obj"});
  if (!opt.json.empty()) files.output("--json", opt.json, {".json"});
  MeshAttributes result_attributes;
  const TriMesh result = read_mesh(opt.result, &result_attributes);
  const TriMesh truth = read_mesh(opt.truth);
  if (result.n_faces() == 0) throw Error::input(opt.result, "no triangles; give a surface mesh");
  if (truth.n_faces() == 0) throw Error::input(opt.truth, "no triangles; give a surface mesh");
  std::optional<Sketch> sketch;
  if (!opt.sketch.empty()) sketch = read_clean_sketch(opt.sketch, global);

  const Evaluation e = evaluate(result, truth, opt.eval);
  nlohmann::json j = {
      {"result", opt.result},
      {"truth", opt.truth},
      {"diagonal", e.diagonal},
      {"accuracy", stats_json(e.accuracy)},
      {"completeness", stats_json(e.completeness)},
      {"creases", {{"sharp_edges", e.creases.sharp_edges},
                   {"found", e.creases.found},
                   {"error_degrees", stats_json(e.creases.error)}}}};
  if (sketch) {
    const bool open = std::any_of(sketch->strokes.begin(), sketch->strokes.end(),
                                  [](const Stroke& s) { return s.boundary; });
    j["checks"] = checks_json(check_shape(result, result_attributes.labels, *sketch, open));
  }

  std::cout << line("accuracy", e.accuracy, 100.0, "%") << "  (result -> truth, of the diagonal)\n"
            << line("completeness", e.completeness, 100.0, "%") << "  (truth -> result)\n";
  if (e.creases.sharp_edges > 0) {
    char text[160];
    std::snprintf(text, sizeof text, "creases       %zu sharp edges, %.0f%% of their length found",
                  e.creases.sharp_edges, 100.0 * e.creases.found);
    std::cout << text;
    if (e.creases.error.count > 0) std::cout << "; " << line("error", e.creases.error, 1.0, " deg");
    std::cout << "\n";
  }

  MeshAttributes colored;
  for (double d : e.vertex_deviation) colored.colors.push_back(deviation_color(d, opt.scale));
  if (!opt.deviation.empty())
    files.write(opt.deviation, [&](const std::filesystem::path& f) { write_mesh(result, f, colored); });
#ifdef SKETCHSURF_HAVE_ENGINE
  if (!opt.png.empty()) {
    const render::SceneGeometry scene =
        render::build_scene(sketch ? *sketch : Sketch{}, &result, &colored, {});
    const vk::Context context;
    render::HeadlessRenderer renderer(context, 1024, 1024);
    renderer.set_scene(scene);
    const render::RgbaImage picture = renderer.render(render::fit_camera(scene.bounds, render::View::Iso, 1.0));
    files.write(opt.png, [&](const std::filesystem::path& f) { render::write_png(picture, f); });
  }
#endif
  if (!opt.json.empty())
    files.write(opt.json, [&](const std::filesystem::path& f) {
      write_atomically(f, [&](std::ostream& out) { out << j.dump(2) << "\n"; });
    });
  files.commit();
}

}  // namespace

void add_eval_command(CLI::App& app, const GlobalOptions& global) {
  auto opt = std::make_shared<EvalCommandOptions>();
  auto* cmd = app.add_subcommand("eval", "Measure a surface against its ground truth");
  cmd->add_option("RESULT", opt->result, "The surface to judge (.ply or .obj)")->required();
  cmd->add_option("--truth", opt->truth, "The true surface (.ply or .obj)")->required();
  cmd->add_option("--sketch", opt->sketch, "The sketch: adds the shape checks and strokes in --png");
  cmd->add_option("--json", opt->json, "Write the measures as JSON");
  cmd->add_option("--deviation", opt->deviation,
                  "Write RESULT coloured by its distance to the truth (.ply or .obj)");
  cmd->add_option("--png", opt->png, "Render the coloured RESULT (and the strokes) to PNG");
  cmd->add_option("--scale", opt->scale, "Deviation shown red, fraction of the truth's diagonal")
      ->capture_default_str();
  cmd->add_option("--samples", opt->eval.samples, "Sample points per surface")->capture_default_str();
  cmd->add_option("--sharp-angle", opt->eval.sharp_angle,
                  "Truth edges sharper than this are creases (degrees between normals)")
      ->capture_default_str();
  cmd->add_option("--seed", opt->eval.seed, "Seed of the sample points")->capture_default_str();
  cmd->callback([opt, &global] { run_eval(*opt, global); });
}

}  // namespace sketchsurf::cli
