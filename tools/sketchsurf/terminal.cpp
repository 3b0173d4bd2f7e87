#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include "surfacing/proxy/proxy.h"
#include "surfacing/sketch/io/mesh_io.h"
#include "tools/sketchsurf/commands.h"
#include "tools/sketchsurf/run_files.h"

namespace sketchsurf::cli {

ProgressCallback stderr_progress(const GlobalOptions& global) {
  // Ctrl-C stops the work at the next report, quiet or not.
  if (global.quiet) return [](std::string_view, double) { return !cancel_requested(); };
  struct State {
    std::string stage;
    int last_step = -1;
    bool tty = isatty(STDERR_FILENO) != 0;
  };
  auto state = std::make_shared<State>();
  return [state](std::string_view stage, double fraction) {
    fraction = std::clamp(fraction, 0.0, 1.0);
    if (state->tty) {
      const int width = 30, filled = static_cast<int>(std::lround(fraction * width));
      std::fprintf(stderr, "\r%-24.*s [%s%s] %3d%%", static_cast<int>(stage.size()), stage.data(),
                   std::string(filled, '#').c_str(), std::string(width - filled, ' ').c_str(),
                   static_cast<int>(std::lround(fraction * 100)));
      if (fraction >= 1.0) std::fputc('\n', stderr);
      std::fflush(stderr);
    } else {
      const int step = static_cast<int>(fraction * 10);
      if (stage != state->stage || step != state->last_step) {
        std::fprintf(stderr, "%.*s: %d%%\n", static_cast<int>(stage.size()), stage.data(), step * 10);
        state->stage = std::string(stage);
        state->last_step = step;
      }
    }
    return !cancel_requested();
  };
}

void rethrow_naming(const std::string& file, const Error& e) {
  if (e.kind() == ErrorKind::Input) throw Error::input(file, e.what());
  if (e.kind() == ErrorKind::Processing) throw Error::processing(file + ": " + e.what());
  throw e;
}

void note_decorations(const GlobalOptions& global, const std::string& file,
                      const std::vector<Decoration>& decorations, std::size_t tubes,
                      const std::string& keep_hint) {
  if (global.quiet || decorations.empty()) return;
  std::cerr << file << ": note: ignored " << decorations.size()
            << " stroke(s) that depict no surface (id";
  for (const Decoration& d : decorations)
    std::cerr << " " << d.id
              << (d.kind == DecorationKind::SmallGroup ? " (small group apart)"
                  : d.kind == DecorationKind::Dangling ? " (hangs by one end)"
                                                       : " (a dot)");
  if (tubes > 0)
    std::cerr << "), drawn as " << tubes << " thin tube(s) apart from the surface\n";
  else
    std::cerr << "); " << keep_hint << "\n";
}

void print_warnings(const GlobalOptions& global, const std::string& file, const Warnings& warnings) {
  if (global.quiet) return;
  for (const auto& w : warnings) std::cerr << printable(file) << ": warning: " << printable(w) << "\n";
}

std::string printable(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x20 || c == '\n' || c == '\t') {
      out += c;
    } else {
      static constexpr char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[byte >> 4];
      out += kHex[byte & 15];
    }
  }
  return out;
}

Sketch read_clean_sketch(const std::string& file, const GlobalOptions& global) {
  Warnings warnings;
  Sketch sketch = read_sketch(file, &warnings);
  print_warnings(global, file, warnings);
  check_extent(sketch, file);
  const CleanReport cleaning = clean(sketch);
  if (!global.quiet)
    for (const auto& m : cleaning.messages) std::cerr << file << ": cleaned: " << m << "\n";
  return sketch;
}

TriMesh read_proxy_mesh(const std::string& file, const Sketch& sketch) {
  TriMesh mesh = read_mesh(file);
  if (const std::string problem = proxy_mesh_problem(mesh, sketch); !problem.empty())
    throw Error::input(file, "the mesh " + problem);
  return mesh;
}

}  // namespace sketchsurf::cli
