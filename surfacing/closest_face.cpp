#include "surfacing/closest_face.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace sketchsurf {

namespace {

using V3 = Eigen::Vector3d;
constexpr double kInf = std::numeric_limits<double>::infinity();

double box_distance2(const V3& p, const V3& lo, const V3& hi) {
  return (lo - p).cwiseMax(p - hi).cwiseMax(0.0).squaredNorm();
}

}  // namespace

// Ericson, Real-Time Collision Detection, 5.1.5.
V3 closest_on_triangle(const V3& p, const V3& a, const V3& b, const V3& c) {
  const V3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const V3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const V3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = va + vb + vc;
  if (!(std::abs(denom) > 0)) return a;  // degenerate triangle
  return a + ab * (vb / denom) + ac * (vc / denom);
}

struct ClosestFaceTree::Impl {
  struct Node {
    V3 lo, hi;
    int left = -1, right = -1;  // children, -1 for a leaf
    int begin = 0, end = 0;     // range in `order` for a leaf
  };
  Eigen::MatrixX3d V;
  Eigen::MatrixX3i F;
  std::vector<int> order;
  std::vector<Node> nodes;

  int build(int begin, int end, const Eigen::MatrixX3d& centroids) {
    Node node;
    node.lo = V3::Constant(kInf);
    node.hi = V3::Constant(-kInf);
    for (int i = begin; i < end; ++i)
      for (int k = 0; k < 3; ++k) {
        const V3 p = V.row(F(order[i], k));
        node.lo = node.lo.cwiseMin(p);
        node.hi = node.hi.cwiseMax(p);
      }
    const int id = static_cast<int>(nodes.size());
    nodes.push_back(node);
    if (end - begin <= 4) {
      nodes[id].begin = begin;
      nodes[id].end = end;
      return id;
    }
    V3 clo = V3::Constant(kInf), chi = V3::Constant(-kInf);
    for (int i = begin; i < end; ++i) {
      clo = clo.cwiseMin(V3(centroids.row(order[i])));
      chi = chi.cwiseMax(V3(centroids.row(order[i])));
    }
    int axis = 0;
    (chi - clo).maxCoeff(&axis);
    const int mid = (begin + end) / 2;
    std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
                     [&](int a, int b) {
                       const double ca = centroids(a, axis), cb = centroids(b, axis);
                       return ca < cb || (ca == cb && a < b);
                     });
    const int left = build(begin, mid, centroids);
    const int right = build(mid, end, centroids);
    nodes[id].left = left;
    nodes[id].right = right;
    return id;
  }
};

ClosestFaceTree::ClosestFaceTree(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F)
    : impl_(std::make_unique<Impl>()) {
  impl_->V = V;
  impl_->F = F;
  if (F.rows() == 0) return;
  Eigen::MatrixX3d centroids(F.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    centroids.row(f) = (V.row(F(f, 0)) + V.row(F(f, 1)) + V.row(F(f, 2))) / 3.0;
  impl_->order.resize(F.rows());
  for (int f = 0; f < F.rows(); ++f) impl_->order[f] = f;
  impl_->nodes.reserve(2 * F.rows() / 4 + 8);
  impl_->build(0, static_cast<int>(F.rows()), centroids);
}

ClosestFaceTree::~ClosestFaceTree() = default;
ClosestFaceTree::ClosestFaceTree(ClosestFaceTree&&) noexcept = default;
ClosestFaceTree& ClosestFaceTree::operator=(ClosestFaceTree&&) noexcept = default;

int ClosestFaceTree::closest_face(const Eigen::Vector3d& p, Eigen::Vector3d* closest) const {
  const Impl& t = *impl_;
  if (t.nodes.empty()) return -1;
  double best = kInf;
  int best_face = -1;
  V3 best_point = V3::Zero();
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Impl::Node& node = t.nodes[stack[--top]];
    if (box_distance2(p, node.lo, node.hi) > best) continue;
    if (node.left < 0) {
      for (int i = node.begin; i < node.end; ++i) {
        const int f = t.order[i];
        const V3 q = closest_on_triangle(p, t.V.row(t.F(f, 0)), t.V.row(t.F(f, 1)),
                                         t.V.row(t.F(f, 2)));
        const double d = (q - p).squaredNorm();
        if (d < best || (d == best && f < best_face)) {
          best = d;
          best_face = f;
          best_point = q;
        }
      }
      continue;
    }
    const Impl::Node& l = t.nodes[node.left];
    const Impl::Node& r = t.nodes[node.right];
    const double dl = box_distance2(p, l.lo, l.hi), dr = box_distance2(p, r.lo, r.hi);
    // Push the farther child first so the nearer one is visited first.
    if (dl <= dr) {
      stack[top++] = node.right;
      stack[top++] = node.left;
    } else {
      stack[top++] = node.left;
      stack[top++] = node.right;
    }
  }
  if (closest) *closest = best_point;
  return best_face;
}

}  // namespace sketchsurf
