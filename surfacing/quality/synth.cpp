#include "surfacing/quality/synth.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include "surfacing/error.h"
#include "surfacing/portable_math.h"

namespace sketchsurf {

namespace {

using V3 = Eigen::Vector3d;
using Polyline = std::vector<V3>;

/// Random numbers that are the same on every platform: std::mt19937's output is specified, its
/// distributions are not, so the few used here are written out.
class Random {
 public:
  explicit Random(unsigned seed) : engine_(seed) {}
  /// Uniform in [0, 1).
  double uniform() { return static_cast<double>(engine_()) * (1.0 / 4294967296.0); }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  bool chance(double probability) { return uniform() < probability; }
  /// A uniformly distributed unit vector (normalised Gaussian by Box-Muller).
  V3 direction() {
    V3 d;
    do {
      for (int i = 0; i < 3; ++i) {
        const double u1 = 1.0 - uniform(), u2 = uniform();
        d[i] = std::sqrt(-2.0 * portable::log(u1)) * portable::cos(2.0 * M_PI * u2);
      }
    } while (d.squaredNorm() < 1e-12);
    return d.normalized();
  }

 private:
  std::mt19937 engine_;
};

/// The mesh as flat arrays, with what every curve family needs.
struct MeshData {
  const TriMesh& mesh;
  std::vector<V3> points;
  std::vector<V3> face_normals;    // unit; zero for a degenerate face
  std::vector<V3> vertex_normals;  // area-weighted, unit
  double diagonal = 0;

  explicit MeshData(const TriMesh& m) : mesh(m) {
    if (m.n_faces() == 0) throw Error(ErrorKind::Input, "the mesh has no triangles");
    points.reserve(m.n_vertices());
    BoundingBox box;
    for (const auto v : m.vertices()) {
      points.push_back(to_eigen(m.point(v)));
      if (!points.back().allFinite())
        throw Error(ErrorKind::Input, "vertex " + std::to_string(v.idx()) + " is not finite");
      box.extend(points.back());
    }
    diagonal = box.diagonal();
    if (!(diagonal > 0)) throw Error(ErrorKind::Input, "the mesh has zero extent");
    face_normals.assign(m.n_faces(), V3::Zero());
    vertex_normals.assign(m.n_vertices(), V3::Zero());
    for (const auto f : m.faces()) {
      const auto [a, b, c] = corners(f);
      const V3 n = (points[b] - points[a]).cross(points[c] - points[a]);
      for (const int v : {a, b, c}) vertex_normals[v] += n;  // |n| = 2 area: area weighting
      if (n.norm() > 1e-14 * diagonal * diagonal) face_normals[f.idx()] = n.normalized();
    }
    for (auto& n : vertex_normals)
      if (n.norm() > 0) n.normalize();
  }

  std::array<int, 3> corners(OpenMesh::FaceHandle f) const {
    std::array<int, 3> c{};
    int i = 0;
    for (const auto v : mesh.fv_range(f)) c[i++] = v.idx();
    return c;
  }
};

/// Principal axes of the surface (area-weighted covariance of the triangles), largest first.
/// Where two or three variances are equal (a cube, a body of revolution) the eigenvectors are
/// arbitrary, so that eigenspace gets the coordinate axes closest to it instead: a cube is cut
/// parallel to its faces, a vase across its axis.
std::array<V3, 3> principal_axes(const MeshData& d, V3* centre) {
  double area = 0;
  V3 c = V3::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (const auto f : d.mesh.faces()) {
    const auto [a, b, cc] = d.corners(f);
    const V3 &p = d.points[a], &q = d.points[b], &r = d.points[cc];
    const double w = 0.5 * (q - p).cross(r - p).norm();
    // Exact second moment of a triangle: area / 12 * (sum of the corners' outer products + the
    // outer product of their sum).
    const V3 s = p + q + r;
    second += w / 12.0 * (p * p.transpose() + q * q.transpose() + r * r.transpose() + s * s.transpose());
    c += w * s / 3.0;
    area += w;
  }
  if (!(area > 0)) throw Error(ErrorKind::Input, "the mesh has zero area");
  c /= area;
  *centre = c;
  const Eigen::Matrix3d cov = second / area - c * c.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  std::array<double, 3> val{eig.eigenvalues()[2], eig.eigenvalues()[1], eig.eigenvalues()[0]};
  std::array<V3, 3> axes{eig.eigenvectors().col(2), eig.eigenvectors().col(1), eig.eigenvectors().col(0)};
  const double tol = 1e-3 * std::max(val[0], 1e-300);
  const bool eq01 = val[0] - val[1] < tol, eq12 = val[1] - val[2] < tol;
  if (eq01 && eq12) {
    axes = {V3::UnitX(), V3::UnitY(), V3::UnitZ()};
  } else if (eq01 || eq12) {
    // Two equal variances: keep the distinct axis u, span the plane orthogonal to it by the
    // coordinate axis closest to that plane and its cross product.
    const int distinct = eq01 ? 2 : 0;
    const V3 u = axes[distinct];
    V3 best = V3::Zero();
    for (int i = 0; i < 3; ++i) {
      const V3 proj = V3::Unit(i) - u.dot(V3::Unit(i)) * u;
      if (proj.norm() > best.norm() + 1e-9) best = proj;
    }
    const V3 a = best.normalized(), b = u.cross(a).normalized();
    if (eq01) axes = {a, b, u};
    else axes = {u, a, b};
  }
  for (auto& a : axes) {
    int k = 0;
    a.cwiseAbs().maxCoeff(&k);
    if (a[k] < 0) a = -a;
  }
  return axes;
}

/// Polylines where the piecewise-linear interpolation of `values` (one per vertex) is zero,
/// through the faces not `skipped`. A vertex counts as positive when its value is >= 0, so a
/// zero set through a vertex is still a clean curve. Each point lies on a mesh edge (linear
/// interpolation of its ends), so on the mesh. Closed curves repeat their first point at the end.
std::vector<Polyline> level_set(const MeshData& d, const std::vector<double>& values,
                                const std::vector<char>& skipped) {
  const TriMesh& m = d.mesh;
  std::vector<int> crossing(m.n_edges(), -1);
  std::vector<V3> pts;
  for (const auto e : m.edges()) {
    const int a = e.v0().idx(), b = e.v1().idx();
    if ((values[a] >= 0) == (values[b] >= 0)) continue;
    const double t = values[a] / (values[a] - values[b]);
    crossing[e.idx()] = static_cast<int>(pts.size());
    pts.push_back(d.points[a] + t * (d.points[b] - d.points[a]));
  }
  std::vector<std::array<int, 2>> next(pts.size(), {-1, -1});
  auto link = [&](int a, int b) { (next[a][0] < 0 ? next[a][0] : next[a][1]) = b; };
  for (const auto f : m.faces()) {
    if (skipped[f.idx()]) continue;
    std::array<int, 2> ends{-1, -1};
    int n = 0;
    for (const auto e : m.fe_range(f))
      if (crossing[e.idx()] >= 0 && n < 2) ends[n++] = crossing[e.idx()];
    if (n != 2) continue;
    link(ends[0], ends[1]);
    link(ends[1], ends[0]);
  }
  std::vector<char> used(pts.size(), 0);
  std::vector<Polyline> out;
  auto walk = [&](int start) {
    Polyline line{pts[start]};
    used[start] = 1;
    int prev = -1, cur = start;
    for (;;) {
      int nxt = next[cur][0] != prev && next[cur][0] >= 0 ? next[cur][0] : next[cur][1];
      if (next[cur][0] == prev && next[cur][1] == prev) nxt = -1;  // a two-point loop is a line
      if (nxt < 0) break;
      line.push_back(pts[nxt]);
      if (used[nxt]) break;  // back at the start: closed
      used[nxt] = 1;
      prev = cur;
      cur = nxt;
    }
    if (line.size() >= 2) out.push_back(std::move(line));
  };
  // Open curves (ending at a border or a skipped face) from one end, then the closed ones.
  for (std::size_t i = 0; i < pts.size(); ++i)
    if (!used[i] && (next[i][0] < 0) != (next[i][1] < 0)) walk(static_cast<int>(i));
  for (std::size_t i = 0; i < pts.size(); ++i)
    if (!used[i] && next[i][0] >= 0) walk(static_cast<int>(i));
  return out;
}

/// Chains of feature edges (dihedral above the sharp angle, or on a border), split at vertices
/// where the number of feature edges is not two and where the chain turns by more than the
/// corner angle.
std::vector<Polyline> feature_curves(const MeshData& d, const SynthOptions& o,
                                     std::vector<char>* on_feature) {
  const TriMesh& m = d.mesh;
  const double cos_sharp = portable::cos(o.sharp_angle * M_PI / 180.0);
  const double cos_corner = portable::cos(o.corner_angle * M_PI / 180.0);
  std::vector<char> feature(m.n_edges(), 0);
  std::vector<int> degree(m.n_vertices(), 0);
  for (const auto e : m.edges()) {
    bool f = e.is_boundary();
    if (!f) {
      const V3 &n0 = d.face_normals[e.h0().face().idx()], &n1 = d.face_normals[e.h1().face().idx()];
      f = n0.squaredNorm() > 0 && n1.squaredNorm() > 0 && n0.dot(n1) < cos_sharp;
    }
    if (!f) continue;
    feature[e.idx()] = 1;
    ++degree[e.v0().idx()];
    ++degree[e.v1().idx()];
  }
  on_feature->assign(m.n_vertices(), 0);
  for (std::size_t v = 0; v < degree.size(); ++v) (*on_feature)[v] = degree[v] > 0;

  // The two feature neighbours of every degree-2 vertex; a break where the turn is sharp.
  std::vector<char> breaks(m.n_vertices(), 0);
  for (const auto v : m.vertices()) {
    const int i = v.idx();
    if (degree[i] == 0) continue;
    if (degree[i] != 2) {
      breaks[i] = 1;
      continue;
    }
    std::array<int, 2> nb{};
    int n = 0;
    for (const auto h : m.voh_range(v))
      if (feature[h.edge().idx()]) nb[n++] = h.to().idx();
    const V3 in = (d.points[i] - d.points[nb[0]]).normalized(),
             out = (d.points[nb[1]] - d.points[i]).normalized();
    breaks[i] = in.dot(out) < cos_corner;
  }

  std::vector<char> used(m.n_edges(), 0);
  std::vector<Polyline> out;
  auto walk = [&](OpenMesh::SmartHalfedgeHandle h) {
    Polyline line{d.points[h.from().idx()]};
    for (;;) {
      used[h.edge().idx()] = 1;
      const auto v = h.to();
      line.push_back(d.points[v.idx()]);
      if (breaks[v.idx()]) break;
      OpenMesh::SmartHalfedgeHandle nxt;
      for (const auto g : m.voh_range(v))
        if (feature[g.edge().idx()] && !used[g.edge().idx()]) nxt = g;
      if (!nxt.is_valid()) break;  // closed loop back at its start
      h = nxt;
    }
    out.push_back(std::move(line));
  };
  for (const auto v : m.vertices())
    if (breaks[v.idx()])
      for (const auto h : m.voh_range(v))
        if (feature[h.edge().idx()] && !used[h.edge().idx()]) walk(h);
  for (const auto e : m.edges())  // loops without a corner start at their first edge
    if (feature[e.idx()] && !used[e.idx()]) walk(e.h0());
  return out;
}

/// A stroke through `line`, resampled to `spacing`, or nothing when shorter than `min_length`.
void add_stroke(std::vector<Stroke>& strokes, const Polyline& line, double spacing,
                double min_length) {
  Stroke s;
  s.points = line;
  if (s.length() < min_length || s.length() <= 0) return;
  strokes.push_back(resample(s, spacing));
}

/// Arc length at every point of `p`.
std::vector<double> arc_lengths(const Polyline& p) {
  std::vector<double> arc(p.size(), 0.0);
  for (std::size_t i = 1; i < p.size(); ++i) arc[i] = arc[i - 1] + (p[i] - p[i - 1]).norm();
  return arc;
}

/// Straight extension of length `length` past the end `p.back()`, along the direction of the
/// last `reach` of the stroke, spaced about `spacing`.
void extend_end(Polyline& p, double length, double reach, double spacing) {
  if (length <= 0 || p.size() < 2) return;
  const V3 end = p.back();
  V3 from = p[p.size() - 2];
  for (std::size_t i = p.size() - 1; i-- > 0;) {
    from = p[i];
    if ((end - from).norm() >= reach) break;
  }
  const V3 dir = end - from;
  if (dir.norm() <= 0) return;
  const int n = std::max(1, static_cast<int>(std::ceil(length / spacing)));
  for (int k = 1; k <= n; ++k) p.push_back(end + dir.normalized() * (length * k / n));
}

/// One drawing of `base` with the flaws of the vr style (all lengths absolute here).
struct Flaws {
  double spacing, tremor, wavelength, gap_probability, gap_length, overshoot, offset;
};

void draw_vr(std::vector<Stroke>& out, const Polyline& base, bool second_copy, const Flaws& f,
             Random& rng) {
  Polyline p = base;
  const bool closed = (p.front() - p.back()).norm() <= 1e-9 * f.spacing;
  const double start_ext = rng.uniform(0.0, f.overshoot), end_ext = rng.uniform(0.0, f.overshoot);
  if (!closed) {
    extend_end(p, end_ext, 3 * f.spacing, f.spacing);
    std::reverse(p.begin(), p.end());
    extend_end(p, start_ext, 3 * f.spacing, f.spacing);
    std::reverse(p.begin(), p.end());
  }
  // Tremor: per axis three sinusoids of arc length with random wavelengths and phases; a
  // constant amplitude a gives an RMS offset of a * sqrt(3 axes * 3 waves / 2).
  const double a = f.tremor / std::sqrt(4.5);
  std::array<std::array<double, 3>, 3> wave{}, phase{};
  for (int axis = 0; axis < 3; ++axis)
    for (int k = 0; k < 3; ++k) {
      wave[axis][k] = f.wavelength * rng.uniform(0.5, 2.0);
      phase[axis][k] = rng.uniform(0.0, 2.0 * M_PI);
    }
  const V3 shift = second_copy ? V3(f.offset * rng.direction()) : V3::Zero();
  const std::vector<double> arc = arc_lengths(p);
  for (std::size_t i = 0; i < p.size(); ++i) {
    V3 t = shift;
    for (int axis = 0; axis < 3; ++axis)
      for (int k = 0; k < 3; ++k)
        t[axis] += a * portable::sin(2 * M_PI * arc[i] / wave[axis][k] + phase[axis][k]);
    p[i] += t;
  }
  // A gap: the stroke lifted for gap_length somewhere in its middle part.
  const double total = arc.back();
  std::vector<Polyline> pieces;
  if (rng.chance(f.gap_probability) && total > 3 * f.gap_length && f.gap_length > 0) {
    const double at = rng.uniform(0.3, 0.7) * total;
    Polyline before, after;
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (arc[i] < at - 0.5 * f.gap_length) before.push_back(p[i]);
      else if (arc[i] > at + 0.5 * f.gap_length) after.push_back(p[i]);
    }
    pieces = {before, after};
  } else {
    pieces = {p};
  }
  for (auto& piece : pieces)  // already spaced: the extensions at most `spacing` apart
    if (piece.size() >= 2) {
      Stroke s;
      s.points = std::move(piece);
      out.push_back(std::move(s));
    }
}

}  // namespace

bool SynthOptions::valid(std::string* why) const {
  auto fail = [&](const std::string& w) {
    if (why) *why = w;
    return false;
  };
  auto fraction = [](double x) { return std::isfinite(x) && x >= 0; };
  auto probability = [](double x) { return x >= 0 && x <= 1; };
  if (!(sharp_angle > 0 && sharp_angle < 180)) return fail("synth: sharp angle must be in (0, 180) degrees");
  if (!(corner_angle > 0 && corner_angle <= 180)) return fail("synth: corner angle must be in (0, 180] degrees");
  if (sections < 0 || sections > 1000) return fail("synth: sections must be in [0, 1000]");
  if (silhouettes < 0 || silhouettes > 1000) return fail("synth: silhouettes must be in [0, 1000]");
  if (!(spacing > 0 && spacing <= 0.5)) return fail("synth: spacing must be in (0, 0.5] of the diagonal");
  if (!fraction(min_length)) return fail("synth: min length must be >= 0");
  if (!(thin_extent >= 0 && thin_extent <= 1)) return fail("synth: thin extent must be in [0, 1]");
  if (!fraction(tremor)) return fail("synth: tremor must be >= 0");
  if (!(tremor_wavelength > 0 && std::isfinite(tremor_wavelength)))
    return fail("synth: tremor wavelength must be > 0");
  if (!fraction(gap_length)) return fail("synth: gap length must be >= 0");
  if (!fraction(overshoot)) return fail("synth: overshoot must be >= 0");
  if (!fraction(duplicate_offset)) return fail("synth: duplicate offset must be >= 0");
  if (!probability(gap)) return fail("synth: gap must be a probability in [0, 1]");
  if (!probability(duplicate)) return fail("synth: duplicate must be a probability in [0, 1]");
  if (!probability(drop)) return fail("synth: drop must be a probability in [0, 1]");
  return true;
}

Sketch synthesize_sketch(const TriMesh& mesh, const SynthOptions& o) {
  std::string why;
  if (!o.valid(&why)) throw Error::usage(why);
  const MeshData d(mesh);
  const double spacing = o.spacing * d.diagonal, min_length = o.min_length * d.diagonal;

  std::vector<Polyline> lines;
  std::vector<char> on_feature;
  for (auto& l : feature_curves(d, o, &on_feature)) lines.push_back(std::move(l));

  V3 centre;
  const std::array<V3, 3> axes = principal_axes(d, &centre);
  const std::vector<char> none(mesh.n_faces(), 0);
  std::vector<double> values(mesh.n_vertices());
  std::array<double, 3> lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  for (int a = 0; a < 3; ++a)
    for (const V3& p : d.points) {
      lo[a] = std::min(lo[a], (p - centre).dot(axes[a]));
      hi[a] = std::max(hi[a], (p - centre).dot(axes[a]));
    }
  const double longest = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  for (int a = 0; a < 3; ++a) {
    // Sections across a thin direction (a plate's thickness) repeat its outline: not drawn.
    if (hi[a] - lo[a] < o.thin_extent * longest) continue;
    for (int k = 0; k < o.sections; ++k) {
      const double offset = lo[a] + (hi[a] - lo[a]) * (k + 1) / (o.sections + 1);
      for (std::size_t v = 0; v < values.size(); ++v)
        values[v] = (d.points[v] - centre).dot(axes[a]) - offset;
      for (auto& l : level_set(d, values, none)) lines.push_back(std::move(l));
    }
  }

  // Contours for view directions spread in azimuth (golden angle) and elevation over the
  // hemisphere above the two main axes; faces touching a feature curve are left out.
  std::vector<char> near_feature(mesh.n_faces(), 0);
  for (const auto f : mesh.faces())
    for (const int v : d.corners(f)) near_feature[f.idx()] |= on_feature[v];
  for (int k = 0; k < o.silhouettes; ++k) {
    const double azimuth = 0.5 + k * 2.39996323, elevation = (15.0 + 45.0 * (k % 3) / 2.0) * M_PI / 180.0;
    const V3 dir =
        portable::cos(elevation) * (portable::cos(azimuth) * axes[0] + portable::sin(azimuth) * axes[1]) +
        portable::sin(elevation) * axes[2];
    for (std::size_t v = 0; v < values.size(); ++v) values[v] = d.vertex_normals[v].dot(dir);
    for (auto& l : level_set(d, values, near_feature)) lines.push_back(std::move(l));
  }

  Sketch sketch;
  std::vector<Stroke> clean;
  for (const auto& l : lines) add_stroke(clean, l, spacing, min_length);
  if (o.style == SynthOptions::Style::Net) {
    sketch.strokes = std::move(clean);
  } else {
    Random rng(o.seed);
    const Flaws flaws{spacing, o.tremor * d.diagonal, o.tremor_wavelength * d.diagonal, o.gap,
                      o.gap_length * d.diagonal, o.overshoot * d.diagonal,
                      o.duplicate_offset * d.diagonal};
    for (const auto& s : clean) {
      const bool dropped = rng.chance(o.drop), twice = rng.chance(o.duplicate);
      if (dropped) continue;
      draw_vr(sketch.strokes, s.points, false, flaws, rng);
      if (twice) draw_vr(sketch.strokes, s.points, true, flaws, rng);
    }
  }
  for (std::size_t i = 0; i < sketch.strokes.size(); ++i)
    sketch.strokes[i].id = static_cast<std::int64_t>(i);
  sketch.provenance = std::string("synthesized ") +
                      (o.style == SynthOptions::Style::Net ? "net" : "vr") + " sketch, seed " +
                      std::to_string(o.seed);
  return sketch;
}

}  // namespace sketchsurf
