// Receptors for generated objects: what a hand operates, by joint type and
// size. Revolute: knob, lever (small: knob, rocker switch). Prismatic: palm
// button, drawer (small: push button, slider). Continuous: hand-wheel crank
// (small: encoder dial). Knobs and dials carry a pointer ridge, so their turn
// is visible; small ones have a largest size of at most 5 cm.
#pragma once

#include <string>

#include "synth/suite/object_layout.h"
#include "synth/suite/template_params.h"

namespace efc::synth::suite {

struct ReceptorBuild {
  SpecJson part;     // named after its kind, role receptor, joint to the body
  std::string kind;  // knob, rocker, lever, button, slider, drawer, dial, crank
  ReceptorTravel travel;
  Face face;            // the face it is mounted on
  double a = 0, b = 0;  // its centre on that face (along u, v)
  double reach = 0;     // its largest size across the face
  bool sweeps = false;  // it travels across the face (lever, slider, drawer)
};

// joint_type: revolute, prismatic or continuous. `colour` is the part's rgba.
ReceptorBuild build_receptor(const std::string& joint_type, bool small, const Body& body,
                             const SpecJson& colour, SuiteRng& rng);

}  // namespace efc::synth::suite
