// efc infer, between stages 3 and 4: the hand's own motion while it holds a
// part. hands.txt gives one point per frame, with a hand detector's error
// (~1 cm): a button's 5 mm press or a knob's twist about its centre hardly
// moves it. The hand's depth points around that point do: a hand holding a
// part moves rigidly with it, so its fingers and palm, registered frame to
// frame like a part (track_clouds()), turn with a knob and slide with a
// button, whose own points are hidden under the hand or too round to show
// the motion. This is the grip's track: the hand's points near the contact,
// in the frames the hand holds the part.
#pragma once

#include <Eigen/Geometry>

#include <vector>

#include "pipeline/infer/observations.h"
#include "pipeline/infer/part_tracking.h"

namespace efc::pipeline {

// The hand's points taken for the grip: within this distance of its contact
// point. The fingers and the front of the palm (the palm's centre sits some
// 7 cm behind the fingertips), not the wrist and the arm, which bend.
constexpr double kGripRadius = 0.10;

// contacts[f]: the hand's contact point with the part in the object frame in
// the frames it holds it (NaN elsewhere; assign_hand_contacts()). Returns,
// per frame, the hand's points (Observations::hand_clouds, world frame)
// within kGripRadius of that point; empty where the hand does not hold the
// part or the recording has no hand mask.
std::vector<Cloud> grip_clouds(const Observations& obs, const std::vector<Eigen::Vector3d>& contacts,
                               const std::vector<Eigen::Isometry3d>& to_object);

// How the grip's clouds are tracked (track_clouds()): only the motion a
// registration saw is carried to the next frame (a finger's roll is not a
// motion), a leap is not searched for (it is a new grasp), and within a
// grasp no frame restarts from the reference pose (the hand moves on from
// where it was). efc infer and bench/part_motion_eval share it.
TrackOptions grip_tracking_options();

// The turn of motion `m` about `axis` (unit): the angle of its twist in the
// swing-twist decomposition, in (-pi, pi].
double twist_about(const Eigen::Isometry3d& m, const Eigen::Vector3d& axis);

// A held part's position about a hinge (axis unit, origin; the frame of
// `grip` and `points`) as its grip gives it, frame by frame: the grip's
// registered twist about the hinge, searched through a whole turn where the
// registration fell short (twist_search.h), then unwrapped by half turns
// over the frames `held` (twist_unwrap.h). NaN where the grip has none.
// estimate_joint and bench/part_motion_eval --twists share it.
std::vector<double> grip_twists_about(const PartTrack& grip, const std::vector<Cloud>& points,
                                      const Eigen::Vector3d& axis, const Eigen::Vector3d& origin,
                                      const std::vector<bool>& held);

}  // namespace efc::pipeline
