// What the MJCF will contain, decided before any text is written: body
// layout, mesh assets, droplet pools, drives (with their gains) and the
// warnings the backend owes the user. Keeps the writer a plain printer.
#pragma once

#include <string>
#include <vector>

#include "backends/mujoco/mjcf_internal.h"
#include "backends/mujoco/mujoco_backend.h"

namespace efc {
namespace mjcf {

struct MeshAsset {
  std::string name;  // <part>_<i>
  std::string file;  // <mesh_dir>/<part>_<i>.stl, relative to the XML
  const MeshData* mesh = nullptr;
  Vec3 offset{0, 0, 0};  // added to every vertex: minus the body's world position
};

struct Pool {
  std::string function;
  double radius = 0;
  int count = 0;
};

struct Drive {
  std::string name, damp_name, joint;
  double kp = 0, kv = 0;
  bool limited = true;
  double ctrl_lo = 0, ctrl_hi = 0;
};

struct Plan {
  Layout layout;
  Vec3 bbox_min{0, 0, 0}, bbox_max{0, 0, 0};  // the whole object
  std::vector<MeshAsset> meshes;
  std::vector<Pool> pools;
  int droplet_total = 0;
  std::vector<double> armature;  // per part
  std::vector<Drive> drives;     // geometry effects first, then receptor drives
  std::vector<std::string> warnings;
};

Plan make_plan(const Object& obj, const MjcfOptions& options);

std::string mesh_name(const std::string& part, int index);
// The effect's point in the object frame (resolve() fills it; the fallback
// is the effector's bounding-box centre) and its unit direction.
Vec3 effect_point(const Object& obj, const Function& f, int effector);
Vec3 effect_direction(const Effect& e);
// Where droplet number `serial` (over all pools) waits: a spaced grid at
// z = +50 m, far from the object and from each other.
Vec3 park_position(int serial, double radius);

bool make_dirs(const std::string& path, std::string* error);

}  // namespace mjcf
}  // namespace efc
