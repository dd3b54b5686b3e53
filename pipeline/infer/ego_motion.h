// efc infer, stage 2: the camera poses made consistent with the object.
// poses.txt comes from a tracker that drifts (a random walk) and shakes
// (per-frame jitter). The parts that do not move (role "object") and the
// room around them (the pixels no mask claims) are the same rigid surface in
// every frame, so registering each frame's static points onto a model of
// them (robust point-to-plane ICP, twice: onto the best frame, then onto the
// fused model) gives a per-frame correction. The room matters: close up, the
// object alone is often one plane, which cannot fix a turn about its normal
// (bench/ego_motion_eval: on a synthetic box with a vent, seen close up,
// 1.0 degree median error from the object alone, 0.05 with the room).
// Drift starts at zero, so the model is anchored where the tracker was still
// right: the first frames, weighted by the tracker's noise (ego_anchor.h).
#pragma once

#include <Eigen/Geometry>

#include <vector>

#include "pipeline/infer/ego_anchor.h"
#include "pipeline/infer/observations.h"

namespace efc::pipeline {

struct EgoMotion {
  // Per frame: maps points of that frame (world frame of poses.txt) into the
  // refined world frame.
  std::vector<Eigen::Isometry3d> correction;
  std::vector<bool> registered;     // false: too few static points, interpolated
  std::vector<double> rmse;         // ICP residual per frame (m)
  std::vector<double> inliers;      // ICP inlier fraction per frame
  Cloud model;                      // the fused static parts (not the room), refined world frame
  int reference_frame = -1;
  EgoAnchor anchor;                 // where the model frame sits in the world
  double seconds = 0;
};

// `static_parts` and `mostly_still_parts` index Observations::parts. The
// static parts are the body (role object): the model and the object frame
// are theirs. The mostly-still parts (effectors: most never move) are
// registered on too, each frame's thinned to at most 0.3 of the rest's
// points: a box's front face and the floor leave a slide along both nearly
// free, and the tracker's drift along it stayed in the camera (4 cm on one
// synthetic recording) until a small spout beside the box held it.
EgoMotion refine_ego_motion(const Observations& obs, const std::vector<int>& static_parts, int threads,
                            const ProgressFn& progress, const std::vector<int>& mostly_still_parts = {});

// The mean of rigid transforms (translations averaged, rotations by the
// quaternion eigen-mean), each weighted by `weights` where given (one per
// transform; they need not sum to one).
Eigen::Isometry3d mean_transform(const std::vector<Eigen::Isometry3d>& transforms,
                                 const std::vector<double>& weights = {});

}  // namespace efc::pipeline
