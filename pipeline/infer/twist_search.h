// efc infer, stage 4: a held knob's turn, frame by frame, searched about its
// hinge once the hinge is known.
//
// A registration follows a part from where it last was (part_tracking.h):
// a turn faster than its reach is missed. The synthetic hand turns a knob
// about a radian a frame, and the grip's registration settles a fraction of
// the way there, or half a turn off (seed 0's s0045 right knob: its grip
// turned 0.1 rad a frame the wrong way while the knob turned 0.9 the
// right way). Once the hinge is known the turn is one number a frame: each
// frame's points are turned back about the hinge through a whole turn, and
// the angle where they lie best on the model (truncated squared distances
// to its nearest points) is the frame's twist, refined on a finer grid
// around it. The search keeps the registration's twist wherever it fits no
// better (a frame whose points fit several angles alike keeps the
// registration's, which at least moved on smoothly from the last).
#pragma once

#include <Eigen/Geometry>

#include <vector>

#include "pipeline/cloud/cloud.h"

namespace efc::pipeline {

// clouds[f]: the points of frame f (object frame; empty where unseen);
// model: the points at twist 0 (object frame); axis (unit) and origin: the
// hinge (object frame); registered[f]: the registration's twist of frame f
// about that hinge (NaN where it has none). Returns the twist per frame
// (radians, right modulo a half turn only: a hand seen from one side fits
// about as well half a turn off, twist_unwrap.h; NaN where the frame has
// too few points).
std::vector<double> search_twists(const std::vector<Cloud>& clouds, const Cloud& model, const Eigen::Vector3d& axis,
                                  const Eigen::Vector3d& origin, const std::vector<double>& registered);

}  // namespace efc::pipeline
