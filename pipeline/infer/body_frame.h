// The body's own axes: man-made objects are built square, and their joints
// turn and slide along the axes of the box they are built on (a door's hinge
// upright, a drawer out of the front, a knob's spin through the front).
// Gravity gives the object frame's z; the upright faces' normals give the
// yaw of the other two (their azimuths times four, so that a box's four
// sides point the same way, averaged on the circle). The frame is found
// where most of the body's fused surface faces the six faces of that box
// (normals within kBoxNormalDegrees of its axes: a share at least kBoxShare,
// of all the surface and of its upright part alone, so that a disc's top and
// bottom do not carry a round base past the share). A round body (a drum, a
// lamp's base) has no such frame; up is still up.
#pragma once

#include <Eigen/Geometry>

#include "pipeline/cloud/cloud.h"

namespace efc::pipeline {

constexpr double kBoxShare = 0.7;
constexpr double kBoxNormalDegrees = 20;

struct BodyFrame {
  bool found = false;  // the body is square: u and v are its horizontal axes
  double yaw = 0;      // rad, of u from the object frame's x about z
  Eigen::Vector3d u = Eigen::Vector3d::UnitX(), v = Eigen::Vector3d::UnitY(), up = Eigen::Vector3d::UnitZ();
  double box_share = 0;      // the share of the surface facing the box's faces
  double upright_share = 0;  // the same of the upright surface alone
};

// `fused`: the body's points with normals, in the object frame (z up).
BodyFrame body_frame(const Cloud& fused);

}  // namespace efc::pipeline
