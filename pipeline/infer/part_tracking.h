// efc infer, stage 3: how each part moves relative to the static object.
// Every frame's points of the part (object frame, after the ego-motion
// correction) are registered onto a model of the part by robust
// point-to-plane ICP: first the frame that sees most of it, then the fusion
// of every registered frame (a fuller surface, and the hand's occlusion of
// one frame no longer matters). Frames are visited outward from the
// reference, each starting from its neighbour's motion extrapolated at
// constant velocity, so a fast door does not lose the track; a state the
// chain loses to a leap (a lid snapped open and held) is searched for
// globally and the chain goes on from there (reacquisition.h).
#pragma once

#include <Eigen/Geometry>

#include <vector>

#include "pipeline/infer/observations.h"

namespace efc::pipeline {

// Directions whose normalised ICP eigenvalue (IcpResult) is below this are
// left alone by the tracker: noise along a near-symmetry (a round knob's
// spin) is not motion, and the pose there is only the registration's start.
constexpr double kTrackDegenerateThreshold = 0.05;

struct PartTrack {
  int part = -1;             // index in Observations::parts
  int reference_frame = -1;  // the model's configuration is this frame's
  // Per frame: the rigid motion taking the part from the reference
  // configuration to this frame's (object frame). Identity where untracked.
  std::vector<Eigen::Isometry3d> motion;
  std::vector<bool> tracked;
  std::vector<double> rmse, inliers;
  // The ICP system's smallest normalised eigenvalue per frame (about 1 when
  // every direction is constrained; near 0, a motion the shape cannot show,
  // such as a plain cylinder turning on its axis).
  std::vector<double> conditioning;
  // Per frame: the ICP's Gauss-Newton Hessian (J^T W J over the matched
  // points, rotation first, about `hessian_center`, model frame) at the end
  // of the registration. With rmse it says how well each direction of the
  // frame's pose is known (part_samples() turns it into Track::information).
  std::vector<Eigen::Matrix<double, 6, 6>> hessian;
  std::vector<Eigen::Vector3d> hessian_center;
  // The ICP's length scale (IcpResult::scale_length) per frame: with it the
  // Hessian's normalised eigenvalues, which say which directions the
  // registration left alone, can be recomputed.
  std::vector<double> hessian_scale;
  Cloud model;  // reference configuration, object frame
  int frames_tracked = 0;
  double seconds = 0;
};

// to_object[f] maps frame f's points (world of poses.txt) into the object frame.
PartTrack track_part(const Observations& obs, int part, const std::vector<Eigen::Isometry3d>& to_object);
struct TrackOptions {
  // Each frame's registration starts from the last one's motion carried on
  // a step (constant velocity). true: the whole step, also along the
  // directions the last registration left alone: a drawer pulled fast,
  // whose slide its faces show only now and then, keeps moving. false: only
  // what the last registration saw; along a direction the shape cannot show
  // (a finger's roll, a round knob's spin) a step was never measured, and
  // carried on frame after frame it runs away (the grip's track).
  bool carry_unseen_motion = true;
  // A state the chain loses to a leap is searched for (reacquisition.h): a
  // part's lid snapped open. Not the grip's: the hand's points around its
  // contact are seen only while it holds, and a leap there is a new grasp,
  // not a held state to find again.
  bool reacquire_leaps = true;
  // Each frame may also start from the reference configuration (a chain
  // that lost the part finds it again). Not the grip's within a grasp: a
  // hand's fingers and palm look much alike turned a quarter turn on a
  // knob, and where the hand pauses the reference start's match wins by a
  // few points; a hand holding a part moves on from where it was. A frame
  // more than kRegraspFrames after the last registered one is a new grasp
  // and may start there.
  bool restart_from_reference = true;
};
// A hand unseen on a part for more than this many frames has let go of it:
// its next frame there is a new grasp (the grip's tracking, and the joint
// position read from the hand's contacts).
constexpr int kRegraspFrames = 3;

// The same for any rigid thing seen frame by frame: clouds[f] in the world
// frame of poses.txt (empty where unseen). `part` is left -1.
PartTrack track_clouds(const std::vector<Cloud>& clouds, const std::vector<Eigen::Isometry3d>& to_object,
                       const TrackOptions& options = {});

// The part's points of frame f in the object frame.
Cloud part_cloud_in_object(const Observations& obs, int part, int frame,
                           const std::vector<Eigen::Isometry3d>& to_object);

}  // namespace efc::pipeline
