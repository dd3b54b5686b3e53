// efc infer, between stages 3 and 4: which part the hand holds in each frame.
// A hands.txt point belongs to the moving part whose surface (its model, at
// the part's registered pose in that frame) lies within kContactDistance of
// it. A grasp then holds on while the part's registration fails: a small
// lever or rocker leaves its model's place under the hand, often hidden by
// it, and would otherwise lose the hand in exactly the frames that show its
// motion.
#pragma once

#include <Eigen/Geometry>

#include <string>
#include <vector>

#include "pipeline/infer/part_tracking.h"

namespace efc::pipeline {

// The hand holds a part when its contact point lies this close to the part's
// surface: the hand detector's error (~1 cm) and the grasp point sitting on
// the part.
constexpr double kContactDistance = 0.03;

// Untracked frames take the nearest tracked frame's motion (the part holds
// still while it is out of sight, as far as we can tell).
std::vector<Eigen::Isometry3d> filled_motion(const PartTrack& track);

// hand[f]: the hand's contact point in the object frame (NaN where not
// seen). tracks[p]: part p's track, or null for a part that is not tracked
// (static parts). Returns, per part, the hand's points in the frames it
// holds that part (NaN elsewhere). A held part stays held in a frame its
// registration failed when the hand was its own at most two frames before
// and lies within kContactDistance plus the part's diameter of its model.
std::vector<std::vector<Eigen::Vector3d>> assign_hand_contacts(const std::vector<Eigen::Vector3d>& hand,
                                                               const std::vector<const PartTrack*>& tracks);

// hands.txt is where the hand touches a receptor (sequence.md); an effector
// moves because a function drives it. So after assign_hand_contacts (which
// gives each contact to the nearest part, so that a hand on a lamp is not
// one on the switch beside it), only parts whose role is "receptor" alone
// keep their contacts: not effectors, not a chain's middle part
// ("receptor+effector", driven too), not "object" parts. Where no part has
// the role "receptor" (masks named by part only) every part keeps its own.
// roles[p] is part p's role; contacts[p] as assign_hand_contacts returns.
void keep_receptor_contacts(const std::vector<std::string>& roles,
                            std::vector<std::vector<Eigen::Vector3d>>* contacts);

}  // namespace efc::pipeline
