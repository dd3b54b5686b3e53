// Nearest-neighbour queries over a vector of points (nanoflann; pimpl so
// nanoflann stays out of every includer). Used by ICP, the filters and the
// normal estimation.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <memory>
#include <vector>

namespace efc::pipeline {

// Keeps a pointer to `points`: the vector must outlive the tree and not change.
// Points with a NaN or infinite coordinate are left out of the tree (they
// would corrupt its splits); returned indices are always into `points`.
class KdTree {
 public:
  explicit KdTree(const std::vector<Eigen::Vector3d>& points);
  ~KdTree();
  KdTree(const KdTree&) = delete;
  KdTree& operator=(const KdTree&) = delete;

  size_t size() const;  // the points indexed (the finite ones)
  // Index of the nearest point and its squared distance; false when empty
  // (or q is not finite).
  bool nearest(const Eigen::Vector3d& q, size_t* index, double* dist2) const;
  // The same, but only among the points nearer than r (squared distance
  // below r^2): false when none is, or the tree is empty, or q is not
  // finite. The search stops descending where no point can be that near,
  // so a far query costs a few nodes (a truncated score's far points).
  bool nearest_within(const Eigen::Vector3d& q, double r, size_t* index, double* dist2) const;
  // The min(k, size()) nearest, closest first (q itself included when it is
  // one of the points). Empty outputs for an empty tree or non-finite q.
  void knn(const Eigen::Vector3d& q, size_t k, std::vector<size_t>* indices, std::vector<double>* dist2) const;
  // Every point within distance r (inclusive-ish: nanoflann's test is d^2 < r^2),
  // closest first.
  void radius(const Eigen::Vector3d& q, double r, std::vector<size_t>* indices) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace efc::pipeline
