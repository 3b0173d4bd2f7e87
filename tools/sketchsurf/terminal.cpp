#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include "tools/sketchsurf/commands.h"

namespace sketchsurf::cli {

ProgressCallback stderr_progress(const GlobalOptions& global) {
  if (global.quiet) return {};
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
    return true;
  };
}

void print_warnings(const GlobalOptions& global, const std::string& file, const Warnings& warnings) {
  if (global.quiet) return;
  for (const auto& w : warnings) std::cerr << file << ": warning: " << w << "\n";
}

Sketch read_clean_sketch(const std::string& file, const GlobalOptions& global) {
  Warnings warnings;
  Sketch sketch = read_sketch(file, &warnings);
  print_warnings(global, file, warnings);
  const CleanReport cleaning = clean(sketch);
  if (!global.quiet)
    for (const auto& m : cleaning.messages) std::cerr << file << ": cleaned: " << m << "\n";
  return sketch;
}

}  // namespace sketchsurf::cli
