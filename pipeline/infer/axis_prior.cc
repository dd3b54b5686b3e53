#include "pipeline/infer/axis_prior.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace efc::pipeline {

AxisPrior apply_axis_prior(const BodyFrame& frame, JointEstimate* joint, const Cloud* part) {
  AxisPrior prior;
  if (joint->type == "fixed" || !(joint->axis.norm() > 0)) return prior;
  const Eigen::Vector3d a = joint->axis.normalized();
  prior.estimated = a;
  std::vector<std::pair<std::string, Eigen::Vector3d>> axes{{"up", frame.up}};
  if (frame.found) axes.emplace_back("u", frame.u), axes.emplace_back("v", frame.v);
  auto nearest_to = [&](const Eigen::Vector3d& d, double* cos) {
    const std::pair<std::string, Eigen::Vector3d>* nearest = nullptr;
    *cos = -1;
    for (const auto& e : axes)
      if (std::abs(d.dot(e.second)) > *cos) *cos = std::abs(d.dot(e.second)), nearest = &e;
    return nearest;
  };
  double best = 0;
  const std::pair<std::string, Eigen::Vector3d>* nearest = nearest_to(a, &best);
  prior.angle = std::acos(std::min(1.0, best));
  if (prior.angle > kAxisPriorDegrees * 3.14159265358979323846 / 180) {
    Eigen::Vector3d face;
    if (joint->type != "prismatic" || joint->range_hi - joint->range_lo > kMaxDriftedPress || !part ||
        !best_shown_slide(*part, &face))
      return prior;
    double cos = 0;
    nearest = nearest_to(face, &cos);
    prior.by_face = true;
  }
  prior.axis = nearest->first;
  // The same sense as the estimate: q keeps its sign.
  joint->axis = a.dot(nearest->second) >= 0 ? nearest->second : Eigen::Vector3d(-nearest->second);
  return prior;
}

}  // namespace efc::pipeline
