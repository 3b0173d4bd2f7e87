#include "engine/render/scene.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "engine/render/palette.h"
#include "surfacing/error.h"

namespace sketchsurf::render {

namespace {

std::uint32_t pack(const Rgb8& c) {
  return std::uint32_t(c[0]) | (std::uint32_t(c[1]) << 8) | (std::uint32_t(c[2]) << 16) | (255u << 24);
}

/// Douglas-Peucker: the points of `points` to keep so that every dropped point is within
/// `tolerance` of the kept polyline (first and last always kept). Iterative, O(n log n) typical.
/// Works in double precision so that the choice does not depend on the sketch's scale or position.
std::vector<glm::vec3> simplify(const std::vector<glm::dvec3>& points, double tolerance) {
  const std::size_t n = points.size();
  if (n < 3 || tolerance <= 0.0) return {points.begin(), points.end()};
  std::vector<char> keep(n, 0);
  keep.front() = keep.back() = 1;
  std::vector<std::pair<std::size_t, std::size_t>> stack{{0, n - 1}};
  while (!stack.empty()) {
    const auto [a, b] = stack.back();
    stack.pop_back();
    const glm::dvec3 ab = points[b] - points[a];
    const double len2 = glm::dot(ab, ab);
    double worst = -1.0;
    std::size_t worst_i = a;
    for (std::size_t i = a + 1; i < b; ++i) {
      const glm::dvec3 ap = points[i] - points[a];
      const double t = len2 > 0.0 ? glm::clamp(glm::dot(ap, ab) / len2, 0.0, 1.0) : 0.0;
      const double d = glm::length(ap - t * ab);
      if (d > worst) worst = d, worst_i = i;
    }
    if (worst > tolerance) {
      keep[worst_i] = 1;
      stack.emplace_back(a, worst_i);
      stack.emplace_back(worst_i, b);
    }
  }
  std::vector<glm::vec3> kept;
  for (std::size_t i = 0; i < n; ++i)
    if (keep[i]) kept.emplace_back(points[i]);
  return kept;
}

/// Accumulates ribbons (polylines drawn as camera-facing quads strips) into the scene arrays.
class RibbonBuilder {
 public:
  RibbonBuilder(SceneGeometry& scene) : scene_(scene) {}

  /// Adds the polyline `points` (scene-relative) with the given colour and half width.
  /// Consecutive duplicate points are harmless: their tangent falls back to a neighbour's.
  void add(const std::vector<glm::vec3>& points, std::uint32_t color, float half_width) {
    const std::size_t n = points.size();
    if (n < 2) return;
    const auto base = static_cast<std::uint32_t>(scene_.ribbon_vertices.size());
    glm::vec3 last_tangent(1.0f, 0.0f, 0.0f);
    for (std::size_t i = 0; i < n; ++i) {
      const glm::vec3 d = points[std::min(i + 1, n - 1)] - points[i == 0 ? 0 : i - 1];
      const float len = glm::length(d);
      const glm::vec3 tangent = len > 0.0f ? d / len : last_tangent;
      last_tangent = tangent;
      for (float side : {-1.0f, 1.0f})
        scene_.ribbon_vertices.push_back({points[i], side, tangent, half_width, color});
    }
    for (std::uint32_t i = 0; i + 1 < n; ++i) {
      const std::uint32_t a = base + 2 * i;
      scene_.ribbon_indices.insert(scene_.ribbon_indices.end(), {a, a + 1, a + 2, a + 1, a + 3, a + 2});
    }
  }

 private:
  SceneGeometry& scene_;
};

/// Builds the mesh part: shared smooth vertices, faces split along region boundaries, outlines.
class MeshBuilder {
 public:
  MeshBuilder(const TriMesh& mesh, const MeshAttributes* attributes, const SceneOptions& options,
              SceneGeometry& scene, RibbonBuilder& ribbons, float diagonal)
      : mesh_(mesh), options_(options), scene_(scene), ribbons_(ribbons) {
    const std::size_t nv = mesh.n_vertices();
    if (attributes && !attributes->labels.empty()) {
      if (attributes->labels.size() != nv)
        throw Error::usage("mesh has " + std::to_string(nv) + " vertices but " +
                           std::to_string(attributes->labels.size()) + " labels");
      labels_ = &attributes->labels;
    }
    if (attributes && !attributes->colors.empty()) {
      if (attributes->colors.size() != nv)
        throw Error::usage("mesh has " + std::to_string(nv) + " vertices but " +
                           std::to_string(attributes->colors.size()) + " colours");
      colors_ = &attributes->colors;
    }
    regions_ = options.regions && labels_;
    edge_half_width_ = 0.5f * float(options.edge_width) * diagonal;
    wire_half_width_ = 0.5f * float(options.wire_width) * diagonal;
  }

  void build() {
    const std::size_t nv = mesh_.n_vertices();
    positions_.resize(nv);
    for (auto v : mesh_.vertices()) positions_[v.idx()] = relative(mesh_.point(v));
    face_normals_.resize(mesh_.n_faces());
    for (auto f : mesh_.faces()) face_normals_[f.idx()] = face_area_normal(face_vertices(f));
    crease_.assign(mesh_.n_edges(), 0);
    if (options_.sharp_angle < 180.0) {
      const double cos_limit = std::cos(options_.sharp_angle * M_PI / 180.0);
      for (auto e : mesh_.edges()) {
        if (mesh_.is_boundary(e)) continue;
        const glm::dvec3& n0 = face_normals_[mesh_.face_handle(mesh_.halfedge_handle(e, 0)).idx()];
        const glm::dvec3& n1 = face_normals_[mesh_.face_handle(mesh_.halfedge_handle(e, 1)).idx()];
        const double l0 = glm::length(n0), l1 = glm::length(n1);
        crease_[e.idx()] = l0 > 0.0 && l1 > 0.0 && glm::dot(n0, n1) / (l0 * l1) < cos_limit;
      }
    }
    add_vertices();
    scene_.mesh_indices.reserve(3 * mesh_.n_faces());
    for (auto f : mesh_.faces()) add_face(face_vertices(f), corners_[f.idx()]);
    add_edges();
  }

 private:
  glm::dvec3 relative(const OpenMesh::Vec3d& p) const {
    return glm::dvec3(p[0] - scene_.origin.x(), p[1] - scene_.origin.y(), p[2] - scene_.origin.z());
  }

  std::array<int, 3> face_vertices(TriMesh::FaceHandle f) const {
    std::array<int, 3> idx{};
    int k = 0;
    for (auto v : mesh_.fv_range(f))
      if (k < 3) idx[k++] = v.idx();
    return idx;
  }

  glm::dvec3 face_area_normal(const std::array<int, 3>& idx) const {
    return glm::cross(positions_[idx[1]] - positions_[idx[0]], positions_[idx[2]] - positions_[idx[0]]);
  }

  int label(int v) const { return (*labels_)[v]; }

  std::uint32_t vertex_color(int v) const {
    if (regions_) return pack(region_color(label(v)));
    if (colors_) return pack((*colors_)[v]);
    return pack(kSurfaceColor);
  }

  /// A new vertex at the mean of `vs` with the mean normal, coloured as region `region`.
  std::uint32_t blend_vertex(std::initializer_list<std::uint32_t> vs, int region) {
    glm::vec3 p(0.0f), n(0.0f);
    for (std::uint32_t v : vs) {
      p += scene_.mesh_vertices[v].position;
      n += scene_.mesh_vertices[v].normal;
    }
    p /= float(vs.size());
    const float len = glm::length(n);
    n = len > 0.0f ? n / len : scene_.mesh_vertices[*vs.begin()].normal;
    scene_.mesh_vertices.push_back({p, n, pack(region_color(region))});
    return static_cast<std::uint32_t>(scene_.mesh_vertices.size() - 1);
  }

  void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    scene_.mesh_indices.insert(scene_.mesh_indices.end(), {a, b, c});
  }

  void boundary_segment(std::uint32_t a, std::uint32_t b) {
    if (!options_.region_boundaries) return;
    ribbons_.add({scene_.mesh_vertices[a].position, scene_.mesh_vertices[b].position},
                 pack(kSharpEdgeColor), edge_half_width_);
    ++scene_.outlined_edges;
  }

  /// One render vertex per smooth fan of faces around each mesh vertex: faces meeting across a
  /// crease get separate vertices (and normals), so creases stay sharp under smooth shading.
  void add_vertices() {
    corners_.assign(mesh_.n_faces(), {0, 0, 0});
    scene_.mesh_vertices.reserve(mesh_.n_vertices());
    std::vector<int> faces, group;
    for (auto v : mesh_.vertices()) {
      faces.clear();
      for (auto f : mesh_.vf_range(v)) faces.push_back(f.idx());
      group.resize(faces.size());
      for (std::size_t i = 0; i < faces.size(); ++i) group[i] = int(i);
      const auto slot = [&](int face) {
        return int(std::find(faces.begin(), faces.end(), face) - faces.begin());
      };
      for (auto h : mesh_.voh_range(v)) {
        const auto f0 = mesh_.face_handle(h), f1 = mesh_.opposite_face_handle(h);
        if (!f0.is_valid() || !f1.is_valid() || crease_[mesh_.edge_handle(h).idx()]) continue;
        const int g0 = group[slot(f0.idx())], g1 = group[slot(f1.idx())];
        for (int& g : group)
          if (g == g1) g = g0;
      }
      for (std::size_t i = 0; i < faces.size(); ++i) {
        if (std::find(group.begin(), group.begin() + i, group[i]) != group.begin() + i)
          continue;  // this fan already has its vertex
        glm::dvec3 sum(0.0);
        for (std::size_t j = 0; j < faces.size(); ++j)
          if (group[j] == group[i]) sum += face_normals_[faces[j]];  // area weighted
        const double len = glm::length(sum);
        const glm::vec3 n = len > 0.0 ? glm::vec3(sum / len) : glm::vec3(0.0f, 0.0f, 1.0f);
        const auto index = static_cast<std::uint32_t>(scene_.mesh_vertices.size());
        scene_.mesh_vertices.push_back({glm::vec3(positions_[v.idx()]), n, vertex_color(v.idx())});
        for (std::size_t j = 0; j < faces.size(); ++j)
          if (group[j] == group[i]) {
            const auto corners = face_vertices(mesh_.face_handle(faces[j]));
            for (int k = 0; k < 3; ++k)
              if (corners[k] == v.idx()) corners_[faces[j]][k] = index;
          }
      }
    }
  }

  /// Adds a face; with regions, a face whose corners carry different labels is split along the
  /// midpoints of its mixed edges so that each part has one colour and the boundary is a clean
  /// curve through edge midpoints (drawn as an outline).
  void add_face(std::array<int, 3> idx, std::array<std::uint32_t, 3> corner) {
    if (!regions_ || (label(idx[0]) == label(idx[1]) && label(idx[1]) == label(idx[2]))) {
      triangle(corner[0], corner[1], corner[2]);
      return;
    }
    const int l0 = label(idx[0]), l1 = label(idx[1]), l2 = label(idx[2]);
    if (l0 != l1 && l1 != l2 && l0 != l2) {
      // Three regions: each corner keeps the quad (corner, edge midpoint, centroid, edge midpoint).
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = corner[k], b = corner[(k + 1) % 3], c = corner[(k + 2) % 3];
        const int region = label(idx[k]);
        const std::uint32_t m_ab = blend_vertex({a, b}, region);
        const std::uint32_t centre = blend_vertex({a, b, c}, region);
        const std::uint32_t m_ca = blend_vertex({c, a}, region);
        triangle(a, m_ab, centre);
        triangle(a, centre, m_ca);
        boundary_segment(m_ab, centre);
      }
      return;
    }
    // Two regions: rotate (keeping the winding) so that idx[2] is the odd corner.
    while (label(idx[0]) != label(idx[1])) {
      std::rotate(idx.begin(), idx.begin() + 1, idx.end());
      std::rotate(corner.begin(), corner.begin() + 1, corner.end());
    }
    const int a = label(idx[0]), b = label(idx[2]);
    const std::uint32_t m12a = blend_vertex({corner[1], corner[2]}, a);
    const std::uint32_t m20a = blend_vertex({corner[2], corner[0]}, a);
    const std::uint32_t m12b = blend_vertex({corner[1], corner[2]}, b);
    const std::uint32_t m20b = blend_vertex({corner[2], corner[0]}, b);
    triangle(corner[0], corner[1], m12a);
    triangle(corner[0], m12a, m20a);
    triangle(m20b, m12b, corner[2]);
    boundary_segment(m12a, m20a);
  }

  /// Creases (dihedral angle above the threshold), mesh boundary edges and the wireframe.
  void add_edges() {
    const bool outlines = options_.sharp_angle < 180.0;
    if (!outlines && !options_.wireframe) return;
    for (auto e : mesh_.edges()) {
      const auto h = mesh_.halfedge_handle(e, 0);
      const glm::vec3 a(positions_[mesh_.from_vertex_handle(h).idx()]);
      const glm::vec3 b(positions_[mesh_.to_vertex_handle(h).idx()]);
      if (outlines && (crease_[e.idx()] || mesh_.is_boundary(e))) {
        ribbons_.add({a, b}, pack(kSharpEdgeColor), edge_half_width_);
        ++scene_.outlined_edges;
      } else if (options_.wireframe) {
        ribbons_.add({a, b}, pack(kWireColor), wire_half_width_);
      }
    }
  }

  const TriMesh& mesh_;
  const SceneOptions& options_;
  SceneGeometry& scene_;
  RibbonBuilder& ribbons_;
  const std::vector<int>* labels_ = nullptr;
  const std::vector<std::array<std::uint8_t, 3>>* colors_ = nullptr;
  bool regions_ = false;
  float edge_half_width_ = 0.0f;
  float wire_half_width_ = 0.0f;
  std::vector<glm::dvec3> positions_;                  // per mesh vertex, scene-relative
  std::vector<glm::dvec3> face_normals_;               // per face, area weighted
  std::vector<char> crease_;                           // per edge
  std::vector<std::array<std::uint32_t, 3>> corners_;  // per face: its render vertices
};

}  // namespace

bool SceneOptions::valid(std::string* why) const {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return false;
  };
  for (auto [name, value] : {std::pair{"stroke_width", stroke_width}, {"edge_width", edge_width},
                             {"wire_width", wire_width}})
    if (!(value > 0.0) || !std::isfinite(value))
      return fail(std::string(name) + " must be positive and finite, got " + std::to_string(value));
  if (!(sharp_angle >= 0.0)) return fail("sharp_angle must be >= 0 degrees");
  if (!(stroke_tolerance >= 0.0) || !std::isfinite(stroke_tolerance))
    return fail("stroke_tolerance must be >= 0 and finite");
  if (!(reference_diagonal >= 0.0) || !std::isfinite(reference_diagonal))
    return fail("reference_diagonal must be >= 0 and finite");
  return true;
}

SceneGeometry build_scene(const Sketch& sketch, const TriMesh* mesh,
                          const MeshAttributes* attributes, const SceneOptions& options) {
  std::string why;
  if (!options.valid(&why)) throw Error::usage("render options: " + why);
  SceneGeometry scene;
  scene.bounds = sketch.bounding_box();
  if (mesh)
    for (auto v : mesh->vertices()) scene.bounds.extend(to_eigen(mesh->point(v)));
  if (!scene.bounds.empty()) scene.origin = 0.5 * (scene.bounds.min + scene.bounds.max);
  const double diagonal = options.reference_diagonal > 0.0 ? options.reference_diagonal
                          : scene.bounds.diagonal() > 0.0  ? scene.bounds.diagonal()
                                                           : 1.0;

  RibbonBuilder ribbons(scene);
  const float stroke_half_width = float(0.5 * options.stroke_width * diagonal);
  const double tolerance = options.stroke_tolerance * options.stroke_width * diagonal;
  const glm::dvec3 origin(scene.origin.x(), scene.origin.y(), scene.origin.z());
  std::vector<glm::dvec3> points;
  for (const Stroke& stroke : sketch.strokes) {
    if (stroke.points.size() < 2) continue;
    points.clear();
    for (const auto& p : stroke.points) points.push_back(glm::dvec3(p.x(), p.y(), p.z()) - origin);
    std::uint32_t color = pack(kStrokeColor);
    if (options.stroke_colors)
      color = pack_rgba(stroke.color[0], stroke.color[1], stroke.color[2],
                        options.stroke_alpha ? stroke.color[3] : 1.0f);
    else if (stroke.ignored)
      color = pack(kIgnoredStrokeColor);
    else if (stroke.boundary)
      color = pack(kBoundaryStrokeColor);
    const auto kept = simplify(points, tolerance);
    ribbons.add(kept, color, stroke_half_width);
    scene.stroke_points += points.size();
    scene.ribbon_points += kept.size();
  }
  scene.stroke_index_count = static_cast<std::uint32_t>(scene.ribbon_indices.size());
  if (mesh) {
    MeshBuilder(*mesh, attributes, options, scene, ribbons, float(diagonal)).build();
    // Closed and outward: no boundary edge, positive signed volume (sum of p0 . (p1 x p2) / 6).
    bool closed = mesh->n_faces() > 0;
    for (auto e : mesh->edges())
      if (mesh->is_boundary(e)) {
        closed = false;
        break;
      }
    double volume = 0.0;
    if (closed)
      for (auto f : mesh->faces()) {
        std::array<Eigen::Vector3d, 3> p;
        int k = 0;
        for (auto v : mesh->fv_range(f))
          if (k < 3) p[k++] = to_eigen(mesh->point(v)) - scene.origin;
        volume += p[0].dot(p[1].cross(p[2])) / 6.0;
      }
    scene.mesh_closed = closed && volume > 0.0;
  }
  return scene;
}

}  // namespace sketchsurf::render
