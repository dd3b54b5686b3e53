#include "pipeline/infer/twist_search.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pipeline/cloud/kdtree.h"

namespace efc::pipeline {

namespace {

constexpr double kPi = 3.14159265358979323846;
// The whole turn in 10-degree steps, then 2-degree steps within one step of
// the best: a hand's points 5 cm from the axis move 9 mm a step, within the
// truncation below, so no step jumps over the minimum.
constexpr int kCoarseSteps = 36;
constexpr int kFineSteps = 5;
// Points per frame scored (evenly taken): the search's cost, 47 angles a frame.
constexpr size_t kScoredPoints = 150;
constexpr size_t kMinPoints = 12;
// A point farther than this from the model counts this far (m): the hand's
// fingers and the part's edges come and go between frames.
constexpr double kTruncation = 0.01;
// The search replaces the registration's twist only where it fits better
// by this share of the truncated error: a flat hand or a round knob fits
// many angles alike, and there the registration's continuity is worth more.
constexpr double kBetterShare = 0.9;

double score(const std::vector<Eigen::Vector3d>& points, const KdTree& tree, const Eigen::Vector3d& axis,
             const Eigen::Vector3d& origin, double twist) {
  // Turning the frame's points back by the twist lays them on the model.
  const Eigen::Matrix3d back = Eigen::AngleAxisd(-twist, axis).toRotationMatrix();
  double sum = 0;
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d q = origin + back * (p - origin);
    if (!q.allFinite()) return std::numeric_limits<double>::infinity();
    // Only a model point within the truncation counts by its distance: the
    // search for one stops where none can be (most points, at most angles).
    size_t index = 0;
    double d2 = 0;
    sum += tree.nearest_within(q, kTruncation, &index, &d2) ? d2 : kTruncation * kTruncation;
  }
  return sum / static_cast<double>(points.size());
}

}  // namespace

std::vector<double> search_twists(const std::vector<Cloud>& clouds, const Cloud& model, const Eigen::Vector3d& axis,
                                  const Eigen::Vector3d& origin, const std::vector<double>& registered) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> out(clouds.size(), nan);
  if (model.size() < kMinPoints || !axis.allFinite() || axis.norm() == 0) return out;
  const Eigen::Vector3d a = axis.normalized();
  const KdTree tree(model.points);
  if (tree.size() == 0) return out;  // no finite model point
  std::vector<Eigen::Vector3d> points;
  for (size_t f = 0; f < clouds.size(); ++f) {
    const Cloud& c = clouds[f];
    if (c.size() < kMinPoints) continue;
    points.clear();
    const size_t stride = std::max<size_t>(1, c.size() / kScoredPoints);
    for (size_t i = 0; i < c.size(); i += stride) points.push_back(c.points[i]);
    double best = -kPi, best_score = std::numeric_limits<double>::infinity();
    const double step = 2 * kPi / kCoarseSteps;
    for (int k = 0; k < kCoarseSteps; ++k) {
      const double t = -kPi + k * step;
      const double s = score(points, tree, a, origin, t);
      if (s < best_score) best_score = s, best = t;
    }
    const double centre = best;
    for (int k = -kFineSteps; k <= kFineSteps; ++k) {
      const double t = centre + step * k / kFineSteps;
      const double s = score(points, tree, a, origin, t);
      if (s < best_score) best_score = s, best = t;
    }
    const double reg = f < registered.size() ? registered[f] : nan;
    if (std::isfinite(reg) && !(best_score < kBetterShare * score(points, tree, a, origin, reg))) {
      out[f] = reg;
      continue;
    }
    out[f] = best;
  }
  return out;
}

}  // namespace efc::pipeline
