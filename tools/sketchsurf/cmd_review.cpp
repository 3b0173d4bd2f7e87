// sketchsurf review DIR|MESHES... -o OUTDIR: one contact sheet per result and an index page with
// the shape checks, for a person judging results by eye.

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

#include "engine/render/sheet.h"
#include "surfacing/error.h"
#include "surfacing/quality/checks.h"
#include "surfacing/sketch/io/atomic_file.h"
#include "surfacing/sketch/io/mesh_io.h"
#include "tools/sketchsurf/commands.h"
#include "tools/sketchsurf/run_files.h"

namespace sketchsurf::cli {

namespace {

namespace fs = std::filesystem;

struct ReviewCommandOptions {
  std::vector<std::string> inputs;
  std::string output;
  std::string sketches;
  render::SheetOptions sheet;
};

// The result meshes named: .ply files, and the .ply files of named folders (sorted).
std::vector<fs::path> result_meshes(const std::vector<std::string>& inputs) {
  std::vector<fs::path> out;
  for (const std::string& input : inputs) {
    if (fs::is_directory(input)) {
      std::vector<fs::path> found;
      for (const auto& entry : fs::directory_iterator(input))
        if (entry.is_regular_file() && entry.path().extension() == ".ply") found.push_back(entry.path());
      if (found.empty()) throw Error::input(input, "no .ply result mesh in this folder");
      std::sort(found.begin(), found.end());
      out.insert(out.end(), found.begin(), found.end());
    } else if (fs::is_regular_file(input)) {
      out.emplace_back(input);
    } else {
      throw Error::input(input, "no such file or folder");
    }
  }
  return out;
}

// The sketch a result was made from: the same name with a sketch extension, in `folder`.
std::optional<fs::path> find_sketch(const fs::path& mesh, const fs::path& folder) {
  for (const char* ext : {".json", ".curves", ".tilt", ".obj"}) {
    const fs::path candidate = folder / (mesh.stem().string() + ext);
    if (fs::is_regular_file(candidate) && candidate != mesh) return candidate;
  }
  return std::nullopt;
}

std::string html_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

std::string fixed(double value, int digits) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", digits, value);
  return text;
}

struct ReviewRow {
  std::string name, sketch, picture, error;
  ShapeChecks checks;
};

void write_index(const fs::path& file, const std::vector<ReviewRow>& rows) {
  write_atomically(file, [&](std::ostream& out) {
    out << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>sketchsurf review</title>\n"
           "<style>body{font-family:sans-serif;margin:1em}table{border-collapse:collapse}"
           "td,th{border:1px solid #ccc;padding:4px;vertical-align:top;font-size:13px}"
           "img{width:576px}.warn{color:#b00}</style></head><body>\n"
           "<h1>sketchsurf review</h1>\n<p>Pictures, left to right, top to bottom: strokes "
           "(three-quarter view), strokes (opposite side), surface with strokes, regions, surface "
           "alone from both sides. Area fractions are of the surface; beyond = farther than 5% of the "
           "diagonal from every stroke and not framed by strokes; outside = outside the strokes' box grown by 2%.</p>\n"
           "<table><tr><th>result</th><th>picture</th><th>regions</th><th>genus</th>"
           "<th>parts</th><th>holes</th><th>beyond</th><th>outside</th><th>crossing triangles</th>"
           "<th>border ratio</th><th>warnings</th></tr>\n";
    for (const ReviewRow& r : rows) {
      out << "<tr><td>" << html_escape(r.name) << "<br><small>" << html_escape(r.sketch)
          << "</small></td>";
      if (!r.error.empty()) {
        out << "<td colspan=\"10\" class=\"warn\">" << html_escape(r.error) << "</td></tr>\n";
        continue;
      }
      const ShapeChecks& c = r.checks;
      out << "<td><a href=\"" << html_escape(r.picture) << "\"><img src=\"" << html_escape(r.picture)
          << "\"></a></td><td>" << c.regions << "</td><td>" << c.genus << "</td><td>" << c.components
          << "</td><td>" << c.boundary_loops << "</td><td>" << fixed(100 * c.beyond, 1) << "%</td><td>"
          << fixed(100 * c.outside_box, 1) << "%</td><td>" << c.self_intersections << "</td><td>"
          << fixed(c.border_ratio, 2) << "</td><td class=\"warn\">";
      for (const std::string& w : c.warnings) out << html_escape(w) << "<br>";
      out << "</td></tr>\n";
    }
    out << "</table></body></html>\n";
  });
}

void run_review(const ReviewCommandOptions& opt, const GlobalOptions& global) {
  if (opt.sheet.tile < 64 || opt.sheet.tile > 2048)
    throw Error::usage("--tile: the picture size must be between 64 and 2048 pixels");
  const std::vector<fs::path> meshes = result_meshes(opt.inputs);
  // Every output is known before any work: a contact sheet per result and the index. The
  // folder is made first, so that RunFiles can check the outputs in it.
  std::error_code ec;
  fs::create_directories(opt.output, ec);
  if (ec || !fs::is_directory(opt.output))
    throw Error::usage("-o: cannot create the folder '" + opt.output + "' (" + ec.message() + ")");
  RunFiles files;
  std::vector<ReviewRow> rows(meshes.size());
  std::vector<std::optional<fs::path>> sketch_files(meshes.size());
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    const fs::path folder = opt.sketches.empty() ? meshes[i].parent_path() : fs::path(opt.sketches);
    sketch_files[i] = find_sketch(meshes[i], folder);
    files.input(meshes[i].string());
    if (sketch_files[i]) files.input(sketch_files[i]->string());
    rows[i].name = meshes[i].stem().string();
    rows[i].picture = rows[i].name + ".png";
  }
  const fs::path index = fs::path(opt.output) / "index.html";
  files.output("-o", index.string());
  for (const ReviewRow& row : rows) files.output("-o", (fs::path(opt.output) / row.picture).string());

  vk::ContextOptions context_options;
  context_options.log = [&global](const std::string& text) {
    if (!global.quiet) std::cerr << "sketchsurf: " << text << "\n";
  };
  const vk::Context context(context_options);

  std::size_t failed = 0;
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    if (cancel_requested()) break;  // commit() says so
    const fs::path& mesh_file = meshes[i];
    ReviewRow& row = rows[i];
    if (!global.quiet)
      std::cerr << "review: [" << i + 1 << "/" << meshes.size() << "] " << mesh_file.string() << "\n";
    try {
      if (!sketch_files[i])
        throw Error::input(mesh_file, "no sketch named " + row.name + ".(json|curves|tilt|obj) in '" +
                                          (opt.sketches.empty() ? mesh_file.parent_path().string()
                                                                : opt.sketches) +
                                          "' (set --sketches)");
      row.sketch = sketch_files[i]->string();
      Warnings warnings;
      const Sketch sketch = read_sketch(*sketch_files[i], &warnings);
      MeshAttributes attributes;
      const TriMesh mesh = read_mesh(mesh_file, &attributes);
      const bool open = std::any_of(sketch.strokes.begin(), sketch.strokes.end(),
                                    [](const Stroke& s) { return s.boundary; });
      row.checks = check_shape(mesh, attributes.labels, sketch, open);
      const render::RgbaImage sheet = render::contact_sheet(context, sketch, &mesh, attributes, opt.sheet);
      files.write((fs::path(opt.output) / row.picture).string(),
                  [&](const fs::path& file) { render::write_png(sheet, file); });
    } catch (const Error& e) {
      if (e.kind() == ErrorKind::Cancelled) throw;
      row.error = e.what();
      row.picture.clear();
      ++failed;
      if (!global.quiet) std::cerr << "review: " << e.what() << "\n";
    }
  }
  files.write(index.string(), [&](const fs::path& file) { write_index(file, rows); });
  files.commit();
  if (!global.quiet)
    std::cerr << "review: " << rows.size() - failed << " contact sheets in " << index.string()
              << (failed ? ", " + std::to_string(failed) + " failed" : "") << "\n";
  if (failed) throw Error::processing(std::to_string(failed) + " of " + std::to_string(rows.size()) +
                                      " results could not be reviewed (see index.html)");
}

}  // namespace

void add_review_command(CLI::App& app, const GlobalOptions& global) {
  auto opt = std::make_shared<ReviewCommandOptions>();
  auto* cmd = app.add_subcommand("review", "Contact sheets of results and an index page with the shape checks");
  cmd->add_option("RESULTS", opt->inputs, "Result meshes (.ply) or folders of them")->required();
  cmd->add_option("-o,--output", opt->output, "Folder for the pictures and index.html")->required();
  cmd->add_option("--sketches", opt->sketches,
                  "Folder of the sketches (NAME.json|curves|tilt|obj for NAME.ply); default: beside each result");
  cmd->add_option("--tile", opt->sheet.tile, "Pixels per picture (6 per sheet)")->capture_default_str();
  cmd->callback([opt, &global] { run_review(*opt, global); });
}

}  // namespace sketchsurf::cli
