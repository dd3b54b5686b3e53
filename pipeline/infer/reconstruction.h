// efc infer, stage 5: each part's surface and a closed mesh of it. Every
// frame's points are taken back to the part's q = 0 configuration (for a
// moving part, through its registered motion; a fixed part's points are
// already there once the camera is corrected) and fused (pipeline/cloud/
// fusion.h: a voxel grid that keeps what several frames agree on, and
// what the masks put inside the part more often than just outside it:
// the observations' outlines), then closed (the convex hull: watertight,
// so the compiler can take collision and inertia from it).
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
  int outline_dropped = 0;   // voxels the masks' vote dropped (PartFusion::fused)
  double volume = 0;         // m^3
  Eigen::AlignedBox3d bounds;
  bool stood = false;        // the mesh stands on its foot (stand_on_its_foot)
  double seconds = 0;
};

// `track` and `joint` may be null (a static part).
PartReconstruction reconstruct_part(const Observations& obs, int part, const std::vector<Eigen::Isometry3d>& to_object,
                                    const PartTrack* track, const JointEstimate* joint);

// The object's body (the root: a static part) as it stands: its surface is
// seen from in front and above, so the convex hull of what was seen is a
// wedge that cuts away the body's back and bottom (s0000's cabinet: 0.12 of
// its 0.34 m^3, and its back-bottom edge 0.44 m from the hull). A body rests
// on what holds it up, under gravity (the object frame's -z): where its
// surface faces up (normal z >= kFacingUp), it stands on a column down to
// the body's foot, and the mesh is the hull of the fine hull's corners, those
// points and their feet. The foot is the lowest point but a half percent of
// a fusion at kStandingVoxel, where the far frames of the approach, the only
// ones that see the body's foot, are as dense as the near ones (their
// points, a centimetre apart from 2.7 m away, are sparse beside the near
// frames' at 3 mm, and the fine fusion's outlier test drops them: s0000's
// hull's lowest point is 0.16 m up with the test, at the foot without it).
// Only what faces up stands: a mask that spills past the body's outline
// takes in the wall behind it (facing the camera), whose columns would fill
// the gap between the two. `recon`'s mesh and volume are replaced; its fused points and
// bounds, which the template stage reads, are kept. False (recon unchanged)
// without a hull to start from or when the new one cannot be built.
constexpr double kStandingVoxel = 0.01;
constexpr double kFacingUp = 0.8;
bool stand_on_its_foot(const Observations& obs, int part, const std::vector<Eigen::Isometry3d>& to_object,
                       PartReconstruction* recon);

}  // namespace efc::pipeline
