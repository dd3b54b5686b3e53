#include "backends/python/functions_table.h"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "backends/common/lowering.h"
#include "backends/common/naming.h"

namespace efc {

namespace {

// Ordered, so the file reads top-down; doubles print shortest-round-trip, so
// Python reads back bit-identical values.
using json = nlohmann::ordered_json;

constexpr double kTwoPi = 2 * 3.14159265358979323846;

const char* const kMappingKinds[] = {"binary", "step", "linear", "cumulative"};
const char* const kEffectKinds[] = {"geometry", "illumination", "temperature", "fluid", "airflow"};

json vec(const Vec3& v) { return json::array({v[0], v[1], v[2]}); }

json drive_json(const lowering::DriveGains& g) {
  return {{"kp", g.kp}, {"kv", g.kv}, {"armature", g.armature}};
}

json end_json(const Object& obj, const urdf::Plan& plan, int part, bool movable_only) {
  const Part& p = obj.parts[part];
  json j = {{"part", p.name}, {"link", plan.link[part]}};
  const bool has_joint = p.joint && (!movable_only || p.joint->movable());
  j["joint"] = has_joint ? json(plan.joint[part]) : json(nullptr);
  return j;
}

json joints_json(const Object& obj, const urdf::Plan& plan, const lowering::Layout& layout) {
  const std::vector<int> profile = lowering::profile_driven_receptors(obj);
  json joints = json::array();
  for (size_t i = 0; i < obj.parts.size(); ++i) {
    const Part& p = obj.parts[i];
    if (!p.joint || !p.joint->movable()) continue;
    const Joint& jt = *p.joint;
    const int part = static_cast<int>(i);
    const bool continuous = jt.type == JointType::Continuous;
    json j = {{"part", p.name},
              {"joint", plan.joint[i]},
              {"link", plan.link[i]},
              {"parent_link", plan.link[jt.parent_index >= 0 ? jt.parent_index : obj.find_part(jt.parent)]},
              {"type", to_string(jt.type)},
              {"lo", continuous ? 0.0 : jt.lo},
              {"hi", continuous ? kTwoPi : jt.hi},
              {"initial", jt.initial.value_or(0.0)},
              {"axis", vec(jt.axis)},
              {"origin", vec(jt.origin)}};
    const Function* geometry = nullptr;
    for (const Function& f : obj.functions)
      if (f.effect.type == EffectType::Geometry && lowering::effector_part(obj, f) == part) geometry = &f;
    if (geometry) {
      j["drive_by"] = "function";
      j["drive"] = drive_json(lowering::geometry_drive(obj, layout, *geometry, kPythonTimestep));
    } else if (std::find(profile.begin(), profile.end(), part) != profile.end()) {
      j["drive_by"] = "profile";
      j["drive"] = drive_json(lowering::receptor_drive(obj, layout, part, kPythonTimestep));
    } else {
      j["drive_by"] = nullptr;
      j["drive"] = nullptr;
    }
    j["spring"] = jt.spring ? json{{"stiffness", jt.spring->stiffness}, {"rest", jt.spring->rest}} : json(nullptr);
    j["damping"] = jt.damping;
    j["friction"] = jt.friction;
    joints.push_back(j);
  }
  return joints;
}

json function_json(const Object& obj, const urdf::Plan& plan, const lowering::Layout& layout,
                   const lowering::FunctionRow& r) {
  const Function& f = obj.functions[r.function];
  const efc_rt::MappingParams& m = r.params.mapping;
  const efc_rt::EffectParams& e = r.params.effect;
  const EffectType type = f.effect.type;
  json j = {{"name", f.name},
            {"receptor", end_json(obj, plan, r.receptor, false)},
            {"effector", end_json(obj, plan, r.effector, true)}};
  j["mapping"] = {{"kind", kMappingKinds[m.kind]}, {"r_lo", m.r_lo},       {"r_hi", m.r_hi},
                  {"e_lo", m.e_lo},                {"e_hi", m.e_hi},       {"threshold", m.threshold},
                  {"hysteresis", m.hysteresis},    {"latching", m.latching != 0},
                  {"gain", m.gain},                {"offset", m.offset},   {"delta", m.delta},
                  {"initial", m.initial}};
  j["effect"] = {{"kind", kEffectKinds[e.kind]},     {"e_lo", e.e_lo}, {"e_hi", e.e_hi},
                 {"time_constant", e.time_constant}, {"droplet_volume_l", e.droplet_volume_l}};
  j["unit"] = lowering::effect_unit(obj, f);
  const int si = plan.site_of_function[r.function];
  if (si >= 0) {
    const urdf::Site& s = plan.sites[si];
    j["site"] = {{"link", s.link},
                 {"parent_link", plan.link[s.effector]},
                 {"xyz", vec(s.xyz)},
                 {"rpy", vec(s.rpy)},
                 {"point", vec(s.point)}};
  } else {
    j["site"] = nullptr;
  }
  const bool directed = type == EffectType::Fluid || type == EffectType::Airflow;
  const bool fluid = type == EffectType::Fluid, air = type == EffectType::Airflow;
  j["direction"] = directed ? vec(r.direction) : json(nullptr);
  j["color"] = type == EffectType::Illumination ? vec(r.color) : json(nullptr);
  j["speed"] = fluid ? json(r.speed) : json(nullptr);
  j["droplet_radius"] = fluid ? json(r.droplet_radius) : json(nullptr);
  j["droplet_pool"] = fluid ? json(r.droplet_count) : json(nullptr);
  j["cone_angle"] = air ? json(r.cone_angle) : json(nullptr);
  j["reach"] = air ? json(r.reach) : json(nullptr);
  j["glow_max"] = type == EffectType::Temperature ? json(r.glow_max) : json(nullptr);
  j["drive"] = type == EffectType::Geometry
                   ? drive_json(lowering::geometry_drive(obj, layout, f, kPythonTimestep))
                   : json(nullptr);
  return j;
}

}  // namespace

std::string functions_table_json(const Object& obj, const urdf::Plan& plan) {
  const lowering::Layout layout = lowering::make_layout(obj);
  json out = {{"format", "efc-functions"}, {"version", 1}, {"object", obj.name}};
  if (obj.description) out["description"] = *obj.description;
  out["urdf"] = naming::urdf_file(obj);
  out["root_link"] = plan.link[plan.root];
  out["timestep"] = kPythonTimestep;
  out["joints"] = joints_json(obj, plan, layout);
  json functions = json::array();
  for (const lowering::FunctionRow& r : lowering::function_rows(obj))
    functions.push_back(function_json(obj, plan, layout, r));
  out["functions"] = functions;
  // Replace invalid UTF-8 (a description is free text) rather than throw.
  return out.dump(1, ' ', false, json::error_handler_t::replace) + "\n";
}

}  // namespace efc
