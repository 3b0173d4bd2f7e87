#pragma once
// Sketches and meshes with known answers, generated for the tests (and the bundled examples).
// Every generator is deterministic; noise takes an explicit seed.

#include <array>
#include <functional>
#include <vector>

#include "surfacing/mesh.h"
#include "surfacing/sketch/sketch.h"

namespace sketchsurf::testing {

/// Points of a parametric curve c(t), t in [t0, t1], spaced about `spacing` apart.
Stroke sample_curve(const std::function<Eigen::Vector3d(double)>& c, double t0, double t1,
                    double spacing);

/// A closed circle of `radius` round the z axis at height z: points + 1 points, the last on the
/// first.
Stroke horizontal_ring(double radius, double z, int points = 64);

/// A polyline through `corners`, points `step` apart or closer, back to the first when `closed`.
Stroke polyline_stroke(std::vector<Eigen::Vector3d> corners, bool closed, double step = 0.002);

/// A box's sections only (no edge drawn): a closed rectangle at each x, corners at y = +-half.y(),
/// z = +-half.z(); each starts and ends at a corner.
Sketch box_sections_sketch(const Eigen::Vector3d& half, const std::vector<double>& xs);

/// Axis-aligned cube centred at the origin with side `side`: one stroke along each of the 12
/// edges, plus (when `cross_strokes`) one stroke across the middle of each of the 6 faces.
/// Points about side/50 apart.
Sketch cube_sketch(double side = 1.0, bool cross_strokes = true);

/// Cylinder around +z centred at the origin: the two rim circles, `side_strokes` vertical strokes
/// along the side, and one stroke across each cap.
Sketch cylinder_sketch(double radius = 0.5, double height = 1.0, int side_strokes = 4);

/// Open cup around +z, standing on z = 0 and open at z = height: the rim circle (radius `rim`),
/// the bottom circle (radius `bottom`) and `sections` U-shaped strokes, each down one side,
/// across the bottom through the axis and up the opposite side. Nothing crosses the opening.
Sketch cup_sketch(double rim = 0.5, double bottom = 0.35, double height = 0.8, int sections = 2);

/// `strokes` circles of `points` points each around the tube of the torus of radii 0.5 and 0.21
/// about +z, evenly spaced: a dense VR-like capture for the renderer's benchmarks.
Sketch torus_ring_sketch(int strokes, int points);

/// Sphere centred at the origin: `meridians` great half-circles through the poles and the equator.
Sketch sphere_sketch(double radius = 0.5, int meridians = 4);
/// sphere_sketch(0.5, 4) with an antenna: a straight stroke from (0.5, 0, 0) to (0.9, 0, 0),
/// hanging off the sphere by one end (a stroke that depicts no surface).
Sketch sphere_with_antenna_sketch();

/// Torus around +z: `tube_circles` small circles around the tube, plus the outer and inner equators.
Sketch torus_sketch(double major = 0.5, double minor = 0.2, int tube_circles = 8);

/// An open saddle-like sheet z = c (x^2 - y^2) over [-h, h]^2: its 4 border curves marked
/// boundary, plus 3 interior strokes in each direction.
Sketch sheet_sketch(double half = 0.5, double curvature = 0.4);

/// A hatching scene in the unit cube (centred at the origin): `patches` groups of six short
/// parallel strokes 0.03 apart, each group at a random place, direction and depth, as shading
/// drawn in space; it depicts no surface.
Sketch hatching_sketch(int patches, unsigned seed);

/// Every stroke drawn `passes` times, as people over-sketch mid-air: the first pass whole, each
/// other one a span of it (up to 15% shorter at either end) moved by an offset that changes
/// linearly along it between two random vectors (standard deviation `offset` per axis).
/// Ids renumbered 0, 1, ...
Sketch over_sketched(const Sketch& sketch, int passes, double offset, unsigned seed);

/// The sketch as the sketch checks see it: ids assigned, resampled every 0.5% of its diagonal.
Sketch prepared_sketch(Sketch sketch);

/// Adds independent Gaussian noise of standard deviation `sigma` to every point.
void add_noise(Sketch& sketch, double sigma, unsigned seed);
/// Scales by `s` then translates by `t` every point (and the mirror plane).
void transform(Sketch& sketch, double s, const Eigen::Vector3d& t);

/// Icosphere: an icosahedron subdivided `subdivisions` times, projected to the sphere.
/// 10 * 4^k + 2 vertices, closed, outward oriented.
TriMesh icosphere(int subdivisions, double radius = 1.0,
                  const Eigen::Vector3d& center = Eigen::Vector3d::Zero());
/// An icosphere whose vertices are pushed radially onto the surface of a box with half extents
/// `half` and corners rounded with radius `rounding` (the rounded-cube proxy of the tests).
TriMesh rounded_box_mesh(int subdivisions, const Eigen::Vector3d& half, double rounding);
/// An icosphere pushed radially onto a capped cylinder around +z (radius, half height, rim
/// rounding), the cylinder proxy of the tests.
TriMesh rounded_cylinder_mesh(int subdivisions, double radius, double half_height, double rounding);
/// Torus around +z as a closed triangle mesh, `n_major` x `n_minor` quads split in two.
TriMesh torus_mesh(int n_major, int n_minor, double major, double minor);

/// Distance from p to the surface of the axis-aligned box with half extents `half` at the origin.
double box_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& half);

/// Edges of a side x side grid of vertices (v = y * side + x), each cell split by its diagonal:
/// right, up and up-right neighbours, in row-major order.
std::vector<std::array<int, 2>> triangulated_grid_edges(int side);

}  // namespace sketchsurf::testing
