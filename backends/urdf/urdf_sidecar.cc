// write_sidecar: <name>.functions.json, what the URDF cannot hold. The
// function templates exactly as the compiler resolved them (every default
// filled, as `efc check --dump-ir` shows them), each end named by part, URDF
// link and URDF joint; the effect's point as a site link; per movable joint
// its spring and initial position.
//
// Positions inside "mapping"/"effect" are in the object frame at joint
// position 0 (as in the spec); "links[].origin" gives each link frame's
// origin in that frame (link frames are axis-aligned with it), and
// "effect.site.xyz"/"rpy" place the site in its parent link's frame.
#include <nlohmann/json.hpp>

#include "backends/urdf/urdf_backend.h"
#include "compiler/core/ir_json.h"
#include "backends/common/lowering.h"
#include "backends/common/naming.h"
#include "compiler/core/resolve.h"

namespace efc {
namespace urdf {

namespace {

// Ordered, so the file reads top-down (object, links, joints, functions);
// the resolved mapping/effect come from ir_to_json (keys sorted there).
using json = nlohmann::ordered_json;

json jvec(const Vec3& v) { return json::array({v[0], v[1], v[2]}); }

json end(const Plan& plan, const Object& obj, int part) {
  json j = {{"part", obj.parts[part].name}, {"link", plan.link[part]}};
  j["joint"] = plan.joint[part].empty() ? json(nullptr) : json(plan.joint[part]);
  return j;
}

}  // namespace

std::string write_sidecar(const Object& obj, const Plan& plan) {
  const json ir = json::parse(ir_to_json(obj).dump());
  json out = {{"format", "efc-urdf-functions"},
              {"version", 1},
              {"object", obj.name},
              {"urdf", naming::urdf_file(obj)},
              {"spec", spec_file_name(obj)},
              {"root_link", plan.link[plan.root]}};
  if (obj.description) out["description"] = *obj.description;
  out["frames"] =
      "Positions in mapping/effect are in the object frame at joint position 0; links[].origin "
      "is each URDF link frame's origin in that frame (all link frames are axis-aligned with "
      "it); effect.site.xyz/rpy place the site link in its parent link's frame, and a "
      "fluid/airflow site's +z is the emitter/outlet direction.";

  json links = json::array();
  for (size_t i = 0; i < obj.parts.size(); ++i) {
    json l = end(plan, obj, static_cast<int>(i));
    l["origin"] = jvec(plan.link_origin[i]);
    links.push_back(l);
  }
  out["links"] = links;

  // Joint state URDF cannot hold.
  json joints = json::object();
  for (size_t i = 0; i < obj.parts.size(); ++i) {
    const Part& p = obj.parts[i];
    if (!p.joint || !p.joint->movable()) continue;
    const Joint& jt = *p.joint;
    json j = {{"part", p.name}, {"link", plan.link[i]}, {"type", to_string(jt.type)}};
    j["initial"] = jt.initial.value_or(0.0);
    if (jt.spring)
      j["spring"] = {{"stiffness", jt.spring->stiffness}, {"rest", jt.spring->rest}};
    else
      j["spring"] = nullptr;
    j["damping"] = jt.damping;
    j["friction"] = jt.friction;
    joints[plan.joint[i]] = j;
  }
  out["joints"] = joints;

  json fns = json::array();
  for (size_t fi = 0; fi < obj.functions.size(); ++fi) {
    const Function& f = obj.functions[fi];
    const json& fj = ir["functions"][fi];
    const int rec = lowering::receptor_part(obj, f);
    const int eff = lowering::effector_part(obj, f);
    double lo = 0, hi = 0;
    receptor_range(obj, f, &lo, &hi);
    json j = {{"name", f.name}, {"receptor", end(plan, obj, rec)}, {"effector", end(plan, obj, eff)}};
    j["receptor_range"] = json::array({lo, hi});
    j["mapping"] = fj["mapping"];
    json effect = fj["effect"];
    const int si = plan.site_of_function[fi];
    if (si >= 0) {
      const Site& s = plan.sites[si];
      effect["site"] = {{"link", s.link},
                        {"joint", s.joint},
                        {"parent_link", plan.link[s.effector]},
                        {"xyz", jvec(s.xyz)},
                        {"rpy", jvec(s.rpy)}};
    } else {
      effect["site"] = nullptr;
    }
    j["effect"] = effect;
    if (!f.extensions.empty()) {
      json ext = json::object();
      for (const auto& [k, v] : f.extensions) ext[k] = v;
      j["extensions"] = ext;
    }
    fns.push_back(j);
  }
  out["functions"] = fns;
  return out.dump(2) + "\n";
}

}  // namespace urdf
}  // namespace efc
