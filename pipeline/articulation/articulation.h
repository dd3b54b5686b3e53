// Which joint moved a track, and where: fixed, revolute or prismatic, chosen
// by a likelihood-plus-complexity criterion (BIC), not by a threshold.
//
// Each model explains every sample with a shared geometry and one latent
// coordinate per sample (none for fixed):
//   fixed      p_i = c,                          R_i = R
//   prismatic  p_i = c + t_i d,                  R_i = R
//   revolute   p_i = o + Rot(a, th_i)(q - o),    R_i = Rot(a, th_i) R
// Residuals are Gaussian with a floor (the tracker's precision: 1 mm, and
// 1 degree for orientations), so a noise-free track does not make the
// likelihood infinite; BIC = n_obs log(sigma^2) + k log(n_obs) per channel.
// A part that never moves is `fixed`: more parameters must pay for
// themselves. A revolute fit to a straight line needs one more parameter than
// the line and explains nothing more, so lines stay prismatic.
//
// Pose tracks that carry each sample's information matrix (a part's
// registration in efc infer) are fit and scored with their residuals
// weighted by it instead (weighted_fits.h).
//
// Point tracks (a hand, a handle): the revolute fit is a circle in 3D (the
// plane by PCA, an algebraic circle refined by Gauss-Newton on the geometric
// distance). Pose tracks: the axis from the relative rotations, then the
// axis point from the positions.
#pragma once

#include <Eigen/Geometry>

#include <limits>
#include <string>
#include <vector>

#include "pipeline/articulation/track.h"

namespace efc::pipeline {

struct ModelFit {
  bool valid = false;
  double rss_position = 0;  // sum of squared position residuals (m^2)
  double rss_rotation = 0;  // sum of squared rotation residuals (rad^2), pose tracks
  double rss_weighted = 0;  // tracks with information: sum of r^T W r (weighted_fits.h)
  int parameters = 0;
  double bic = 0;
};

struct Articulation {
  std::string type;  // "fixed", "revolute", "prismatic"
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // unit; the motion from the first sample is positive
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // revolute: the axis point nearest the track;
                                                     // prismatic: the first sample's fitted point
  double range_lo = 0, range_hi = 0;  // joint positions seen (rad or m), the first sample at 0
  double radius = 0;                  // revolute: distance of the tracked point from the axis (m)
  double residual = 0;                // RMS position residual of the chosen model (m)
  ModelFit fixed, prismatic, revolute;
  // Posterior probability of each model (softmax of -BIC / 2).
  double p_fixed = 0, p_prismatic = 0, p_revolute = 0;
  size_t samples = 0;
  // The chosen model's joint coordinate of every sample (rad or m; the first
  // sample at 0, positive along `axis`); empty for fixed.
  std::vector<double> q;
  // Pose tracks with information, the hinge fitted: the same hinge also
  // sliding along its axis (HingeFit::slide). `slide` per sample (m, along
  // `slide_axis`), and the BIC of hinge and slide together (infinite when
  // not fitted).
  Eigen::Vector3d slide_axis = Eigen::Vector3d::UnitZ();
  std::vector<double> slide;
  double slide_bic = std::numeric_limits<double>::infinity();
};

// Tracker precision floors (the residuals' smallest standard deviation).
constexpr double kPositionFloor = 0.001;  // m
constexpr double kRotationFloor = 0.0175;  // rad (1 degree)

Articulation estimate_articulation(const Track& track);
// The same with the model given ("fixed", "prismatic" or "revolute") rather
// than chosen: only that model is fitted (the others stay invalid, its
// probability 1). efc infer types a track on averaged samples, then asks
// the frame-by-frame track for the chosen model's geometry.
Articulation estimate_articulation_as(const Track& track, const std::string& type);

// The result as `efc articulate` prints it (shared/spec/cli.md).
std::string articulation_json(const Articulation& a);

}  // namespace efc::pipeline
