#include "pipeline/cloud/cloud.h"

namespace efc::pipeline {

void transform_cloud(const Eigen::Isometry3d& T, Cloud* cloud) {
  if (cloud == nullptr) return;
  for (auto& p : cloud->points) p = T * p;
  if (cloud->has_normals()) {
    const Eigen::Matrix3d R = T.linear();
    for (auto& n : cloud->normals) n = R * n;
  }
}

Cloud concatenate(const Cloud& a, const Cloud& b) {
  Cloud out;
  out.points.reserve(a.size() + b.size());
  out.points.insert(out.points.end(), a.points.begin(), a.points.end());
  out.points.insert(out.points.end(), b.points.begin(), b.points.end());
  // Normals survive only when every point gets one.
  const bool a_ok = a.has_normals() || a.size() == 0;
  const bool b_ok = b.has_normals() || b.size() == 0;
  if (a_ok && b_ok && (a.has_normals() || b.has_normals())) {
    out.normals.reserve(out.points.size());
    out.normals.insert(out.normals.end(), a.normals.begin(), a.normals.end());
    out.normals.insert(out.normals.end(), b.normals.begin(), b.normals.end());
  }
  return out;
}

Eigen::Vector3d centroid(const Cloud& cloud) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : cloud.points) c += p;
  return cloud.points.empty() ? c : Eigen::Vector3d(c / static_cast<double>(cloud.points.size()));
}

}  // namespace efc::pipeline
