// The difficulty knobs of one synthetic sequence: everything about the scene
// that is not the object itself. `efc synth` uses the defaults (and its seed
// for the small random motions); `efc synth-suite` draws them per sequence
// (suite_plan.h) and lists them in DIR/index.json.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace efc::synth {

enum class NoiseLevel { None, Mild, Realistic };
const char* to_string(NoiseLevel level);
// "none", "mild", "realistic"; false for anything else.
bool parse_noise_level(const std::string& text, NoiseLevel* out);

struct SceneKnobs {
  // Where the object stands: rotation about the world's up axis (rad) and a
  // shift on its support (m). The camera always faces the object's front
  // (its -y side, as the examples are drawn) within +-camera_azimuth_spread.
  double object_yaw = 0;
  double object_x = 0, object_y = 0;
  // Uniform scale applied to the object's geometry by the suite (1 = as
  // specified); recorded here, applied to the spec by the suite.
  double object_scale = 1;
  // Camera: distance from the object's centre in units of its size (its
  // bounding sphere's radius), its height above the object's centre in the
  // same units, the spread of the approach azimuth (rad), head bob (m),
  // glance amplitude (rad), how many fast turns, and the jitter (rad).
  double camera_distance = 3.2;
  double camera_height = 1.2;
  double camera_azimuth = 0;  // rad, relative to the object's front
  double head_bob = 0.012;
  double glance = 0.08;
  int fast_turns = 1;
  double jitter = 0.002;
  // Lighting: the key light's intensity (1 = default) and azimuth (rad),
  // ambient level (0..1).
  double light_intensity = 1.0;
  double light_azimuth = 0.6;
  double ambient = 0.25;
  // The room's look: a seed for the floor, wall and counter colours/textures.
  int room_style = 0;
  // Hand: size multiplier (1 = an adult's hand) and skin tone index (0..3).
  double hand_scale = 1.0;
  int skin_tone = 0;
  NoiseLevel noise = NoiseLevel::Mild;
};

nlohmann::json to_json(const SceneKnobs& knobs);

}  // namespace efc::synth
