// The effect a function's names speak of, for when the pixels say nothing.
// The EgoFun3D paper infers templates with a vision-language model that
// reads what the parts are ("a burner", "a spout") as well as what they do;
// efc's own stage reads the pixels (templates.cc), and where no signal at
// the effector follows the receptor (an effector out of view, droplets
// behind the counter, a heater that does not glow within the clip) the
// names are what is left: a part called "spout" pours, one called "lamp"
// lights. A small lexicon of English device words, not a model: each word
// names one effect or none ("head", "panel", "speed" name none).
#pragma once

#include <map>
#include <string>

namespace efc::pipeline {

// The effect (0 geometry, 1 illumination, 2 temperature, 3 fluid,
// 4 airflow, as templates.cc orders them) that the names give, or -1. The
// effector's name decides first, by its last word that names an effect (its
// head noun: "hob_lamp" is a lamp, "burner_left" a burner), then the
// function's the same way ("lights", "heat_left", "extract"). Words are split
// at anything but letters and digits and at lower-to-upper case changes
// ("doorLight"), compared in lower case, a plural's "s" dropped where the
// word itself is not listed.
int effect_named(const std::string& effector, const std::string& function);

// The value in `words` of the last word of `name` listed there, or -1:
// words as effect_named splits and compares them (the lexicon's lookup,
// shared with mapping_named).
int last_named_in(const std::map<std::string, int>& words, const std::string& name);

}  // namespace efc::pipeline
