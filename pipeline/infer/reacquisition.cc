#include "pipeline/infer/reacquisition.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>

namespace efc::pipeline {
namespace {

// The points' covariance, decomposed: principal axes (columns, the thinnest
// first) and variances.
Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> spread(const Cloud& c) {
  const Eigen::Vector3d mean = centroid(c);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : c.points) cov += (p - mean) * (p - mean).transpose();
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov / static_cast<double>(std::max<size_t>(1, c.size())));
}

// The mean distance between the model's points moved by a and by b (at
// most 200 of them).
double mean_displacement(const Cloud& model, const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  const size_t stride = std::max<size_t>(1, model.size() / 200);
  double sum = 0;
  int count = 0;
  for (size_t i = 0; i < model.size(); i += stride, ++count) sum += (a * model.points[i] - b * model.points[i]).norm();
  return count ? sum / count : 0.0;
}

}  // namespace

std::vector<Eigen::Isometry3d> reacquisition_starts(const Cloud& frame, const Cloud& model,
                                                    const std::vector<Eigen::Isometry3d>& registered) {
  std::vector<Eigen::Isometry3d> starts = registered;
  const Eigen::Vector3d cf = centroid(frame), cm = centroid(model);
  const Eigen::Matrix3d model_axes = spread(model).eigenvectors();
  const std::vector<Eigen::Vector3d> axes = {model_axes.col(0), model_axes.col(1), model_axes.col(2),
                                             Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                                             Eigen::Vector3d::UnitZ()};
  auto add = [&](const Eigen::Matrix3d& R) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = R;
    T.translation() = cm - R * cf;
    starts.push_back(T);
  };
  add(Eigen::Matrix3d::Identity());
  constexpr double kPi = 3.14159265358979323846;
  for (const Eigen::Vector3d& a : axes)
    for (double angle = kReacquireStep; angle <= kPi + 1e-9; angle += kReacquireStep) {
      add(Eigen::AngleAxisd(angle, a.normalized()).toRotationMatrix());
      if (angle < kPi - 1e-9) add(Eigen::AngleAxisd(-angle, a.normalized()).toRotationMatrix());
    }
  return starts;
}

Cloud with_back_face(const Cloud& model) {
  if (!model.has_normals() || model.size() < 50) return model;
  const Eigen::Vector3d mean = centroid(model);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig = spread(model);
  const double thin = std::sqrt(std::max(0.0, eig.eigenvalues()(0))), narrow = std::sqrt(eig.eigenvalues()(1));
  if (!(narrow > 0.02 && thin < 0.15 * narrow)) return model;  // not a plate of a few centimetres or more
  Eigen::Vector3d n = eig.eigenvectors().col(0);
  Eigen::Vector3d mean_normal = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& m : model.normals) mean_normal += m;
  if (n.dot(mean_normal) < 0) n = -n;
  size_t on_face = 0;
  for (const Eigen::Vector3d& m : model.normals) on_face += m.dot(n) >= 0.7;
  if (on_face * 2 < model.size()) return model;  // mostly edges, or a curved part
  // The thickness its edges show, where they are seen (the spread of the
  // points along the normal, from 2nd to 98th percentile).
  std::vector<double> along;
  for (const Eigen::Vector3d& p : model.points) along.push_back((p - mean).dot(n));
  std::sort(along.begin(), along.end());
  const double seen = along[along.size() * 98 / 100] - along[along.size() * 2 / 100];
  const double depth = seen > 0.005 ? std::min(seen, 0.05) : kBackFaceDepth;
  Cloud out = model;
  for (size_t i = 0; i < model.size(); ++i) {
    if (model.normals[i].dot(n) < 0.7) continue;  // the edges keep one side
    out.points.push_back(model.points[i] - depth * n);
    out.normals.push_back(-model.normals[i]);
  }
  return out;
}

const IcpResult* nearest_of_the_best(const std::vector<IcpResult>& fits, const Cloud& model,
                                     const std::vector<Eigen::Isometry3d>& beside) {
  double most = 0;
  for (const IcpResult& r : fits) most = std::max(most, r.inlier_fraction);
  const std::vector<Eigen::Isometry3d> near =
      beside.empty() ? std::vector<Eigen::Isometry3d>{Eigen::Isometry3d::Identity()} : beside;
  // How far a fit puts the part from the nearest of those poses (frame ->
  // model transforms: the part's motion is their inverse).
  auto away = [&](const IcpResult& r) {
    double d = std::numeric_limits<double>::infinity();
    for (const Eigen::Isometry3d& b : near) d = std::min(d, mean_displacement(model, r.transform.inverse(), b.inverse()));
    return d;
  };
  const IcpResult* chosen = nullptr;
  double chosen_away = 0;
  for (const IcpResult& r : fits) {
    if (r.inlier_fraction < most - kReacquireTie) continue;
    const double a = away(r);
    if (!chosen || a < chosen_away) chosen = &r, chosen_away = a;
  }
  return chosen;
}

}  // namespace efc::pipeline
