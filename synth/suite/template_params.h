// Function-template parameters for generated objects: a mapping whose
// thresholds, hysteresis, gain, offset and delta fit the receptor's range and
// the effect's [off, on], drawn so that an estimator that assumes the spec's
// defaults (midpoint threshold, range-to-range gain, off at rest) is often
// wrong, while the playback profiles still reach every switching point.
#pragma once

#include <string>

#include "synth/suite/spec_json.h"
#include "synth/suite/suite_rng.h"

namespace efc::synth::suite {

// The receptor's travel as the profiles see it: its joint range, or for a
// continuous joint the [0, 2 pi] sweep of cli.md.
struct ReceptorTravel {
  bool continuous = false;
  double lo = 0, hi = 0;
  bool push_button = false;  // a spring-return press: latching makes sense
};

// A MAPPING object of `type` (binary, step, linear, cumulative). [off, on] is
// the effect's range. Switching points lie in the middle 15-85 % of the
// travel, so a sweep, a ramp, a press or hold:hi crosses them.
SpecJson draw_mapping(const std::string& type, const ReceptorTravel& travel, double off, double on,
                      SuiteRng& rng);

}  // namespace efc::synth::suite
