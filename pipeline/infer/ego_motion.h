// efc infer, stage 2: the camera poses made consistent with the object.
// poses.txt comes from a tracker that drifts (a random walk) and shakes
// (per-frame jitter). The parts that do not move (role "object") are the
// same rigid surface in every frame, so registering each frame's static
// points onto a model of them (robust point-to-plane ICP, twice: onto the
// best frame, then onto the fused model) gives a per-frame correction.
// Drift starts at zero, so the model is anchored where the tracker was still
// right: the mean correction over the first second.
#pragma once

#include <Eigen/Geometry>

#include <vector>

#include "pipeline/infer/observations.h"

namespace efc::pipeline {

struct EgoMotion {
  // Per frame: maps points of that frame (world frame of poses.txt) into the
  // refined world frame.
  std::vector<Eigen::Isometry3d> correction;
  std::vector<bool> registered;     // false: too few static points, interpolated
  std::vector<double> rmse;         // ICP residual per frame (m)
  std::vector<double> inliers;      // ICP inlier fraction per frame
  Cloud model;                      // the fused static surface, refined world frame
  int reference_frame = -1;
  double seconds = 0;
};

// `static_parts` index Observations::parts.
EgoMotion refine_ego_motion(const Observations& obs, const std::vector<int>& static_parts, int threads,
                            const ProgressFn& progress);

// The mean of rigid transforms (translations averaged, rotations by the
// quaternion eigen-mean).
Eigen::Isometry3d mean_transform(const std::vector<Eigen::Isometry3d>& transforms);

}  // namespace efc::pipeline
