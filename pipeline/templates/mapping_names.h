// The mapping a receptor's name speaks of, for when the pixels say nothing.
// Where no signal at the effector follows the receptor (E1062), the fitted
// mapping is a fit to noise; what the receptor is still says how it maps,
// as the paper's vision-language model would read it: a door, a lid or a
// drawer works a switch that trips at a point of its travel (a fridge's
// light, an oven's lamp: binary); a switch is on or off (binary); a slider,
// a wheel or a dimmer sets a level along its travel (linear); a plus, a
// minus, an up or a down button adds a step each press (cumulative). Knobs,
// dials, levers and plain buttons name none: they come in every kind.
#pragma once

#include <string>

namespace efc::pipeline {

// The mapping (0 binary, 1 step, 2 linear, 3 cumulative, as templates.cc
// orders them) the receptor's name gives, by its last word that names one
// ("fan_slider" is a slider, "flow_up" an up button, "power_switch" a
// switch), or -1. Words as effect_named (effect_names.h) splits them, a
// plural's "s" dropped where the word itself is not listed.
int mapping_named(const std::string& receptor);

}  // namespace efc::pipeline
