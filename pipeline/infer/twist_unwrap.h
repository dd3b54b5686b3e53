// efc infer, stage 4: a grip's twist about a joint's axis, frame by frame,
// with its half-turn ambiguity resolved.
//
// A hand holding a knob is nearly flat: registered onto its reference
// frame, its points fit about as well turned half a turn about the knob's
// axis, and the registration of a hand turned past a quarter turn often
// lands there (s0029's knob turned 170 degrees read -10). Its twist is
// right modulo a half turn. A hand cannot turn half a turn between two
// frames, so the twist is unwrapped by half turns along the recording: the
// branch each frame takes is the one that keeps the hand's angular speed
// smoothest (a dynamic programme over the frames), and a frame whose twist
// fits no smooth course (a hand seen edge on, its few points registered
// anywhere) is dropped.
#pragma once

#include <vector>

namespace efc::pipeline {

// twist[f]: the grip's twist about the axis in frame f (radians, any
// branch; NaN where the grip was not registered); held[f]: whether the hand
// held the part in frame f. Returns the twist unwrapped by half turns, NaN
// where dropped or unregistered. Samples with more than `regrasp_frames`
// frames between them where the hand did not hold the part belong to
// different grasps: the hand's speed starts again from rest, and the new
// grasp takes the branch nearest the last one's end. Within a grasp, frames
// the registration missed are only a longer step.
std::vector<double> unwrap_half_turns(const std::vector<double>& twist, const std::vector<bool>& held,
                                      int regrasp_frames);

}  // namespace efc::pipeline
