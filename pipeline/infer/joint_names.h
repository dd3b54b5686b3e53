// The joint a part's name speaks of, for when its motion does not show
// or shows no more plainly one way than the other. A receptor the hand held whose motion neither its own track nor the
// hand's shows (a button pressed under the finger, a knob turned by its
// centre) was operated all the same, and its joint was a coin toss between
// two fits to noise (estimate_joint(): JointEstimate::assumed_moving). What
// the part is still says how it moves, as the paper's vision-language model
// would read it: a button, a key or a slider slides; a knob, a dial, a
// lever or a rocker turns. A "switch" names none: it comes as a rocker, a
// toggle and a slide. The same name settles a track's near-tie between a
// turn and a slide (kNamePriorOdds, joint_estimate.h) and a round button's
// press its slipping registration hides.
#pragma once

#include <string>

namespace efc::pipeline {

// "prismatic" or "revolute", by the last word of the part's name that
// names one ("speed_button" is a button, "knob_left" a knob), or "" where
// none does. Words as effect_named (pipeline/templates/effect_names.h)
// splits and compares them.
std::string joint_named(const std::string& part);

// Whether that word names a press (a button, a key, a plunger: a slide
// into the face the part sits on), not a slide along it or out of it (a
// slider, a fader, a drawer).
bool press_named(const std::string& part);

// Whether that word names a turn about the normal of the face the part
// stands out of (a knob, a dial), not about an axis along that face (a
// lever, a rocker, a door, a thumbwheel standing edge out).
bool face_turn_named(const std::string& part);

}  // namespace efc::pipeline
