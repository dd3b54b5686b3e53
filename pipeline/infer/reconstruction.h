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
#include "pipeline/infer/body_frame.h"
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
  bool squared = false;      // the mesh is the body's box (square_the_body)
  double box_share = 0;      // square_the_body: the share of its surface facing the box's faces,
  double box_surface_share = 0;  // the share on the box's faces,
  double box_fill = 0;       // and the hull's volume over the box's
  BodyFrame frame;           // square_the_body: the body's axes (body_frame.h), found or not
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

// A body that is a box (a cabinet, a stove, a microwave) seen from one
// corner: its two faces in view and a sliver of its top, at a grazing
// angle, stand as a prism whose footprint is the hull of an L, half the
// box's (s0020's stove: 0.045 of its 0.084 m^3, its middle 19 cm from the
// hull's slanted face). Where most of the fused surface faces the six
// faces of one box upright under gravity (normals within kBoxNormalDegrees
// of the box's axes: share at least kBoxShare), the mesh becomes that box:
// its yaw from the upright faces' normals (their azimuths' circular mean
// modulo a quarter turn), its extent the standing hull's along its axes,
// down to the foot. A body of other shapes (a lamp's round base, a
// faucet) keeps its hull; so does one that is two boxes (a hood's chimney
// on its canopy) or a disc and a pole (a lamp's base), where much of what
// was seen lies inside the box rather than on its faces (within
// kBoxSurfaceNear, or kBoxSurfaceShareOfSize of its smallest side: a share
// under kBoxSurfaceShare), and one whose hull fills the box already (a
// share kBoxFilled: the bevels of a hull seen all round fit an inset foot
// better than the box's corners; measured on the suite, 5 to 20 % worse
// Chamfer squared). `recon`'s fused points and bounds are kept; false
// (recon unchanged) where the body is not such a box.
constexpr double kBoxSurfaceNear = 0.015;       // m
constexpr double kBoxSurfaceShareOfSize = 0.05;
constexpr double kBoxSurfaceShare = 0.7;
constexpr double kBoxFilled = 0.9;
bool square_the_body(PartReconstruction* recon);

}  // namespace efc::pipeline
