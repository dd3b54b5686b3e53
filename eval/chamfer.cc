#include "eval/chamfer.h"

#include <algorithm>
#include <limits>
#include <numeric>

#include "compiler/geometry/vec.h"

namespace efc::eval {

KdTree::KdTree(std::vector<Vec3> points) : points_(std::move(points)) {
  std::vector<int> order(points_.size());
  std::iota(order.begin(), order.end(), 0);
  nodes_.reserve(points_.size());
  root_ = build(order.data(), order.data() + order.size(), 0);
}

// Median split along the axes in turn: a balanced tree in O(n log n).
int KdTree::build(int* first, int* last, int depth) {
  if (first == last) return -1;
  const int axis = depth % 3;
  int* mid = first + (last - first) / 2;
  std::nth_element(first, mid, last, [&](int a, int b) { return points_[a][axis] < points_[b][axis]; });
  const int index = static_cast<int>(nodes_.size());
  nodes_.push_back({*mid, axis, -1, -1});
  const int left = build(first, mid, depth + 1);
  const int right = build(mid + 1, last, depth + 1);
  nodes_[index].left = left;
  nodes_[index].right = right;
  return index;
}

void KdTree::search(int node, const Vec3& q, double* best) const {
  if (node < 0) return;
  const Node& n = nodes_[node];
  const Vec3& p = points_[n.point];
  const Vec3 d = geom::sub(q, p);
  *best = std::min(*best, geom::dot(d, d));
  const double gap = q[n.axis] - p[n.axis];
  search(gap < 0 ? n.left : n.right, q, best);
  if (gap * gap < *best) search(gap < 0 ? n.right : n.left, q, best);  // the far side may hold a nearer point
}

double KdTree::nearest_squared(const Vec3& q) const {
  double best = std::numeric_limits<double>::infinity();
  search(root_, q, &best);
  return best;
}

namespace {

double mean_nearest_squared(const std::vector<Vec3>& from, const KdTree& to) {
  double sum = 0;
  for (const Vec3& p : from) sum += to.nearest_squared(p);
  return sum / static_cast<double>(from.size());
}

}  // namespace

double chamfer_distance(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  if (a.empty() || b.empty()) return std::numeric_limits<double>::infinity();
  return mean_nearest_squared(a, KdTree(b)) + mean_nearest_squared(b, KdTree(a));
}

}  // namespace efc::eval
