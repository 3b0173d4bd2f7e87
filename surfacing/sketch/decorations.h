#pragma once
// Strokes that depict no surface: a dot or a small scribble apart from the rest, a dot anywhere
// (a tap of the trigger: too short to show the surface's direction), a single stroke
// that hangs off the sketch by one end (an antenna, a cable, a stem), possibly carrying a small
// group at its free end (a cable's plug, a ring on a string). Left in, each becomes a blob, a horn
// or a fin of the surface; so they are found before surfacing and marked ignored.

#include <cstdint>
#include <string>
#include <vector>

#include "surfacing/sketch/sketch.h"

namespace sketchsurf {

/// Options for find_decorations(). Distances are fractions of the sketch's bounding-box diagonal.
struct DecorationOptions {
  double touch = 0.02;         ///< two strokes touch where their points come this close
  double small_group = 0.05;   ///< a group of touching strokes whose extent is below this, and
                               ///< that is not the largest group, depicts no surface
  double end_share = 0.25;     ///< "touches by one end only": every touching point lies within
                               ///< this share of the stroke's length from the same end
  double min_dangling = 0.08;  ///< a one-end stroke counts only when at least this long
  double free_end = 0.06;      ///< ... and when its free end is this far from every other stroke
                               ///< but those of the group it carries:
  double carried = 0.15;       ///< strokes that touch a one-end stroke away from that end and
                               ///< reach the rest only through it (a cable's plug) go with it when
                               ///< their extent is below this and half the stroke's length
  double dot = 0.01;           ///< a stroke shorter than this depicts no surface wherever it lies:
                               ///< a tap, under one cell of the proxy's grid, draws no curve and
                               ///< shows no direction, yet the segmentation would take it for a
                               ///< curve on the surface (0 = off)
  bool valid(std::string* why) const;
};

/// Why a stroke was found to depict no surface.
enum class DecorationKind { SmallGroup, Dangling, Dot };

/// The kind's name in reports: "small group", "dangling" or "dot".
const char* decoration_kind_name(DecorationKind kind);

/// One stroke that find_decorations() would ignore.
struct Decoration {
  std::size_t stroke = 0;  ///< index into sketch.strokes
  std::int64_t id = -1;    ///< that stroke's id
  DecorationKind kind = DecorationKind::Dangling;
};

/// The strokes of `sketch` that depict no surface: members of a small group of touching strokes
/// apart from the largest group (dots, small scribbles); the other strokes shorter than `dot`
/// (kind Dot); strokes longer than min_dangling that
/// touch the others by at most one end while the other end is free_end away from them (closed
/// strokes excepted); and the small group such a stroke carries, when the strokes it touches away
/// from its attached end reach the rest only through it and at most half of the stroke's
/// middle (between the end shares) comes within free_end of other strokes (they are reported
/// as a small group). A one-end stroke lying within `touch` of a side of the box of the strokes
/// not found by these tests, and inside that box grown by `touch`, is an edge of a face drawn on
/// that side whose neighbouring edge is missing, not an antenna, and is kept. Strokes already
/// ignored, boundary strokes and strokes of fewer than 2 points are left out of the test
/// (boundary strokes still count as neighbours). Deterministic; `sketch` should be resampled
/// (the test runs on its points).
std::vector<Decoration> find_decorations(const Sketch& sketch, const DecorationOptions& options = {});

}  // namespace sketchsurf
