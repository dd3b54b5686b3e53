// A point cloud (points, optional per-point unit normals) and the two
// operations every stage of `efc infer` needs on it, and its centroid. The other files of
// pipeline/cloud/ are the primitives built on it: depth back-projection,
// k-d tree, robust ICP, filters, convex hull and per-part fusion.
#pragma once

#include <Eigen/Geometry>

#include <cstddef>
#include <vector>

namespace efc::pipeline {

struct Cloud {
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector3d> normals;  // empty, or one unit normal per point
  size_t size() const { return points.size(); }
  bool has_normals() const { return !normals.empty() && normals.size() == points.size(); }
};

// Maps points by T and normals by T's rotation (normals only when has_normals()).
void transform_cloud(const Eigen::Isometry3d& T, Cloud* cloud);
// a's points then b's. The result has normals only when both inputs have them
// (or one is empty and the other has them): a half-normalled cloud is useless.
Cloud concatenate(const Cloud& a, const Cloud& b);
// The mean of the points (the origin for an empty cloud).
Eigen::Vector3d centroid(const Cloud& cloud);

}  // namespace efc::pipeline
