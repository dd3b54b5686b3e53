#include "eval/axis_metrics.h"

#include <algorithm>
#include <cmath>

#include "compiler/geometry/vec.h"

namespace efc::eval {

using namespace geom;

double axis_error_rad(const Vec3& a, const Vec3& b) {
  const double c = std::fabs(dot(normalized(a), normalized(b)));
  return std::acos(std::min(1.0, c));  // rounding can push |a.b| past 1
}

double axis_line_distance(const AxisLine& a, const AxisLine& b) {
  const Vec3 da = normalized(a.direction), db = normalized(b.direction);
  const Vec3 n = cross(da, db);
  const double n_len = norm(n);
  const Vec3 d = sub(b.origin, a.origin);
  if (n_len < 1e-9) return norm(sub(d, mul(da, dot(d, da))));  // parallel: point to line
  return std::fabs(dot(d, n)) / n_len;
}

bool same_joint_type(JointType a, JointType b) {
  auto rotates = [](JointType t) { return t == JointType::Revolute || t == JointType::Continuous; };
  return a == b || (rotates(a) && rotates(b));
}

JointScore score_joint(JointType pred_type, const AxisLine& pred, JointType gt_type, const AxisLine& gt) {
  JointScore s;
  s.failed = false;
  s.type_correct = same_joint_type(pred_type, gt_type);
  s.axis_error_rad = axis_error_rad(pred.direction, gt.direction);
  s.origin_error_m = gt_type == JointType::Prismatic ? 0.0 : axis_line_distance(gt, pred);
  return s;
}

}  // namespace efc::eval
