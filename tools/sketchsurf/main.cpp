// sketchsurf: the command-line front end. Parses, dispatches to a command, maps errors to exit
// codes (0 ok, 2 usage, 3 invalid input, 4 processing failed, 130 cancelled).

#include <malloc.h>

#include <iostream>
#include <new>

#include "surfacing/error.h"
#include "tools/sketchsurf/commands.h"

int main(int argc, char** argv) {
  using namespace sketchsurf;
  // A run allocates and frees the same large arrays again and again (VIPSS's matrices for each
  // smoothing weight, each polygonisation's tables). From the heap, and kept there when freed,
  // they cost no fresh pages each time; handed back to the system, every reuse faults its pages
  // in anew (measured in docs/performance.md).
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
  CLI::App app{"sketchsurf: piecewise-smooth surfaces from unstructured 3D sketches"};
  app.set_version_flag("--version", std::string("sketchsurf ") + SKETCHSURF_VERSION);
  app.require_subcommand(1);
  app.fallthrough();
  cli::GlobalOptions global;
  app.add_flag("-v,--verbose", global.verbose, "Print the parameters in effect and more detail");
  app.add_flag("-q,--quiet", global.quiet, "No progress or warnings on stderr");

  cli::add_info_command(app, global);
  cli::add_convert_command(app, global);
  cli::add_proxy_command(app, global);
  cli::add_segment_command(app, global);
  cli::add_surface_command(app, global);
  cli::add_batch_command(app, global);
  cli::add_eval_command(app, global);
  cli::add_synth_command(app, global);
#ifdef SKETCHSURF_HAVE_ENGINE
  cli::add_render_command(app, global);
  cli::add_review_command(app, global);
#endif

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);  // prints help, version or the parse error
    return rc == 0 ? 0 : 2;
  } catch (const Error& e) {
    std::cerr << "sketchsurf: error: " << cli::printable(e.what()) << "\n";
    return exit_code(e.kind());
  } catch (const std::bad_alloc&) {
    std::cerr << "sketchsurf: error: out of memory\n";
    return 4;
  } catch (const std::exception& e) {
    std::cerr << "sketchsurf: error: " << cli::printable(e.what()) << "\n";
    return 4;
  }
  return 0;
}
