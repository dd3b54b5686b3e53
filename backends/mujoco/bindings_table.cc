// build_bindings: the function table (efc_mj::FunctionBinding rows) in
// evaluation order: lowering's rows with the MJCF names the binding resolves.
// Both `efc play` and the generated callbacks use exactly these rows, so the
// in-memory and the compiled controller agree bit for bit.
#include <cstring>

#include "backends/common/lowering.h"
#include "backends/mujoco/mujoco_backend.h"

namespace efc {

// The MuJoCo binding carries its own copies of the shared realisation
// constants (generated programs include it without backends/common).
static_assert(efc_mj::kGlowFullC == lowering::kGlowFullC, "glow constants differ");
static_assert(efc_mj::kDropletLifetime == lowering::kDropletLifetime, "droplet lifetimes differ");
static_assert(efc_mj::kFlowWindow == lowering::kFlowWindow, "flow windows differ");

namespace {

void copy_name(char* dst, size_t cap, const std::string& s) {
  std::memset(dst, 0, cap);
  std::strncpy(dst, s.c_str(), cap - 1);
}

}  // namespace

std::vector<efc_mj::FunctionBinding> build_bindings(const Object& obj) {
  std::vector<efc_mj::FunctionBinding> rows;
  for (const lowering::FunctionRow& r : lowering::function_rows(obj)) {
    const Function& f = obj.functions[r.function];
    efc_mj::FunctionBinding b{};
    copy_name(b.name, sizeof b.name, f.name);
    copy_name(b.receptor_joint, sizeof b.receptor_joint, obj.parts[r.receptor].name);
    copy_name(b.effector_body, sizeof b.effector_body, obj.parts[r.effector].name);
    if (f.effect.type == EffectType::Geometry)
      copy_name(b.effector_joint, sizeof b.effector_joint, obj.parts[r.effector].name);
    b.params = r.params;
    for (int k = 0; k < 3; ++k) {
      b.direction[k] = r.direction[k];
      b.color[k] = r.color[k];
    }
    b.speed = r.speed;
    b.droplet_radius = r.droplet_radius;
    b.droplet_count = r.droplet_count;
    b.cone_angle = r.cone_angle;
    b.reach = r.reach;
    b.glow_max = r.glow_max;
    rows.push_back(b);
  }
  return rows;
}

}  // namespace efc
