#pragma once
// Pieces of report.json shared by the `segment` and `surface` commands.

#include <nlohmann/json.hpp>

#include "surfacing/segment/pearl.h"

namespace sketchsurf::cli {

/// The region models: [{label, degree, vertices, center, scale, coefficients}], input units.
nlohmann::json models_json(const Segmentation& segmentation);

/// Peak resident set size of this process so far, in MiB.
double peak_rss_mb();

}  // namespace sketchsurf::cli
