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
//
// A part named for a press (press_named: a button, a key) that slides
// where no track could type its motion (JointEstimate::motion_untyped: its
// few millimetres under the registration's noise, the hand's turn or slide
// its own, whether or not the name changed its type) has an estimate that
// is the hand's, not the press's (and its range the hand's wander). It
// goes into the face of the body it sits on: the body's axis most of the
// body's surface nearest the part faces along (face_it_sits_on), where the
// body is square and that surface says. (A slider's slide goes along the
// face: not the name of a press.) So does a knob's or a dial's turn
// (face_turn_named) where no track typed it: the grip's turn there is a
// fingertip's wander, tens of degrees off, while a knob turns about the
// normal of the face it stands out of (seed 0's s0005 and s0039 dials,
// their grips' turns taken onto "up", 1.57 rad off).
#pragma once

#include <Eigen/Geometry>

#include <string>

#include "pipeline/infer/body_frame.h"
#include "pipeline/infer/joint_estimate.h"

namespace efc::pipeline {

constexpr double kAxisPriorDegrees = 20;

// The body's surface nearest the part: its kFacePoints points nearest
// `at`, all within kFaceReach of it, and the share of them whose normal
// lies within kBoxNormalDegrees of one body axis at least kFaceShare.
constexpr int kFacePoints = 200;
constexpr double kFaceShare = 0.6;
constexpr double kFaceReach = 0.1;  // m

struct AxisPrior {
  std::string axis;  // the body's axis the joint was taken onto: "u", "v", "up"; empty when kept
  bool by_face = false;  // a press, taken onto the axis nearest its face's normal
  bool by_body_face = false;  // a press or knob no track typed, taken into the body's face it sits on
  Eigen::Vector3d estimated = Eigen::Vector3d::UnitZ();  // the joint's axis as estimated
  double angle = 0;  // rad, between the estimate and the body's axis nearest it
};

// The body's axis the surface of `body` (points with normals, object
// frame) nearest `at` faces along; false where the body is not square, its
// surface is not there (the part sits on another part), or no axis holds
// kFaceShare of that surface (an edge, a round patch).
bool face_it_sits_on(const BodyFrame& frame, const Cloud& body, const Eigen::Vector3d& at, Eigen::Vector3d* axis);

// Nothing for a fixed joint. `part`: the part's model with its normals
// (object frame; may be null). `body`: the body's fused surface with its
// normals, and `part_at` the part's centre (object frame, at rest), given
// for a part named for a press or a knob (may be null).
AxisPrior apply_axis_prior(const BodyFrame& frame, JointEstimate* joint, const Cloud* part = nullptr,
                           const Cloud* body = nullptr, const Eigen::Vector3d* part_at = nullptr);

}  // namespace efc::pipeline
