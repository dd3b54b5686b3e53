#include "synth/suite/scene_draw.h"

#include <vector>

#include "synth/suite/spec_json.h"

namespace efc::synth::suite {
namespace {

// Knob values are written to index.json: 1e-4 is finer than any effect they have.
double draw(SuiteRng& rng, const KnobRange& r) { return snap(rng.uniform(r.lo, r.hi), 1e4); }
int draw_int(SuiteRng& rng, const KnobRange& r) {
  return rng.between(static_cast<int>(r.lo), static_cast<int>(r.hi));
}

}  // namespace

const KnobRanges& knob_ranges() {
  static const KnobRanges kRanges{};
  return kRanges;
}

SceneKnobs draw_scene_knobs(SuiteRng& rng, const NoiseLevel* forced) {
  const KnobRanges& r = knob_ranges();
  SceneKnobs k;
  k.object_yaw = draw(rng, r.object_yaw);
  k.object_x = draw(rng, r.object_offset);
  k.object_y = draw(rng, r.object_offset);
  k.camera_distance = draw(rng, r.camera_distance);
  k.camera_height = draw(rng, r.camera_height);
  k.camera_azimuth = draw(rng, r.camera_azimuth);
  k.head_bob = draw(rng, r.head_bob);
  k.glance = draw(rng, r.glance);
  k.fast_turns = draw_int(rng, r.fast_turns);
  k.jitter = draw(rng, r.jitter);
  k.light_intensity = draw(rng, r.light_intensity);
  k.light_azimuth = draw(rng, r.light_azimuth);
  k.ambient = draw(rng, r.ambient);
  k.room_style = draw_int(rng, r.room_style);
  k.hand_scale = draw(rng, r.hand_scale);
  k.skin_tone = draw_int(rng, r.skin_tone);
  // Drawn even when forced, so forcing the noise changes nothing else.
  static const std::vector<NoiseLevel> kLevels = {NoiseLevel::None, NoiseLevel::Mild,
                                                  NoiseLevel::Realistic};
  const NoiseLevel drawn = kLevels[rng.weighted({0.15, 0.45, 0.4})];
  k.noise = forced ? *forced : drawn;
  return k;
}

std::string draw_profile(SuiteRng& rng) {
  // As a person demonstrating the function would: through the receptor's
  // whole travel and back, at least twice. One ramp, hold or press cannot
  // tell binary, step, latching and cumulative apart (they all switch on
  // once), so those profiles are no longer drawn (efc synth still has them).
  static const std::vector<std::string> kProfiles = {"press:2", "press:3"};
  return kProfiles[rng.weighted({0.7, 0.3})];
}

}  // namespace efc::synth::suite
