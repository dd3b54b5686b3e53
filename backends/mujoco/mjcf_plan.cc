// make_plan: decisions behind the MJCF (see mjcf_plan.h).
//
// Drive gains (documented in the output README):
// - geometry effect: kp = max(I w^2 with w = 2 pi 4 Hz, load / (1% of the
//   effect range)), where I is the effector subtree's inertia about the joint
//   and load = spring force at the far end of the range + worst-case gravity +
//   joint friction; so the effector settles within 2% of its range with a
//   factor-two margin. kv critically damps kp + spring (minus joint damping).
//   An explicit effect stiffness/damping replaces the computed value.
// - receptor drive (drive_receptors): the same rule at 10 Hz, so a profile is
//   followed within 1% of the joint range.
// - a gain too stiff for the part's inertia at the time step (w dt > 0.4) adds
//   joint armature instead of being weakened.
#include "backends/mujoco/mjcf_plan.h"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>

#include "compiler/geometry/geometry.h"

namespace efc {
namespace mjcf {

namespace {

constexpr double kTwoPi = 2 * 3.14159265358979323846;

void collect_meshes(const Object& obj, const Layout& L, int part, const Geometry& g,
                    const std::string& dir, int* counter, std::vector<MeshAsset>* out) {
  if (g.kind == GeomKind::Compound) {
    for (const Geometry& c : g.children) collect_meshes(obj, L, part, c, dir, counter, out);
    return;
  }
  if (g.kind != GeomKind::Mesh) return;
  MeshAsset a;
  a.name = mesh_name(obj.parts[part].name, (*counter)++);
  a.file = (dir.empty() ? std::string() : dir + "/") + a.name + ".stl";
  a.mesh = g.mesh ? &*g.mesh : nullptr;
  for (int k = 0; k < 3; ++k) a.offset[k] = -L.body_world[part][k];
  out->push_back(a);
}

}  // namespace

std::string mesh_name(const std::string& part, int index) { return part + "_" + std::to_string(index); }

Vec3 effect_point(const Object& obj, const Function& f, int effector) {
  if (f.effect.position) return *f.effect.position;
  const Part& p = obj.parts[effector];
  return {(p.bbox_min[0] + p.bbox_max[0]) / 2, (p.bbox_min[1] + p.bbox_max[1]) / 2,
          (p.bbox_min[2] + p.bbox_max[2]) / 2};
}

Vec3 effect_direction(const Effect& e) {
  const Vec3 fallback = e.type == EffectType::Airflow ? Vec3{1, 0, 0} : Vec3{0, 0, -1};
  const Vec3 d = e.direction.value_or(fallback);
  const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(n > 0)) return fallback;
  return {d[0] / n, d[1] / n, d[2] / n};
}

Vec3 park_position(int serial, double radius) {
  const double spacing = std::max(0.2, 5 * radius);
  return {(serial % 20) * spacing, (serial / 20) * spacing, 50.0};
}

Plan make_plan(const Object& obj, const MjcfOptions& options) {
  Plan plan;
  plan.layout = make_layout(obj);
  const Layout& L = plan.layout;
  plan.armature.assign(obj.parts.size(), 0.0);
  for (size_t i = 0; i < obj.parts.size(); ++i) {
    const Part& p = obj.parts[i];
    for (int k = 0; k < 3; ++k) {
      plan.bbox_min[k] = i ? std::min(plan.bbox_min[k], p.bbox_min[k]) : p.bbox_min[k];
      plan.bbox_max[k] = i ? std::max(plan.bbox_max[k], p.bbox_max[k]) : p.bbox_max[k];
    }
    int counter = 0;
    collect_meshes(obj, L, static_cast<int>(i), p.geometry, options.mesh_dir, &counter, &plan.meshes);
  }
  int lights = 0;
  std::vector<bool> driven(obj.parts.size(), false);  // effector of a geometry effect
  const std::vector<int> pool_sizes = droplet_pool_sizes(obj);
  for (size_t fi = 0; fi < obj.functions.size(); ++fi) {
    const Function& f = obj.functions[fi];
    const Effect& e = f.effect;
    const int eff = f.effector_index >= 0 ? f.effector_index : obj.find_part(f.effector);
    if (e.type == EffectType::Fluid) {
      Pool pool{f.name, e.droplet_radius.value_or(0.004), pool_sizes[fi]};
      plan.droplet_total += pool.count;
      plan.pools.push_back(pool);
    } else if (e.type == EffectType::Illumination) {
      ++lights;
    } else if (e.type == EffectType::Geometry) {
      driven[eff] = true;
      const double lo = std::min(e.lo, e.hi), hi = std::max(e.lo, e.hi);
      const double stiffness = e.stiffness.value_or(0), damping = e.damping.value_or(0);
      const DriveGains g = drive_gains(obj, L, eff, lo, hi, 0.01 * (hi - lo), 4.0, options.timestep,
                                       e.stiffness ? &stiffness : nullptr,
                                       e.damping ? &damping : nullptr);
      plan.armature[eff] = std::max(plan.armature[eff], g.armature);
      if (e.stiffness) {
        // Report a user gain that cannot hold the target within 2%.
        const DriveGains need = drive_gains(obj, L, eff, lo, hi, 0.02 * (hi - lo), 0.0,
                                            options.timestep, nullptr, nullptr);
        if (*e.stiffness < need.kp)
          plan.warnings.push_back("geometry effect '" + f.name + "': stiffness " +
                                  num(*e.stiffness) + " is below the " + num(need.kp) +
                                  " needed to hold the effector within 2% of its range against"
                                  " its spring, gravity and friction; emitted as given");
      }
      plan.drives.push_back({"efc_" + f.name + "_drive", "efc_" + f.name + "_damp",
                             obj.parts[eff].name, g.kp, g.kv, true, lo, hi});
    }
  }
  if (lights > 7)
    plan.warnings.push_back("illumination: MuJoCo renders at most 8 lights (one is the scene light); " +
                            std::to_string(lights) +
                            " effect lights were emitted and the runtime drives them all, but only "
                            "the first 7 appear in renders");
  if (options.drive_receptors) {
    std::vector<bool> done(obj.parts.size(), false);
    for (const Function& f : obj.functions) {
      const int rec = f.receptor_index >= 0 ? f.receptor_index : obj.find_part(f.receptor);
      if (rec < 0 || driven[rec] || done[rec]) continue;
      done[rec] = true;
      const Joint& j = *obj.parts[rec].joint;
      const bool continuous = j.type == JointType::Continuous;
      const double lo = continuous ? 0 : j.lo, hi = continuous ? kTwoPi : j.hi;
      const DriveGains g = drive_gains(obj, L, rec, lo, hi, 0.01 * (hi - lo), 10.0,
                                       options.timestep, nullptr, nullptr);
      plan.armature[rec] = std::max(plan.armature[rec], g.armature);
      const std::string& n = obj.parts[rec].name;
      plan.drives.push_back({"efc_drive_" + n, "efc_drive_" + n + "_damp", n, g.kp, g.kv,
                             !continuous, lo, hi});
    }
  }
  return plan;
}

bool make_dirs(const std::string& path, std::string* error) {
  std::string cur;
  size_t pos = 0;
  while (pos != std::string::npos) {
    pos = path.find('/', pos + 1);
    cur = path.substr(0, pos);
    if (cur.empty()) continue;
    if (::mkdir(cur.c_str(), 0777) != 0 && errno != EEXIST) {
      *error = std::strerror(errno);
      return false;
    }
  }
  return true;
}


}  // namespace mjcf
}  // namespace efc
