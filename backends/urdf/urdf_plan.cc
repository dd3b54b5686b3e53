// make_plan: link frames, names, sites, mesh files and the warnings of the
// URDF target (conventions in urdf_backend.h).
#include <cmath>
#include <set>

#include "backends/urdf/urdf_backend.h"
#include "compiler/geometry/geometry.h"

namespace efc {
namespace urdf {

namespace {

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }

Vec3 bbox_center(const Part& p) {
  return {(p.bbox_min[0] + p.bbox_max[0]) / 2, (p.bbox_min[1] + p.bbox_max[1]) / 2,
          (p.bbox_min[2] + p.bbox_max[2]) / 2};
}

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
  m.file = "meshes/" + obj.parts[part].name + "_" + std::to_string((*counter)++) + ".stl";
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
  plan.root = obj.root_index();
  plan.link_origin.assign(n, Vec3{0, 0, 0});
  plan.children.assign(n, {});
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
    const int parent = p.joint->parent_index >= 0 ? p.joint->parent_index : obj.find_part(p.joint->parent);
    if (parent >= 0) plan.children[parent].push_back(static_cast<int>(i));
    const bool hinge = p.joint->type == JointType::Revolute || p.joint->type == JointType::Continuous;
    plan.link_origin[i] = hinge ? p.joint->origin : p.mass_props.com;
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
    const int eff = f.effector_index >= 0 ? f.effector_index : obj.find_part(f.effector);
    if (eff < 0) continue;
    Site s;
    s.function = static_cast<int>(fi);
    s.effector = eff;
    s.link = unique_name(f.name + "_site", &links);
    s.joint = unique_name(s.link + "_joint", &joints);
    s.point = f.effect.position.value_or(bbox_center(obj.parts[eff]));
    s.xyz = sub(s.point, plan.link_origin[eff]);
    if (f.effect.type == EffectType::Fluid || f.effect.type == EffectType::Airflow) {
      const Vec3 fallback = f.effect.type == EffectType::Airflow ? Vec3{1, 0, 0} : Vec3{0, 0, -1};
      Vec3 d = f.effect.direction.value_or(fallback);
      const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      if (!(len > 0)) d = fallback;
      else for (double& v : d) v /= len;
      s.directed = true;
      s.direction = d;
      s.rpy = matrix_to_rpy(rotation_z_to(d));
    }
    plan.site_of_function[fi] = static_cast<int>(plan.sites.size());
    plan.sites.push_back(s);
  }

  // What URDF cannot say, and where it went instead.
  const std::string side = sidecar_file_name(obj);
  for (size_t i = 0; i < n; ++i) {
    const Part& p = obj.parts[i];
    if (!p.joint || !p.joint->movable()) continue;
    const Joint& j = *p.joint;
    if (j.spring && j.spring->stiffness != 0) {
      SourceLoc loc = j.spring->loc.pointer.empty() ? j.loc : j.spring->loc;
      plan.warnings.push_back(
          {loc, "joint '" + p.name + "': spring (stiffness " + num(j.spring->stiffness) + ", rest " +
                    num(j.spring->rest) + "): URDF has no joint springs; the " +
                    joint_word(j.type) + " joint was emitted without it and the spring is in " +
                    side + " (joints/" + p.name + "/spring)"});
    }
    if (j.initial && *j.initial != 0) {
      plan.warnings.push_back(
          {j.loc, "joint '" + p.name + "': initial position " + num(*j.initial) +
                      ": URDF has no initial joint state (simulators start at 0); it is in " + side +
                      " (joints/" + p.name + "/initial)"});
    }
  }
  if (!obj.functions.empty()) {
    std::string list;
    for (const Function& f : obj.functions)
      list += (list.empty() ? "" : ", ") + f.name + " (" + to_string(f.mapping.type) + " " +
              to_string(f.effect.type) + ")";
    SourceLoc loc;
    loc.pointer = "/functions";
    auto it = obj.positions.find("/functions");
    if (it != obj.positions.end()) {
      loc.line = it->second.first;
      loc.col = it->second.second;
    }
    plan.warnings.push_back(
        {loc, "function templates: URDF has no functions or effects; " + list + " written to " +
                  side + (plan.sites.empty() ? std::string()
                                             : std::string(", effect points as fixed '*_site' links"))});
  }
  return plan;
}

std::string urdf_file_name(const Object& obj) { return obj.name + ".urdf"; }
std::string sidecar_file_name(const Object& obj) { return obj.name + ".functions.json"; }

std::string spec_file_name(const Object& obj) {
  if (obj.file.empty()) return obj.name;
  const size_t slash = obj.file.find_last_of('/');
  return slash == std::string::npos ? obj.file : obj.file.substr(slash + 1);
}

}  // namespace urdf
}  // namespace efc
