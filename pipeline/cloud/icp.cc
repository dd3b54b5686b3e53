#include "pipeline/cloud/icp.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <vector>

namespace efc::pipeline {

namespace {


double tuning_constant(RobustLoss loss) {
  switch (loss) {
    case RobustLoss::Huber: return 1.345;
    case RobustLoss::Tukey: return 4.685;
    case RobustLoss::Cauchy: return 2.385;
  }
  return 4.685;
}

// The IRLS weight rho'(r)/r of each loss at scale k.
double robust_weight(RobustLoss loss, double r, double k) {
  const double a = std::abs(r) / k;
  switch (loss) {
    case RobustLoss::Huber: return a <= 1 ? 1.0 : 1.0 / a;
    case RobustLoss::Tukey: return a < 1 ? (1 - a * a) * (1 - a * a) : 0.0;
    case RobustLoss::Cauchy: return 1.0 / (1 + a * a);
  }
  return 0;
}

struct Pair {
  Eigen::Vector3d p;  // transformed source point
  Eigen::Vector3d n;  // target normal
  double r;           // n . (p - t)
};

// The matched pairs at T (nearest target point within max_correspondence).
void match(const Cloud& source, const std::vector<size_t>& used, const Cloud& target, const KdTree& tree,
           const Eigen::Isometry3d& T, double max_dist, double min_normal_dot, std::vector<Pair>* pairs) {
  pairs->clear();
  const bool check_normals = min_normal_dot > -1 && source.has_normals();
  const double max2 = max_dist * max_dist;
  for (size_t i : used) {
    const Eigen::Vector3d p = T * source.points[i];
    size_t j = 0;
    double d2 = 0;
    if (!tree.nearest(p, &j, &d2) || d2 > max2 || j >= target.size()) continue;
    const Eigen::Vector3d& n = target.normals[j];
    if (!n.allFinite()) continue;
    // A surface seen from its other side is not the same surface: without
    // this, a thin disc matches itself flipped over.
    if (check_normals && n.dot(T.linear() * source.normals[i]) < min_normal_dot) continue;
    pairs->push_back({p, n, n.dot(p - target.points[j])});
  }
}

double kernel_for(const std::vector<Pair>& pairs, const IcpOptions& o) {
  std::vector<double> a(pairs.size());
  for (size_t i = 0; i < pairs.size(); ++i) a[i] = std::abs(pairs[i].r);
  std::nth_element(a.begin(), a.begin() + a.size() / 2, a.end());
  const double sigma = 1.4826 * a[a.size() / 2];
  const double hi = std::max(o.kernel_scale, o.max_correspondence);
  return std::clamp(tuning_constant(o.loss) * sigma, o.kernel_scale, hi);
}

// The weighted normal equations about `center`, rotation scaled by `L`
// (H_s, g_s, both divided by the weight sum), plus the unscaled Hessian.
struct System {
  Eigen::Matrix<double, 6, 6> H_scaled = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> g_scaled = Eigen::Matrix<double, 6, 1>::Zero();
  Eigen::Matrix<double, 6, 6> H = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double L = 1;
  double weight_sum = 0;
};

System build(const std::vector<Pair>& pairs, RobustLoss loss, double k) {
  System s;
  for (const auto& pr : pairs) s.center += pr.p;
  s.center /= static_cast<double>(pairs.size());
  double ss = 0;
  for (const auto& pr : pairs) ss += (pr.p - s.center).squaredNorm();
  s.L = std::max(std::sqrt(ss / pairs.size()), 1e-6);
  for (const auto& pr : pairs) {
    const double w = robust_weight(loss, pr.r, k);
    if (w <= 0) continue;
    Eigen::Matrix<double, 6, 1> J;
    J.head<3>() = (pr.p - s.center).cross(pr.n);
    J.tail<3>() = pr.n;
    s.H += w * J * J.transpose();
    J.head<3>() /= s.L;
    s.H_scaled += w * J * J.transpose();
    s.g_scaled += w * pr.r * J;
    s.weight_sum += w;
  }
  if (s.weight_sum > 0) {
    s.H_scaled /= s.weight_sum;
    s.g_scaled /= s.weight_sum;
  }
  return s;
}

}  // namespace

IcpResult icp_point_to_plane(const Cloud& source, const Cloud& target, const KdTree& target_tree,
                             const Eigen::Isometry3d& initial, const IcpOptions& options) {
  IcpResult res;
  res.transform = initial;
  if (!target.has_normals() || target_tree.size() == 0 || source.size() == 0) return res;
  if (!(options.max_correspondence > 0) || !(options.kernel_scale > 0)) return res;

  // The source points used: finite ones, thinned by a fixed stride.
  std::vector<size_t> finite;
  finite.reserve(source.size());
  for (size_t i = 0; i < source.size(); ++i)
    if (source.points[i].allFinite()) finite.push_back(i);
  std::vector<size_t> used;
  if (options.subsample > 0 && finite.size() > static_cast<size_t>(options.subsample)) {
    const size_t m = static_cast<size_t>(options.subsample);
    used.reserve(m);
    for (size_t i = 0; i < m; ++i) used.push_back(finite[i * finite.size() / m]);
  } else {
    used = std::move(finite);
  }
  if (used.empty()) return res;

  Eigen::Isometry3d T = initial;
  std::vector<Pair> pairs;
  for (int it = 0; it < options.max_iterations; ++it) {
    match(source, used, target, target_tree, T, options.max_correspondence, options.min_normal_dot, &pairs);
    if (pairs.size() < 6) break;
    const System sys = build(pairs, options.loss, kernel_for(pairs, options));
    if (!(sys.weight_sum > 0)) break;

    // Truncated eigen-solve: only the directions the data constrains move.
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(sys.H_scaled);
    Eigen::Matrix<double, 6, 1> delta = Eigen::Matrix<double, 6, 1>::Zero();
    for (int k = 0; k < 6; ++k) {
      const double lambda = eig.eigenvalues()(k);
      if (lambda < options.degenerate_threshold) continue;
      const auto v = eig.eigenvectors().col(k);
      delta -= (v.dot(sys.g_scaled) / lambda) * v;
    }
    if (!delta.allFinite()) break;
    const Eigen::Vector3d omega = delta.head<3>() / sys.L;
    const Eigen::Vector3d v = delta.tail<3>();

    // p' = R (p - c) + c + v, R exact (angle-axis): T stays rigid.
    const double angle = omega.norm();
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    if (angle > 0) R = Eigen::AngleAxisd(angle, omega / angle).toRotationMatrix();
    Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
    step.linear() = R;
    step.translation() = sys.center + v - R * sys.center;
    T = step * T;
    // Keep the rotation orthonormal despite the accumulated rounding.
    T.linear() = Eigen::Quaterniond(T.rotation()).normalized().toRotationMatrix();
    res.iterations = it + 1;
    if (angle < options.min_rotation_step && v.norm() < options.min_translation_step) {
      res.converged = true;
      break;
    }
  }
  res.transform = T;

  // The statistics at the final transform.
  match(source, used, target, target_tree, T, options.max_correspondence, options.min_normal_dot, &pairs);
  res.correspondences = pairs.size();
  res.inlier_fraction = static_cast<double>(pairs.size()) / used.size();
  if (pairs.empty()) {
    res.converged = false;
    return res;
  }
  double sum2 = 0;
  for (const auto& pr : pairs) sum2 += pr.r * pr.r;
  res.rmse = std::sqrt(sum2 / pairs.size());
  const System sys = build(pairs, options.loss, kernel_for(pairs, options));
  res.hessian = sys.H;
  res.hessian_center = sys.center;
  res.scale_length = sys.L;
  res.hessian_eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>>(
                                sys.H, Eigen::EigenvaluesOnly).eigenvalues();
  res.normalized_eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>>(
                                   sys.H_scaled, Eigen::EigenvaluesOnly).eigenvalues();
  res.degenerate_directions = 0;
  for (int k = 0; k < 6; ++k)
    if (res.normalized_eigenvalues(k) < options.degenerate_threshold) ++res.degenerate_directions;
  return res;
}

Eigen::Matrix<double, 6, 6> hessian_without_unconstrained(const Eigen::Matrix<double, 6, 6>& hessian,
                                                          double scale_length, double threshold) {
  using Mat6 = Eigen::Matrix<double, 6, 6>;
  // The weight sum is the translation block's trace (unit normals).
  const double weight_sum = hessian.block<3, 3>(3, 3).trace();
  if (!(scale_length > 0) || !(weight_sum > 0)) return hessian;
  Eigen::Matrix<double, 6, 1> d;
  d << 1 / scale_length, 1 / scale_length, 1 / scale_length, 1, 1, 1;
  const Eigen::SelfAdjointEigenSolver<Mat6> eig(d.asDiagonal() * hessian * d.asDiagonal() / weight_sum);
  Mat6 kept = Mat6::Zero();
  for (int k = 0; k < 6; ++k)
    if (eig.eigenvalues()(k) >= threshold)
      kept += eig.eigenvalues()(k) * eig.eigenvectors().col(k) * eig.eigenvectors().col(k).transpose();
  const Eigen::Matrix<double, 6, 1> d_inv = d.cwiseInverse();
  return weight_sum * d_inv.asDiagonal() * kept * d_inv.asDiagonal();
}

}  // namespace efc::pipeline
