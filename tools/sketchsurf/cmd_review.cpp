// sketchsurf review DIR|MESHES... -o OUTDIR: one contact sheet per result and an index page with
// the shape checks, for a person judging results by eye. A folder is searched with its
// subfolders, so a batch's output folder is reviewed as it is, its summary naming the sketches.

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
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

// A result to review: its mesh, the name it is listed by (its path under the folder named, without
// the extension) and its sketch when a batch's summary names it.
struct ResultMesh {
  fs::path mesh;
  fs::path name;
  std::optional<fs::path> sketch;
};

// The sketch of each result in a folder that a batch wrote (its summary.json, from `sketchsurf
// batch` or the Python package's: output, relative to the folder or not -> sketch), keyed by the
// output's absolute path; empty when the folder has no summary.
std::map<fs::path, fs::path> batch_sketches(const fs::path& folder) {
  const fs::path file = folder / "summary.json";
  std::map<fs::path, fs::path> out;
  if (!fs::is_regular_file(file)) return out;
  nlohmann::json rows;
  try {
    std::ifstream in(file);
    rows = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw Error::input(file, std::string("not a batch summary: ") + e.what());
  }
  if (!rows.is_array()) throw Error::input(file, "not a batch summary: not a list of results");
  for (const nlohmann::json& row : rows)
    if (row.is_object() && row.contains("output") && row["output"].is_string() && row.contains("sketch") &&
        row["sketch"].is_string())
      out[fs::absolute(folder / row["output"].get<std::string>()).lexically_normal()] =
          row["sketch"].get<std::string>();
  return out;
}

// The results named: .ply files, and the .ply files in named folders and their subfolders (sorted).
std::vector<ResultMesh> result_meshes(const std::vector<std::string>& inputs) {
  std::vector<ResultMesh> out;
  for (const std::string& input : inputs) {
    if (fs::is_directory(input)) {
      const std::map<fs::path, fs::path> sketches = batch_sketches(input);
      std::vector<ResultMesh> found;
      for (const auto& entry : fs::recursive_directory_iterator(input)) {
        if (!entry.is_regular_file() || entry.path().extension() != ".ply") continue;
        const fs::path relative = entry.path().lexically_relative(input);
        ResultMesh result{entry.path(), fs::path(relative).replace_extension(), std::nullopt};
        if (const auto it = sketches.find(fs::absolute(entry.path()).lexically_normal()); it != sketches.end())
          result.sketch = it->second;
        found.push_back(std::move(result));
      }
      if (found.empty()) throw Error::input(input, "no .ply result mesh in this folder or its subfolders");
      std::sort(found.begin(), found.end(),
                [](const ResultMesh& a, const ResultMesh& b) { return a.mesh < b.mesh; });
      out.insert(out.end(), found.begin(), found.end());
    } else if (fs::is_regular_file(input)) {
      out.push_back({fs::path(input), fs::path(input).stem(), std::nullopt});
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

// Where a result's sketch is: under --sketches (at the result's place in its folder, else at the
// top), else the one its batch's summary names, else beside it.
std::optional<fs::path> result_sketch(const ResultMesh& result, const std::string& sketches) {
  if (!sketches.empty()) {
    if (auto found = find_sketch(result.mesh, fs::path(sketches) / result.name.parent_path())) return found;
    return find_sketch(result.mesh, sketches);
  }
  if (result.sketch) return fs::is_regular_file(*result.sketch) ? result.sketch : std::nullopt;
  return find_sketch(result.mesh, result.mesh.parent_path());
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
  const std::vector<ResultMesh> meshes = result_meshes(opt.inputs);
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
    sketch_files[i] = result_sketch(meshes[i], opt.sketches);
    files.input(meshes[i].mesh.string());
    if (sketch_files[i]) files.input(sketch_files[i]->string());
    rows[i].name = meshes[i].name.generic_string();
    rows[i].picture = rows[i].name + ".png";
  }
  const fs::path index = fs::path(opt.output) / "index.html";
  files.output("-o", index.string());
  for (const ReviewRow& row : rows) {
    const fs::path picture = fs::path(opt.output) / row.picture;
    fs::create_directories(picture.parent_path(), ec);  // a subfolder's results: the same subfolder
    files.output("-o", picture.string());
  }

  vk::ContextOptions context_options;
  context_options.log = [&global](const std::string& text) {
    if (!global.quiet) std::cerr << "sketchsurf: " << text << "\n";
  };
  const vk::Context context(context_options);

  std::size_t failed = 0;
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    if (cancel_requested()) break;  // commit() says so
    const fs::path& mesh_file = meshes[i].mesh;
    ReviewRow& row = rows[i];
    if (!global.quiet)
      std::cerr << "review: [" << i + 1 << "/" << meshes.size() << "] " << mesh_file.string() << "\n";
    try {
      if (!sketch_files[i])
        throw Error::input(mesh_file, meshes[i].sketch && opt.sketches.empty()
                                          ? "its batch summary names the sketch " + meshes[i].sketch->string() +
                                                ", which is not there (set --sketches)"
                                          : "no sketch named " + mesh_file.stem().string() +
                                                ".(json|curves|tilt|obj) in '" +
                                                (opt.sketches.empty() ? mesh_file.parent_path().string()
                                                                      : opt.sketches) +
                                                "' (set --sketches)");
      row.sketch = sketch_files[i]->string();
      Warnings warnings;
      Sketch sketch;
      try {
        sketch = read_sketch(*sketch_files[i], &warnings);
      } catch (const Error& e) {  // e.g. a batch's report beside its result, taken for the sketch
        if (e.kind() != ErrorKind::Input) throw;
        throw Error::input(mesh_file, std::string("its sketch could not be read (") + e.what() +
                                          "); set --sketches to the folder of the sketches");
      }
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
  cmd->add_option("RESULTS", opt->inputs,
                  "Result meshes (.ply) or folders of them (with their subfolders: a batch's output folder)")
      ->required();
  cmd->add_option("-o,--output", opt->output, "Folder for the pictures and index.html")->required();
  cmd->add_option("--sketches", opt->sketches,
                  "Folder of the sketches (NAME.json|curves|tilt|obj for NAME.ply, in the same subfolder "
                  "as the result or at the top); default: those a batch's summary.json names, else beside "
                  "each result");
  cmd->add_option("--tile", opt->sheet.tile, "Pixels per picture (6 per sheet)")->capture_default_str();
  cmd->callback([opt, &global] { run_review(*opt, global); });
}

}  // namespace sketchsurf::cli
