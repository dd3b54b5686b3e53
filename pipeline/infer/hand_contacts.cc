#include "pipeline/infer/hand_contacts.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "pipeline/cloud/kdtree.h"

namespace efc::pipeline {

std::vector<Eigen::Isometry3d> filled_motion(const PartTrack& t) {
  const int n = static_cast<int>(t.motion.size());
  std::vector<Eigen::Isometry3d> out = t.motion;
  for (int f = 0; f < n; ++f) {
    if (t.tracked[f]) continue;
    for (int d = 1; d < n; ++d) {
      if (f - d >= 0 && t.tracked[f - d]) { out[f] = t.motion[f - d]; break; }
      if (f + d < n && t.tracked[f + d]) { out[f] = t.motion[f + d]; break; }
    }
  }
  return out;
}

std::vector<std::vector<Eigen::Vector3d>> assign_hand_contacts(const std::vector<Eigen::Vector3d>& hand,
                                                               const std::vector<const PartTrack*>& tracks) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const int n = static_cast<int>(hand.size());
  const size_t parts = tracks.size();
  std::vector<std::vector<Eigen::Vector3d>> out(
      parts, std::vector<Eigen::Vector3d>(n, Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN())));
  std::vector<std::unique_ptr<KdTree>> trees(parts);
  std::vector<std::vector<Eigen::Isometry3d>> motion(parts);
  // How far a held part's surface may move from its model's place: its
  // diameter (a lever lifted through a right angle moves its tip about that
  // far), plus the contact distance.
  std::vector<double> reach(parts, 0);
  for (size_t p = 0; p < parts; ++p) {
    const PartTrack* t = tracks[p];
    if (!t || t->model.size() == 0 || static_cast<int>(t->motion.size()) < n) continue;
    trees[p] = std::make_unique<KdTree>(t->model.points);
    motion[p] = filled_motion(*t);
    const Eigen::Vector3d c = centroid(t->model);
    double r2 = 0;
    for (const Eigen::Vector3d& q : t->model.points) r2 = std::max(r2, (q - c).squaredNorm());
    reach[p] = kContactDistance + 2 * std::sqrt(r2);
  }
  int held = -1, held_last = -10;
  for (int f = 0; f < n; ++f) {
    const Eigen::Vector3d& h = hand[f];
    if (!h.allFinite()) continue;
    // Squared distance from the hand to part p's surface in frame f.
    auto distance2 = [&](size_t p) {
      size_t idx;
      double d2 = kInf;
      if (!trees[p] || !trees[p]->nearest(motion[p][f].inverse() * h, &idx, &d2)) return kInf;
      return d2;
    };
    int owner = -1;
    double best = kContactDistance * kContactDistance;
    for (size_t p = 0; p < parts; ++p) {
      const double d2 = distance2(p);
      if (d2 < best) best = d2, owner = static_cast<int>(p);
    }
    // Only where the part's registration failed: where it succeeded, its
    // pose is known and the contact test above is the right one (holding on
    // there would keep the hand's retreat after a release).
    if (owner < 0 && held >= 0 && f - held_last <= 2 && !tracks[held]->tracked[f] &&
        distance2(held) < reach[held] * reach[held])
      owner = held;
    if (owner >= 0) out[owner][f] = h, held_last = f;
    held = owner;
  }
  return out;
}

void keep_receptor_contacts(const std::vector<std::string>& roles,
                            std::vector<std::vector<Eigen::Vector3d>>* contacts) {
  if (std::find(roles.begin(), roles.end(), "receptor") == roles.end()) return;
  for (size_t p = 0; p < contacts->size() && p < roles.size(); ++p)
    if (roles[p] != "receptor")
      std::fill((*contacts)[p].begin(), (*contacts)[p].end(),
                Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()));
}

}  // namespace efc::pipeline
