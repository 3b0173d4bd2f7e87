// sketchsurf-studio: draw a 3D sketch with a 6-DoF controller (the mouse emulating one, or a
// replayed track), mark what matters, surface it and see the surface appear over the strokes.
// Thin main(): parses into StudioOptions, runs the window, --headless or --xr, maps errors to exit
// codes (0 ok, 2 usage, 3 invalid input, 4 processing failed / no display, 130 cancelled).

#include <CLI/CLI.hpp>

#include <iostream>
#include <new>

#include "surfacing/error.h"
#include "tools/sketchsurf-studio/run.h"

namespace {

using namespace sketchsurf;

/// "WxH" -> width, height (each 1..16384).
std::pair<int, int> parse_size(const std::string& text) {
  const auto x = text.find('x');
  int w = 0, h = 0;
  try {
    std::size_t used = 0;
    if (x == std::string::npos) throw std::invalid_argument("no x");
    w = std::stoi(text.substr(0, x), &used);
    if (used != x) throw std::invalid_argument("width");
    h = std::stoi(text.substr(x + 1), &used);
    if (used != text.size() - x - 1) throw std::invalid_argument("height");
  } catch (const std::exception&) {
    throw Error::usage("--size: expected WIDTHxHEIGHT (e.g. 1280x720), got '" + text + "'");
  }
  if (w < 1 || h < 1 || w > 16384 || h > 16384)
    throw Error::usage("--size: each side must be 1..16384 pixels, got '" + text + "'");
  return {w, h};
}

/// "name=value" -> (name, value).
std::pair<std::string, double> parse_param(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw Error::usage("--param: expected NAME=VALUE (e.g. segment.epsilon=0.02), got '" + text + "'");
  try {
    std::size_t used = 0;
    const double v = std::stod(text.substr(eq + 1), &used);
    if (used != text.size() - eq - 1) throw std::invalid_argument("trailing");
    return {text.substr(0, eq), v};
  } catch (const std::exception&) {
    throw Error::usage("--param: '" + text.substr(eq + 1) + "' is not a number");
  }
}

}  // namespace

int main(int argc, char** argv) {
  studio::StudioOptions o;
  studio::Log log;
  CLI::App app{"sketchsurf-studio: draw a 3D sketch with a 6-DoF controller (or the mouse), surface it"};
  app.set_version_flag("--version", std::string("sketchsurf-studio ") + SKETCHSURF_VERSION);
  std::string size = "1280x720";
  std::vector<std::string> params;
  app.add_option("sketch", o.sketch, "Sketch to open (.json, .tilt, .curves, .obj)");
  app.add_option("--replay", o.replay, "Replay a recorded track (JSON) from the start");
  app.add_option("--record", o.record, "Record the session (controller and panel) to a track at exit");
  app.add_option("--screenshot", o.screenshot, "Write the last frame to this PNG");
  app.add_option("--frames", o.frames, "Run this many frames, then exit (a replay is spread over them)")
      ->check(CLI::Range(1, 100000000));
  app.add_option("--size", size, "Window or picture size WIDTHxHEIGHT")->capture_default_str();
  app.add_flag("--headless", o.headless, "No window: render offscreen (CI, scripted demos)");
  app.add_flag("--xr", o.xr, "In a headset through OpenXR (the desktop studio when there is none)");
  app.add_option("--save", o.save, "Write the sketch here at exit (.json, .tilt, .obj)");
  app.add_flag("--surface", o.surface, "Surface once the replay is over, and wait for it");
  app.add_option("--save-surface", o.save_surface, "Write the surface here at exit (implies --surface)");
  app.add_option("--proxy", o.proxy, "A proxy mesh (.obj, .ply) for surfacing instead of VIPSS's");
  app.add_option("--param", params, "Surfacing parameter NAME=VALUE (repeatable), e.g. segment.restarts=2");
  app.add_option("--autosave", o.autosave, "Autosave file (.json); default: one in the temporary directory");
  app.add_flag("--no-autosave", o.no_autosave, "Do not autosave");
  app.add_option("--msaa", o.msaa, "Multisampling: 1, 2 or 4 (default: 4 on a GPU, 1 on lavapipe)")
      ->check(CLI::IsMember({1, 2, 4}));
  app.add_option("--device", o.device, "Vulkan device whose name contains this");
  app.add_flag("--validation", o.validation, "Enable the Khronos validation layer and print its messages");
  bool no_vsync = false;
  app.add_flag("--no-vsync", no_vsync, "Present without waiting for the display's refresh");
  app.add_flag("-v,--verbose", o.verbose, "Say what happens (actions, autosaves, panel layout)");
  app.add_flag("-q,--quiet", o.quiet, "Nothing on stderr but errors");
  try {
    app.parse(argc, argv);
    o.vsync = !no_vsync;
    std::tie(o.width, o.height) = parse_size(size);
    for (const auto& p : params) o.params.insert(parse_param(p));
    if (!o.save_surface.empty()) o.surface = true;
    if (!o.replay.empty() && !o.record.empty() && o.replay == o.record)
      throw Error::usage("--record and --replay name the same file");
    log.verbose = o.verbose;
    log.quiet = o.quiet;
    if (o.xr) return studio::run_xr(o, log);
    return o.headless ? studio::run_headless(o, log) : studio::run_window(o, log);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  } catch (const Error& e) {
    std::cerr << "sketchsurf-studio: error: " << e.what() << "\n";
    return exit_code(e.kind());
  } catch (const std::bad_alloc&) {
    std::cerr << "sketchsurf-studio: error: out of memory\n";
    return 4;
  } catch (const std::exception& e) {
    std::cerr << "sketchsurf-studio: error: " << e.what() << "\n";
    return 4;
  }
}
