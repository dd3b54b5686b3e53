// The reconstruction stage's core: one part's points over many frames fused
// into one clean cloud, and a closed mesh of it for collision and inertia.
#pragma once

#include <string>
#include <unordered_map>
#include <vector>

#include "pipeline/cloud/cloud.h"
#include "pipeline/cloud/mesh.h"
#include "pipeline/cloud/voxel_key.h"

namespace efc::pipeline {

// Points of one part seen over many frames, each frame's cloud already mapped into the
// part's own frame (the caller undoes the part's motion). Fuses them: a voxel grid
// (voxel size) keeping per-voxel point count and centroid (normals averaged), drops voxels seen in
// fewer than min_observations frames (each frame counts once per voxel: transient outliers
// such as the hand do not survive), optionally those another fusion (the part's mask
// outline, fused alike) holds in more frames (mask bleed a segmenter repeats in
// several frames does survive the count), then statistical outlier removal.
//
// Adaptive threshold: the observations a voxel needs are
// clamp(min_observations, 1, frames()), so a part seen in a single frame keeps
// all of its points instead of vanishing (and 2 frames with min_observations
// 3 need both). A non-positive or non-finite voxel counts as 0.003 m; outlier
// removal is skipped when outlier_k < 1 or there are too few voxels (<= outlier_k).
// Frames with no points still count as frames (the part was looked for and not
// seen there). Non-finite points are ignored.
struct FusionOptions {
  double voxel = 0.003;
  int min_observations = 2;
  int outlier_k = 12;
  double outlier_std_ratio = 2.0;
};

class PartFusion {
 public:
  explicit PartFusion(const FusionOptions& options);
  void add_frame(const Cloud& cloud_in_part_frame);
  int frames() const;
  // The surviving voxel centroids (with normals when every non-empty frame
  // had them), in the order the voxels were first seen.
  Cloud fused() const;
  // The same, after the masks' vote: `outside` fused the points just
  // outside the part's mask in the same frames, the same way (the
  // observations' outlines); a voxel more frames put there than in this
  // part is what a mask drawn too wide took in, and goes before the
  // outlier test. *dropped (may be null): how many went.
  Cloud fused(const PartFusion* outside, int* dropped) const;

  // Additions: voxels occupied so far (before any thresholding), and the
  // observation count fused() requires now.
  size_t voxels() const { return voxels_.size(); }
  // The frames that put a point in the voxel holding p (0 for none).
  int observations_at(const Eigen::Vector3d& p) const;
  int required_observations() const;

 private:
  struct Voxel {
    detail::VoxelKey key;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Vector3d normal_sum = Eigen::Vector3d::Zero();
    Eigen::Vector3d first_normal = Eigen::Vector3d::UnitZ();
    long count = 0;
    int observations = 0;   // frames that put a point here
    int last_frame = -1;    // so a frame counts once
  };
  int observations_of(const detail::VoxelKey& key) const;
  static int outside_observations(const PartFusion& outside, const Voxel& v, bool same_grid);
  FusionOptions options_;
  int frames_ = 0;
  bool normals_ = true;  // every non-empty frame so far had normals
  std::vector<Voxel> voxels_;  // in the order first seen: fused() is deterministic
  std::unordered_map<detail::VoxelKey, size_t, detail::VoxelKeyHash> index_;  // -> voxels_
};

// A closed mesh for collision and inertia from a fused cloud: the convex hull of the points,
// after dropping the points of the (up to) 1% most isolated ones. Explains in *note what it did.
bool closed_mesh(const Cloud& fused, TriMesh* out, std::string* error);
// The same, and *note (may be nullptr) says what it did: the points used,
// those dropped as isolated, the hull's vertices, faces, volume and area.
// "Isolated": among the 1% with the largest mean distance to their 8 nearest
// neighbours, those whose distance is over 3x the median one (a clean cloud
// loses nothing).
bool closed_mesh(const Cloud& fused, TriMesh* out, std::string* error, std::string* note);

}  // namespace efc::pipeline
