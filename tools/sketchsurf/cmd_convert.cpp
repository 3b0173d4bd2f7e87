// sketchsurf convert IN OUT: any sketch reader to any sketch writer, by extension.

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iostream>
#include <memory>

#include "tools/sketchsurf/commands.h"

namespace sketchsurf::cli {

namespace {

struct ConvertOptions {
  std::string input, output;
  bool clean = false;
};

void run_convert(const ConvertOptions& opt, const GlobalOptions& global) {
  // A wrong output extension is a usage error before any time goes into reading.
  std::string ext = std::filesystem::path(opt.output).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const auto writable = writable_sketch_extensions();
  if (std::find(writable.begin(), writable.end(), ext) == writable.end()) {
    std::string list;
    for (const auto& w : writable) list += (list.empty() ? "" : ", ") + w;
    throw Error::usage(opt.output + ": unknown sketch extension '" + ext + "' (writable: " + list + ")");
  }
  Warnings warnings;
  Sketch sketch = read_sketch(opt.input, &warnings);
  print_warnings(global, opt.input, warnings);
  if (opt.clean) {
    const CleanReport report = clean(sketch);
    if (!global.quiet)
      for (const auto& m : report.messages) std::cerr << opt.input << ": " << m << "\n";
  }
  write_sketch(sketch, opt.output);
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
  cmd->callback([opt, &global] {
    if (opt->input == opt->output) throw Error::usage("IN and OUT are the same file");
    run_convert(*opt, global);
  });
}

}  // namespace sketchsurf::cli
