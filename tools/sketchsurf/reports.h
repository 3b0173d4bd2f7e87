#pragma once
// Pieces of report.json shared by the `segment` and `surface` commands.

#include <nlohmann/json.hpp>

#include "surfacing/quality/checks.h"
#include "surfacing/segment/pearl.h"
#include "surfacing/sketch/decorations.h"
#include "surfacing/sketch/openings.h"

namespace sketchsurf::cli {

/// The region models: [{label, degree, vertices, center, scale, coefficients}], input units.
nlohmann::json models_json(const Segmentation& segmentation);

/// The shape checks: {far_5, far_10, beyond, outside_box, components, genus, boundary_loops,
/// self_intersections, regions, border_length, border_ratio, warnings}.
nlohmann::json checks_json(const ShapeChecks& checks);

/// The strokes ignored as decorations: [{id, kind: "small group" | "dangling" | "dot"}].
nlohmann::json decorations_json(const std::vector<Decoration>& decorations);
/// Rims made boundary strokes: stroke id, the normal through the opening, centre and radius.
nlohmann::json openings_json(const std::vector<Opening>& openings);

/// Peak resident set size of this process so far, in MiB.
double peak_rss_mb();

}  // namespace sketchsurf::cli
