// The naming contract between the backends, the runtime bindings and users'
// code: what every generated element and file is called. Parts keep their
// spec names (bodies, links and joints are named after their part); what efc
// adds starts with "efc_" in MJCF (the front-end rejects spec names with that
// prefix, so they never collide) and ends in "_site" in URDF (collisions get
// a suffix _2, _3, ... there). runtime/mujoco/efc_mujoco.h repeats the MJCF
// half, because generated programs carry the runtime without this header.
#pragma once

#include <string>

#include "compiler/ir.h"

namespace efc {
namespace naming {

// ---- MJCF elements (runtime/mujoco/efc_mujoco.h resolves them by these names)
inline std::string mjcf_drive(const std::string& fn) { return "efc_" + fn + "_drive"; }  // position actuator
inline std::string mjcf_damp(const std::string& fn) { return "efc_" + fn + "_damp"; }    // its velocity actuator
inline std::string mjcf_light(const std::string& fn) { return "efc_" + fn + "_light"; }
inline std::string mjcf_point(const std::string& fn) { return "efc_" + fn + "_point"; }  // site at the effect point
inline std::string mjcf_droplet(const std::string& fn, int i) {
  return "efc_" + fn + "_drop" + std::to_string(i);
}
inline std::string mjcf_receptor_drive(const std::string& part) { return "efc_drive_" + part; }
inline std::string mjcf_receptor_damp(const std::string& part) { return "efc_drive_" + part + "_damp"; }
// The scene elements every MJCF model carries (harness/render.cc frames the
// object with the camera).
constexpr const char* kMjcfCamera = "efc_camera";
constexpr const char* kMjcfSceneLight = "efc_scene_light";
constexpr const char* kMjcfFloor = "efc_floor";
// C API prefix of the generated callbacks: efc_<object>_install, ...
inline std::string callbacks_prefix(const Object& obj) { return "efc_" + obj.name; }

// ---- URDF
// The site link of a function's effect point and its fixed joint, before a
// collision suffix (urdf_plan.cc makes them unique).
inline std::string urdf_site_link(const std::string& fn) { return fn + "_site"; }
inline std::string urdf_site_joint(const std::string& link) { return link + "_joint"; }
inline std::string urdf_material(const std::string& part) { return part + "_material"; }

// ---- Meshes: the i-th mesh of a part (compounds may hold several)
inline std::string mesh_stem(const std::string& part, int i) { return part + "_" + std::to_string(i); }
inline std::string mesh_file(const std::string& dir, const std::string& part, int i) {
  return (dir.empty() ? std::string() : dir + "/") + mesh_stem(part, i) + ".stl";
}

// ---- Files of an output folder
inline std::string mjcf_file(const Object& obj) { return obj.name + ".xml"; }
inline std::string callbacks_source(const Object& obj) { return obj.name + "_callbacks.cc"; }
inline std::string callbacks_header(const Object& obj) { return obj.name + "_callbacks.h"; }
inline std::string urdf_file(const Object& obj) { return obj.name + ".urdf"; }
inline std::string urdf_sidecar(const Object& obj) { return obj.name + ".functions.json"; }
inline std::string bullet_program(const Object& obj) { return obj.name + "_bullet"; }
inline std::string functions_table(const Object& obj) { return obj.name + "_functions.json"; }
inline std::string python_script(const Object& obj, const std::string& target) {
  return obj.name + "_" + target + ".py";
}

}  // namespace naming
}  // namespace efc
