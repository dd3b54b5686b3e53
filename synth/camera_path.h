// The head camera of someone who walks up to the object and operates it:
// an approach, then standing with head bob and sway, glances (slow yaw and
// pitch wander), an occasional fast turn, small jitter, a little roll; the
// gaze follows a focus point (the object, or the receptor the hand is on),
// so the object stays mostly in view.
#pragma once

#include <Eigen/Geometry>

#include <cstdint>
#include <vector>

#include "synth/scene.h"
#include "synth/suite/knobs.h"

namespace efc::synth {

// A camera in the simulation frame, OpenCV axes: x right, y down, z forward.
struct CameraPose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // columns: the camera's axes
};

// Where the wearer stands once arrived (simulation frame): in front of the
// object, at the knobs' distance and height.
Eigen::Vector3d standing_eye(const Layout& layout, const SceneKnobs& knobs);

// One pose per frame; focus[i] is what frame i looks at (simulation frame).
std::vector<CameraPose> plan_camera_path(const Layout& layout, const SceneKnobs& knobs,
                                         const std::vector<Eigen::Vector3d>& focus, double fps,
                                         double approach_seconds, uint64_t seed);

// MuJoCo's camera frame (x right, y up, z backward) from OpenCV's.
Eigen::Quaterniond mujoco_camera_quat(const Eigen::Matrix3d& opencv_rotation);

}  // namespace efc::synth
