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
  // The body's axis nearest `d`, and the cosine of the angle between them.
  auto nearest_to = [&](const Eigen::Vector3d& d, double* cos_nearest) {
    const std::pair<std::string, Eigen::Vector3d>* nearest = nullptr;
    *cos_nearest = -1;
    for (const auto& e : axes)
      if (std::abs(d.dot(e.second)) > *cos_nearest) *cos_nearest = std::abs(d.dot(e.second)), nearest = &e;
    return nearest;
  };
  double cos_estimate = 0;
  const std::pair<std::string, Eigen::Vector3d>* nearest = nearest_to(a, &cos_estimate);
  prior.angle = std::acos(std::min(1.0, cos_estimate));
  if (prior.angle > kAxisPriorDegrees * 3.14159265358979323846 / 180) {
    // A press's face chooses among the body's three axes; on a round body,
    // up is the only one, and a face would choose nothing.
    Eigen::Vector3d face;
    if (!frame.found || joint->type != "prismatic" || joint->range_hi - joint->range_lo > kMaxDriftedPress ||
        !part || !best_shown_slide(*part, &face))
      return prior;
    double cos_face = 0;
    nearest = nearest_to(face, &cos_face);
    prior.by_face = true;
  }
  prior.axis = nearest->first;
  // The same sense as the estimate: q keeps its sign.
  joint->axis = a.dot(nearest->second) >= 0 ? nearest->second : Eigen::Vector3d(-nearest->second);
  return prior;
}

}  // namespace efc::pipeline
