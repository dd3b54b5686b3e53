// The Chamfer distance between two point sets (the paper's reconstruction
// metric), with nearest neighbours from a small k-d tree.
#pragma once

#include <vector>

#include "compiler/ir.h"

namespace efc::eval {

// Nearest-neighbour queries over a fixed point set.
class KdTree {
 public:
  explicit KdTree(std::vector<Vec3> points);
  // Squared distance from q to the nearest point; +inf when the set is empty.
  double nearest_squared(const Vec3& q) const;

 private:
  struct Node {
    int point = -1;  // index into points_
    int axis = 0;
    int left = -1, right = -1;
  };
  int build(int* first, int* last, int depth);
  void search(int node, const Vec3& q, double* best) const;

  std::vector<Vec3> points_;
  std::vector<Node> nodes_;
  int root_ = -1;
};

// Two-way Chamfer distance in m^2: the mean over a of the squared distance to
// the nearest point of b, plus the same from b to a. +inf when either set is
// empty (nothing to compare).
double chamfer_distance(const std::vector<Vec3>& a, const std::vector<Vec3>& b);

}  // namespace efc::eval
