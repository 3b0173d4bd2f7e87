// sketchsurf synth MESH -o SKETCH [--style net|vr] [--seed N] ...: a sketch drawn on a known
// surface (feature curves, cross sections, silhouettes), clean or with the flaws of VR drawing,
// so that a surfacing of it can be measured against the mesh (eval).

#include <iostream>
#include <map>
#include <memory>

#include "surfacing/quality/synth.h"
#include "surfacing/sketch/io/mesh_io.h"
#include "tools/sketchsurf/commands.h"
#include "tools/sketchsurf/run_files.h"

namespace sketchsurf::cli {

namespace {

struct SynthCommandOptions {
  std::string mesh, output;
  SynthOptions synth;
};

void run_synth(const SynthCommandOptions& opt, const GlobalOptions& global) {
  std::string why;
  if (!opt.synth.valid(&why)) throw Error::usage(why);
  RunFiles files;
  files.input(opt.mesh);
  files.output("-o", opt.output, writable_sketch_extensions());
  const TriMesh mesh = read_mesh(opt.mesh);
  if (global.verbose) {
    const SynthOptions& s = opt.synth;
    std::cerr << "synth: style " << (s.style == SynthOptions::Style::Net ? "net" : "vr") << ", seed "
              << s.seed << ", sharp angle " << s.sharp_angle << ", sections " << s.sections
              << ", silhouettes " << s.silhouettes << ", spacing " << s.spacing << ", tremor "
              << s.tremor << ", gap " << s.gap << ", overshoot " << s.overshoot << ", duplicate "
              << s.duplicate << ", drop " << s.drop << "\n";
  }
  Sketch sketch;
  try {
    sketch = synthesize_sketch(mesh, opt.synth);
  } catch (const Error& e) {
    if (e.kind() != ErrorKind::Input) throw;
    throw Error::input(opt.mesh, e.what());
  }
  if (sketch.strokes.empty())
    throw Error::processing(opt.mesh + ": no stroke drawn (no crease, section or silhouette long "
                            "enough); lower --min-length or add --sections");
  files.write(opt.output, [&](const auto& file) { write_sketch(sketch, file); });
  files.commit();
  if (!global.quiet)
    std::cerr << "synth: " << sketch.strokes.size() << " strokes, " << sketch.point_count()
              << " points\n";
}

}  // namespace

void add_synth_command(CLI::App& app, const GlobalOptions& global) {
  auto opt = std::make_shared<SynthCommandOptions>();
  SynthOptions& s = opt->synth;
  auto* cmd = app.add_subcommand("synth", "Draw a synthetic sketch on a mesh (ground truth for eval)");
  cmd->add_option("MESH", opt->mesh, "Mesh to draw on (.obj, .ply)")->required();
  cmd->add_option("-o,--output", opt->output, "Sketch (.json, .obj, .curves, .tilt)")->required();
  const std::map<std::string, SynthOptions::Style> styles{{"net", SynthOptions::Style::Net},
                                                          {"vr", SynthOptions::Style::Vr}};
  cmd->add_option("--style", s.style, "net: clean strokes on the mesh; vr: tremor, gaps, "
                                      "overshoots, duplicates, dropped strokes")
      ->transform(CLI::CheckedTransformer(styles, CLI::ignore_case))
      ->default_str("net");
  cmd->add_option("--seed", s.seed, "Seed of the vr flaws")->capture_default_str();
  cmd->add_option("--sharp-angle", s.sharp_angle, "Edges with a larger dihedral angle (degrees) "
                                                  "are feature curves")
      ->capture_default_str()
      ->check(positive_number());
  cmd->add_option("--sections", s.sections, "Cross sections per principal axis")
      ->capture_default_str()
      ->check(whole_number(0, 1000));
  cmd->add_option("--silhouettes", s.silhouettes, "View directions whose contour is drawn")
      ->capture_default_str()
      ->check(whole_number(0, 1000));
  cmd->add_option("--spacing", s.spacing, "Point spacing, fraction of the bbox diagonal")
      ->capture_default_str()
      ->check(positive_number());
  cmd->add_option("--min-length", s.min_length, "Shorter pieces are dropped, fraction of the diagonal")
      ->capture_default_str()
      ->check(non_negative_number());
  cmd->add_option("--tremor", s.tremor, "vr: RMS hand tremor, fraction of the diagonal")
      ->capture_default_str()
      ->check(non_negative_number());
  cmd->add_option("--gap", s.gap, "vr: probability of a stroke drawn in two pieces")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--overshoot", s.overshoot, "vr: largest extension past a stroke's end, "
                                              "fraction of the diagonal")
      ->capture_default_str()
      ->check(non_negative_number());
  cmd->add_option("--duplicate", s.duplicate, "vr: probability of a stroke drawn twice")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--drop", s.drop, "vr: probability of a stroke left out")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd->callback([opt, &global] {
    run_synth(*opt, global);
  });
}

}  // namespace sketchsurf::cli
