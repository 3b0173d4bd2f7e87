// sketchsurf info FILE [--json]: what a sketch holds, and what cleaning would remove.

#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "tools/sketchsurf/commands.h"

namespace sketchsurf::cli {

namespace {

struct InfoOptions {
  std::string file;
  bool json = false;
};

nlohmann::json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

void run_info(const InfoOptions& opt, const GlobalOptions& global) {
  Warnings warnings;
  const Sketch sketch = read_sketch(opt.file, &warnings);
  Sketch cleaned = sketch;
  const CleanReport cleaning = clean(cleaned);

  std::size_t boundary = 0, ignored = 0;
  for (const auto& s : sketch.strokes) {
    boundary += s.boundary;
    ignored += s.ignored;
  }
  const BoundingBox box = sketch.bounding_box();
  const Eigen::Vector3d lo = box.empty() ? Eigen::Vector3d::Zero() : box.min;
  const Eigen::Vector3d hi = box.empty() ? Eigen::Vector3d::Zero() : box.max;

  if (opt.json) {
    nlohmann::json j;
    j["file"] = opt.file;
    j["strokes"] = sketch.strokes.size();
    j["points"] = sketch.point_count();
    j["total_length"] = sketch.total_length();
    j["bbox_min"] = vec(lo);
    j["bbox_max"] = vec(hi);
    j["diagonal"] = box.diagonal();
    j["units"] = sketch.units;
    j["mirror"] = sketch.mirror ? nlohmann::json{{"normal", vec(sketch.mirror->normal)},
                                                 {"offset", sketch.mirror->offset}}
                                : nlohmann::json(nullptr);
    j["annotations"] = {{"boundary", boundary}, {"ignored", ignored}};
    j["warnings"] = warnings;
    j["cleaning"] = cleaning.messages;
    std::cout << j.dump(2) << "\n";
    return;
  }
  print_warnings(global, opt.file, warnings);
  std::cout << opt.file << "\n"
            << "  strokes       " << sketch.strokes.size() << "\n"
            << "  points        " << sketch.point_count() << "\n"
            << "  total length  " << sketch.total_length() << " " << sketch.units << "\n"
            << "  bbox min      " << lo.transpose() << "\n"
            << "  bbox max      " << hi.transpose() << "\n"
            << "  diagonal      " << box.diagonal() << " " << sketch.units << "\n";
  if (sketch.mirror)
    std::cout << "  mirror plane  normal (" << sketch.mirror->normal.transpose() << "), offset "
              << sketch.mirror->offset << "\n";
  else
    std::cout << "  mirror plane  none\n";
  std::cout << "  annotations   " << boundary << " boundary, " << ignored << " ignored\n";
  if (cleaning.messages.empty()) std::cout << "  cleaning      nothing to remove\n";
  for (const auto& m : cleaning.messages) std::cout << "  cleaning      " << m << "\n";
}

}  // namespace

void add_info_command(CLI::App& app, const GlobalOptions& global) {
  auto opt = std::make_shared<InfoOptions>();
  auto* cmd = app.add_subcommand("info", "Describe a sketch: counts, size, annotations, problems");
  cmd->add_option("FILE", opt->file, "Sketch (.tilt, .curves, .obj, .json)")->required();
  cmd->add_flag("--json", opt->json, "Print one JSON object on stdout");
  cmd->callback([opt, &global] { run_info(*opt, global); });
}

}  // namespace sketchsurf::cli
