// The hand that operates the object: a palm, four finger capsules, a thumb
// and a sleeved forearm on one mocap body (visual only: the receptor moves by
// its drive, exactly as in `efc play`; the hand follows it, occluding it as
// a real hand does). The hand frame: origin at the grasp point (between the
// fingertips), +z from the wrist to the fingertips, +y the palm's normal.
#pragma once

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>

#include <string>
#include <vector>

#include "compiler/ir.h"
#include "synth/camera_path.h"
#include "synth/timeline.h"
#include "synth/suite/knobs.h"

namespace efc::synth {

// The hand's <body> element (named kHandBody, mocap), parked at `parked`.
std::string hand_body_xml(const SceneKnobs& knobs, const Eigen::Vector3d& parked);

// Where and how the hand holds a receptor, in the receptor body's frame so
// the hand moves with the part.
struct Grasp {
  int part = -1;  // index into Object::parts
  int body = -1;  // MuJoCo body of the part
  Eigen::Vector3d point_body = Eigen::Vector3d::Zero();  // contact point
  Eigen::Quaterniond hand_body = Eigen::Quaterniond::Identity();  // hand orientation
  // The hand's pose in the simulation frame for the body's current pose.
  Eigen::Isometry3d hand_pose(const mjData* d) const;
  Eigen::Vector3d point(const mjData* d) const;  // contact point, simulation frame
};

// Picks a grasp for `part` in the current state: a knob is held on its face
// (and twisted), a lever or door at the point farthest from its hinge, a
// drawer or button on the face its slide points out of, always on a side the
// eye (simulation frame) can see; the point is put on the part's surface by a
// ray cast.
Grasp plan_grasp(const Object& obj, int part, const mjModel* m, const mjData* d, const Eigen::Vector3d& eye);

// Where the hand is at time t: at rest low beside the camera, reaching a
// receptor, holding it (moving with the part), letting go. grasps[i] is
// visits[i]'s. `holding` is the grasp in use while the hand holds a part.
struct HandState {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // the hand frame, simulation frame
  const Grasp* holding = nullptr;
};
HandState hand_at(double t, const CameraPose& camera, const std::vector<Grasp>& grasps,
                  const std::vector<Visit>& visits, const mjData* d);

}  // namespace efc::synth
