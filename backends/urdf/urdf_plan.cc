// make_plan: link frames, names, sites, mesh files and the warnings of the
// URDF target (conventions in urdf_backend.h).
#include <set>

#include "backends/common/lowering.h"
#include "backends/common/naming.h"
#include "backends/common/report.h"
#include "backends/common/text.h"
#include "backends/urdf/urdf_backend.h"
#include "compiler/geometry/geometry.h"

namespace efc {
namespace urdf {

namespace {

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }

// `base`, or `base_2`, `base_3`, ... whichever is free in `taken`; records it.
std::string unique_name(const std::string& base, std::set<std::string>* taken) {
  std::string name = base;
  for (int k = 2; taken->count(name); ++k) name = base + "_" + std::to_string(k);
  taken->insert(name);
  return name;
}

void collect_meshes(const Plan& plan, const Object& obj, int part, const Geometry& g,
                    int* counter, std::vector<MeshFile>* out) {
  if (g.kind == GeomKind::Compound) {
    for (const Geometry& c : g.children) collect_meshes(plan, obj, part, c, counter, out);
    return;
  }
  if (g.kind != GeomKind::Mesh) return;
  MeshFile m;
  m.part = part;
  m.file = naming::mesh_file("meshes", obj.parts[part].name, (*counter)++);
  m.mesh = g.mesh ? &*g.mesh : nullptr;
  for (int k = 0; k < 3; ++k) m.offset[k] = -plan.link_origin[part][k];
  out->push_back(m);
}

bool has_point(EffectType t) { return t != EffectType::Geometry; }

const char* joint_word(JointType t) { return to_string(t); }

}  // namespace

Plan make_plan(const Object& obj) {
  Plan plan;
  const size_t n = obj.parts.size();
  // Link frames are lowering's part frames, but the root link is the object
  // origin (a URDF's base frame is the object's frame).
  lowering::Layout layout = lowering::make_layout(obj);
  plan.root = layout.root;
  plan.link_origin = std::move(layout.frame);
  if (plan.root >= 0) plan.link_origin[plan.root] = {0, 0, 0};
  plan.children = std::move(layout.children);
  plan.link.assign(n, "");
  plan.joint.assign(n, "");
  std::set<std::string> links, joints;
  for (size_t i = 0; i < n; ++i) {
    const Part& p = obj.parts[i];
    plan.link[i] = p.name;
    links.insert(p.name);
    if (!p.joint) continue;
    plan.joint[i] = p.name;
    joints.insert(p.name);
  }
  for (size_t i = 0; i < n; ++i) {
    int counter = 0;
    collect_meshes(plan, obj, static_cast<int>(i), obj.parts[i].geometry, &counter, &plan.meshes);
  }

  // Sites: generated names never collide with a part's link/joint or each other.
  plan.site_of_function.assign(obj.functions.size(), -1);
  for (size_t fi = 0; fi < obj.functions.size(); ++fi) {
    const Function& f = obj.functions[fi];
    if (!has_point(f.effect.type)) continue;
    const int eff = lowering::effector_part(obj, f);
    if (eff < 0) continue;
    Site s;
    s.function = static_cast<int>(fi);
    s.effector = eff;
    s.link = unique_name(naming::urdf_site_link(f.name), &links);
    s.joint = unique_name(naming::urdf_site_joint(s.link), &joints);
    s.point = lowering::effect_point(obj, f);
    s.xyz = sub(s.point, plan.link_origin[eff]);
    if (f.effect.type == EffectType::Fluid || f.effect.type == EffectType::Airflow) {
      s.directed = true;
      s.direction = lowering::effect_direction(f.effect);
      s.rpy = matrix_to_rpy(rotation_z_to(s.direction));
    }
    plan.site_of_function[fi] = static_cast<int>(plan.sites.size());
    plan.sites.push_back(s);
  }

  // What URDF cannot say, and where it went instead.
  const std::string side = naming::urdf_sidecar(obj);
  for (size_t i = 0; i < n; ++i) {
    const Part& p = obj.parts[i];
    if (!p.joint || !p.joint->movable()) continue;
    const Joint& j = *p.joint;
    if (j.spring && j.spring->stiffness != 0) {
      SourceLoc loc = j.spring->loc.pointer.empty() ? j.loc : j.spring->loc;
      plan.warnings.push_back(
          {loc, "joint '" + p.name + "': spring (stiffness " + text::number(j.spring->stiffness) + ", rest " +
                    text::number(j.spring->rest) + "): URDF has no joint springs; the " +
                    joint_word(j.type) + " joint was emitted without it and the spring is in " +
                    side + " (joints/" + p.name + "/spring)"});
    }
    if (j.initial && *j.initial != 0) {
      plan.warnings.push_back(
          {j.loc, "joint '" + p.name + "': initial position " + text::number(*j.initial) +
                      ": URDF has no initial joint state (simulators start at 0); it is in " + side +
                      " (joints/" + p.name + "/initial)"});
    }
  }
  if (!obj.functions.empty()) {
    std::string list;
    for (const Function& f : obj.functions)
      list += (list.empty() ? "" : ", ") + f.name + " (" + to_string(f.mapping.type) + " " +
              to_string(f.effect.type) + ")";
    const SourceLoc loc = spec_location(obj, "/functions");
    plan.warnings.push_back(
        {loc, "function templates: URDF has no functions or effects; " + list + " written to " +
                  side + (plan.sites.empty() ? std::string()
                                             : std::string(", effect points as fixed '*_site' links"))});
  }
  return plan;
}

std::string spec_file_name(const Object& obj) {
  if (obj.file.empty()) return obj.name;
  const size_t slash = obj.file.find_last_of('/');
  return slash == std::string::npos ? obj.file : obj.file.substr(slash + 1);
}

}  // namespace urdf
}  // namespace efc
