// The per-sequence difficulty: scene knobs (placement, camera path, lighting,
// hand, noise) and the receptor motion profile, drawn from a seed. The
// ranges are the suite's contract with its consumers (index.json readers,
// tests), so they are named here.
#pragma once

#include <string>

#include "synth/suite/knobs.h"
#include "synth/suite/suite_rng.h"

namespace efc::synth::suite {

struct KnobRange {
  double lo, hi;
};
struct KnobRanges {
  KnobRange object_yaw{-0.6, 0.6};
  KnobRange object_offset{-0.15, 0.15};  // object_x and object_y
  KnobRange camera_distance{2.2, 4.0};
  KnobRange camera_height{0.6, 1.8};
  KnobRange camera_azimuth{-0.7, 0.7};
  KnobRange head_bob{0.005, 0.025};
  KnobRange glance{0.03, 0.2};
  KnobRange fast_turns{0, 3};
  KnobRange jitter{0.001, 0.006};
  KnobRange light_intensity{0.5, 1.4};
  KnobRange light_azimuth{-3.14159, 3.14159};
  KnobRange ambient{0.1, 0.4};
  KnobRange room_style{0, 7};
  KnobRange hand_scale{0.85, 1.15};
  KnobRange skin_tone{0, 3};
};
const KnobRanges& knob_ranges();

// Everything but object_scale (the object's own business). With `forced`
// null the noise level is drawn: mostly mild or realistic, some none.
SceneKnobs draw_scene_knobs(SuiteRng& rng, const NoiseLevel* forced);

// A motion profile for `efc synth --profile` that demonstrates the function:
// press:2 (70 %) or press:3 (30 %), i.e. the receptor's whole travel and back
// two or three times, with rests between (a latching switch goes on and off
// again, a counter counts on, a step shows its hysteresis on the way down).
// Film at least 300 frames (10 s at 30 fps) so each press is slow enough
// for a lagging effect to show.
std::string draw_profile(SuiteRng& rng);

}  // namespace efc::synth::suite
