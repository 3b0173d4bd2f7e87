// sketchsurf render SKETCH [--mesh MESH] -o OUT.png: pictures of a sketch and a surface, rendered
// headless with Vulkan (lavapipe on machines without a GPU).

#include <cmath>
#include <iostream>
#include <memory>

#include "engine/render/headless.h"
#include "surfacing/error.h"
#include "surfacing/sketch/io/mesh_io.h"
#include "tools/sketchsurf/commands.h"
#include "tools/sketchsurf/run_files.h"

namespace sketchsurf::cli {

namespace {

struct RenderCommandOptions {
  std::string sketch;
  std::string mesh;
  std::string output;
  std::string size = "1024x1024";
  std::string view = "iso";
  std::string camera;
  std::string background = "#ffffff";
  std::string device;
  int turntable = 0;
  int msaa = 4;
  bool regions = false;
  bool no_strokes = false;
  bool no_hidden = false;
  render::SceneOptions scene;
};

std::pair<int, int> parse_size(const std::string& text) {
  const auto x = text.find('x');
  try {
    std::size_t used_w = 0, used_h = 0;
    if (x == std::string::npos) throw std::invalid_argument("no x");
    const int w = std::stoi(text.substr(0, x), &used_w);
    const int h = std::stoi(text.substr(x + 1), &used_h);
    if (used_w != x || used_h != text.size() - x - 1 || w < 1 || h < 1 || w > 16384 || h > 16384)
      throw std::invalid_argument("range");
    return {w, h};
  } catch (const std::logic_error&) {
    throw Error::usage("--size: expected WIDTHxHEIGHT with each in 1..16384, e.g. 800x600; got '" +
                       text + "'");
  }
}

/// "#rrggbb", "rrggbb" or "r,g,b" with components in [0, 1].
std::array<float, 4> parse_color(const std::string& text) {
  std::string hex = text.rfind('#', 0) == 0 ? text.substr(1) : text;
  if (hex.size() == 6 && hex.find_first_not_of("0123456789abcdefABCDEF") == std::string::npos) {
    const unsigned long v = std::stoul(hex, nullptr, 16);
    return {float((v >> 16) & 255) / 255.f, float((v >> 8) & 255) / 255.f, float(v & 255) / 255.f, 1.f};
  }
  std::array<float, 4> c{0.f, 0.f, 0.f, 1.f};
  std::size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    const std::size_t comma = i < 2 ? text.find(',', start) : text.size();
    try {
      if (comma == std::string::npos) throw std::invalid_argument("count");
      std::size_t used = 0;
      const std::string item = text.substr(start, comma - start);
      c[i] = std::stof(item, &used);
      if (used != item.size() || !(c[i] >= 0.f && c[i] <= 1.f)) throw std::invalid_argument("range");
    } catch (const std::logic_error&) {
      throw Error::usage("--background: expected #rrggbb or r,g,b with components in [0, 1]; got '" +
                         text + "'");
    }
    start = comma + 1;
  }
  return c;
}

/// Refuses a picture whose images (multisampled colour and depth, resolved colour, readback)
/// would take more than 2 GiB, before any Vulkan memory is asked for: beyond that lavapipe and
/// most GPUs run out of memory with a driver error that says nothing about --size.
void check_image_memory(int width, int height, int msaa) {
  constexpr double kMaxBytes = 2.0 * (1ull << 30);
  const double bytes = double(width) * double(height) * (8.0 * msaa + 8.0);
  if (bytes > kMaxBytes) {
    char text[64];
    std::snprintf(text, sizeof text, "%.1f GiB", bytes / (1ull << 30));
    throw Error::usage("--size " + std::to_string(width) + "x" + std::to_string(height) +
                       " with --msaa " + std::to_string(msaa) + " needs about " + text +
                       " of image memory, more than the 2 GiB a render may take: choose a "
                       "smaller --size or a lower --msaa");
  }
}

/// OUT.png for a single picture; OUT_000.png, OUT_001.png, ... for a turntable.
std::filesystem::path frame_path(const std::filesystem::path& out, int frame, int frames) {
  if (frames <= 1) return out;
  char suffix[16];
  std::snprintf(suffix, sizeof suffix, "_%03d", frame);
  return out.parent_path() / (out.stem().string() + suffix + out.extension().string());
}

void run_render(const RenderCommandOptions& opt, const GlobalOptions& global) {
  const auto [width, height] = parse_size(opt.size);
  const std::array<float, 4> background = parse_color(opt.background);
  const auto view = render::parse_view(opt.view);
  if (!view) {
    std::string names;
    for (const auto& n : render::view_names()) names += (names.empty() ? "" : ", ") + n;
    throw Error::usage("--view: unknown view '" + opt.view + "' (one of " + names + ")");
  }
  check_image_memory(width, height, opt.msaa);
  RunFiles files;
  files.input(opt.sketch);
  files.input(opt.mesh);
  const int frames = std::max(opt.turntable, 1);
  for (int f = 0; f < frames; ++f)
    files.output("-o", frame_path(opt.output, f, opt.turntable).string(), {".png"});
  if (opt.regions && opt.mesh.empty()) throw Error::usage("--regions needs --mesh");
  std::string why;
  if (!opt.scene.valid(&why)) throw Error::usage(why);

  Warnings warnings;
  const Sketch sketch = read_sketch(opt.sketch, &warnings);
  print_warnings(global, opt.sketch, warnings);
  std::optional<TriMesh> mesh;
  MeshAttributes attributes;
  if (!opt.mesh.empty()) mesh = read_mesh(opt.mesh, &attributes);
  if (opt.regions && attributes.labels.empty() && !global.quiet)
    std::cerr << opt.mesh << ": warning: no vertex labels; --regions draws one colour\n";

  render::SceneOptions scene_options = opt.scene;
  scene_options.regions = opt.regions;
  const render::SceneGeometry scene =
      render::build_scene(sketch, mesh ? &*mesh : nullptr, &attributes, scene_options);

  vk::ContextOptions context_options;
  context_options.device = opt.device;
  context_options.log = [&global](const std::string& line) {
    if (!global.quiet) std::cerr << "sketchsurf: " << line << "\n";
  };
  const vk::Context context(context_options);
  render::HeadlessRenderer renderer(context, width, height,
                                    static_cast<VkSampleCountFlagBits>(opt.msaa));
  renderer.set_scene(scene);

  const double aspect = double(width) / double(height);
  const render::Camera camera = opt.camera.empty()
                                    ? render::fit_camera(scene.bounds, *view, aspect)
                                    : render::parse_camera(opt.camera, scene.bounds);
  render::DrawOptions draw;
  draw.background = background;
  draw.strokes = !opt.no_strokes;
  draw.hidden_strokes = !opt.no_hidden;
  if (global.verbose)
    std::cerr << "render: device '" << context.device_info().name << "', " << width << "x" << height
              << ", " << renderer.samples() << "x MSAA, " << scene.stroke_points << " stroke points, "
              << scene.mesh_indices.size() / 3 << " triangles, " << scene.outlined_edges
              << " outlined edges; eye (" << camera.eye.transpose() << "), target ("
              << camera.target.transpose() << ")\n";

  for (int f = 0; f < frames; ++f) {
    if (cancel_requested()) break;  // commit() reports it
    const render::Camera frame_camera = render::orbit(camera, 2.0 * M_PI * f / frames);
    const auto file = frame_path(opt.output, f, opt.turntable);
    const render::RgbaImage image = renderer.render(frame_camera, draw);
    files.write(file.string(), [&](const auto& path) { render::write_png(image, path); });
    if (global.verbose) std::cerr << "render: wrote " << file.string() << "\n";
  }
  files.commit();
}

}  // namespace

void add_render_command(CLI::App& app, const GlobalOptions& global) {
  auto opt = std::make_shared<RenderCommandOptions>();
  auto* cmd = app.add_subcommand("render", "Render a sketch (and a surface) to PNG, headless (Vulkan)");
  cmd->add_option("SKETCH", opt->sketch, "Sketch (.tilt, .curves, .obj, .json)")->required();
  cmd->add_option("--mesh", opt->mesh, "Surface mesh to draw (.obj or .ply; PLY vertex labels give regions)");
  cmd->add_option("-o,--output", opt->output, "Output PNG (with --turntable N: OUT_000.png ...)")->required();
  cmd->add_option("--size", opt->size, "Picture size WIDTHxHEIGHT in pixels")->capture_default_str();
  auto* view = cmd->add_option("--view", opt->view, "Named view: front, back, left, right, top, iso")
                   ->capture_default_str();
  cmd->add_option("--camera", opt->camera, "Explicit camera ex,ey,ez,tx,ty,tz[,ux,uy,uz] (up defaults to +y)")
      ->excludes(view);
  cmd->add_option("--turntable", opt->turntable, "Render N frames turning around the up axis")
      ->check(CLI::Range(1, 3600));
  cmd->add_option("--background", opt->background, "Background colour #rrggbb or r,g,b in [0, 1]")
      ->capture_default_str();
  cmd->add_option("--msaa", opt->msaa, "Multisampling: 1, 2 or 4 samples per pixel (fewer if unsupported)")
      ->check(CLI::IsMember({1, 2, 4}))
      ->capture_default_str();
  cmd->add_option("--device", opt->device, "Use the Vulkan device whose name contains this");
  cmd->add_flag("--regions", opt->regions, "Colour the mesh by its vertex labels (region palette)");
  cmd->add_flag("--no-strokes", opt->no_strokes, "Do not draw the strokes");
  cmd->add_flag("--no-hidden", opt->no_hidden, "Do not draw strokes hidden by the surface (faint)");
  cmd->add_flag("--wireframe", opt->scene.wireframe, "Draw every mesh edge");
  cmd->add_flag("--stroke-colors", opt->scene.stroke_colors, "Draw strokes in their own colours");
  cmd->add_option("--stroke-width", opt->scene.stroke_width, "Stroke width, fraction of the bbox diagonal")
      ->capture_default_str();
  cmd->add_option("--sharp-angle", opt->scene.sharp_angle,
                  "Outline mesh edges with a dihedral angle above this (degrees; 180 = off)")
      ->capture_default_str();
  cmd->callback([opt, &global] { run_render(*opt, global); });
}

}  // namespace sketchsurf::cli
