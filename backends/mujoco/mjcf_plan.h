// What the MJCF will contain, decided before any text is written: body
// layout, mesh assets, droplet pools, drives (with their gains) and the
// warnings the backend owes the user. Keeps the writer a plain printer.
#pragma once

#include <string>
#include <vector>

#include "backends/common/lowering.h"
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

// A warning the target owes the user, located at a spec field.
struct Warning {
  SourceLoc loc;
  std::string message;
};

struct Plan {
  lowering::Layout layout;  // every body frame: lowering's part frames
  Vec3 bbox_min{0, 0, 0}, bbox_max{0, 0, 0};  // the whole object
  std::vector<MeshAsset> meshes;
  std::vector<Pool> pools;
  int droplet_total = 0;
  std::vector<double> armature;  // per part
  std::vector<Drive> drives;     // geometry effects first, then receptor drives
  std::vector<Warning> warnings;
};

Plan make_plan(const Object& obj, const MjcfOptions& options);

// Where droplet number `serial` (over all pools) waits: a spaced grid at
// z = +50 m, far from the object and from each other.
Vec3 park_position(int serial, double radius);

}  // namespace mjcf
}  // namespace efc
