// The body's axes as a prior on its joints' axes. A joint's axis is taken
// onto the nearest of the body's axes (body_frame.h: its two horizontal axes
// where the body is square, and up, which gravity gives, always) where the
// estimate lies within kAxisPriorDegrees of it: a door's hinge read 8
// degrees off upright is upright. The width, 20 degrees, is where the
// suites' mean axis error stops falling (bench/README, "The body's axes as a
// prior on the joints' axes"); an estimate further off every axis is kept as
// it is (a lamp's arm on a slanted hinge, or a joint the estimator got
// wrong, which the prior would only make wrong along another axis). A
// hinge's axis turns about its origin, the axis point nearest the part's
// track, which stays on it. (Fitting the hinge's point again on the new
// axis, from the part's or the grip's registered poses, put it further from
// the truth on seed 1: origin error summed over its joints 0.19 m worse;
// bench/README.) The joint's positions q stay as measured (the angle between
// the two axes is at most kAxisPriorDegrees).
//
// A press (a slide of at most kMaxDriftedPress) on a square body whose
// estimate lies off every body axis is taken onto the body's axis nearest
// its face's normal (best_shown_slide): a button's few millimetres of
// travel, beside the registration's millimetre and a finger's wander
// across its face, do not put its axis anywhere the body's square does
// not, and its face, seen on hundreds of points, says which of the body's
// axes it presses along. It keeps the estimate's sense, and its q as
// measured along the estimate.
#pragma once

#include <Eigen/Geometry>

#include <string>

#include "pipeline/infer/body_frame.h"
#include "pipeline/infer/joint_estimate.h"

namespace efc::pipeline {

constexpr double kAxisPriorDegrees = 20;

struct AxisPrior {
  std::string axis;  // the body's axis the joint was taken onto: "u", "v", "up"; empty when kept
  bool by_face = false;  // a press, taken onto the axis nearest its face's normal
  Eigen::Vector3d estimated = Eigen::Vector3d::UnitZ();  // the joint's axis as estimated
  double angle = 0;  // rad, between the estimate and the body's axis nearest it
};

// Nothing for a fixed joint. `part`: the part's model with its normals
// (object frame; may be null).
AxisPrior apply_axis_prior(const BodyFrame& frame, JointEstimate* joint, const Cloud* part = nullptr);

}  // namespace efc::pipeline
