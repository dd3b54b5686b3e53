// Generated objects: a plausible appliance built around one function of a
// given mapping x effect pair and receptor joint type. A box body (0.3-0.9 m
// wide, standing at z >= 0, front towards -y) carries the receptor
// (receptor_parts.h) and the effector (effector_parts.h); the mapping's
// parameters come from template_params.h. To trip careless estimators some
// objects also carry look-alike decoys of the receptor (fixed, no function),
// a second function (an indicator light on the same receptor), a receptor on
// the side face, or a receptor the colour of the body.
#pragma once

#include <string>

#include "synth/suite/spec_json.h"
#include "synth/suite/suite_rng.h"

namespace efc::synth::suite {

struct ObjectRequest {
  std::string mapping;          // binary, step, linear, cumulative
  std::string effect;           // geometry, illumination, temperature, fluid, airflow
  std::string receptor_joint;   // revolute, prismatic, continuous (not with binary)
  bool small_receptor = false;  // a receptor of at most 5 cm
};

struct GeneratedObject {
  SpecJson spec;         // a spec v1 document with primitive geometry only
  std::string function;  // the requested function's name
  std::string receptor, effector;
};

GeneratedObject generate_object(const ObjectRequest& request, SuiteRng& rng);

}  // namespace efc::synth::suite
