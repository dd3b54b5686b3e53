#include "pipeline/cloud/filters.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

#include "pipeline/cloud/kdtree.h"
#include "pipeline/cloud/voxel_key.h"

namespace efc::pipeline {

namespace {

// The finite points (and their normals when the cloud has them).
Cloud finite_only(const Cloud& cloud) {
  Cloud out;
  const bool normals = cloud.has_normals();
  for (size_t i = 0; i < cloud.size(); ++i) {
    if (!cloud.points[i].allFinite()) continue;
    out.points.push_back(cloud.points[i]);
    if (normals) out.normals.push_back(cloud.normals[i]);
  }
  return out;
}

Cloud select(const Cloud& cloud, const std::vector<bool>& keep) {
  Cloud out;
  const bool normals = cloud.has_normals();
  for (size_t i = 0; i < cloud.size(); ++i) {
    if (!keep[i]) continue;
    out.points.push_back(cloud.points[i]);
    if (normals) out.normals.push_back(cloud.normals[i]);
  }
  return out;
}

}  // namespace

void thin(Cloud* cloud, int max_points) {
  if (max_points <= 0 || static_cast<int>(cloud->size()) <= max_points) return;
  const double step = static_cast<double>(cloud->size()) / max_points;
  Cloud out;
  out.points.reserve(max_points);
  if (cloud->has_normals()) out.normals.reserve(max_points);
  for (int i = 0; i < max_points; ++i) {
    const size_t k = static_cast<size_t>(i * step);
    out.points.push_back(cloud->points[k]);
    if (cloud->has_normals()) out.normals.push_back(cloud->normals[k]);
  }
  *cloud = std::move(out);
}

Cloud voxel_downsample(const Cloud& cloud, double voxel) {
  if (!(voxel > 0) || !std::isfinite(voxel)) return finite_only(cloud);
  struct Acc {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero(), normal_sum = Eigen::Vector3d::Zero(), first_normal;
    int count = 0;
  };
  std::unordered_map<detail::VoxelKey, size_t, detail::VoxelKeyHash> slot;
  std::vector<Acc> accs;
  const bool normals = cloud.has_normals();
  for (size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d& p = cloud.points[i];
    if (!p.allFinite()) continue;
    auto [it, fresh] = slot.emplace(detail::voxel_of(p, voxel), accs.size());
    if (fresh) accs.emplace_back();
    Acc& a = accs[it->second];
    a.sum += p;
    if (normals) {
      if (a.count == 0) a.first_normal = cloud.normals[i];
      a.normal_sum += cloud.normals[i];
    }
    ++a.count;
  }
  Cloud out;
  out.points.reserve(accs.size());
  for (const Acc& a : accs) {
    out.points.push_back(a.sum / a.count);
    if (normals) {
      // Opposite normals (both sides of a thin sheet) can cancel: keep the first.
      const double len = a.normal_sum.norm();
      out.normals.push_back(len > 1e-9 ? Eigen::Vector3d(a.normal_sum / len) : a.first_normal.normalized());
    }
  }
  return out;
}

Cloud remove_statistical_outliers(const Cloud& cloud, int k, double std_ratio) {
  Cloud in = finite_only(cloud);
  if (k < 1 || in.size() < static_cast<size_t>(k) + 1 || !std::isfinite(std_ratio)) return in;
  KdTree tree(in.points);
  std::vector<double> mean_dist(in.size());
  std::vector<size_t> idx;
  std::vector<double> d2;
  for (size_t i = 0; i < in.size(); ++i) {
    tree.knn(in.points[i], static_cast<size_t>(k) + 1, &idx, &d2);  // +1: the point itself
    double sum = 0;
    int n = 0;
    for (size_t j = 0; j < idx.size(); ++j) {
      if (idx[j] == i) continue;
      if (n == k) break;
      sum += std::sqrt(d2[j]);
      ++n;
    }
    mean_dist[i] = n > 0 ? sum / n : 0;
  }
  double mean = 0, var = 0;
  for (double d : mean_dist) mean += d;
  mean /= mean_dist.size();
  for (double d : mean_dist) var += (d - mean) * (d - mean);
  const double stddev = std::sqrt(var / mean_dist.size());
  const double limit = mean + std_ratio * stddev;
  std::vector<bool> keep(in.size());
  for (size_t i = 0; i < in.size(); ++i) keep[i] = mean_dist[i] <= limit;
  return select(in, keep);
}

Cloud remove_radius_outliers(const Cloud& cloud, double radius, int min_neighbours) {
  Cloud in = finite_only(cloud);
  if (min_neighbours <= 0) return in;
  if (!(radius > 0) || !std::isfinite(radius)) return Cloud{};  // nobody has a neighbour
  KdTree tree(in.points);
  std::vector<bool> keep(in.size());
  std::vector<size_t> idx;
  for (size_t i = 0; i < in.size(); ++i) {
    tree.radius(in.points[i], radius, &idx);
    const size_t others = idx.empty() ? 0 : idx.size() - 1;  // the point finds itself
    keep[i] = others >= static_cast<size_t>(min_neighbours);
  }
  return select(in, keep);
}

void estimate_normals(Cloud* cloud, int k, const Eigen::Vector3d* viewpoint) {
  if (cloud == nullptr) return;
  cloud->normals.clear();
  const size_t n = cloud->size();
  if (n < 3) return;
  const size_t kk = std::clamp<size_t>(k < 3 ? 3 : static_cast<size_t>(k), 3, n);
  KdTree tree(cloud->points);
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  size_t finite = 0;
  for (const auto& p : cloud->points)
    if (p.allFinite()) centroid += p, ++finite;
  if (finite > 0) centroid /= static_cast<double>(finite);

  cloud->normals.resize(n, Eigen::Vector3d::UnitZ());
  std::vector<size_t> idx;
  std::vector<double> d2;
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d& p = cloud->points[i];
    if (!p.allFinite()) continue;  // keeps the placeholder: one unit normal per point
    tree.knn(p, kk, &idx, &d2);
    if (idx.size() < 3) continue;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (size_t j : idx) mean += cloud->points[j];
    mean /= static_cast<double>(idx.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (size_t j : idx) {
      const Eigen::Vector3d d = cloud->points[j] - mean;
      cov += d * d.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    Eigen::Vector3d normal = eig.eigenvectors().col(0);  // smallest variance
    if (!normal.allFinite() || normal.norm() < 1e-12) continue;
    normal.normalize();
    const Eigen::Vector3d toward = viewpoint != nullptr ? Eigen::Vector3d(*viewpoint - p) : Eigen::Vector3d(p - centroid);
    if (normal.dot(toward) < 0) normal = -normal;
    cloud->normals[i] = normal;
  }
}

}  // namespace efc::pipeline
