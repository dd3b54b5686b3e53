// Depth images to camera-frame points: the first step of every per-frame
// cloud `efc infer` builds (a part's masked pixels, the scene for ICP).
#pragma once

#include <Eigen/Core>

#include "pipeline/cloud/cloud.h"
#include "sequence/sequence.h"

namespace efc::pipeline {

// Back-projects depth pixels (metres = value * depth_scale; 0 = no reading) where
// `mask` (8-bit grey, may be nullptr = all pixels) is non-zero, every `stride`-th
// pixel in x and y, into the camera frame (OpenCV: x right, y down, z forward;
// pixel (u,v) -> ((u-cx) z/fx, (v-cy) z/fy, z)). Normals from the depth image's
// neighbours (cross product of the +/- stride neighbours' differences),
// oriented towards the camera (n . p < 0). A pixel is dropped when it or a needed
// neighbour has no reading, or when a neighbour's depth differs by more than
// max_jump_rel * z (a depth edge: mixed pixels, flying points). Mask and depth sizes must match
// (else empty cloud). min_depth/max_depth in metres bound accepted readings.
//
// Details: with normals, all four +/- stride neighbours are needed (so a
// stride-wide border of the image and of every hole is dropped). Without
// normals no neighbour is needed, but a neighbour that has a reading and
// jumps still drops the pixel (flying points are wrong either way).
// max_jump_rel <= 0 disables the jump test; stride < 1 counts as 1. Bad
// intrinsics (fx or fy not > 0), depth_scale not > 0 or a pixel buffer of the
// wrong size give an empty cloud.
struct BackprojectOptions {
  int stride = 1;
  double max_jump_rel = 0.03;
  double min_depth = 0.05;
  double max_depth = 10.0;
  bool normals = true;
};
Cloud backproject(const seq::Image16& depth, double depth_scale, const seq::Intrinsics& K,
                  const seq::Image8* mask, const BackprojectOptions& options);

// The pixel a camera-frame point projects to (false when behind the camera).
bool project(const seq::Intrinsics& K, const Eigen::Vector3d& p_camera, double* u, double* v);

}  // namespace efc::pipeline
