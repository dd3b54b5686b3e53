#include "pipeline/cloud/fusion.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "pipeline/cloud/filters.h"
#include "pipeline/cloud/kdtree.h"

namespace efc::pipeline {

PartFusion::PartFusion(const FusionOptions& options) : options_(options) {
  if (!(options_.voxel > 0) || !std::isfinite(options_.voxel)) options_.voxel = 0.003;
}

void PartFusion::add_frame(const Cloud& cloud) {
  const int frame = frames_++;
  if (cloud.size() == 0) return;
  const bool normals = cloud.has_normals();
  if (!normals) normals_ = false;
  for (size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d& p = cloud.points[i];
    if (!p.allFinite()) continue;
    const detail::VoxelKey key = detail::voxel_of(p, options_.voxel);
    auto [it, fresh] = index_.emplace(key, voxels_.size());
    if (fresh) voxels_.emplace_back().key = key;
    Voxel& v = voxels_[it->second];
    v.sum += p;
    if (normals && cloud.normals[i].allFinite()) {
      if (v.count == 0) v.first_normal = cloud.normals[i];
      v.normal_sum += cloud.normals[i];
    }
    ++v.count;
    if (v.last_frame != frame) {  // each frame counts once per voxel
      v.last_frame = frame;
      ++v.observations;
    }
  }
}

int PartFusion::frames() const { return frames_; }

int PartFusion::observations_at(const Eigen::Vector3d& p) const {
  return p.allFinite() ? observations_of(detail::voxel_of(p, options_.voxel)) : 0;
}

int PartFusion::observations_of(const detail::VoxelKey& key) const {
  const auto it = index_.find(key);
  return it == index_.end() ? 0 : voxels_[it->second].observations;
}

int PartFusion::required_observations() const {
  return std::clamp(options_.min_observations, 1, std::max(1, frames_));
}

// By the voxel's key where the grids agree, not its centroid: the mean of
// points on a voxel's face may round across it.
int PartFusion::outside_observations(const PartFusion& outside, const Voxel& v, bool same_grid) {
  return same_grid ? outside.observations_of(v.key) : outside.observations_at(v.sum / static_cast<double>(v.count));
}

Cloud PartFusion::fused() const { return fused(nullptr, nullptr); }

Cloud PartFusion::fused(const PartFusion* outside, int* dropped) const {
  Cloud out;
  const int need = required_observations();
  const bool normals = normals_ && !voxels_.empty();
  if (dropped) *dropped = 0;
  const bool same_grid = outside && outside->options_.voxel == options_.voxel;
  for (const Voxel& v : voxels_) {
    if (v.observations < need) continue;
    if (outside && outside_observations(*outside, v, same_grid) > v.observations) {
      if (dropped) ++*dropped;
      continue;
    }
    out.points.push_back(v.sum / static_cast<double>(v.count));
    if (normals) {
      // Opposite normals (both faces of a thin part in one voxel) can cancel.
      const double len = v.normal_sum.norm();
      out.normals.push_back(len > 1e-9 ? Eigen::Vector3d(v.normal_sum / len) : v.first_normal.normalized());
    }
  }
  if (options_.outlier_k >= 1 && out.size() > static_cast<size_t>(options_.outlier_k))
    out = remove_statistical_outliers(out, options_.outlier_k, options_.outlier_std_ratio);
  return out;
}

bool closed_mesh(const Cloud& fused, TriMesh* out, std::string* error) {
  return closed_mesh(fused, out, error, nullptr);
}

bool closed_mesh(const Cloud& fused, TriMesh* out, std::string* error, std::string* note) {
  std::vector<Eigen::Vector3d> points;
  points.reserve(fused.size());
  for (const auto& p : fused.points)
    if (p.allFinite()) points.push_back(p);

  // Isolation: mean distance to the 8 nearest others. Only the worst 1% may
  // go, and only when clearly apart from the rest (3x the median), so a
  // clean cloud keeps its extreme points (they make the hull).
  size_t dropped = 0;
  if (points.size() >= 100) {
    const size_t k = 8;
    KdTree tree(points);
    std::vector<double> score(points.size());
    std::vector<size_t> idx;
    std::vector<double> d2;
    for (size_t i = 0; i < points.size(); ++i) {
      tree.knn(points[i], k + 1, &idx, &d2);
      double sum = 0;
      int n = 0;
      for (size_t j = 0; j < idx.size(); ++j) {
        if (idx[j] == i) continue;
        sum += std::sqrt(d2[j]);
        ++n;
      }
      score[i] = n > 0 ? sum / n : 0;
    }
    std::vector<size_t> order(points.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return score[a] > score[b]; });
    std::vector<double> sorted = score;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double median = sorted[sorted.size() / 2];
    const size_t budget = points.size() / 100;
    std::vector<bool> drop(points.size(), false);
    for (size_t r = 0; r < budget; ++r) {
      if (!(score[order[r]] > 3 * median)) break;
      drop[order[r]] = true;
      ++dropped;
    }
    if (dropped > 0) {
      std::vector<Eigen::Vector3d> kept;
      kept.reserve(points.size() - dropped);
      for (size_t i = 0; i < points.size(); ++i)
        if (!drop[i]) kept.push_back(points[i]);
      points.swap(kept);
    }
  }

  std::string hull_error;
  if (!convex_hull(points, out, &hull_error)) {
    if (error != nullptr) *error = "cannot build a closed mesh from " + std::to_string(points.size()) + " points: " + hull_error;
    return false;
  }
  if (note != nullptr) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "convex hull of %zu points (%zu isolated points dropped): %zu vertices, %zu faces, "
                  "volume %.6g m^3, area %.6g m^2",
                  points.size(), dropped, out->vertices.size(), out->faces.size(), mesh_volume(*out),
                  mesh_area(*out));
    *note = text;
  }
  return true;
}

}  // namespace efc::pipeline
