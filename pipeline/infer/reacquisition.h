// efc infer, part tracking: finding a part again after a leap. A part that
// moves by tens of degrees between two frames (a lid a servo snaps open, a
// door flung wide) leaves ICP's basin, and every frame of that state is lost
// with it, though each shows the part plainly. Where at least
// kReacquireRun consecutive frames are lost, each with kReacquireMinPoints
// points or more of which the chain's registration matched almost none
// (under kReacquireLost: out of the basin altogether, not a part pulled so
// far that little of it shows, whose chained pose is roughly right), and
// the part's points leap further than the registration reaches at an end
// of the run (a part that left the basin slowly, a drawer shut until only
// its front shows, was lost to something else, and a global search there
// finds a wrong turn as readily as the right pose), the run's frame with
// most points is registered from a global set of starts
// (reacquisition_starts()) and the chain goes on from it through the run
// (part_tracking.cc). Among fits almost as good as the best (kReacquireTie
// of the inliers), the one nearest the part's pose next to the run is kept:
// a flat face fits itself turned about its normal as well as not, and a box
// turned about a face as well as slid along it.
#pragma once

#include <Eigen/Geometry>

#include <cstddef>
#include <vector>

#include "pipeline/cloud/cloud.h"
#include "pipeline/cloud/icp.h"

namespace efc::pipeline {

constexpr size_t kReacquireMinPoints = 60;
constexpr int kReacquireRun = 3;
constexpr double kReacquireLost = 0.2;
constexpr double kReacquireTie = 0.05;
// The turns tried about each axis: every 30 degrees up to half a turn.
constexpr double kReacquireStep = 30.0 * 3.14159265358979323846 / 180.0;

// Starts (frame -> model) for a frame the chain did not register: the
// `registered` poses as they are, then the frame's centroid onto the
// model's, turned about each of the model's principal axes and the object's
// axes by every kReacquireStep up to half a turn.
std::vector<Eigen::Isometry3d> reacquisition_starts(const Cloud& frame, const Cloud& model,
                                                    const std::vector<Eigen::Isometry3d>& registered);

// A thin flat part (a lid, a door panel) shows one face at rest and, once it
// opens, often the other (a chest lid lifts its inside towards the person in
// front). A model of the seen face alone fits the open part only flipped
// over, so the search gets the unseen face too: the seen face's points as
// far behind it as its edges show the part thick (else kBackFaceDepth, a
// centimetre or two for such parts), facing the other way. Any other model
// is returned as it is. Only runs found again are registered onto it:
// registration never pairs points whose normals disagree, so a frame that
// shows the front face still matches the front alone, but a closed drawer's
// front is a plate too, and its track is best left to the face it shows.
constexpr double kBackFaceDepth = 0.015;
Cloud with_back_face(const Cloud& model);

// Among `fits` (frame -> model) within kReacquireTie of the best inliers,
// the one that puts the model's points nearest, on average, to where the
// poses `beside` put them (the part just before and after the run; at rest
// when there are none). Null when `fits` is empty.
const IcpResult* nearest_of_the_best(const std::vector<IcpResult>& fits, const Cloud& model,
                                     const std::vector<Eigen::Isometry3d>& beside);

}  // namespace efc::pipeline
