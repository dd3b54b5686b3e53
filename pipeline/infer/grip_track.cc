#include "pipeline/infer/grip_track.h"

#include <cmath>

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

}  // namespace efc::pipeline
