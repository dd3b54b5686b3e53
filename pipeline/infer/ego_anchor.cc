#include "pipeline/infer/ego_anchor.h"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <limits>

#include "pipeline/infer/ego_motion.h"

namespace efc::pipeline {
namespace {

// The registration's own precision, a floor under the jitter: a tracker
// that does not shake still leaves each frame's correction this uncertain.
constexpr double kRegistrationNoise = 0.0002;  // m
// The drift-to-jitter ratios tried, w^2 / j^2 in 1/s (and 0): from a
// drift of a thirtieth of the jitter per sqrt(s) to a hundred times it.
constexpr double kRatioMin = 1e-3, kRatioMax = 1e4;
constexpr int kRatioSteps = 43;  // a factor of about 1.5 apart
// The frames that measure (the first ones): a dense solve each try.
constexpr size_t kMaxWeighted = 240;

}  // namespace

EgoAnchor anchor_refined_world(const std::vector<double>& times, const std::vector<Eigen::Isometry3d>& correction,
                               const std::vector<bool>& registered, const Eigen::Vector3d& centre) {
  EgoAnchor out;
  const size_t n = std::min({times.size(), correction.size(), registered.size()});
  std::vector<double> t;
  std::vector<Eigen::Vector3d> y;
  std::vector<Eigen::Isometry3d> inverse;
  for (size_t f = 0; f < n; ++f) {
    if (!registered[f]) continue;
    const Eigen::Isometry3d inv = correction[f].inverse();
    t.push_back(times[f] - times[0]);
    y.push_back(inv * centre);
    inverse.push_back(inv);
  }
  const size_t m = t.size();
  if (m == 0) return out;

  // The noise by maximum likelihood (restricted: the constant A is
  // unknown), over the ratio q = w^2 / j^2 on a grid: per axis of the
  // centre y = c + walk + jitter, Cov = j^2 (q K + I), K(a, b) = min(t_a,
  // t_b), j^2 in closed form given q. Then the weights at the best q.
  const size_t k = std::min(m, kMaxWeighted);
  Eigen::MatrixXd K(k, k), Y(k, 3);
  for (size_t a = 0; a < k; ++a) {
    Y.row(static_cast<Eigen::Index>(a)) = y[a].transpose();
    for (size_t b = 0; b < k; ++b) K(a, b) = std::min(t[a], t[b]);
  }
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(k));
  double best_deviance = std::numeric_limits<double>::infinity(), best_q = 0, best_j2 = 0;
  Eigen::VectorXd best_x = ones / static_cast<double>(k);
  for (int g = -1; g < kRatioSteps; ++g) {
    // q = 0 (no drift), then kRatioMin ... kRatioMax (1 / s) log-spaced.
    const double q = g < 0 ? 0.0 : kRatioMin * std::pow(kRatioMax / kRatioMin, g / (kRatioSteps - 1.0));
    const Eigen::LLT<Eigen::MatrixXd> llt(q * K + Eigen::MatrixXd::Identity(k, k));
    if (llt.info() != Eigen::Success) continue;
    const Eigen::VectorXd x = llt.solve(ones);
    const Eigen::MatrixXd SY = llt.solve(Y);
    const double total = ones.dot(x);
    double quad = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const double c = x.dot(Y.col(axis)) / total;
      quad += Y.col(axis).dot(SY.col(axis)) - c * c * total;  // r' S^-1 r with r = y - c 1
    }
    const double dof = 3.0 * (static_cast<double>(k) - 1);
    if (!(dof > 0)) break;
    const double j2 = std::max(quad / dof, 1e-18);
    double log_det = 0;
    for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(k); ++i) log_det += 2 * std::log(llt.matrixL()(i, i));
    const double deviance = dof * std::log(j2) + 3 * log_det + 3 * std::log(total);
    if (deviance < best_deviance) best_deviance = deviance, best_q = q, best_j2 = j2, best_x = x;
  }
  const double jitter2 = std::max(best_j2, kRegistrationNoise * kRegistrationNoise);
  out.jitter_m = std::sqrt(jitter2);
  out.walk_m_per_sqrt_s = std::sqrt(best_q * best_j2);

  // The weights: Sigma^-1 1, normalised (uniform where nothing drifts).
  std::vector<double> w(m, 0.0);
  double sum = 0;
  for (size_t a = 0; a < k; ++a) sum += w[a] = std::max(0.0, best_x(static_cast<Eigen::Index>(a)));
  if (!(sum > 0) || !std::isfinite(sum)) {
    std::fill(w.begin(), w.end(), 0.0);
    w[0] = 1.0;
  } else {
    for (double& v : w) v /= sum;
  }

  Eigen::Vector3d mean_centre = Eigen::Vector3d::Zero();
  for (size_t a = 0; a < m; ++a) {
    mean_centre += w[a] * y[a];
    out.frames += w[a] > 1e-6;
    if (t[a] <= 1.0) out.weight_first_second += w[a];
  }
  // The rotation: the weighted quaternion mean of the frames' (their
  // translations' mean is the centre's, above).
  out.model_to_world.linear() = mean_transform(inverse, w).linear();
  out.model_to_world.translation() = mean_centre - out.model_to_world.linear() * centre;
  return out;
}

}  // namespace efc::pipeline
