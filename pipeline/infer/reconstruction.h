// efc infer, stage 5: each part's surface and a closed mesh of it. Every
// frame's points are taken back to the part's q = 0 configuration (for a
// moving part, through its registered motion; a fixed part's points are
// already there once the camera is corrected) and fused (pipeline/cloud/
// fusion.h: a voxel grid that keeps what several frames agree on), then
// closed (the convex hull: watertight, so the compiler can take collision
// and inertia from it).
#pragma once

#include <Eigen/Geometry>

#include <string>
#include <vector>

#include "pipeline/cloud/mesh.h"
#include "pipeline/infer/joint_estimate.h"
#include "pipeline/infer/part_tracking.h"

namespace efc::pipeline {

struct PartReconstruction {
  bool ok = false;
  std::string error;         // why there is no mesh
  Cloud fused;               // object frame, q = 0
  TriMesh mesh;              // object frame, q = 0
  int frames_fused = 0;
  double volume = 0;         // m^3
  Eigen::AlignedBox3d bounds;
  double seconds = 0;
};

// `track` and `joint` may be null (a static part).
PartReconstruction reconstruct_part(const Observations& obs, int part, const std::vector<Eigen::Isometry3d>& to_object,
                                    const PartTrack* track, const JointEstimate* joint);

}  // namespace efc::pipeline
