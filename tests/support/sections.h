#pragma once
// A mesh cut across by a horizontal plane, measured: how the tests tell thin parts apart (a chair's
// four legs are four loops; a lamp's pole is a narrow section, its wall a wide one).

#include <cstddef>

#include "surfacing/mesh.h"

namespace sketchsurf::testing {

/// Loops of the mesh's section by the plane y = height: the faces that the plane cuts, joined
/// across the edges it cuts.
std::size_t section_loops(const TriMesh& mesh, double height);

/// Diagonal of the bounding box of the mesh's section by the plane y = height (the points where
/// its edges cross the plane); 0 when the plane misses the mesh.
double section_width(const TriMesh& mesh, double height);

/// Area enclosed by the section of a closed mesh by the plane y = height (its holes taken out):
/// how much of the slab a part fills, a thin arm's little, a hull's round it much.
double section_area(const TriMesh& mesh, double height);

}  // namespace sketchsurf::testing
