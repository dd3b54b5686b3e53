// The three joint models fit to a pose track whose samples carry their own
// information matrices (Track::information): each sample's residual is
// weighted by how well its registration pinned the pose down, direction by
// direction. A round button's spin about its own axis, or a flat vent's
// slide in its own plane, is noise the registration cannot see; unweighted,
// that noise looks like motion (a spinning button fits a hinge better than
// a slide), and the part's real motion loses to it. Weighted, a direction
// the part's shape does not constrain costs nothing either way.
//
// The models are those of articulation.h, each fit by Levenberg-Marquardt
// on the whitened residuals r_i (rotation vector, position) from several
// starts (the unweighted fits' geometry, each principal direction), with
// the noise's scale s over the registration's prediction fitted too:
//   BIC = RSS_w / s^2 + 12 n log s + k log(6n),  RSS_w = sum_i r_i^T W_i r_i,
//   s^2 = max(1, RSS_w / 6n)
// The information is capped at the tracker's precision floors
// (kRotationFloor, kPositionFloor: the covariance is W^-1 + F), so s = 1
// means errors at about the floors, as the unweighted fits' floor does.
// One scale for rotations and positions alike: a scale per channel lets
// each absorb its own drift, and typed no better than the unweighted fits
// (bench/part_motion_eval on 18 sequences of the suite: 12 of 31 moving
// joints typed right unweighted, 11 with two scales, 15 with one and the
// circle start).
#pragma once

#include <Eigen/Geometry>

#include <limits>
#include <vector>

#include "pipeline/articulation/track.h"

namespace efc::pipeline {

struct ModelFit;

struct LineFit {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero(), direction = Eigen::Vector3d::UnitZ();
  std::vector<double> t;  // per sample, the position along the line from centre
};

struct HingeFit {
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ(), point = Eigen::Vector3d::Zero();  // the axis line
  double radius = 0;
  std::vector<double> theta;  // per sample, the first at 0, unwrapped
  // The same hinge also sliding along its own axis (a cylinder), for a part
  // that turns about an axis through itself: its turn may be only the
  // registration slipping round a near-symmetry while the part is pressed
  // in. Per sample the slide (m, along `axis`, from the part's rest; 0
  // where a sample is better described at rest), and the BIC of hinge and
  // slide together (fit_revolute_weighted(): the slide is measured against
  // the hinge's noise scale or against the axis's own, whichever shows it
  // better). Infinite when not fitted.
  std::vector<double> slide;
  double slide_bic = std::numeric_limits<double>::infinity();
};

// Each needs track.has_information(). `starts`: hinges fit otherwise (the
// unweighted pose fit, a circle through the positions), starting points
// besides the principal directions of the rotations.
ModelFit fit_fixed_weighted(const Track& track);
ModelFit fit_prismatic_weighted(const Track& track, LineFit* line);
ModelFit fit_revolute_weighted(const Track& track, const std::vector<HingeFit>& starts, HingeFit* hinge);

}  // namespace efc::pipeline
