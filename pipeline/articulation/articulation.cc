#include "pipeline/articulation/articulation.h"

#include "pipeline/articulation/weighted_fits.h"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <limits>

#include <nlohmann/json.hpp>

namespace efc::pipeline {
namespace {

using Eigen::Matrix3d;
using Eigen::Quaterniond;
using Eigen::Vector3d;

constexpr double kPi = 3.14159265358979323846;

Vector3d mean_of(const std::vector<Vector3d>& p) {
  Vector3d m = Vector3d::Zero();
  for (const Vector3d& x : p) m += x;
  return m / static_cast<double>(p.size());
}

// Eigenvectors of the scatter of `v` about `centre`, by increasing eigenvalue.
Matrix3d principal_axes(const std::vector<Vector3d>& v, const Vector3d& centre) {
  Matrix3d S = Matrix3d::Zero();
  for (const Vector3d& x : v) S += (x - centre) * (x - centre).transpose();
  Eigen::SelfAdjointEigenSolver<Matrix3d> eig(S);
  return eig.eigenvectors();
}

// The rotation that best stands for all of `q` (the normalised sum of the
// quaternions, signs aligned with the first: the chordal L2 mean, near enough
// for rotations this close together).
Quaterniond mean_rotation(const std::vector<Quaterniond>& q) {
  Eigen::Vector4d sum = Eigen::Vector4d::Zero();
  for (const Quaterniond& x : q) sum += (x.coeffs().dot(q[0].coeffs()) < 0 ? -1.0 : 1.0) * x.coeffs();
  Quaterniond m;
  m.coeffs() = sum.normalized();
  return m;
}

double angle_between(const Quaterniond& a, const Quaterniond& b) {
  return Eigen::AngleAxisd(a.inverse() * b).angle();
}

// Fills the BIC of a fit over n samples (positions, and rotations when present).
void score(ModelFit* fit, size_t n, bool rotations) {
  const double n_pos = 3.0 * n, n_rot = rotations ? 3.0 * n : 0.0;
  double bic = n_pos * std::log(fit->rss_position / n_pos + kPositionFloor * kPositionFloor);
  if (rotations) bic += n_rot * std::log(fit->rss_rotation / n_rot + kRotationFloor * kRotationFloor);
  fit->bic = bic + fit->parameters * std::log(n_pos + n_rot);
  fit->valid = std::isfinite(fit->bic);
}

double rotation_rss_about(const std::vector<Quaterniond>& rotations, const Quaterniond& constant) {
  double rss = 0;
  for (const Quaterniond& r : rotations) rss += std::pow(angle_between(constant, r), 2);
  return rss;
}

ModelFit fit_fixed(const Track& track) {
  ModelFit fit;
  const Vector3d c = mean_of(track.positions);
  for (const Vector3d& p : track.positions) fit.rss_position += (p - c).squaredNorm();
  fit.parameters = 3;
  if (track.has_rotations()) {
    fit.rss_rotation = rotation_rss_about(track.rotations, mean_rotation(track.rotations));
    fit.parameters += 3;
  }
  score(&fit, track.size(), track.has_rotations());
  return fit;
}

ModelFit fit_prismatic(const Track& track, LineFit* line) {
  ModelFit fit;
  line->centre = mean_of(track.positions);
  line->direction = principal_axes(track.positions, line->centre).col(2);
  line->t.clear();
  for (const Vector3d& p : track.positions) {
    const double t = line->direction.dot(p - line->centre);
    line->t.push_back(t);
    fit.rss_position += (p - line->centre - t * line->direction).squaredNorm();
  }
  // A line has four degrees of freedom (a direction, a point across it).
  fit.parameters = 4 + static_cast<int>(track.size());
  if (track.has_rotations()) {
    fit.rss_rotation = rotation_rss_about(track.rotations, mean_rotation(track.rotations));
    fit.parameters += 3;
  }
  score(&fit, track.size(), track.has_rotations());
  return fit;
}

// Unwraps angles into a continuous sequence starting at 0.
std::vector<double> unwrap_from_first(const std::vector<double>& raw) {
  std::vector<double> out(raw.size());
  double offset = 0;
  for (size_t i = 0; i < raw.size(); ++i) {
    if (i > 0) {
      double step = raw[i] - raw[i - 1];
      if (step > kPi) offset -= 2 * kPi;
      if (step < -kPi) offset += 2 * kPi;
    }
    out[i] = raw[i] + offset - raw[0];
  }
  return out;
}

// A circle through the points: the plane by PCA, then the circle in it.
ModelFit fit_revolute_points(const Track& track, HingeFit* hinge) {
  ModelFit fit;
  const size_t n = track.size();
  const Vector3d m = mean_of(track.positions);
  const Matrix3d axes = principal_axes(track.positions, m);
  const Vector3d normal = axes.col(0), e1 = axes.col(2), e2 = axes.col(1);
  Eigen::MatrixXd A(n, 3);
  Eigen::VectorXd b(n);
  std::vector<double> u(n), v(n), w(n);
  for (size_t i = 0; i < n; ++i) {
    const Vector3d d = track.positions[i] - m;
    u[i] = d.dot(e1), v[i] = d.dot(e2), w[i] = d.dot(normal);
    A.row(i) << 2 * u[i], 2 * v[i], 1;
    b(i) = u[i] * u[i] + v[i] * v[i];
  }
  // Algebraic (Kasa) circle, then Gauss-Newton on the geometric distance.
  const Eigen::Vector3d x = A.colPivHouseholderQr().solve(b);
  double cu = x(0), cv = x(1), r2 = x(2) + cu * cu + cv * cv;
  if (!(r2 > 0) || !std::isfinite(r2)) return fit;
  double r = std::sqrt(r2);
  for (int iter = 0; iter < 20; ++iter) {
    Eigen::MatrixXd J(n, 3);
    Eigen::VectorXd e(n);
    for (size_t i = 0; i < n; ++i) {
      const double du = u[i] - cu, dv = v[i] - cv, dist = std::max(std::hypot(du, dv), 1e-12);
      e(i) = dist - r;
      J.row(i) << -du / dist, -dv / dist, -1;
    }
    const Eigen::Vector3d step = J.colPivHouseholderQr().solve(-e);
    if (!step.allFinite()) return fit;
    cu += step(0), cv += step(1), r += step(2);
    if (step.norm() < 1e-12) break;
  }
  r = std::fabs(r);
  // Then the plane too: Gauss-Newton on each sample's distance to the 3D
  // circle (out of the plane, and from the rim within it), over the centre,
  // the normal (two tilts) and the radius.
  Vector3d centre = m + cu * e1 + cv * e2, axis = normal;
  auto residuals = [&](const Vector3d& c, const Vector3d& a, double radius, Eigen::VectorXd* e) {
    e->resize(2 * n);
    for (size_t i = 0; i < n; ++i) {
      const Vector3d d = track.positions[i] - c;
      const double along = d.dot(a);
      (*e)(2 * i) = along;
      (*e)(2 * i + 1) = (d - along * a).norm() - radius;
    }
  };
  for (int iter = 0; iter < 30; ++iter) {
    const Vector3d t1 = axis.unitOrthogonal(), t2 = axis.cross(t1);
    auto apply = [&](const Eigen::Matrix<double, 6, 1>& x, Vector3d* c, Vector3d* a, double* radius) {
      *c = centre + x.head<3>();
      *a = (axis + x(3) * t1 + x(4) * t2).normalized();
      *radius = r + x(5);
    };
    Eigen::VectorXd e0;
    residuals(centre, axis, r, &e0);
    Eigen::MatrixXd J(2 * n, 6);
    for (int k = 0; k < 6; ++k) {  // central differences: six parameters, cheap
      Eigen::Matrix<double, 6, 1> dx = Eigen::Matrix<double, 6, 1>::Zero();
      const double h = 1e-7 * std::max(1.0, r);
      dx(k) = h;
      Vector3d c;
      Vector3d a;
      double radius;
      Eigen::VectorXd ep, em;
      apply(dx, &c, &a, &radius);
      residuals(c, a, radius, &ep);
      apply(-dx, &c, &a, &radius);
      residuals(c, a, radius, &em);
      J.col(k) = (ep - em) / (2 * h);
    }
    const Eigen::Matrix<double, 6, 1> step = J.colPivHouseholderQr().solve(-e0);
    if (!step.allFinite()) break;
    Vector3d c, a;
    double radius;
    apply(step, &c, &a, &radius);
    Eigen::VectorXd e1v;
    residuals(c, a, radius, &e1v);
    if (e1v.squaredNorm() > e0.squaredNorm()) break;  // no better: keep what we have
    centre = c, axis = a, r = radius;
    if (step.norm() < 1e-12) break;
  }
  r = std::fabs(r);
  const Vector3d f1 = axis.unitOrthogonal(), f2 = axis.cross(f1);
  std::vector<double> raw(n);
  for (size_t i = 0; i < n; ++i) {
    const Vector3d d = track.positions[i] - centre;
    const double along = d.dot(axis);
    fit.rss_position += std::pow((d - along * axis).norm() - r, 2) + along * along;
    raw[i] = std::atan2(d.dot(f2), d.dot(f1));
  }
  hinge->axis = axis;
  hinge->point = centre;
  hinge->radius = r;
  hinge->theta = unwrap_from_first(raw);
  fit.parameters = 6 + static_cast<int>(n);
  score(&fit, n, false);
  return fit;
}

// A hinge from a pose track: the axis from the relative rotations, the axis
// point from the positions (each sample's position is the reference point
// turned about the axis).
ModelFit fit_revolute_poses(const Track& track, HingeFit* hinge) {
  ModelFit fit;
  const size_t n = track.size();
  // The axis and the angles from the rotations relative to a reference
  // orientation: first the first sample's, then the mean of the samples
  // turned back (one noisy first sample would otherwise tilt the axis).
  Quaterniond reference = track.rotations[0];
  Vector3d axis = Vector3d::UnitZ();
  std::vector<double> theta(n);
  for (int pass = 0; pass < 3; ++pass) {
    std::vector<Vector3d> w(n);
    for (size_t i = 0; i < n; ++i) {
      const Eigen::AngleAxisd aa(track.rotations[i] * reference.inverse());
      w[i] = aa.angle() * aa.axis();
    }
    Matrix3d S = Matrix3d::Zero();
    for (const Vector3d& x : w) S += x * x.transpose();
    if (S.trace() < 1e-18) return fit;  // no rotation at all: not a hinge
    Eigen::SelfAdjointEigenSolver<Matrix3d> eig(S);
    axis = eig.eigenvectors().col(2).normalized();
    for (size_t i = 0; i < n; ++i) theta[i] = w[i].dot(axis);
    std::vector<Quaterniond> back(n);
    for (size_t i = 0; i < n; ++i) back[i] = Quaterniond(Eigen::AngleAxisd(-theta[i], axis)) * track.rotations[i];
    reference = mean_rotation(back);
  }
  // Angles from the first sample.
  const double theta0 = theta[0];
  for (double& t : theta) t -= theta0;
  std::vector<Matrix3d> turn(n);
  for (size_t i = 0; i < n; ++i) turn[i] = Eigen::AngleAxisd(theta[i], axis).toRotationMatrix();
  const Vector3d m = mean_of(track.positions);
  // (I - Rot_i) o = p_i - Rot_i q, with a . o = a . m fixing o along the axis;
  // q (the reference point) and o refined in turn. Samples are reweighted
  // (Cauchy weights on the residual, its scale from the median) so a few
  // bad marker detections do not drag the axis: real pose trackers have them.
  Vector3d q = track.positions[0], o = m;
  std::vector<double> weight(n, 1.0);
  for (int iter = 0; iter < 8; ++iter) {
    Eigen::MatrixXd A(3 * n + 1, 3);
    Eigen::VectorXd b(3 * n + 1);
    for (size_t i = 0; i < n; ++i) {
      A.block<3, 3>(3 * i, 0) = weight[i] * (Matrix3d::Identity() - turn[i]);
      b.segment<3>(3 * i) = weight[i] * (track.positions[i] - turn[i] * q);
    }
    A.row(3 * n) = axis.transpose();
    b(3 * n) = axis.dot(m);
    o = A.colPivHouseholderQr().solve(b);
    Vector3d sum = Vector3d::Zero();
    double total = 0;
    for (size_t i = 0; i < n; ++i) {
      sum += weight[i] * (o + turn[i].transpose() * (track.positions[i] - o));
      total += weight[i];
    }
    q = sum / total;
    std::vector<double> r(n);
    for (size_t i = 0; i < n; ++i) r[i] = (track.positions[i] - (o + turn[i] * (q - o))).norm();
    std::vector<double> sorted = r;
    std::nth_element(sorted.begin(), sorted.begin() + n / 2, sorted.end());
    const double scale = std::max(1.4826 * sorted[n / 2], kPositionFloor);
    for (size_t i = 0; i < n; ++i) weight[i] = 1.0 / (1.0 + std::pow(r[i] / (2.5 * scale), 2));
  }
  std::vector<Quaterniond> unturned(n);
  for (size_t i = 0; i < n; ++i) {
    fit.rss_position += (track.positions[i] - (o + turn[i] * (q - o))).squaredNorm();
    unturned[i] = Quaterniond(turn[i]).inverse() * track.rotations[i];
  }
  const Quaterniond ref = mean_rotation(unturned);
  for (size_t i = 0; i < n; ++i) fit.rss_rotation += std::pow(angle_between(Quaterniond(turn[i]) * ref, track.rotations[i]), 2);
  hinge->axis = axis;
  hinge->point = o;
  hinge->radius = ((q - o) - (q - o).dot(axis) * axis).norm();
  hinge->theta = theta;
  // The axis line (4), the reference point (3) and orientation (3).
  fit.parameters = 10 + static_cast<int>(n);
  score(&fit, n, true);
  return fit;
}

}  // namespace

Articulation estimate_articulation(const Track& track) { return estimate_articulation_as(track, ""); }

Articulation estimate_articulation_as(const Track& track, const std::string& forced) {
  Articulation a;
  a.samples = track.size();
  if (track.size() < 3) return a;
  LineFit line;
  HingeFit hinge;
  // With the model given, only that one is fitted: its geometry is what is
  // asked for (the weighted fits are the articulation stage's main cost).
  const bool want_fixed = forced.empty() || forced == "fixed";
  const bool want_prismatic = forced.empty() || forced == "prismatic";
  const bool want_revolute = forced.empty() || forced == "revolute";
  if (track.has_information()) {
    // Registered poses: each sample weighted by what its registration saw
    // (weighted_fits.h), the unweighted hinges among the starting points.
    if (want_fixed) a.fixed = fit_fixed_weighted(track);
    if (want_prismatic) a.prismatic = fit_prismatic_weighted(track, &line);
    if (want_revolute) {
      HingeFit from_poses, from_points;
      fit_revolute_poses(track, &from_poses);
      fit_revolute_points(track, &from_points);
      a.revolute = fit_revolute_weighted(track, {from_poses, from_points}, &hinge);
      a.slide_axis = hinge.axis;
      a.slide = hinge.slide;
      a.slide_bic = hinge.slide_bic;
    }
  } else {
    if (want_fixed) a.fixed = fit_fixed(track);
    if (want_prismatic) a.prismatic = fit_prismatic(track, &line);
    if (want_revolute)
      a.revolute = track.has_rotations() ? fit_revolute_poses(track, &hinge) : fit_revolute_points(track, &hinge);
  }

  double best = std::numeric_limits<double>::infinity();
  for (const ModelFit* f : {&a.fixed, &a.prismatic, &a.revolute})
    if (f->valid) best = std::min(best, f->bic);
  auto weight = [&](const ModelFit& f) { return f.valid ? std::exp(-(f.bic - best) / 2) : 0.0; };
  const double total = weight(a.fixed) + weight(a.prismatic) + weight(a.revolute);
  a.p_fixed = weight(a.fixed) / total;
  a.p_prismatic = weight(a.prismatic) / total;
  a.p_revolute = weight(a.revolute) / total;

  const size_t n = track.size();
  const Vector3d centroid = mean_of(track.positions);
  const bool choose_revolute = forced.empty() ? a.revolute.valid && a.revolute.bic == best
                                              : forced == "revolute" && a.revolute.valid;
  const bool choose_prismatic = forced.empty() ? a.prismatic.valid && a.prismatic.bic == best
                                               : forced == "prismatic" && a.prismatic.valid;
  if (choose_revolute) {
    a.type = "revolute";
    // Positive from the first sample to the last.
    const double sign = hinge.theta.back() < 0 ? -1.0 : 1.0;
    a.axis = sign * hinge.axis;
    a.origin = hinge.point + (centroid - hinge.point).dot(hinge.axis) * hinge.axis;
    a.radius = hinge.radius;
    a.range_lo = a.range_hi = 0;
    for (double t : hinge.theta) {
      a.range_lo = std::min(a.range_lo, sign * t);
      a.range_hi = std::max(a.range_hi, sign * t);
      a.q.push_back(sign * t);
    }
    a.residual = std::sqrt(a.revolute.rss_position / n);
  } else if (choose_prismatic) {
    a.type = "prismatic";
    const double sign = line.t.back() < line.t.front() ? -1.0 : 1.0;
    a.axis = sign * line.direction;
    a.origin = line.centre + line.t.front() * line.direction;
    double lo = 0, hi = 0;
    for (double t : line.t) {
      lo = std::min(lo, sign * (t - line.t.front()));
      hi = std::max(hi, sign * (t - line.t.front()));
      a.q.push_back(sign * (t - line.t.front()));
    }
    a.range_lo = lo, a.range_hi = hi;
    a.residual = std::sqrt(a.prismatic.rss_position / n);
  } else {
    a.type = "fixed";
    a.origin = centroid;
    a.residual = std::sqrt(a.fixed.rss_position / n);
  }
  return a;
}

std::string articulation_json(const Articulation& a) {
  using nlohmann::json;
  auto vec = [](const Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); };
  auto bic = [](const ModelFit& f) { return f.valid ? json(f.bic) : json(nullptr); };
  json out = {{"type", a.type},
              {"axis", vec(a.axis)},
              {"origin", vec(a.origin)},
              {"range", json::array({a.range_lo, a.range_hi})},
              {"residual", a.residual},
              {"scores", {{"fixed", a.p_fixed}, {"prismatic", a.p_prismatic}, {"revolute", a.p_revolute}}},
              {"bic", {{"fixed", bic(a.fixed)}, {"prismatic", bic(a.prismatic)}, {"revolute", bic(a.revolute)}}},
              {"samples", a.samples}};
  if (a.type == "revolute") out["radius"] = a.radius;
  return out.dump();
}

}  // namespace efc::pipeline
