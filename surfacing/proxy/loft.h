#pragma once
// A proxy lofted through a sketch's parallel section loops: a dress drawn as a waist circle, a wavy
// hem and a profile. Such sketches are too sparse for VIPSS, whose zero set
// then runs out between the sections to the polygonisation box; the surface the designer means
// passes through each section in turn. Tried by make_proxy() only where VIPSS's surface lies
// mostly far from every stroke, and kept only when it holds every stroke.

#include <cstddef>
#include <optional>

#include "surfacing/proxy/polygonize.h"
#include "surfacing/sketch/sketch.h"

namespace sketchsurf {

/// Options of loft_sections(). Lengths are in the units of the sketch it is given (make_proxy
/// gives the unit-diagonal sketch).
struct LoftOptions {
  double edge = 0.007;             ///< about the edge length of the lofted mesh
  double parallel_degrees = 20.0;  ///< section planes are parallel within this angle
  double min_radius = 0.03;        ///< loops of a smaller mean radius are no sections
  double min_spacing = 0.05;       ///< consecutive sections are at least this far apart along
                                   ///< their common normal
  double fit = 0.02;               ///< the loft holds the strokes when 95% of their points lie
                                   ///< within this distance of it
  double smoothing = 0.0075;        ///< each section's outline is smoothed over about this length
                                   ///< (the spread of a binomial filter): a hand's jitter would
                                   ///< corrugate the loft along its rulings; 0 = as drawn
};

/// What loft_sections() built.
struct Loft {
  TriangleArrays mesh;        ///< closed, outward-oriented, genus 0
  std::size_t sections = 0;   ///< section loops it passes through
};

/// The surface through the largest family of closed, flat, parallel stroke loops (sections, at
/// least two), in order along their common normal: each section's outline is read as a radius per
/// direction round its centre (the farthest crossing of that ray), radii and centres are
/// interpolated from section to section (linearly between two, by a cubic through more), and the
/// end sections are closed by flat caps. nullopt when there are no such sections, one is not
/// star-shaped about its centre, or the loft does not hold the strokes (LoftOptions::fit): the
/// other strokes must lie on it (a profile, a section's diameter on its cap). Deterministic;
/// ignored strokes are left out.
std::optional<Loft> loft_sections(const Sketch& sketch, const LoftOptions& options = {});

}  // namespace sketchsurf
