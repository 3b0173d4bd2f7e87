#include "surfacing/pipeline.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <iomanip>
#include <sstream>

#include "surfacing/error.h"
#include "surfacing/extract/mirror.h"
#include "surfacing/sketch/crossings.h"
#include "surfacing/sketch/decorations.h"
#include "surfacing/sketch/scribbles.h"
#include "surfacing/sketch/symmetry.h"

namespace sketchsurf {

bool PrepareOptions::valid(std::string* why) const {
  if (!(resample_spacing >= 0.0 && resample_spacing < 1.0)) {
    if (why) *why = "prepare.resample_spacing must be in [0, 1)";
    return false;
  }
  if (min_points < 2) {
    if (why) *why = "prepare.min_points must be at least 2";
    return false;
  }
  return consolidation.valid(why) && decorations.valid(why) && tubes.valid(why) &&
         openings.valid(why) && mirror_detection.valid(why);
}

bool Params::valid(std::string* why) const {
  if (!(checks.refuse_scribbled >= 0.0 && checks.refuse_scribbled <= 1.0)) {
    if (why) *why = "checks.refuse_scribbled must be in [0, 1]";
    return false;
  }
  if (!(checks.scribble_fill >= 1.0 && std::isfinite(checks.scribble_fill))) {
    if (why) *why = "checks.scribble_fill must be at least 1";
    return false;
  }
  if (!(checks.refuse_unmet >= 0.0 && checks.refuse_unmet <= 1.0)) {
    if (why) *why = "checks.refuse_unmet must be in [0, 1]";
    return false;
  }
  if (!(checks.meet_reach > 0.0 && checks.meet_reach <= 1.0)) {
    if (why) *why = "checks.meet_reach must be in (0, 1]";
    return false;
  }
  if (!(checks.meet_angle >= 0.0 && checks.meet_angle <= 90.0)) {
    if (why) *why = "checks.meet_angle must be in [0, 90] degrees";
    return false;
  }
  return prepare.valid(why) && proxy.valid(why) && segment.valid(why) && extract.valid(why);
}

namespace {

using Setter = std::function<void(Params&, double)>;

template <class Member>
Setter setter(Member member) {
  return [member](Params& p, double value) {
    auto& field = std::invoke(member, p);
    using T = std::remove_reference_t<decltype(field)>;
    if constexpr (std::is_same_v<T, bool>) {
      field = value != 0.0;
    } else if constexpr (std::is_integral_v<T>) {
      if (value != std::floor(value) || value < 0.0)
        throw Error::usage("expects a whole number >= 0, got " + std::to_string(value));
      field = static_cast<T>(value);
    } else {
      field = value;
    }
  };
}

/// Every parameter apply() knows, by dotted name.
const std::map<std::string, Setter>& parameter_table() {
  static const std::map<std::string, Setter> table = {
      {"prepare.resample_spacing", setter([](Params& p) -> auto& { return p.prepare.resample_spacing; })},
      {"prepare.min_points", setter([](Params& p) -> auto& { return p.prepare.min_points; })},
      {"prepare.consolidate", setter([](Params& p) -> auto& { return p.prepare.consolidate; })},
      {"prepare.consolidation_radius", setter([](Params& p) -> auto& { return p.prepare.consolidation.radius; })},
      {"prepare.ignore_decorations", setter([](Params& p) -> auto& { return p.prepare.ignore_decorations; })},
      {"prepare.decoration_dot", setter([](Params& p) -> auto& { return p.prepare.decorations.dot; })},
      {"prepare.decoration_tubes", setter([](Params& p) -> auto& { return p.prepare.decoration_tubes; })},
      {"prepare.tube_radius", setter([](Params& p) -> auto& { return p.prepare.tubes.radius; })},
      {"prepare.tube_max_radius", setter([](Params& p) -> auto& { return p.prepare.tubes.max_radius; })},
      {"prepare.tube_sides", setter([](Params& p) -> auto& { return p.prepare.tubes.sides; })},
      {"prepare.open_rims", setter([](Params& p) -> auto& { return p.prepare.open_rims; })},
      {"prepare.complete_half", setter([](Params& p) -> auto& { return p.prepare.complete_half; })},
      {"proxy.points", setter([](Params& p) -> auto& { return p.proxy.points; })},
      {"proxy.lambda", setter([](Params& p) -> auto& { return p.proxy.lambda; })},
      {"proxy.edge", setter([](Params& p) -> auto& { return p.proxy.edge; })},
      {"proxy.cell", setter([](Params& p) -> auto& { return p.proxy.cell; })},
      {"proxy.padding", setter([](Params& p) -> auto& { return p.proxy.padding; })},
      {"proxy.remesh_iterations", setter([](Params& p) -> auto& { return p.proxy.remesh_iterations; })},
      {"proxy.attract_weight", setter([](Params& p) -> auto& { return p.proxy.attract_weight; })},
      {"proxy.attract_levels", setter([](Params& p) -> auto& { return p.proxy.attract_levels; })},
      {"proxy.attract_vipss", setter([](Params& p) -> auto& { return p.proxy.attract_vipss; })},
      {"proxy.max_proxy_distance", setter([](Params& p) -> auto& { return p.proxy.max_proxy_distance; })},
      {"proxy.lambda_min", setter([](Params& p) -> auto& { return p.proxy.lambda_min; })},
      {"proxy.lambda_max", setter([](Params& p) -> auto& { return p.proxy.lambda_max; })},
      {"proxy.lambda_step", setter([](Params& p) -> auto& { return p.proxy.lambda_step; })},
      {"proxy.clean_gap", setter([](Params& p) -> auto& { return p.proxy.clean_gap; })},
      {"proxy.clean_crossings", setter([](Params& p) -> auto& { return p.proxy.clean_crossings; })},
      {"proxy.clean_points", setter([](Params& p) -> auto& { return p.proxy.clean_points; })},
      {"proxy.clean_lambda", setter([](Params& p) -> auto& { return p.proxy.clean_lambda; })},
      {"extract.smooth_fallback", setter([](Params& p) -> auto& { return p.extract.smooth_fallback.enabled; })},
      {"extract.smooth_fallback_margin", setter([](Params& p) -> auto& { return p.extract.smooth_fallback.margin; })},
      {"extract.smooth_fallback_rounded_margin", setter([](Params& p) -> auto& { return p.extract.smooth_fallback.rounded_margin; })},
      {"extract.smooth_fallback_rounded_degree", setter([](Params& p) -> auto& { return p.extract.smooth_fallback.rounded_degree; })},
      {"extract.smooth_fallback_pull_ratio", setter([](Params& p) -> auto& { return p.extract.smooth_fallback.pull_ratio; })},
      {"extract.smooth_fallback_pull_weight", setter([](Params& p) -> auto& { return p.extract.smooth_fallback.pull_weight; })},
      {"extract.smooth_fallback_pull_curvature", setter([](Params& p) -> auto& { return p.extract.smooth_fallback.pull_curvature; })},
      {"extract.back_side_gap", setter([](Params& p) -> auto& { return p.extract.back_sides.gap; })},
      {"extract.outline_margin", setter([](Params& p) -> auto& { return p.extract.outline.margin; })},
      {"extract.outline_tolerance", setter([](Params& p) -> auto& { return p.extract.outline.tolerance; })},
      {"extract.outline_reach", setter([](Params& p) -> auto& { return p.extract.outline.reach; })},
      {"extract.outline_angle", setter([](Params& p) -> auto& { return p.extract.outline.angle; })},
      {"extract.outline_flat_share", setter([](Params& p) -> auto& { return p.extract.outline.flat_share; })},
      {"extract.outline_drawn_share", setter([](Params& p) -> auto& { return p.extract.outline.drawn_share; })},
      {"proxy.far_distance", setter([](Params& p) -> auto& { return p.proxy.far_distance; })},
      {"proxy.far_tie", setter([](Params& p) -> auto& { return p.proxy.far_tie; })},
      {"proxy.far_most", setter([](Params& p) -> auto& { return p.proxy.far_most; })},
      {"proxy.far_extra_genus", setter([](Params& p) -> auto& { return p.proxy.far_extra_genus; })},
      {"proxy.rounded_misfit", setter([](Params& p) -> auto& { return p.proxy.rounded_misfit; })},
      {"proxy.rounded_far", setter([](Params& p) -> auto& { return p.proxy.rounded_far; })},
      {"proxy.misfit_reach", setter([](Params& p) -> auto& { return p.proxy.misfit_reach; })},
      {"proxy.miss_distance", setter([](Params& p) -> auto& { return p.proxy.miss_distance; })},
      {"proxy.confine_margin", setter([](Params& p) -> auto& { return p.proxy.confine_margin; })},
      {"proxy.confine_radius", setter([](Params& p) -> auto& { return p.proxy.confine_radius; })},
      {"proxy.confine_near", setter([](Params& p) -> auto& { return p.proxy.confine_near; })},
      {"proxy.near_open_least", setter([](Params& p) -> auto& { return p.proxy.near_open_least; })},
      {"proxy.near_open_ratio", setter([](Params& p) -> auto& { return p.proxy.near_open_ratio; })},
      {"proxy.framed_gap", setter([](Params& p) -> auto& { return p.proxy.framed_gap; })},
      {"proxy.part_reach", setter([](Params& p) -> auto& { return p.proxy.part_reach; })},
      {"proxy.part_webs", setter([](Params& p) -> auto& { return p.proxy.part_webs; })},
      {"proxy.part_free", setter([](Params& p) -> auto& { return p.proxy.part_free; })},
      {"proxy.part_far_ratio", setter([](Params& p) -> auto& { return p.proxy.part_far_ratio; })},
      {"proxy.confine_box", setter([](Params& p) -> auto& { return p.proxy.confine_box; })},
      {"proxy.confine_box_tight", setter([](Params& p) -> auto& { return p.proxy.confine_box_tight; })},
      {"proxy.confine_box_span", setter([](Params& p) -> auto& { return p.proxy.confine_box_span; })},
      {"proxy.confine_box_partial", setter([](Params& p) -> auto& { return p.proxy.confine_box_partial; })},
      {"proxy.overshoot", setter([](Params& p) -> auto& { return p.proxy.overshoot; })},
      {"proxy.outline_gap", setter([](Params& p) -> auto& { return p.proxy.outline_gap; })},
      {"proxy.outline_reach", setter([](Params& p) -> auto& { return p.proxy.outline_reach; })},
      {"proxy.outline_from", setter([](Params& p) -> auto& { return p.proxy.outline_from; })},
      {"proxy.outline_to", setter([](Params& p) -> auto& { return p.proxy.outline_to; })},
      {"proxy.outline_blend", setter([](Params& p) -> auto& { return p.proxy.outline_blend; })},
      {"proxy.outline_most", setter([](Params& p) -> auto& { return p.proxy.outline_most; })},
      {"proxy.loft_fit", setter([](Params& p) -> auto& { return p.proxy.loft_fit; })},
      {"proxy.window_value", setter([](Params& p) -> auto& { return p.proxy.window_value; })},
      {"proxy.window_undrawn", setter([](Params& p) -> auto& { return p.proxy.window_undrawn; })},
      {"proxy.window_reach", setter([](Params& p) -> auto& { return p.proxy.window_reach; })},
      {"proxy.window_points", setter([](Params& p) -> auto& { return p.proxy.window_points; })},
      {"proxy.window_tight", setter([](Params& p) -> auto& { return p.proxy.window_tight; })},
      {"proxy.face_hole_thickness", setter([](Params& p) -> auto& { return p.proxy.face_hole_thickness; })},
      {"proxy.bridge_value", setter([](Params& p) -> auto& { return p.proxy.bridge_value; })},
      {"proxy.neck_value", setter([](Params& p) -> auto& { return p.proxy.neck_value; })},
      {"proxy.min_component", setter([](Params& p) -> auto& { return p.proxy.min_component; })},
      {"proxy.vipss_tolerance", setter([](Params& p) -> auto& { return p.proxy.vipss_tolerance; })},
      {"proxy.vipss_remesh_iterations", setter([](Params& p) -> auto& { return p.proxy.vipss_remesh_iterations; })},
      {"proxy.projection_steps", setter([](Params& p) -> auto& { return p.proxy.projection_steps; })},
      {"proxy.sample_spacing", setter([](Params& p) -> auto& { return p.proxy.sample_spacing; })},
      {"segment.epsilon", setter([](Params& p) -> auto& { return p.segment.epsilon; })},
      {"segment.w_smooth", setter([](Params& p) -> auto& { return p.segment.w_smooth; })},
      {"segment.w_simp", setter([](Params& p) -> auto& { return p.segment.w_simp; })},
      {"segment.mu", setter([](Params& p) -> auto& { return p.segment.mu; })},
      {"segment.lambda", setter([](Params& p) -> auto& { return p.segment.lambda; })},
      {"segment.init_boost", setter([](Params& p) -> auto& { return p.segment.init_boost; })},
      {"segment.max_degree", setter([](Params& p) -> auto& { return p.segment.max_degree; })},
      {"segment.merges_per_iteration", setter([](Params& p) -> auto& { return p.segment.merges_per_iteration; })},
      {"segment.max_iterations", setter([](Params& p) -> auto& { return p.segment.max_iterations; })},
      {"segment.min_gain", setter([](Params& p) -> auto& { return p.segment.min_gain; })},
      {"segment.restarts", setter([](Params& p) -> auto& { return p.segment.restarts; })},
      {"segment.tie", setter([](Params& p) -> auto& { return p.segment.tie; })},
      {"segment.tie_distance", setter([](Params& p) -> auto& { return p.segment.tie_distance; })},
      {"segment.tie_share", setter([](Params& p) -> auto& { return p.segment.tie_share; })},
      {"segment.fold", setter([](Params& p) -> auto& { return p.segment.fold; })},
      {"segment.fold_share", setter([](Params& p) -> auto& { return p.segment.fold_share; })},
      {"segment.seed", setter([](Params& p) -> auto& { return p.segment.seed; })},
      {"segment.simplify", setter([](Params& p) -> auto& { return p.segment.simplify; })},
      {"segment.crease_guides", setter([](Params& p) -> auto& { return p.segment.association.guides.enabled; })},
      {"segment.crease_same_way", setter([](Params& p) -> auto& { return p.segment.association.guides.same_way; })},
      {"segment.threads", setter([](Params& p) -> auto& { return p.segment.threads; })},
      {"checks.refuse_score", setter([](Params& p) -> auto& { return p.checks.refuse_score; })},
      {"checks.refuse_scribbled", setter([](Params& p) -> auto& { return p.checks.refuse_scribbled; })},
      {"checks.scribble_fill", setter([](Params& p) -> auto& { return p.checks.scribble_fill; })},
      {"checks.refuse_unmet", setter([](Params& p) -> auto& { return p.checks.refuse_unmet; })},
      {"checks.meet_reach", setter([](Params& p) -> auto& { return p.checks.meet_reach; })},
      {"checks.meet_angle", setter([](Params& p) -> auto& { return p.checks.meet_angle; })},
      {"checks.meet_least_strokes", setter([](Params& p) -> auto& { return p.checks.meet_least_strokes; })},
      {"extract.gamma_2d", setter([](Params& p) -> auto& { return p.extract.energy.gamma_2d; })},
      {"extract.gamma_1d", setter([](Params& p) -> auto& { return p.extract.energy.gamma_1d; })},
      {"extract.smooth_angle", setter([](Params& p) -> auto& { return p.extract.energy.smooth_angle; })},
      {"extract.sharp_angle", setter([](Params& p) -> auto& { return p.extract.energy.sharp_angle; })},
      {"extract.attract_weight", setter([](Params& p) -> auto& { return p.extract.energy.attract_weight; })},
      {"extract.trust_distance", setter([](Params& p) -> auto& { return p.extract.energy.trust_distance; })},
      {"extract.box_margin", setter([](Params& p) -> auto& { return p.extract.energy.box_margin; })},
      {"extract.face_tolerance", setter([](Params& p) -> auto& { return p.extract.face_tolerance; })},
      {"extract.unfold_rings", setter([](Params& p) -> auto& { return p.extract.unfold.rings; })},
      {"extract.unfold_rounds", setter([](Params& p) -> auto& { return p.extract.unfold.rounds; })},
      {"extract.unfold_max_share", setter([](Params& p) -> auto& { return p.extract.unfold.max_share; })},
      {"extract.unfold_refit_share", setter([](Params& p) -> auto& { return p.extract.unfold.refit_share; })},
      {"extract.unfold_hold_fit", setter([](Params& p) -> auto& { return p.extract.unfold.hold_fit; })},
      {"extract.unfold_zone_share", setter([](Params& p) -> auto& { return p.extract.unfold.zone_share; })},
      {"extract.face_share", setter([](Params& p) -> auto& { return p.extract.face_share; })},
      {"extract.max_iterations", setter([](Params& p) -> auto& { return p.extract.energy.max_iterations; })},
      {"extract.lbfgs_rank", setter([](Params& p) -> auto& { return p.extract.energy.lbfgs_rank; })},
      {"extract.projection_steps", setter([](Params& p) -> auto& { return p.extract.energy.projection_steps; })},
      {"extract.local_global_iterations", setter([](Params& p) -> auto& { return p.extract.energy.local_global_iterations; })},
      {"extract.local_global_tolerance", setter([](Params& p) -> auto& { return p.extract.energy.local_global_tolerance; })},
      {"extract.global_step_tolerance", setter([](Params& p) -> auto& { return p.extract.energy.global_step_tolerance; })},
      {"extract.function_tolerance", setter([](Params& p) -> auto& { return p.extract.energy.function_tolerance; })},
      {"extract.threads", setter([](Params& p) -> auto& { return p.extract.energy.threads; })},
      {"extract.edge_margin", setter([](Params& p) -> auto& { return p.extract.seams.edge_margin; })},
      {"extract.inside_distance", setter([](Params& p) -> auto& { return p.extract.trim.inside_distance; })},
      {"extract.outside_distance", setter([](Params& p) -> auto& { return p.extract.trim.outside_distance; })},
      {"extract.attract_distance", setter([](Params& p) -> auto& { return p.extract.trim.attract_distance; })},
  };
  return table;
}

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

}  // namespace

void Params::apply(const std::map<std::string, double>& values) {
  const auto& table = parameter_table();
  Params updated = *this;
  for (const auto& [name, value] : values) {
    auto it = table.find(name);
    if (it == table.end()) {
      std::string known;
      for (const auto& [k, _] : table) known += (known.empty() ? "" : ", ") + k;
      throw Error::usage("unknown parameter '" + name + "'; known parameters: " + known);
    }
    try {
      it->second(updated, value);
    } catch (const Error& e) {
      throw Error::usage("parameter '" + name + "' " + e.what());
    }
  }
  std::string why;
  if (!updated.valid(&why)) throw Error::usage("invalid parameters: " + why);
  *this = updated;
}

std::vector<std::string> Params::names() {
  std::vector<std::string> out;
  for (const auto& [k, _] : parameter_table()) out.push_back(k);
  return out;
}

Surfacer::Surfacer(Params params, ProgressCallback progress)
    : params_(std::move(params)), progress_(std::move(progress)) {}

Sketch Surfacer::prepare(const Sketch& input, bool refuse_scribbles, SurfaceReport& report) const {
  std::string why;
  if (!params_.valid(&why)) throw Error::usage(why);
  const Progress progress(progress_);
  auto t = Clock::now();
  progress.update("prepare", 0.0);
  Sketch sketch = input;
  CleanOptions clean_options;
  clean_options.min_points = static_cast<std::size_t>(params_.prepare.min_points);
  report.cleaning = clean(sketch, clean_options);
  sketch.assign_ids();
  if (sketch.strokes.empty())
    throw Error(ErrorKind::Input, "the sketch has no stroke (empty, or every stroke was too short "
                                  "or invalid); draw some strokes");
  if (std::all_of(sketch.strokes.begin(), sketch.strokes.end(), [](const Stroke& s) { return s.ignored; }))
    throw Error(ErrorKind::Input, "every stroke of the sketch is marked ignored; unmark the strokes "
                                  "the surface should follow");
  report.diagonal = sketch.bounding_box().diagonal();
  if (!(report.diagonal > 0.0))
    throw Error(ErrorKind::Input, "all the sketch's points coincide; nothing to surface");
  if (params_.prepare.resample_spacing > 0.0)
    resample(sketch, params_.prepare.resample_spacing * report.diagonal);
  // Half a symmetric object: its strokes stop on the mirror plane (found, or given with every
  // stroke on its kept side). Its mirror image makes the whole, surfaced as any whole sketch
  // (with a given plane, as a symmetric one).
  if (params_.prepare.complete_half) {
    const double tolerance = params_.prepare.mirror_detection.tolerance * report.diagonal;
    const auto kept_side = [&](const Plane& plane) {
      for (const Stroke& s : sketch.strokes)
        for (const Eigen::Vector3d& p : s.points)
          if (!s.ignored && plane.signed_distance(p) < -tolerance) return false;
      return true;
    };
    if (!sketch.mirror) {
      // Strokes that hang by one end (a table's legs drawn as lines) stop in the air too; they are
      // not half of a surface.
      Sketch probe = sketch;
      if (params_.prepare.ignore_decorations)
        for (const Decoration& d : find_decorations(probe, params_.prepare.decorations))
          probe.strokes[d.stroke].ignored = true;
      report.symmetry = detect_half_mirror(probe, params_.prepare.mirror_detection);
    }
    if (report.symmetry || (sketch.mirror && kept_side(*sketch.mirror))) {
      complete_half(sketch, report.symmetry ? report.symmetry->plane : *sketch.mirror, tolerance);
      report.diagonal = sketch.bounding_box().diagonal();
    }
  }
  if (params_.prepare.consolidate)
    report.consolidation = consolidate_overdrawn(sketch, params_.prepare.consolidation);
  if (params_.prepare.ignore_decorations) {
    report.decorations = find_decorations(sketch, params_.prepare.decorations);
    for (const Decoration& d : report.decorations) sketch.strokes[d.stroke].ignored = true;
    if (std::all_of(sketch.strokes.begin(), sketch.strokes.end(), [](const Stroke& s) { return s.ignored; }))
      throw Error(ErrorKind::Input, "no stroke is left to surface once the strokes that depict no "
                                    "surface are ignored; keep them with prepare.ignore_decorations = 0");
  }
  // Scribbled ink depicts no surface: refused here, before the work of surfacing it into a blob;
  // `share` of the ink is `what`.
  const auto refuse_ink = [](double share, const char* what) {
    std::ostringstream refusal;
    refusal << std::fixed << std::setprecision(0) << "the strokes do not seem to depict one surface "
            << "(hatching, writing or a painterly scene?): " << 100.0 * share << "% of the ink is " << what
            << ". Draw the object's outlines and cross-sections, give a proxy mesh, or surface it anyway "
            << "(checks.refuse_score = 0; the command line's --force)";
    throw Error::processing(refusal.str());
  };
  if (refuse_scribbles && params_.checks.refuse_score > 0.0 && params_.checks.refuse_scribbled > 0.0) {
    const double scribbled = scribbled_share(sketch, params_.checks.scribble_fill);
    if (scribbled > params_.checks.refuse_scribbled)
      refuse_ink(scribbled,
                 "scribbles, strokes that wind round and round over an area instead of drawing a curve");
  }
  // So is ink laid in strokes side by side that never cross another (hatching, writing).
  const auto drawn = static_cast<std::size_t>(
      std::count_if(sketch.strokes.begin(), sketch.strokes.end(), [](const Stroke& s) { return !s.ignored; }));
  if (refuse_scribbles && params_.checks.refuse_score > 0.0 && params_.checks.refuse_unmet > 0.0 &&
      drawn >= params_.checks.meet_least_strokes) {
    const double unmet = unmet_share(sketch, params_.checks.meet_reach * report.diagonal,
                                     params_.checks.meet_angle * M_PI / 180.0);
    if (unmet > params_.checks.refuse_unmet)
      refuse_ink(unmet,
                 "in strokes that meet no other stroke, where a surface sketch's outlines and sections cross");
  }
  const auto is_boundary = [](const Stroke& s) { return s.boundary && !s.ignored; };
  if (params_.prepare.open_rims && std::none_of(sketch.strokes.begin(), sketch.strokes.end(), is_boundary)) {
    report.openings = find_openings(sketch, params_.prepare.openings);
    for (const Opening& o : report.openings) sketch.strokes[o.stroke].boundary = true;
  }
  if (!sketch.mirror && !report.symmetry) {
    MirrorDetectOptions mirror = params_.prepare.mirror_detection;
    if (mirror.threads == 0) mirror.threads = params_.proxy.threads;
    report.symmetry = detect_mirror(sketch, mirror);
  }
  report.strokes = sketch.strokes.size();
  report.points = sketch.point_count();
  report.prepare_s = seconds_since(t);
  return sketch;
}

SurfaceResult Surfacer::run(const Sketch& input, const TriMesh* user_proxy) const {
  const auto start = Clock::now();
  const Progress progress(progress_);
  SurfaceResult result;
  SurfaceReport& report = result.report;

  // Prepare (METHOD.md §0).
  Sketch sketch = prepare(input, user_proxy == nullptr, report);

  // Proxy (§5 "Proxy creation").
  auto t = Clock::now();
  progress.update("proxy", 0.0);
  report.user_proxy = user_proxy != nullptr;
  if (user_proxy) {
    if (user_proxy->n_faces() == 0)
      throw Error(ErrorKind::Input, "the proxy mesh has no triangles; give a triangle (or polygon) "
                                    "mesh, not points or lines");
    result.proxy = attract_proxy(*user_proxy, sketch, params_.proxy, progress, &report.proxy);
  } else {
    result.proxy = make_proxy(sketch, params_.proxy, progress, &report.proxy);
  }
  // Symmetric sketches (§5): half of the sketch on half of the proxy.
  Sketch work = sketch;
  if (sketch.mirror) {
    result.proxy = clip_to_half_space(result.proxy, *sketch.mirror,
                                      params_.extract.plane_tolerance * report.diagonal)
                       .mesh;
    work = half_sketch(sketch, *sketch.mirror);
    if (work.strokes.empty())
      throw Error(ErrorKind::Input, "no stroke lies on the positive side of the mirror plane; flip "
                                    "the plane (negate a, b, c, d)");
  }
  report.proxy_s = seconds_since(t);

  // Association and segmentation (§4.1-4.2).
  t = Clock::now();
  result.segmentation = segment(work, result.proxy, params_.segment, progress);
  report.segmentation = result.segmentation.summary;
  report.segment_s = seconds_since(t);

  // Final mesh (§4.3, App. D).
  t = Clock::now();
  // A user's proxy is rough by design (a low-poly model): its vertices may rightly move far onto
  // the regions' surfaces and past the strokes' box, so the trust region and the box test are
  // for the automatic proxy only.
  ExtractOptions extract_options = params_.extract;
  if (user_proxy) extract_options.energy.trust_distance = extract_options.energy.box_margin = 0.0;
  // A proxy lofted through the sketch's sections is already the surface they depict between them;
  // a curved region's model, fitted to a few section and profile strokes, only bulges there: every
  // curved region stays at the proxy (planes, a section's cap, are still projected onto).
  if (report.proxy.loft_sections > 0) extract_options.smooth_fallback.hold_curved = true;
  extract_options.smooth_fallback.rounded = report.proxy.rounded;
  extract_options.drawn_faces = report.proxy.drawn_faces;
  ExtractedSurface surface = [&] {
    try {
      return extract(result.proxy, result.segmentation.labels, result.segmentation.models, work,
                     extract_options, progress);
    } catch (const Error& e) {
      // Rims found in the strokes (not marked by the user) that the proxy cannot be opened at:
      // the surface stays closed, as it would be without them, and the report says why.
      if (e.kind() != ErrorKind::Processing || report.openings.empty()) throw;
      report.opening_failure = e.what();
      for (const Opening& o : report.openings)
        for (Sketch* s : {&sketch, &work})
          for (Stroke& stroke : s->strokes)
            if (stroke.id == o.id) stroke.boundary = false;
      report.openings.clear();
      return extract(result.proxy, result.segmentation.labels, result.segmentation.models, work,
                     extract_options, progress);
    }
  }();
  result.mesh = std::move(surface.mesh);
  result.labels = std::move(surface.labels);
  result.sharp = std::move(surface.sharp);
  report.extraction = surface.summary;
  report.extraction_s = seconds_since(t);

  Sketch measured = sketch;
  measured.mirror.reset();
  report.stroke_distance = stroke_distance(result.mesh, measured, report.diagonal);
  t = Clock::now();
  progress.update("checks", 0.0);
  const bool open_expected = std::any_of(sketch.strokes.begin(), sketch.strokes.end(),
                                         [](const Stroke& s) { return s.boundary && !s.ignored; });
  CheckOptions checks = params_.checks;
  if (checks.threads == 0) checks.threads = params_.segment.threads;
  report.checks = check_shape(result.mesh, result.labels, sketch, open_expected, checks);
  report.checks_s = seconds_since(t);
  // A user's proxy says what the surface is; without one, a surface that neither passes through
  // the strokes nor stays within them is not what they depict.
  if (!user_proxy && params_.checks.refuse_score > 0.0 &&
      non_surface_score(report.checks, report.stroke_distance.p95) > params_.checks.refuse_score) {
    std::ostringstream refusal;
    refusal << std::fixed << std::setprecision(1) << "the strokes do not seem to depict one surface "
        << "(hatching, writing or a painterly scene?): the best surface found leaves 5% of the "
        << "stroke points farther than " << 100.0 * report.stroke_distance.p95
        << "% of the diagonal from it and runs out beyond the strokes over " << 100.0 * report.checks.beyond
        << "% of its area. Draw the object's outlines and cross-sections, give a proxy mesh, or "
        << "keep the result anyway (checks.refuse_score = 0; the command line's --force)";
    throw Error::processing(refusal.str());
  }
  // The strokes that depict no surface, as thin tubes apart from it when asked for (the checks
  // above judge the surface alone). Their vertices take the label after the last region's.
  if (params_.prepare.decoration_tubes && !report.decorations.empty()) {
    Sketch decorations;
    decorations.mirror = sketch.mirror;
    for (const Decoration& d : report.decorations) {
      decorations.strokes.push_back(sketch.strokes[d.stroke]);
      decorations.strokes.back().ignored = false;
    }
    const StrokeTubes tubes = stroke_tubes(decorations, report.diagonal, params_.prepare.tubes);
    report.tubes = tubes.count;
    append_mesh(result.mesh, tubes.mesh);
    result.labels.resize(result.mesh.n_vertices(), static_cast<int>(result.segmentation.models.size()));
    result.sharp.resize(result.mesh.n_vertices(), 0);
  }
  report.total_s = seconds_since(start);
  progress.update("done", 1.0);
  return result;
}

SurfaceResult surface(const Sketch& sketch, const Params& params, const TriMesh* user_proxy) {
  return Surfacer(params).run(sketch, user_proxy);
}

}  // namespace sketchsurf
