// NoiseLevel names and SceneKnobs as JSON (DIR/index.json, truth/knobs.json).
// In efc_synth_image so that every user of the knobs links them.
#include "synth/suite/knobs.h"

namespace efc::synth {

const char* to_string(NoiseLevel level) {
  switch (level) {
    case NoiseLevel::None:
      return "none";
    case NoiseLevel::Mild:
      return "mild";
    case NoiseLevel::Realistic:
      return "realistic";
  }
  return "none";
}

bool parse_noise_level(const std::string& text, NoiseLevel* out) {
  for (NoiseLevel level : {NoiseLevel::None, NoiseLevel::Mild, NoiseLevel::Realistic}) {
    if (text == to_string(level)) {
      if (out) *out = level;
      return true;
    }
  }
  return false;
}

nlohmann::json to_json(const SceneKnobs& k) {
  // Keys are the field names, in declaration order (nlohmann::json sorts
  // them on output anyway).
  nlohmann::json j = nlohmann::json::object();
  j["object_yaw"] = k.object_yaw;
  j["object_x"] = k.object_x;
  j["object_y"] = k.object_y;
  j["object_scale"] = k.object_scale;
  j["camera_distance"] = k.camera_distance;
  j["camera_height"] = k.camera_height;
  j["camera_azimuth"] = k.camera_azimuth;
  j["head_bob"] = k.head_bob;
  j["glance"] = k.glance;
  j["fast_turns"] = k.fast_turns;
  j["jitter"] = k.jitter;
  j["light_intensity"] = k.light_intensity;
  j["light_azimuth"] = k.light_azimuth;
  j["ambient"] = k.ambient;
  j["room_style"] = k.room_style;
  j["hand_scale"] = k.hand_scale;
  j["skin_tone"] = k.skin_tone;
  j["noise"] = to_string(k.noise);
  return j;
}

}  // namespace efc::synth
