#include "pipeline/infer/grip_track.h"

#include <cmath>
#include <limits>

#include "pipeline/infer/part_tracking.h"
#include "pipeline/infer/twist_search.h"
#include "pipeline/infer/twist_unwrap.h"

namespace efc::pipeline {

TrackOptions grip_tracking_options() {
  TrackOptions o;
  o.carry_unseen_motion = false;
  o.reacquire_leaps = false;
  o.restart_from_reference = false;
  return o;
}

std::vector<Cloud> grip_clouds(const Observations& obs, const std::vector<Eigen::Vector3d>& contacts,
                               const std::vector<Eigen::Isometry3d>& to_object) {
  const size_t n = obs.hand_clouds.size();
  std::vector<Cloud> grip(obs.times.size());
  for (size_t f = 0; f < n && f < contacts.size() && f < to_object.size(); ++f) {
    if (std::isnan(contacts[f].x())) continue;
    const Eigen::Vector3d at = to_object[f].inverse() * contacts[f];  // world frame, as the clouds
    const Cloud& hand = obs.hand_clouds[f];
    Cloud& out = grip[f];
    for (size_t i = 0; i < hand.size(); ++i) {
      if ((hand.points[i] - at).norm() >= kGripRadius) continue;
      out.points.push_back(hand.points[i]);
      if (hand.has_normals()) out.normals.push_back(hand.normals[i]);
    }
  }
  return grip;
}

double twist_about(const Eigen::Isometry3d& m, const Eigen::Vector3d& axis) {
  Eigen::Quaterniond r(m.linear());
  if (r.w() < 0) r.coeffs() = -r.coeffs();
  return 2 * std::atan2(r.vec().dot(axis), r.w());
}

std::vector<double> grip_twists_about(const PartTrack& grip, const std::vector<Cloud>& points,
                                      const Eigen::Vector3d& axis, const Eigen::Vector3d& origin,
                                      const std::vector<bool>& held) {
  std::vector<double> registered(held.size(), std::numeric_limits<double>::quiet_NaN());
  for (size_t f = 0; f < grip.motion.size() && f < registered.size(); ++f)
    if (grip.tracked[f]) registered[f] = twist_about(grip.motion[f], axis);
  return unwrap_half_turns(search_twists(points, grip.model, axis, origin, registered), held, kRegraspFrames);
}

}  // namespace efc::pipeline
