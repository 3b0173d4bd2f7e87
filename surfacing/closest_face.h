#pragma once
// Closest points on triangle meshes: one AABB tree over the triangles, built once and queried
// many times (strokes to proxy, stroke fit of a result, surface-to-surface deviation).

#include <Eigen/Core>
#include <memory>

namespace sketchsurf {

/// Closest point to p on the triangle abc (a degenerate triangle (a, b, b) is the segment ab).
Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                    const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// Closest point on a triangle mesh, through an AABB tree built once. Degenerate triangles
/// (a, b, b) make it a closest-point tree over segments.
class ClosestFaceTree {
 public:
  /// V: #V x 3 positions, F: #F x 3 triangles. Empty F gives a tree whose queries return -1.
  ClosestFaceTree(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F);
  ~ClosestFaceTree();
  ClosestFaceTree(ClosestFaceTree&&) noexcept;
  ClosestFaceTree& operator=(ClosestFaceTree&&) noexcept;
  /// Index of the face closest to p (ties: lowest index) and, if given, the closest point.
  int closest_face(const Eigen::Vector3d& p, Eigen::Vector3d* closest = nullptr) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sketchsurf
