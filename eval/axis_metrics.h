// The EgoFun3D articulation metrics for one joint, on world-frame axes:
// type accuracy, axis angle error and origin (axis line) distance.
#pragma once

#include "compiler/ir.h"

namespace efc::eval {

constexpr double kPi = 3.14159265358979323846;
// What a joint with no prediction scores (the paper's failure values).
constexpr double kFailureAxisErrorRad = kPi / 2;
constexpr double kFailureOriginErrorM = 1.0;

// A joint axis as a line in the world frame: a point on it and a direction.
struct AxisLine {
  Vec3 origin{0, 0, 0};
  Vec3 direction{0, 0, 1};
};

// arccos(|a . b|) with both normalised: an axis and its reverse are the same
// axis (a joint's sign convention is not observable). Radians, in [0, pi/2].
double axis_error_rad(const Vec3& a, const Vec3& b);

// Distance between two axis lines: |(o2 - o1) . (a1 x a2)| / |a1 x a2| for
// skew lines; for parallel ones (|a1 x a2| < 1e-9) the distance from o2 to
// line 1. Metres.
double axis_line_distance(const AxisLine& a, const AxisLine& b);

// Rotating joints are one type for the metric: revolute and continuous differ
// only in having limits, which the type does not measure.
bool same_joint_type(JointType a, JointType b);

struct JointScore {
  bool type_correct = false;
  double axis_error_rad = kFailureAxisErrorRad;
  double origin_error_m = kFailureOriginErrorM;
  bool failed = true;  // no predicted joint: the failure values above
};

// The score of a predicted joint against the true one (both in the world
// frame). A prismatic truth has no axis position to get wrong: origin error 0.
JointScore score_joint(JointType pred_type, const AxisLine& pred, JointType gt_type, const AxisLine& gt);

}  // namespace efc::eval
