// The room the object stands in, and where. Everything is designed in the
// world frame (z up, the camera on the object's front side); the simulation
// itself runs in the object's frame, exactly as `efc play` runs it, so the
// room, the hand and the camera are written into the model through the
// inverse of the object's placement. That keeps the physics bit for bit the
// same as `efc play` (nothing efc adds collides or has mass).
#pragma once

#include <Eigen/Geometry>

#include <string>
#include <vector>

#include "compiler/ir.h"
#include "synth/suite/knobs.h"

namespace efc::synth {

// MJCF names of what the scene adds (all start with "efc_synth_").
constexpr const char* kHeadBody = "efc_synth_head";
constexpr const char* kCamera = "efc_synth_camera";
constexpr const char* kHandBody = "efc_synth_hand";
constexpr const char* kAirPrefix = "efc_synth_air_";  // efc_synth_air_<function>_<i>
constexpr const char* kGlowMaterialPrefix = "efc_synth_glow_";  // efc_synth_glow_<function>
// A lamp's effector unlit reflects this fraction of its colour; lit, its
// material's emission (up to kGlowEmission) adds its colour back and more.
constexpr double kUnlitAlbedo = 0.45;
constexpr double kGlowEmission = 1.4;

struct Layout {
  Eigen::Isometry3d object_to_world = Eigen::Isometry3d::Identity();
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();  // parts' box, object frame
  Eigen::Vector3d center_object = Eigen::Vector3d::Zero();  // its centre
  double radius = 0.1;        // bounding sphere of the parts (m)
  bool on_counter = false;    // small objects stand on a counter, large ones on the floor
  double support_z = 0;       // world height of what the object stands on
  Eigen::Vector3d center_world() const { return object_to_world * center_object; }
};

// Where the object stands (knobs: yaw, offset) and what it stands on.
Layout plan_layout(const Object& obj, const SceneKnobs& knobs);

// Air made visible: light motes carried out of an airflow outlet.
struct AirMotes {
  std::string function;
  int count = 0;
};

// What the scene adds to the compiled object's MJCF. fovy_deg is the head
// camera's vertical field of view.
struct SceneExtras {
  double fovy_deg = 49.1;
  int width = 640, height = 480;
  std::vector<AirMotes> air;
  std::vector<std::string> glow_functions;  // illumination: effector geoms glow
  std::string hand_xml;                      // the hand's <body> (synth/hand.h)
};

// Rewrites `mjcf` (the document write_mujoco_model wrote): drops efc's own
// floor, camera and scene light, and adds the room, clutter, lights, the
// head camera, the hand and the air motes. False with *error if the document
// is not what the MuJoCo backend writes.
bool build_scene_mjcf(const Object& obj, const Layout& layout, const SceneKnobs& knobs,
                      const SceneExtras& extras, std::string* mjcf, std::string* error);

}  // namespace efc::synth
