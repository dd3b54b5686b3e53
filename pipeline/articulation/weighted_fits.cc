#include "pipeline/articulation/weighted_fits.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>

#include "pipeline/articulation/articulation.h"

namespace efc::pipeline {
namespace {

using Eigen::Matrix3d;
using Eigen::Quaterniond;
using Eigen::Vector3d;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

Vector3d log_map(const Quaterniond& q) {
  const Eigen::AngleAxisd aa(q.normalized());
  return aa.angle() * aa.axis();
}

Quaterniond exp_map(const Vector3d& w) {
  const double angle = w.norm();
  if (angle < 1e-15) return Quaterniond::Identity();
  return Quaterniond(Eigen::AngleAxisd(angle, w / angle));
}

// The residual of an observed pose against a predicted one: the rotation
// that takes the prediction to the observation (on the left, as the
// information is given), then the position difference.
Vec6 pose_residual(const Quaterniond& r_obs, const Vector3d& p_obs, const Quaterniond& r_pred,
                   const Vector3d& p_pred) {
  Vec6 e;
  e.head<3>() = log_map(r_obs * r_pred.inverse());
  e.tail<3>() = p_obs - p_pred;
  return e;
}

// W capped at the precision floors: (W^-1 + F)^-1 = W - W (F^-1 + W)^-1 W,
// which needs no inverse of W (a direction the shape does not constrain has
// none).
Mat6 capped(const Mat6& W) {
  Vec6 f_inv;
  f_inv << Vector3d::Constant(1 / (kRotationFloor * kRotationFloor)),
      Vector3d::Constant(1 / (kPositionFloor * kPositionFloor));
  const Mat6 M = Mat6(f_inv.asDiagonal()) + W;
  Mat6 out = W - W * M.ldlt().solve(W);
  return 0.5 * (out + out.transpose());
}

// The symmetric square root (negative eigenvalues from rounding clipped).
Mat6 sqrt_of(const Mat6& W) {
  Eigen::SelfAdjointEigenSolver<Mat6> eig(W);
  const Vec6 s = eig.eigenvalues().cwiseMax(0).cwiseSqrt();
  return eig.eigenvectors() * s.asDiagonal() * eig.eigenvectors().transpose();
}

// Two unit vectors across `a`.
void across(const Vector3d& a, Vector3d* e1, Vector3d* e2) {
  *e1 = a.unitOrthogonal();
  *e2 = a.cross(*e1);
}

// The track with each sample's whitening matrix, and the noise's scale
// over what the registration predicts (one for rotations and positions
// alike: two would let a hinge whose positions drift explain its turn with
// a larger rotation scale, and the whitening then weighs nothing).
struct Weighted {
  const Track* track;
  std::vector<Mat6> root;  // sqrt of the capped information
  double scale = 1;
  explicit Weighted(const Track& t) : track(&t) {
    root.reserve(t.size());
    for (const Mat6& W : t.information) root.push_back(sqrt_of(capped(W)));
  }
  size_t size() const { return track->size(); }
  Vec6 whiten(size_t i, const Vec6& e) const { return root[i] * e / scale; }
};

// The scale that makes the residuals most likely (s^2 = RSS_w / 6n), at
// least 1: the capped information already holds the floors.
void update_scale(const std::vector<Vec6>& residuals, Weighted* w) {
  double rss = 0;
  for (size_t i = 0; i < residuals.size(); ++i) rss += (w->root[i] * residuals[i]).squaredNorm();
  w->scale = std::max(1.0, std::sqrt(rss / (6.0 * residuals.size())));
}

// Levenberg-Marquardt over a model M: M::kGlobals shared parameters and, when
// M::kLocal, one latent coordinate per sample. M provides residual(track, i)
// and retract(dg, dl) (a step from the current state). The Jacobian is by
// central differences: sample i's residual depends on the globals and its own
// coordinate only, so all coordinates move together in one evaluation.
template <class M>
double weighted_cost(const M& m, const Weighted& w) {
  double c = 0;
  for (size_t i = 0; i < w.size(); ++i) c += w.whiten(i, m.residual(*w.track, i)).squaredNorm();
  return c;
}

template <class M>
double solve_lm(M* model, const Weighted& w) {
  const int n = static_cast<int>(w.size());
  const int G = M::kGlobals, L = M::kLocal ? n : 0;
  double cost = weighted_cost(*model, w);
  double lambda = 1e-3;
  const double h = 1e-6;
  // Per sample: the whitened residual, its derivative by the globals
  // (6 x G) and by its own coordinate (6 x 1).
  std::vector<Vec6> e(n), jl(n, Vec6::Zero());
  std::vector<Eigen::Matrix<double, 6, Eigen::Dynamic>> jg(n, Eigen::Matrix<double, 6, Eigen::Dynamic>::Zero(6, G));
  for (int iter = 0; iter < 60; ++iter) {
    for (int i = 0; i < n; ++i) e[i] = w.whiten(i, model->residual(*w.track, i));
    for (int k = 0; k < G + (L > 0 ? 1 : 0); ++k) {
      M plus = *model, minus = *model;
      Eigen::VectorXd g = Eigen::VectorXd::Zero(G), l = Eigen::VectorXd::Zero(L);
      if (k < G) g(k) = h; else l.setConstant(h);
      plus.retract(g, l);
      minus.retract(-g, -l);
      for (int i = 0; i < n; ++i) {
        const Vec6 d = w.whiten(i, plus.residual(*w.track, i) - minus.residual(*w.track, i)) / (2 * h);
        if (k < G) jg[i].col(k) = d; else jl[i] = d;
      }
    }
    // The normal equations have an arrow shape (each coordinate meets only
    // the globals), so the coordinates are eliminated first (Schur
    // complement): O(n G^2), not O((n + G)^3).
    Eigen::MatrixXd Agg = Eigen::MatrixXd::Zero(G, G);
    Eigen::VectorXd gg = Eigen::VectorXd::Zero(G), all(L), gl(L);
    Eigen::MatrixXd Agl(G, L);
    for (int i = 0; i < n; ++i) {
      Agg += jg[i].transpose() * jg[i];
      gg += jg[i].transpose() * e[i];
      if (L > 0) {
        Agl.col(i) = jg[i].transpose() * jl[i];
        all(i) = jl[i].squaredNorm();
        gl(i) = jl[i].dot(e[i]);
      }
    }
    bool improved = false;
    for (int attempt = 0; attempt < 10 && !improved; ++attempt) {
      Eigen::MatrixXd S = Agg;
      for (int k = 0; k < G; ++k) S(k, k) += lambda * Agg(k, k) + 1e-12;
      Eigen::VectorXd rhs = -gg, dll(L);
      for (int i = 0; i < L; ++i) {
        dll(i) = all(i) * (1 + lambda) + 1e-12;
        S -= Agl.col(i) * Agl.col(i).transpose() / dll(i);
        rhs += Agl.col(i) * gl(i) / dll(i);
      }
      const Eigen::VectorXd dg = S.ldlt().solve(rhs);
      Eigen::VectorXd dl(L);
      for (int i = 0; i < L; ++i) dl(i) = (-gl(i) - Agl.col(i).dot(dg)) / dll(i);
      if (!dg.allFinite() || !dl.allFinite()) break;
      M trial = *model;
      trial.retract(dg, dl);
      const double c = weighted_cost(trial, w);
      if (c < cost) {
        const double gain = cost - c;
        *model = std::move(trial);
        improved = true;
        lambda = std::max(lambda / 3, 1e-9);
        if (gain < 1e-10 * cost) return c;
        cost = c;
      } else {
        lambda *= 4;
      }
    }
    if (!improved) break;
  }
  return cost;
}

struct FixedModel {
  static constexpr int kGlobals = 6;
  static constexpr bool kLocal = false;
  Quaterniond r0 = Quaterniond::Identity();
  Vector3d p0 = Vector3d::Zero();
  Vec6 residual(const Track& t, size_t i) const { return pose_residual(t.rotations[i], t.positions[i], r0, p0); }
  void retract(const Eigen::VectorXd& dg, const Eigen::VectorXd&) {
    r0 = exp_map(dg.head<3>()) * r0;
    p0 += dg.tail<3>();
  }
};

struct PrismaticModel {
  static constexpr int kGlobals = 8;
  static constexpr bool kLocal = true;
  Quaterniond r0 = Quaterniond::Identity();
  Vector3d p0 = Vector3d::Zero(), a = Vector3d::UnitZ();
  std::vector<double> t;
  Vec6 residual(const Track& tr, size_t i) const {
    return pose_residual(tr.rotations[i], tr.positions[i], r0, p0 + t[i] * a);
  }
  void retract(const Eigen::VectorXd& dg, const Eigen::VectorXd& dl) {
    Vector3d e1, e2;
    across(a, &e1, &e2);
    r0 = exp_map(dg.segment<3>(0)) * r0;
    p0 += dg.segment<3>(3);
    a = (a + dg(6) * e1 + dg(7) * e2).normalized();
    for (size_t i = 0; i < t.size(); ++i) t[i] += dl(i);
  }
};

struct RevoluteModel {
  static constexpr int kGlobals = 10;
  static constexpr bool kLocal = true;
  Vector3d a = Vector3d::UnitZ(), o = Vector3d::Zero(), q = Vector3d::Zero();
  Quaterniond r0 = Quaterniond::Identity();
  std::vector<double> theta;
  Vec6 residual(const Track& tr, size_t i) const {
    const Quaterniond turn(Eigen::AngleAxisd(theta[i], a));
    return pose_residual(tr.rotations[i], tr.positions[i], turn * r0, o + turn * (q - o));
  }
  void retract(const Eigen::VectorXd& dg, const Eigen::VectorXd& dl) {
    Vector3d e1, e2;
    across(a, &e1, &e2);
    a = (a + dg(0) * e1 + dg(1) * e2).normalized();
    o += dg(2) * e1 + dg(3) * e2;
    q += dg.segment<3>(4);
    r0 = exp_map(dg.segment<3>(7)) * r0;
    for (size_t i = 0; i < theta.size(); ++i) theta[i] += dl(i);
  }
};

Vector3d mean_position(const Track& t) {
  Vector3d m = Vector3d::Zero();
  for (const Vector3d& p : t.positions) m += p;
  return m / static_cast<double>(t.size());
}

Quaterniond mean_rotation(const std::vector<Quaterniond>& rotations) {
  Eigen::Vector4d sum = Eigen::Vector4d::Zero();
  for (const Quaterniond& r : rotations)
    sum += (r.coeffs().dot(rotations[0].coeffs()) < 0 ? -1.0 : 1.0) * r.coeffs();
  Quaterniond m;
  m.coeffs() = sum.normalized();
  return m;
}

// Principal directions of a set of vectors' scatter, by increasing variance.
Matrix3d principal_directions(const std::vector<Vector3d>& v) {
  Vector3d m = Vector3d::Zero();
  for (const Vector3d& x : v) m += x;
  m /= static_cast<double>(v.size());
  Matrix3d S = Matrix3d::Zero();
  for (const Vector3d& x : v) S += (x - m) * (x - m).transpose();
  return Eigen::SelfAdjointEigenSolver<Matrix3d>(S).eigenvectors();
}

template <class M>
std::vector<Vec6> residuals_of(const M& m, const Track& t) {
  std::vector<Vec6> out;
  for (size_t i = 0; i < t.size(); ++i) out.push_back(m.residual(t, i));
  return out;
}

// -2 log L of a fit with its scale (the BIC's first term).
double deviance(double cost, const Weighted& w) {
  return cost + 12.0 * w.size() * std::log(w.scale);
}

// The BIC of a fit whose scale was fitted too.
void finish(ModelFit* fit, double rss_weighted, const Weighted& w, const std::vector<Vec6>& residuals) {
  fit->rss_weighted = rss_weighted;
  fit->rss_position = fit->rss_rotation = 0;
  for (const Vec6& e : residuals) {
    fit->rss_rotation += e.head<3>().squaredNorm();
    fit->rss_position += e.tail<3>().squaredNorm();
  }
  fit->bic = deviance(rss_weighted, w) + fit->parameters * std::log(6.0 * w.size());
  fit->valid = std::isfinite(fit->bic);
}

// Fits, then the scale for its residuals, then fits again with it: the
// scale and the geometry maximise the likelihood together.
template <class M>
double solve_with_scale(M* model, Weighted* w) {
  for (int round = 0; round < 3; ++round) {
    solve_lm(model, *w);
    update_scale(residuals_of(*model, *w->track), w);
  }
  return weighted_cost(*model, *w);
}

// A hinge that also slides along its axis (HingeFit::slide). u[i] is
// sample i's whitened residual along the axis (unit direction), jn[i] the
// whitened length of a unit slide there (0: the sample says nothing). The
// residual is linear in the slide, so each sample's best slide and what it
// gains (-2 log L) are closed-form. A sample takes its slide only where the
// gain pays for naming it (log(6n), as a coordinate costs); the slide as a
// whole costs one more parameter. A slide from rest goes one way (a button
// pressed in, a plunger pulled out), so only the samples on one side count,
// the side that gains more: a tracker's slips along the axis go both ways
// and split their gain.
struct AxisSlide {
  std::vector<double> slide;  // m along the axis per sample, 0 at rest
  double saved = 0;           // the gains of the side kept, less their coordinates' cost
};

// The slide against a rest level and a noise scale (of u); `held_only`:
// only slides on two consecutive samples or more count.
AxisSlide axis_slide(const std::vector<double>& u, const std::vector<double>& jn, double rest, double sigma,
                     bool held_only) {
  const size_t n = u.size();
  const double per = std::log(6.0 * n);
  AxisSlide out;
  out.slide.assign(n, 0.0);
  std::vector<double> gain(n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    if (!(jn[i] > 0)) continue;
    const double d = (u[i] - rest) / sigma;
    if (d * d <= per) continue;
    gain[i] = d * d - per;
    out.slide[i] = (u[i] - rest) / jn[i];
  }
  double saved[2] = {0, 0};  // negative, positive side
  std::vector<double> kept = out.slide;
  for (size_t i = 0; i < n; ++i) {
    if (out.slide[i] == 0) continue;
    const bool side = out.slide[i] > 0;
    auto same = [&](size_t k) { return out.slide[k] != 0 && (out.slide[k] > 0) == side; };
    if (held_only && !((i > 0 && same(i - 1)) || (i + 1 < n && same(i + 1)))) {
      kept[i] = 0;
      continue;
    }
    saved[side] += gain[i];
  }
  const bool positive = saved[1] >= saved[0];
  for (double& t : kept)
    if ((t > 0) != positive) t = 0;
  out.slide = std::move(kept);
  out.saved = saved[positive];
  return out;
}

double median_of_copy(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// Two noise models, the better kept:
// - the hinge's own: rest at the hinge's reference, noise its scale (a
//   ram's slide, where the hinge fits all else);
// - the axis's own, from the along-axis residuals themselves: rest at the
//   level most samples share within their jitter (consecutive samples'
//   differences: a held press changes the level twice, not every sample,
//   so a ram driven out for most of the clip still leaves its rest apart),
//   noise their median absolute deviation from it (a slow wander counts,
//   unlike in the jitter). The hinge's scale is the residuals' over all six
//   directions; a round part's spin and its slips across its face (weakly
//   constrained, yet not weightless) inflate it far above the noise of the
//   face's offset along its normal, where a button's press shows, and the
//   hinge's reference sits between rest and pressed. A press is held: here
//   only slides on two consecutive samples or more count (a registration
//   that jumps for one sample is not a press).
AxisSlide best_axis_slide(const std::vector<double>& u, const std::vector<double>& jn) {
  AxisSlide best = axis_slide(u, jn, 0.0, 1.0, false);
  std::vector<double> values;
  for (size_t i = 0; i < u.size(); ++i)
    if (jn[i] > 0) values.push_back(u[i]);
  if (values.size() < 3) return best;
  std::vector<double> steps;
  for (size_t i = 1; i < values.size(); ++i) steps.push_back(std::abs(values[i] - values[i - 1]));
  const double jitter = std::max(1.4826 * median_of_copy(steps) / std::sqrt(2.0), 1e-9);
  double rest = median_of_copy(values);
  size_t most = 0;
  for (double level : values) {
    size_t near = 0;
    for (double v : values) near += std::abs(v - level) < jitter;
    if (near > most) most = near, rest = level;
  }
  std::vector<double> off;
  for (double v : values) off.push_back(std::abs(v - rest));
  const double sigma = std::max(1.4826 * median_of_copy(off), jitter);
  AxisSlide own = axis_slide(u, jn, rest, sigma, true);
  return own.saved > best.saved ? own : best;
}

}  // namespace

ModelFit fit_fixed_weighted(const Track& track) {
  ModelFit fit;
  if (!track.has_information() || track.size() < 2) return fit;
  Weighted w(track);
  FixedModel m;
  m.r0 = mean_rotation(track.rotations);
  m.p0 = mean_position(track);
  const double cost = solve_with_scale(&m, &w);
  fit.parameters = 6;
  finish(&fit, cost, w, residuals_of(m, track));
  return fit;
}

ModelFit fit_prismatic_weighted(const Track& track, LineFit* line) {
  ModelFit fit;
  if (!track.has_information() || track.size() < 3) return fit;
  const Weighted unscaled(track);
  const Vector3d centre = mean_position(track);
  const Matrix3d dirs = principal_directions(track.positions);
  double best = std::numeric_limits<double>::infinity(), best_cost = 0;
  PrismaticModel chosen;
  Weighted chosen_w = unscaled;
  for (int k = 2; k >= 0; --k) {  // from the direction of most motion
    PrismaticModel m;
    m.r0 = mean_rotation(track.rotations);
    m.p0 = centre;
    m.a = dirs.col(k);
    for (const Vector3d& p : track.positions) m.t.push_back(m.a.dot(p - centre));
    Weighted w = unscaled;
    const double cost = solve_with_scale(&m, &w);
    if (deviance(cost, w) < best) best = deviance(cost, w), best_cost = cost, chosen = m, chosen_w = w;
  }
  line->centre = chosen.p0;
  line->direction = chosen.a;
  line->t = chosen.t;
  fit.parameters = 7 + static_cast<int>(track.size());
  finish(&fit, best_cost, chosen_w, residuals_of(chosen, track));
  return fit;
}

ModelFit fit_revolute_weighted(const Track& track, const std::vector<HingeFit>& starts, HingeFit* hinge) {
  ModelFit fit;
  if (!track.has_information() || track.size() < 3) return fit;
  const Weighted unscaled(track);
  const size_t n = track.size();
  // Starting axes: the unweighted fit's, each principal direction of the
  // rotations (relative to their mean), and the normal of the positions'
  // plane; the axis point the unweighted fit's, else the positions' centre.
  const Quaterniond mean = mean_rotation(track.rotations);
  std::vector<Vector3d> w_rel;
  for (const Quaterniond& r : track.rotations) w_rel.push_back(log_map(r * mean.inverse()));
  const Matrix3d rot_dirs = principal_directions(w_rel);
  const Matrix3d pos_dirs = principal_directions(track.positions);
  const Vector3d centre = mean_position(track);
  std::vector<RevoluteModel> models;
  for (const HingeFit& h : starts) {
    if (h.theta.size() != n) continue;
    RevoluteModel m;
    m.a = h.axis.normalized();
    m.o = h.point;
    m.theta = h.theta;
    models.push_back(m);
  }
  const std::vector<Vector3d> directions = {rot_dirs.col(2), rot_dirs.col(1), rot_dirs.col(0), pos_dirs.col(0)};
  for (const Vector3d& axis : directions) {
    RevoluteModel m;
    m.a = axis.normalized();
    m.o = centre;
    for (const Vector3d& x : w_rel) m.theta.push_back(x.dot(m.a));
    models.push_back(m);
  }
  double best = std::numeric_limits<double>::infinity(), best_cost = 0;
  RevoluteModel chosen;
  Weighted chosen_w = unscaled;
  for (RevoluteModel& m : models) {
    // The reference orientation and point: each sample's turned back.
    std::vector<Quaterniond> back;
    m.q = Vector3d::Zero();
    for (size_t i = 0; i < n; ++i) {
      const Eigen::AngleAxisd undo(-m.theta[i], m.a);
      back.push_back(Quaterniond(undo) * track.rotations[i]);
      m.q += m.o + undo * (track.positions[i] - m.o);
    }
    m.q /= static_cast<double>(n);
    m.r0 = mean_rotation(back);
    Weighted w = unscaled;
    const double cost = solve_with_scale(&m, &w);
    if (deviance(cost, w) < best) best = deviance(cost, w), best_cost = cost, chosen = m, chosen_w = w;
  }
  const double theta0 = chosen.theta.empty() ? 0 : chosen.theta[0];
  hinge->axis = chosen.a;
  hinge->point = chosen.o;
  hinge->radius = ((chosen.q - chosen.o) - (chosen.q - chosen.o).dot(chosen.a) * chosen.a).norm();
  hinge->theta.clear();
  for (double t : chosen.theta) hinge->theta.push_back(t - theta0);
  fit.parameters = 10 + static_cast<int>(n);
  finish(&fit, best_cost, chosen_w, residuals_of(chosen, track));
  // The hinge also sliding along its axis (HingeFit::slide): each sample's
  // whitened residual along the axis (AxisSlide).
  Vec6 along = Vec6::Zero();
  along.tail<3>() = chosen.a;
  std::vector<double> u(n, 0.0), jn(n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    const Vec6 e = chosen_w.whiten(i, chosen.residual(track, i)), j = chosen_w.whiten(i, along);
    jn[i] = j.norm();
    if (jn[i] > 0) u[i] = j.dot(e) / jn[i];
  }
  const AxisSlide slide = best_axis_slide(u, jn);
  hinge->slide = slide.slide;
  if (fit.valid) hinge->slide_bic = fit.bic + std::log(6.0 * n) - slide.saved;
  return fit;
}

}  // namespace efc::pipeline
