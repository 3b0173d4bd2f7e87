// sketchsurf convert IN OUT: any sketch reader to any sketch writer, by extension.

#include <filesystem>
#include <iostream>
#include <memory>

#include "tools/sketchsurf/commands.h"
#include "tools/sketchsurf/run_files.h"

namespace sketchsurf::cli {

namespace {

struct ConvertOptions {
  std::string input, output;
  bool clean = false;
};

void run_convert(const ConvertOptions& opt, const GlobalOptions& global) {
  // A wrong output is a usage error before any time goes into reading.
  RunFiles files;
  files.input(opt.input);
  files.output("OUT", opt.output, writable_sketch_extensions());
  Warnings warnings;
  Sketch sketch = read_sketch(opt.input, &warnings);
  print_warnings(global, opt.input, warnings);
  if (opt.clean) {
    const CleanReport report = clean(sketch);
    if (!global.quiet)
      for (const auto& m : report.messages) std::cerr << opt.input << ": " << m << "\n";
  }
  files.write(opt.output, [&](const auto& file) { write_sketch(sketch, file); });
  files.commit();
  if (global.verbose)
    std::cerr << "wrote " << opt.output << ": " << sketch.strokes.size() << " strokes, "
              << sketch.point_count() << " points\n";
}

}  // namespace

void add_convert_command(CLI::App& app, const GlobalOptions& global) {
  auto opt = std::make_shared<ConvertOptions>();
  auto* cmd = app.add_subcommand("convert", "Convert a sketch between formats (by extension)");
  cmd->add_option("IN", opt->input, "Input sketch (.tilt, .curves, .obj, .json)")->required();
  cmd->add_option("OUT", opt->output, "Output sketch (.json, .tilt, .obj, .curves)")->required();
  cmd->add_flag("--clean", opt->clean, "Remove NaN/Inf points, duplicates and too-short strokes");
  cmd->callback([opt, &global] { run_convert(*opt, global); });
}

}  // namespace sketchsurf::cli
