#pragma once
// The proxy surface (paper §5 "Proxy creation", METHOD.md section 1): automatic, with VIPSS on
// samples of the strokes, polygonised and remeshed; or a user's rough mesh attracted to the strokes.

#include <cstddef>
#include <string>
#include <vector>

#include "surfacing/mesh.h"
#include "surfacing/progress.h"
#include "surfacing/proxy/vipss.h"
#include "surfacing/sketch/sketch.h"

namespace sketchsurf {

/// Every tunable number of the proxy stage. Lengths are fractions of the bounding-box diagonal of
/// the strokes that are not ignored (the sketch is normalised to unit diagonal internally).
struct ProxyOptions {
  std::size_t points = 400;    ///< VIPSS sample count (Huang et al. 2019): its cost grows as n^3
                               ///< (factorisation) and n^2 per L-BFGS step; with smoothing, 400
                               ///< give the shape (1000: 3-10x the time on real sketches)
  double lambda = -1.0;        ///< VIPSS smoothing weight (VIPSS Eq. 9) on the unit-diagonal
                               ///< sketch; 0 = interpolate; < 0 = chosen per sketch from the
                               ///< ladder lambda_min * lambda_step^k (up to lambda_max): from its
                               ///< second weight up to the first whose zero set is confined (see
                               ///< confine_margin), then the choice of far_distance
  double lambda_min = 1e-5;    ///< smallest smoothing weight tried when lambda < 0; the ladder
                               ///< starts at its second weight, and the first is solved only when
                               ///< that leaves at least far_tie of the surface far from the strokes
  double lambda_max = 1e-3;    ///< last smoothing weight tried when lambda < 0
  double lambda_step = 10.0;   ///< factor between the smoothing weights tried
  double clean_gap = 1e-4;     ///< the ladder starts at its first weight when the strokes are a
                               ///< clean curve network: where they cross, they pass at a median
                               ///< distance below this (fraction of diagonal; 0 = never) from
                               ///< each other (a mesh's feature curves and sections, a modelling
                               ///< tool's network: rounding; a hand's strokes: its tremor, 0.1%
                               ///< and more). Such strokes lie on the surface and need no
                               ///< smoothing; the second weight rounds a smooth shape's bulges
  int clean_crossings = 8;     ///< ... and at least this many pairs of strokes cross
  double clean_lambda = 1e-6;  ///< a clean curve network's ladder starts at this weight, below
                               ///< lambda_min (0 = interpolate), then goes on from lambda_min
                               ///< until the zero set is confined
  std::size_t clean_points = 1000;  ///< that first solve's sample count (or `points`, if more):
                                    ///< nearly interpolating, the surface follows the strokes
                                    ///< between the samples only as closely as they lie (400: a
                                    ///< car's body, a cow's face off their strokes); the ladder's
                                    ///< other weights keep `points`
  double far_distance = 0.05;  ///< when no weight of the ladder is confined, the largest is kept
                               ///< unless a smaller one's polygonised surface has less area
                               ///< farther than this from every stroke (fraction of diagonal) ...
  double far_tie = 0.03;       ///< ... by more than this fraction of the surface's area, has
  double far_most = 0.5;       ///< at most this fraction far (more: the strokes frame no surface,
                               ///< a flower's petals, a painterly scene) ...
  int far_extra_genus = 3;     ///< ... and at most this many more handles (more: windows through
                               ///< thin double walls, not openings the strokes depict)
  double rounded_misfit = 0.6;  ///< the ladder's first weight is kept instead of its second when
                                ///< the second's zero set, confined, rounds the shape off the
                                ///< strokes: their signed misfits correlate between neighbouring
                                ///< strokes above this (misfit.h; tremor alone: below 0.1; a car's
                                ///< or a box's rounded edges: 0.35-0.8; >= 1: never) ...
  double rounded_far = 0.005;   ///< ... and the first's is confined too, with no more handles or
                                ///< parts, and far area at most this fraction more. On a clean
                                ///< network, when the ladder's last weight's misfit is above
                                ///< rounded_misfit, the least smoothed solve before it with no
                                ///< more handles, parts or far area (rounded_far) stays, closed or
                                ///< not
  double misfit_reach = 0.04;   ///< strokes within this (fraction of diagonal) are neighbours
  double miss_distance = 0.02; ///< a stroke point farther than this from the proxy (fraction of
                               ///< diagonal) counts as missed (report: missed_strokes)
  double confine_margin = 0.1;   ///< a zero set is confined when f has one sign all over the faces
                                 ///< of the samples' box grown by this (fraction of diagonal): no
                                 ///< sheet runs out past the strokes' extent to the box
  double confine_radius = 0.3;   ///< no surface farther than this from every stroke (fraction of
                                 ///< diagonal; 0 = off): where VIPSS's zero set runs on past the
                                 ///< strokes (a sheet, a fin) it is cut at this distance and closed
                                 ///< by the strokes' offset surface. Smaller keeps thin parts apart
                                 ///< (ground-truth chair: legs apart at 0.15) but pits faces framed
                                 ///< by strokes far apart (bundled cube: genus 5 at 0.15, 0 at 0.3;
                                 ///< ground-truth torus: 21 at 0.04, 1 at 0.08)
  double confine_near = 0.1;    ///< a nearer radius (fraction of diagonal; 0 = off), used when
                                 ///< the surface farther than this from every stroke is mostly
                                 ///< not framed by strokes: seen in its tangent plane, the strokes
                                 ///< near it leave a gap of framed_gap (a lamp's pole webbed to
                                 ///< its base and shade). Faces framed by strokes far apart would
                                 ///< be pitted by it, hence tried only when ...
  double near_open_least = 0.01;  ///< ... at least this fraction of the surface is farther and
                                  ///< not framed, and
  double near_open_ratio = 10.0;  ///< ... this many times the fraction farther and framed (a
                                  ///< chest's lid: 4.9, pitted; a bar's bulging ends: 6.3, pitted
                                  ///< at its corners; a chair's legs webbed into a skirt: 14.6; a
                                  ///< lamp's web: 152); kept when it adds no handle and splits
                                  ///< nothing
  double framed_gap = 120.0;      ///< a face is framed when the strokes round it, seen in its
                                  ///< tangent plane, leave no gap of this many degrees or more
                                  ///< (a face between its drawn edges); a wall between two legs,
                                  ///< open below them, leaves 120-180 degrees
  double confine_box = 0.02;    ///< with confine_radius > 0, no surface farther than this outside
                                ///< the strokes' bounding box either (fraction of diagonal): the
                                ///< offset surface that closes a cut would reach confine_radius
                                ///< past the outermost strokes
  double confine_box_tight = 1e-4;   ///< the box's sides where the strokes draw a face are then
                                     ///< drawn in to this (fraction of diagonal; 0 = off): onto
                                     ///< their outermost strokes (a face cut farther out lies that
                                     ///< far off them), where
                                     ///< that adds no handle and splits nothing: a box's side, a
                                     ///< plate's face, a cup's cap is cut on its strokes, the cut's
                                     ///< rim on the face's edge strokes (cut farther out, the rim
                                     ///< is a fold inside the face that its patch keeps as a bump);
                                     ///< where that would pierce or split the surface, halfway
                                     ///< between this and confine_box under the same condition;
                                     ///< not during the choice of smoothing, which it would sway
  double confine_box_span = 0.75;    ///< a side is a drawn face when the strokes within
                                     ///< confine_box of it span at least this fraction of the box
                                     ///< along both of its directions (a box's face, a cup's rim);
                                     ///< where they only touch it (the top of a dome) a closer cut
                                     ///< would flatten the surface and its patch would bulge
  double confine_box_partial = 0.15; ///< a side is also a drawn face where flat runs of strokes
                                     ///< (their depth in the band varying by at most half of
                                     ///< confine_box) span confine_box_span along one of its
                                     ///< directions and this fraction along the other: a face
                                     ///< filling part of its side, such as the thin end of an
                                     ///< L-bracket's arm (1 = off)
  double overshoot = 0.03;   ///< how far (fraction of the diagonal, along the stroke) a hand's
                             ///< stroke may run on past the edge where it should stop: a face
                             ///< drawn in lies where the strokes along it are, not at the ends of
                             ///< strokes across it that far out (0 = at the outermost point)
  double outline_gap = 0.04;    ///< with confine_radius > 0, no surface farther than this
                                ///< (fraction of diagonal; 0 = off) beyond the sketch's
                                ///< outline: at a stroke point whose nearby
                                ///< strokes all lie on one side, the
                                ///< surface keeps to the half-space within this gap of it, away
                                ///< from them (a flange past a drawn base, a flare past a handle's
                                ///< strokes, a foot's skirt are cut and closed there)
  double outline_reach = 0.25;  ///< strokes within this distance of a point (fraction of
                                ///< diagonal) decide whether it is on the outline
  double outline_from = 0.3;    ///< a point is on the outline when the mean direction to those
  double outline_to = 0.5;      ///< strokes is longer than outline_from; its gap grows from
                                ///< outline_gap (length outline_to and above) to no limit
  double outline_blend = 0.03;  ///< the half-spaces of nearby outline points are blended over
                                ///< this distance (fraction of diagonal), so that the cut is smooth
  double outline_most = 0.7;    ///< ... and the cut is made only when at most this fraction of the
                                ///< surface lies farther than far_distance from every stroke (more:
                                ///< the strokes frame no surface; cut, it would fall apart)
  double loft_fit = 0.02;       ///< where the surface lies mostly far from every stroke (more than
                                ///< outline_most of it) and the strokes include parallel section
                                ///< loops, the proxy is lofted through them instead (loft.h), when
                                ///< 95% of the stroke points lie within this distance of the loft
                                ///< (fraction of diagonal; 0 = never): a dress drawn as a waist,
                                ///< a hem and a profile
  double window_value = 0.025;  ///< where a solve's surface has handles, the windows through thin
                                ///< double walls are closed: saddles of the distance-scaled VIPSS
                                ///< function with a value below this (fraction of diagonal; 0 =
                                ///< off), a maximum within the window's plane and a minimum
                                ///< across, as between two walls whose inside layer pinches out
                                ///< where no stroke holds it. Kept only when it removes handles
                                ///< and splits nothing. Openings the strokes depict (a mug's
                                ///< handle, holes through a plate) have larger values. The
                                ///< window's open region (where the walls' mid-surface is outside
                                ///< with a value below this) is flooded from the saddle and
                                ///< closed by a membrane: a thin plate's slots are long, not round
  double window_reach = 0.6;    ///< ... at most this far from the saddle (fraction of diagonal)
  int window_points = 400;      ///< ... with at most this many membrane bumps per window
  double window_undrawn = 0.06;  ///< wider windows, saddle values in [window_value, this)
                                 ///< (fraction of diagonal; 0 = off), are closed as well where no
                                 ///< stroke depicts an opening: none winds round it (a hole's
                                 ///< rim, a handle's C) and none runs along it all round (a bore's
                                 ///< wall), and the hole spans the gap between the strokes
                                 ///< round it (a mug's floor between sparse strokes). Tried on
                                 ///< the solve the ladder keeps, kept only when it removes
                                 ///< handles and splits nothing
  bool window_tight = true;     ///< windows whose space across does not open (a chair seat's
                                ///< underside beside a leg; saddles with a value below
                                ///< window_value that the windows' test refuses), with no
                                ///< stroke depicting an opening there, are closed on the kept
                                ///< solve, all together, where that removes handles and neither
                                ///< splits nor joins parts
  double face_hole_thickness = 0.03;  ///< where a face drawn in cuts holes through the surface
                                      ///< (a glass's thin foot whose top dips below its drawn
                                      ///< bottom), the holes that no stroke depicts (face_holes.h)
                                      ///< are closed by a membrane this thick inside the face
                                      ///< (fraction of diagonal; 0 = off); kept when that removes
                                      ///< handles and splits nothing
  double bridge_value = 0.025;  ///< gaps between two parts of the surface that nearly touch
                                ///< (saddles of the distance-scaled VIPSS function with a value in
                                ///< (0, bridge_value), a maximum along the gap and a minimum
                                ///< across it; 0 = off) are bridged where a stroke crosses the gap
                                ///< outside the surface: the strokes depict a connection there (a
                                ///< handle's end drawn onto the wall). Kept when it splits nothing
  double neck_value = 0.02;     ///< thin connections between two parts of the surface (saddles
                                ///< inside it with a value in (-neck_value, 0), a maximum along
                                ///< the neck and a minimum across it; 0 = off) are cut where no
                                ///< stroke crosses the neck: two parts drawn apart that VIPSS
                                ///< merged. Kept when it splits the surface or removes handles
                                ///< and loses no part
  double part_reach = 0.04;     ///< thin parts webbed together (a chair's legs into a skirt, a
                                ///< torch's handle into a sail) are told at the samples whose
                                ///< stroke points within this (fraction of diagonal; 0 = off)
                                ///< surround an axis inside the surface on a round section, and
                                ///< where the space in front of such a sample is inside too, with
                                ///< another part's strokes ahead (part_normals.h)
  std::size_t part_webs = 4;    ///< ... at this many such samples or more, VIPSS is solved again
                                ///< with the parts' normals kept (outward from their axes) ...
  double part_free = 0.1;       ///< ... and the normals within this of a web's samples (fraction
                                ///< of diagonal) free to follow, the others kept ...
  double part_far_ratio = 0.8;  ///< ... and that solve is kept when its area far from every
                                ///< stroke (far_distance) is at most this times the other's and
                                ///< smaller by far_tie (the web was such area: a chair's 0.17, a
                                ///< torch's 0.68; rims and double walls that look like thin
                                ///< parts, 0.87 and more), with at most one handle more and no
                                ///< other part; where more than far_most of the other's surface is
                                ///< far (a hull round all the parts), whenever it is smaller by
                                ///< far_tie, with at most one handle and one part more
  double min_component = 0.01;  ///< parts of the polygonised surface with less than this fraction
                                ///< of its area are dropped (specks the confinement cuts off)
  double vipss_tolerance = 1e-7;  ///< L-BFGS relative energy change at which the normals are
                                  ///< final (VIPSS Eq. 10)
  double edge = 0.007;         ///< target edge length, fraction of diagonal (paper §5: the authors'
                               ///< proxy_resolution)
  double cell = 0.01;          ///< polygonisation grid spacing, fraction of diagonal
  double padding = 0.1;        ///< margin of the polygonisation box around the strokes, fraction of
                               ///< diagonal
  double sample_spacing = 0.002;  ///< stroke resampling before farthest-point sampling, fraction
  int remesh_iterations = 5;   ///< isotropic remeshing rounds of a user proxy (Botsch & Kobbelt
                               ///< 2004)
  int vipss_remesh_iterations = 3;  ///< the same for the automatic proxy: the polygonised surface is
                                    ///< already near the target edge (5 rounds: the same shape,
                                    ///< 1.6x the remeshing time)
  int projection_steps = 1;    ///< Newton steps per projection onto the VIPSS surface (each
                               ///< remeshing round projects again)
  double attract_weight = 2.0; ///< Least-Squares Mesh positional weight (Sorkine & Cohen-Or 2004)
  int attract_rounds = 3;      ///< Least-Squares Mesh rounds (re-assign nearest vertices, re-solve)
  bool attract_vipss = false;  ///< attract the automatic proxy to the strokes as well (paper §5,
                               ///< Fig. 5). The membrane flattens it between strokes: right on
                               ///< sharp, planar sketches (a cube's faces), wrong on curved ones (torus sketch: 0.03% -> 5% of the
                               ///< diagonal off the true surface), hence off by default
  int attract_levels = 1;      ///< the Least-Squares Mesh is solved on a mesh with 2^levels times
                               ///< the target edge, then Loop-subdivided back: the solve's fill-in
                               ///< grows faster than the mesh (80k vertices: 18 s a factorisation,
                               ///< 20k: 0.7 s). Loop, not an interpolating scheme: modified
                               ///< butterfly overshoots at the attracted creases (bundled cube +
                               ///< rough proxy: a bulged, mis-segmented face)
  double max_proxy_distance = 0.25;  ///< user proxy: largest accepted median distance from the
                                    ///< strokes to the proxy, fraction of diagonal
  unsigned threads = 0;        ///< worker threads (0 = all); never changes the result

  /// True when the options can be used; otherwise `why` (if given) says which field is wrong.
  bool valid(std::string* why = nullptr) const;
};

/// Topology of a mesh: per connected component Euler characteristic V - E + F = 2 - 2g - b.
struct MeshTopology {
  std::size_t components = 0;      ///< connected components (through edges)
  std::size_t boundary_loops = 0;  ///< border loops; 0 for a closed mesh
  long euler = 0;                  ///< V - E + F of the whole mesh
  long genus = 0;                  ///< sum of the components' genera
  bool closed() const { return boundary_loops == 0; }
};

/// Components, border loops, Euler characteristic and genus of `mesh`.
MeshTopology mesh_topology(const TriMesh& mesh);

/// What the proxy stage did (the CLI's report.json).
struct ProxyReport {
  std::size_t samples = 0;        ///< VIPSS input points of the kept solve (0 for a user proxy)
  std::size_t vertices = 0, faces = 0;
  MeshTopology topology;
  VipssSummary vipss;             ///< automatic proxy only: the kept solve
  double lambda = 0.0;            ///< automatic proxy: the smoothing weight used
  double crossing_gap = -1.0;     ///< automatic proxy: the strokes' median distance where they
                                  ///< cross (fraction of diagonal; < 0: too few crossings)
  bool clean_windows = false;     ///< automatic proxy: the strokes are a clean network (their
                                  ///< crossing gap below clean_gap), but its first solve opened
                                  ///< windows that a drawn sketch's did not (more than
                                  ///< far_extra_genus handles more): smoothed as drawn
  double shared_misfit = 0.0;     ///< automatic proxy: the ladder's second weight's misfit shared
                                  ///< between neighbouring strokes (a clean network's: its last
                                  ///< weight's; misfit.h; 0: not measured)
  bool rounded = false;           ///< automatic proxy: ... above rounded_misfit, and a less
                                  ///< smoothed solve was kept instead
  double far_area = 0.0;          ///< automatic proxy: area fraction of the kept solve's surface
                                  ///< (or of the loft) farther than far_distance from every stroke
  double missed_strokes = 0.0;    ///< automatic proxy: fraction of the stroke points farther than
                                  ///< miss_distance from the kept solve's surface
  double confine_radius = 0.0;    ///< automatic proxy: R, fraction of diagonal (0: not confined)
  bool outline_cut = false;       ///< automatic proxy: the surface was cut at the outline
  int box_drawn_in = 0;           ///< automatic proxy: sides of the box drawn in (confine_box_tight)
  std::size_t planes_drawn_in = 0;  ///< automatic proxy: slanted faces drawn in the same way
  std::vector<Plane> drawn_faces;   ///< automatic proxy (VIPSS's surface): the planes of the faces
                                    ///< drawn in, box sides and slanted, in the sketch's units,
                                    ///< normals outward; the proxy lies on them where they cut it
  std::size_t loft_sections = 0;  ///< automatic proxy: the section loops it was lofted through
                                  ///< (0: VIPSS's surface)
  std::size_t windows = 0;        ///< automatic proxy: membrane bumps closing windows
  std::size_t bridges = 0;        ///< automatic proxy: gaps bridged
  std::size_t necks = 0;          ///< automatic proxy: necks cut
  std::size_t face_holes = 0;     ///< automatic proxy: holes through faces drawn in, closed
  std::size_t part_normals = 0;   ///< automatic proxy: normals kept from thin parts' strokes (0:
                                  ///< none, or that solve was not kept)
  std::size_t vipss_solves = 0;   ///< automatic proxy: smoothing weights tried
  std::size_t evaluations = 0;    ///< implicit-function evaluations by the polygoniser
  std::size_t anchors = 0;        ///< user proxy: vertices pulled to strokes
  double median_distance_before = 0, median_distance_after = 0;  ///< user proxy: strokes to
                                                                 ///< nearest vertex, sketch units
  double sampling_seconds = 0, vipss_seconds = 0, polygonize_seconds = 0, remesh_seconds = 0,
         attract_seconds = 0, total_seconds = 0;
};

/// The automatic proxy: samples the strokes (not the ignored ones), runs VIPSS (with the smallest
/// smoothing weight of the ladder whose zero set stays within the strokes' extent, unless a lambda
/// is given), polygonises every component of its zero set that passes through the samples,
/// remeshes isotropically onto it and (attract_vipss) attracts it to the strokes as
/// attract_proxy() does.
/// @return a closed, manifold, outward-oriented mesh in the sketch's units.
/// @throws Error (Usage) for invalid options; Error (Processing) when the strokes are too few, lie
///         in a plane or on a line, or VIPSS finds no surface; Error (Cancelled).
TriMesh make_proxy(const Sketch& sketch, const ProxyOptions& options, const Progress& progress = {},
                   ProxyReport* report = nullptr);

/// Largest ratio of a user proxy's bounding-box diagonal to the strokes': remeshing a mesh many
/// times the sketch's size at the sketch's edge length takes memory without bound, and a proxy
/// that large is far from the strokes anyway (often a mesh in other units).
constexpr double kMaxProxyScale = 10.0;
/// Smallest such ratio: a proxy that small cannot be near more than a speck of the strokes.
constexpr double kMinProxyScale = 0.01;

/// Why `mesh` cannot be a proxy of `sketch` (empty when it can): no triangle; a vertex that is
/// not finite or has a coordinate beyond +-kMaxCoordinate; no area (every triangle degenerate,
/// the vertices on a point or a line); a bounding box more than kMaxProxyScale or less than
/// kMinProxyScale times the strokes'. Cheap (one pass over the mesh), meant before any work on
/// a user's mesh; the caller names the file.
std::string proxy_mesh_problem(const TriMesh& mesh, const Sketch& sketch);

/// A user proxy (any resolution, e.g. a low-poly model): checked (proxy_mesh_problem(), median
/// distance from the strokes at most max_proxy_distance), remeshed to 2^attract_levels times the target edge
/// length, attracted to the strokes by a Least-Squares Mesh, then subdivided to the target edge.
/// @throws Error (Usage) for invalid options; Error (Processing) for a mesh that cannot be a proxy,
///         a far-away mesh or a sketch without strokes; Error (Cancelled).
TriMesh attract_proxy(const TriMesh& user_mesh, const Sketch& sketch, const ProxyOptions& options,
                      const Progress& progress = {}, ProxyReport* report = nullptr);

}  // namespace sketchsurf
