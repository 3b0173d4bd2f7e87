#include "surfacing/extract/extract.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>

#include "surfacing/error.h"
#include "surfacing/extract/fold_refit.h"
#include "surfacing/parallel.h"
#include "surfacing/segment/association.h"

namespace sketchsurf {

bool ExtractOptions::valid(std::string* why) const {
  if (!seams.valid(why) || !energy.valid(why) || !trim.valid(why) || !smooth_fallback.valid(why) ||
      !back_sides.valid(why) || !outline.valid(why) || !unfold.valid(why))
    return false;
  if (!(plane_tolerance > 0.0)) {
    if (why) *why = "extract.plane_tolerance must be > 0";
    return false;
  }
  if (!(face_tolerance >= 0.0)) {
    if (why) *why = "extract.face_tolerance must be >= 0";
    return false;
  }
  if (!(face_share >= 0.0 && face_share <= 1.0)) {
    if (why) *why = "extract.face_share must be in [0, 1]";
    return false;
  }
  return true;
}

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

/// Bounding-box diagonal of the sketch, including its mirror image when it is a half sketch.
double sketch_diagonal(const Sketch& sketch) {
  BoundingBox box = sketch.bounding_box();
  if (sketch.mirror && !box.empty()) {
    const BoundingBox half = box;
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d p((corner & 1) ? half.max.x() : half.min.x(),
                              (corner & 2) ? half.max.y() : half.min.y(),
                              (corner & 4) ? half.max.z() : half.min.z());
      box.extend(sketch.mirror->reflect(p));
    }
  }
  return box.diagonal();
}

void check_inputs(const TriMesh& proxy, const std::vector<int>& labels,
                  const std::vector<ImplicitModel>& models, const Sketch& sketch) {
  if (proxy.n_faces() == 0) throw Error::processing("the proxy has no triangles");
  if (labels.size() != proxy.n_vertices())
    throw Error::usage("extract: " + std::to_string(labels.size()) + " labels for a proxy of " +
                       std::to_string(proxy.n_vertices()) + " vertices");
  if (models.empty()) throw Error::usage("extract: no surface models");
  for (std::size_t i = 0; i < models.size(); ++i)
    if (models[i].degree < 1 || models[i].degree > kMaxImplicitDegree ||
        models[i].coefficients.size() != monomial_count(models[i].degree) ||
        !(models[i].scale > 0.0) || !models[i].coefficients.allFinite())
      throw Error::usage("extract: model " + std::to_string(i) + " is malformed");
  for (int l : labels)
    if (l < 0 || l >= static_cast<int>(models.size()))
      throw Error::usage("extract: label " + std::to_string(l) + " names no model (" +
                         std::to_string(models.size()) + " models)");
  bool any = false;
  for (const Stroke& s : sketch.strokes) any = any || (!s.ignored && !s.points.empty());
  if (!any)
    throw Error::processing("the sketch has no stroke to fit (empty, or every stroke is marked "
                            "ignored); draw strokes or unmark some");
}

/// Per vertex: 1 for boundary vertices on the mirror plane.
std::vector<std::uint8_t> plane_boundary(const TriMesh& mesh, const std::optional<Plane>& plane,
                                         double tolerance) {
  std::vector<std::uint8_t> on(mesh.n_vertices(), 0);
  if (!plane) return on;
  for (auto v : mesh.vertices())
    on[v.idx()] = mesh.is_boundary(v) &&
                  std::abs(plane->signed_distance(to_eigen(mesh.point(v)))) <= tolerance;
  return on;
}

/// The strokes but the boundary strokes: those a region's model and the proxy are compared on
/// (smooth_fallback.h). An open border is attracted to its boundary strokes (Eq. 13) whichever
/// surface its region keeps, and the trimmed proxy's border, cut along the proxy's edges, passes
/// off them: their points would make the proxy look farther from the region's strokes than it is.
StrokeSegments surface_strokes(const Sketch& sketch) {
  Sketch inner = sketch;
  for (Stroke& s : inner.strokes) s.ignored = s.ignored || s.boundary;
  return stroke_segments(inner, false);
}

// E_mesh solved from the seamed proxy (its positions `start_positions`) with the regions flagged
// kRegionHeld in `at_proxy` held there, and the vertices flagged in `zone` (empty: none), and
// those flagged kRegionPulled pulled toward it, then its folds ironed out (unfold.h). `held`
// receives the held vertices, `folds` the crossing face pairs left; `summary` the solve's, the back
// sides' and the unfold's figures.
void solve_held(LabeledMesh& seamed, const std::vector<ImplicitModel>& models, const MeshConstraints& base,
                const std::vector<char>& at_proxy, const std::vector<char>& zone,
                const Eigen::MatrixX3d& start_positions,
                const std::vector<std::uint8_t>& on_plane, double diagonal, const ExtractOptions& options,
                const Progress& progress, std::vector<char>& held, ExtractSummary& summary,
                std::vector<std::array<int, 2>>& folds) {
  MeshConstraints c = base;
  held.assign(seamed.labels.size(), 0);
  std::vector<char> attracted(seamed.labels.size(), 0);
  for (const AttractTarget& target : c.attract) attracted[target.vertex] = 1;
  for (auto v : seamed.mesh.vertices()) {
    const auto& l = seamed.labels[v.idx()];
    held[v.idx()] = (!zone.empty() && zone[v.idx()]) ||
                    std::any_of(l.begin(), l.end(), [&](int r) { return at_proxy[r] == kRegionHeld; });
    if (attracted[v.idx()]) continue;  // an open border follows its strokes
    if (held[v.idx()]) {
      c.held.push_back(v.idx());
      c.attract.push_back({v.idx(), start_positions.row(v.idx()).transpose()});
    } else if (!seamed.mesh.is_boundary(v) &&  // an open border keeps its 1D Laplacian (energy.h)
               std::all_of(l.begin(), l.end(), [&](int r) { return at_proxy[r] == kRegionPulled; })) {
      c.attract.push_back(
          {v.idx(), start_positions.row(v.idx()).transpose(), options.smooth_fallback.pull_weight});
    }
  }
  // Vertices on a face drawn in, in regions that lie mostly on such faces (the face's own region:
  // a region that only touches a face, a thin part's side or a web between parts, is not one).
  if (options.face_tolerance > 0.0 && !options.drawn_faces.empty()) {
    std::vector<char> on_face(seamed.labels.size(), 0);
    std::vector<std::size_t> region_on(models.size(), 0), region_all(models.size(), 0);
    for (auto v : seamed.mesh.vertices()) {
      const Eigen::Vector3d p = start_positions.row(v.idx()).transpose();
      on_face[v.idx()] = std::any_of(options.drawn_faces.begin(), options.drawn_faces.end(), [&](const Plane& face) {
        return std::abs(face.signed_distance(p)) <= options.face_tolerance * diagonal;
      });
      for (int r : seamed.labels[v.idx()]) {
        ++region_all[static_cast<std::size_t>(r)];
        region_on[static_cast<std::size_t>(r)] += on_face[v.idx()];
      }
    }
    for (auto v : seamed.mesh.vertices()) {
      const auto& l = seamed.labels[v.idx()];
      if (on_face[v.idx()] && !held[v.idx()] && !attracted[v.idx()] &&
          std::all_of(l.begin(), l.end(), [&](int r) {
            return static_cast<double>(region_on[static_cast<std::size_t>(r)]) >=
                   options.face_share * static_cast<double>(region_all[static_cast<std::size_t>(r)]);
          }))
        c.on_drawn_face.push_back(v.idx());
    }
  }
  // Thin parts' far sides, found on the proxy, end just inside their region's surface, apart
  // from the near side (back_sides.h); held vertices stay where they are held.
  c.inside = find_back_sides(seamed, models, options.back_sides);
  std::erase_if(c.inside, [&](int v) { return held[v] != 0; });
  c.inside_gap = options.back_sides.gap * diagonal;
  summary.back_side_vertices = c.inside.size();
  summary.optimization = optimize_mesh(seamed, models, c, options.energy, progress);
  summary.unfold = unfold(seamed.mesh, start_positions, on_plane, options.unfold, options.energy.threads, &folds);
}

}  // namespace

StrokeDistance stroke_distance(const TriMesh& mesh, const Sketch& sketch, double diagonal,
                               bool mirrored, unsigned threads) {
  std::vector<Eigen::Vector3d> points;
  for (const Stroke& s : sketch.strokes) {
    if (s.ignored) continue;
    for (const auto& p : s.points) {
      points.push_back(p);
      if (mirrored && sketch.mirror) points.push_back(sketch.mirror->reflect(p));
    }
  }
  StrokeDistance out;
  out.points = points.size();
  if (points.empty()) return out;
  const ClosestFaceTree tree(vertex_matrix(mesh), face_matrix(mesh));
  std::vector<double> d(points.size());
  parallel_for(0, points.size(), threads, [&](std::size_t i) {
    Eigen::Vector3d q;
    d[i] = tree.closest_face(points[i], &q) < 0 ? std::numeric_limits<double>::infinity()
                                                : (q - points[i]).norm() / diagonal;
  });
  std::sort(d.begin(), d.end());
  auto quantile = [&](double f) {
    return d[std::min(d.size() - 1, static_cast<std::size_t>(std::floor(f * (d.size() - 1) + 0.5)))];
  };
  out.median = quantile(0.5);
  out.p95 = quantile(0.95);
  out.max = d.back();
  return out;
}

ExtractedSurface extract(const TriMesh& proxy, const std::vector<int>& labels,
                         const std::vector<ImplicitModel>& models, const Sketch& sketch,
                         const ExtractOptions& options, const Progress& progress) {
  const auto start = Clock::now();
  std::string why;
  if (!options.valid(&why)) throw Error::usage(why);
  check_inputs(proxy, labels, models, sketch);
  const double diagonal = sketch_diagonal(sketch);
  if (!(diagonal > 0.0)) throw Error::processing("the sketch has zero extent; nothing to surface");
  const double plane_tolerance = options.plane_tolerance * diagonal;

  ExtractedSurface out;
  ExtractSummary& summary = out.summary;
  summary.proxy_vertices = proxy.n_vertices();
  summary.mirrored = sketch.mirror.has_value();
  progress.update("extract", 0.0);

  // 1. Open surfaces: trim the proxy along the boundary strokes (App. D).
  auto t = Clock::now();
  const bool open = std::any_of(sketch.strokes.begin(), sketch.strokes.end(),
                                [](const Stroke& s) { return s.boundary && !s.ignored; });
  TriMesh trimmed;
  std::vector<int> trimmed_labels;
  if (open) {
    TrimResult cut = trim_open_surface(proxy, sketch, sketch.mirror, plane_tolerance, diagonal,
                                       options.trim);
    trimmed = std::move(cut.mesh);
    trimmed_labels.reserve(cut.source_vertex.size());
    for (int v : cut.source_vertex) trimmed_labels.push_back(labels[v]);
    summary.trimmed_faces = cut.removed_faces;
    summary.open = true;
  }
  summary.trim_s = seconds_since(t);

  // 2. Seams (§4.3).
  t = Clock::now();
  LabeledMesh seamed = insert_seams(open ? trimmed : proxy, open ? trimmed_labels : labels, models,
                                    options.seams);
  for (const auto& l : seamed.labels) {
    summary.seam_vertices += l.size() == 2;
    summary.corner_vertices += l.size() >= 3;
  }
  summary.seams_s = seconds_since(t);
  progress.update("extract", 0.05);

  // 3. E_mesh (Eq. 7-9, 13).
  t = Clock::now();
  MeshConstraints constraints;
  const std::vector<std::uint8_t> on_plane = plane_boundary(seamed.mesh, sketch.mirror, plane_tolerance);
  if (sketch.mirror) {
    constraints.plane = sketch.mirror;
    for (std::size_t v = 0; v < on_plane.size(); ++v)
      if (on_plane[v]) constraints.plane_vertices.push_back(static_cast<int>(v));
  }
  constraints.strokes = stroke_segments(sketch, false);
  constraints.outlines = plane_outlines(seamed, models, *constraints.strokes, diagonal, options.outline);
  constraints.outline_margin = options.outline.margin * diagonal;
  if (open) constraints.attract = boundary_targets(seamed.mesh, sketch, on_plane, diagonal, options.trim);
  summary.attracted_vertices = constraints.attract.size();
  // Regions whose model cannot follow their strokes stay at the proxy; doubly curved ones only a
  // little nearer their strokes are pulled toward it (smooth_fallback.h).
  const Eigen::MatrixX3d start_positions = vertex_matrix(seamed.mesh);
  std::vector<char> at_proxy =
      regions_at_proxy(seamed, models, open ? surface_strokes(sketch) : *constraints.strokes, diagonal,
                       options.smooth_fallback, options.energy, &summary.smooth_fallback);
  std::vector<char> held;
  std::vector<std::array<int, 2>> folds;
  solve_held(seamed, models, constraints, at_proxy, {}, start_positions, on_plane, diagonal, options, progress,
             held, summary, folds);
  // A fold the fills leave is a region's model running through another's surface over more than
  // a fill can span. The mesh is solved again from the start with other models or holds (the
  // fits below), and a solve is kept when it has fewer folds and stays about as near the strokes
  // (stroke distance median and 95th percentile each at most hold_fit times the first's): where
  // the proxy itself is far from the strokes (a shoe's sole rounder than drawn, a lamp's lumpy
  // head) holding it trades an inner fold for a wrong shape, and where it is far from a few (a
  // glass's foot, whose proxy ends on the box below it) the median alone does not show it.
  std::vector<ImplicitModel> fitted = models;  // the models the kept solve projected onto
  if (!folds.empty() && options.unfold.hold_fit > 0.0) {
    const auto fit = [&] { return stroke_distance(seamed.mesh, sketch, diagonal, false, options.energy.threads); };
    const StrokeDistance first_fit = fit();
    // The solve kept so far, and another tried against it.
    struct Solve {
      Eigen::MatrixX3d positions;
      ExtractSummary summary;
      std::vector<char> held, at_proxy;
      std::vector<std::array<int, 2>> folds;
      std::vector<ImplicitModel> models;
    };
    Solve kept{vertex_matrix(seamed.mesh), summary, held, at_proxy, folds, models};
    const auto try_solve = [&](std::vector<ImplicitModel> with, std::vector<char> at,
                               const SmoothFallbackSummary& fallback, const std::vector<char>& zone = {}) {
      set_vertex_matrix(seamed.mesh, start_positions);
      Solve next{Eigen::MatrixX3d(), summary, {}, std::move(at), {}, std::move(with)};
      next.summary.smooth_fallback = fallback;
      solve_held(seamed, next.models, constraints, next.at_proxy, zone, start_positions, on_plane, diagonal,
                 options, progress, next.held, next.summary, next.folds);
      // What the kept solve was made with carries over; the caller adds what this one adds.
      UnfoldSummary& unfold = next.summary.unfold;
      unfold.refitted_regions = kept.summary.unfold.refitted_regions;
      unfold.refit_degree = kept.summary.unfold.refit_degree;
      unfold.held_regions = kept.summary.unfold.held_regions;
      unfold.held_zone = kept.summary.unfold.held_zone;
      const StrokeDistance next_fit = fit();
      const bool better = next.folds.size() < kept.folds.size() &&
                          next_fit.median <= options.unfold.hold_fit * first_fit.median &&
                          next_fit.p95 <= options.unfold.hold_fit * first_fit.p95;
      next.positions = vertex_matrix(seamed.mesh);
      if (better) kept = std::move(next);
      return better;
    };
    // The regions the folds run through, fitted again as a plane, then as a quadric (fold_refit.h:
    // a cubic can turn back on itself as a quartic does); the holds decided again for the new
    // models.
    if (options.unfold.refit_share > 0.0) {
      const RegionSamples samples =
          region_samples(seamed, start_positions, fold_regions(seamed, folds, options.unfold.refit_share),
                         constraints.strokes->points, options.smooth_fallback.reach * diagonal);
      for (int degree = 1; degree <= 2 && !kept.folds.empty(); ++degree) {
        std::size_t refitted = 0;
        std::vector<ImplicitModel> lower = refit_regions(models, samples, degree, diagonal,
                                                         options.smooth_fallback.min_points, &refitted);
        if (refitted == 0) continue;
        set_vertex_matrix(seamed.mesh, start_positions);  // the holds are decided on the proxy
        SmoothFallbackSummary fallback;
        std::vector<char> at = regions_at_proxy(seamed, lower, open ? surface_strokes(sketch) : *constraints.strokes,
                                                diagonal, options.smooth_fallback, options.energy, &fallback);
        if (try_solve(std::move(lower), std::move(at), fallback)) {
          kept.summary.unfold.refitted_regions = refitted;
          kept.summary.unfold.refit_degree = degree;
        }
      }
    }
    // The regions of the triangles still crossing (on any of them) held at the proxy.
    if (!kept.folds.empty()) {
      std::vector<char> at = kept.at_proxy;
      for (const int r : fold_regions(seamed, kept.folds, std::numeric_limits<double>::min()))
        at[static_cast<std::size_t>(r)] = kRegionHeld;
      const auto count = static_cast<std::size_t>(std::count(at.begin(), at.end(), kRegionHeld) -
                                                  std::count(kept.at_proxy.begin(), kept.at_proxy.end(), kRegionHeld));
      if (count > 0 && try_solve(kept.models, std::move(at), kept.summary.smooth_fallback))
        kept.summary.unfold.held_regions = count;
    }
    // Where that is refused too (the proxy of a whole region is farther from its strokes), the
    // triangles still crossing, with the fills' rings round them, held at the proxy when they are
    // few: a lower-degree model's surface that runs a little past another region's where they meet
    // (a shoe's flat sole under its sides), where the proxy is as good a surface. Not a whole
    // part's worth: the proxy there is the shape of a blob, not of the strokes.
    if (!kept.folds.empty()) {
      const std::vector<char> zone = around(seamed.mesh, kept.folds, options.unfold.rings);
      const auto size = static_cast<double>(std::count(zone.begin(), zone.end(), 1));
      if (size <= options.unfold.zone_share * static_cast<double>(zone.size()) &&
          try_solve(kept.models, kept.at_proxy, kept.summary.smooth_fallback, zone))
        kept.summary.unfold.held_zone = static_cast<std::size_t>(size);
    }
    set_vertex_matrix(seamed.mesh, kept.positions);
    summary = kept.summary;
    held = std::move(kept.held);
    fitted = std::move(kept.models);
  }
  summary.optimize_s = seconds_since(t);

  // Region and crease flags, from the final positions.
  const std::vector<double> w = regularization_weights(seamed, fitted, options.energy);
  std::vector<int> half_labels(seamed.labels.size());
  std::vector<std::uint8_t> half_sharp(seamed.labels.size());
  for (std::size_t v = 0; v < seamed.labels.size(); ++v) {
    half_labels[v] = seamed.labels[v].front();
    half_sharp[v] = seamed.is_seam(static_cast<int>(v)) && w[v] < 1.0 && !held[v];
  }
  keep_smooth_proxy(seamed.mesh, start_positions, half_sharp, held, *constraints.strokes, diagonal,
                    options.smooth_fallback, &summary.smooth_fallback);

  // 4. Mirror (§5).
  t = Clock::now();
  if (sketch.mirror) {
    std::vector<int> source;
    out.mesh = mirror_and_weld(seamed.mesh, *sketch.mirror, plane_tolerance, &source);
    for (int v : source) {
      out.labels.push_back(half_labels[v]);
      out.sharp.push_back(half_sharp[v]);
    }
  } else {
    out.mesh = std::move(seamed.mesh);
    out.labels = std::move(half_labels);
    out.sharp = std::move(half_sharp);
  }
  summary.mirror_s = seconds_since(t);
  summary.sharp_vertices = std::count(out.sharp.begin(), out.sharp.end(), 1);
  summary.output_vertices = out.mesh.n_vertices();
  summary.output_faces = out.mesh.n_faces();
  summary.stroke_distance = stroke_distance(out.mesh, sketch, diagonal, /*mirrored=*/true,
                                           options.energy.threads);
  summary.total_s = seconds_since(start);
  progress.update("extract", 1.0);
  return out;
}

TriMesh extract_surface(const TriMesh& proxy, const std::vector<int>& labels,
                        const std::vector<ImplicitModel>& models, const Sketch& sketch,
                        const ExtractOptions& options, const Progress& progress,
                        ExtractSummary* summary) {
  ExtractedSurface result = extract(proxy, labels, models, sketch, options, progress);
  if (summary) *summary = result.summary;
  return std::move(result.mesh);
}

}  // namespace sketchsurf
