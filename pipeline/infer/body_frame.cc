#include "pipeline/infer/body_frame.h"

#include <cmath>

namespace efc::pipeline {

BodyFrame body_frame(const Cloud& c) {
  BodyFrame frame;
  if (!c.has_normals()) return frame;
  double sx = 0, sy = 0;
  for (size_t i = 0; i < c.size(); ++i) {
    const Eigen::Vector3d& n = c.normals[i];
    if (!n.allFinite() || std::abs(n.z()) > 0.5) continue;
    const double a = 4 * std::atan2(n.y(), n.x());
    const double w = std::hypot(n.x(), n.y());
    sx += w * std::cos(a), sy += w * std::sin(a);
  }
  if (!(std::hypot(sx, sy) > 0)) return frame;
  frame.yaw = std::atan2(sy, sx) / 4;
  frame.u = Eigen::Vector3d(std::cos(frame.yaw), std::sin(frame.yaw), 0);
  frame.v = Eigen::Vector3d(-std::sin(frame.yaw), std::cos(frame.yaw), 0);
  const double cos_tol = std::cos(kBoxNormalDegrees * 3.14159265358979323846 / 180);
  size_t facing = 0, counted = 0, upright = 0, upright_facing = 0;
  for (size_t i = 0; i < c.size(); ++i) {
    const Eigen::Vector3d& n = c.normals[i];
    if (!n.allFinite() || !c.points[i].allFinite()) continue;
    ++counted;
    const bool side = std::abs(n.dot(frame.u)) >= cos_tol || std::abs(n.dot(frame.v)) >= cos_tol;
    facing += side || std::abs(n.dot(frame.up)) >= cos_tol;
    if (std::abs(n.z()) < 0.5) ++upright, upright_facing += side;
  }
  frame.box_share = counted ? static_cast<double>(facing) / counted : 0.0;
  frame.upright_share = upright ? static_cast<double>(upright_facing) / upright : 0.0;
  frame.found = frame.box_share >= kBoxShare && frame.upright_share >= kBoxShare;
  return frame;
}

}  // namespace efc::pipeline
