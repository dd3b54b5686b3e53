#include "pipeline/infer/axis_prior.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace efc::pipeline {

bool face_it_sits_on(const BodyFrame& frame, const Cloud& body, const Eigen::Vector3d& at, Eigen::Vector3d* axis) {
  if (!frame.found || !body.has_normals() || body.size() < static_cast<size_t>(kFacePoints)) return false;
  std::vector<std::pair<double, size_t>> by_distance;
  by_distance.reserve(body.size());
  for (size_t i = 0; i < body.size(); ++i) by_distance.emplace_back((body.points[i] - at).squaredNorm(), i);
  std::nth_element(by_distance.begin(), by_distance.begin() + kFacePoints - 1, by_distance.end());
  // The part sits on another part (a kettle's lid button on its jug, not
  // on the base): the body's surface is not its face.
  if (by_distance[kFacePoints - 1].first > kFaceReach * kFaceReach) return false;
  const Eigen::Vector3d axes[3] = {frame.u, frame.v, frame.up};
  const double facing = std::cos(kBoxNormalDegrees * 3.14159265358979323846 / 180);
  int votes[3] = {0, 0, 0};
  for (int k = 0; k < kFacePoints; ++k) {
    const Eigen::Vector3d& n = body.normals[by_distance[k].second];
    for (int e = 0; e < 3; ++e)
      if (std::abs(n.dot(axes[e])) >= facing) ++votes[e];
  }
  const int best = static_cast<int>(std::max_element(votes, votes + 3) - votes);
  if (votes[best] < kFaceShare * kFacePoints) return false;
  *axis = axes[best];
  return true;
}

AxisPrior apply_axis_prior(const BodyFrame& frame, JointEstimate* joint, const Cloud* part, const Cloud* body,
                           const Eigen::Vector3d* part_at) {
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
  // A press or a knob no track typed goes into the body's face it sits on,
  // whatever its range (the hand's wander: its own track showed the press
  // under the registration's noise, or still where the hand turned it).
  Eigen::Vector3d into;
  if (joint->motion_untyped && body && part_at && face_it_sits_on(frame, *body, *part_at, &into)) {
    prior.axis = into == frame.u ? "u" : into == frame.v ? "v" : "up";
    prior.by_body_face = true;
    joint->axis = a.dot(into) >= 0 ? into : Eigen::Vector3d(-into);
    return prior;
  }
  const bool press = joint->type == "prismatic" && joint->range_hi - joint->range_lo <= kMaxDriftedPress;
  if (prior.angle > kAxisPriorDegrees * 3.14159265358979323846 / 180) {
    // A press's face chooses among the body's three axes; on a round body,
    // up is the only one, and a face would choose nothing.
    Eigen::Vector3d face;
    if (!frame.found || !press || !part || !best_shown_slide(*part, &face))
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
