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

#include <algorithm>

#include "backends/common/naming.h"
#include "backends/common/report.h"

namespace efc {
namespace mjcf {

namespace {

void collect_meshes(const Object& obj, const lowering::Layout& L, int part, const Geometry& g,
                    const std::string& dir, int* counter, std::vector<MeshAsset>* out) {
  if (g.kind == GeomKind::Compound) {
    for (const Geometry& c : g.children) collect_meshes(obj, L, part, c, dir, counter, out);
    return;
  }
  if (g.kind != GeomKind::Mesh) return;
  MeshAsset a;
  a.name = naming::mesh_stem(obj.parts[part].name, *counter);
  a.file = naming::mesh_file(dir, obj.parts[part].name, *counter);
  ++*counter;
  a.mesh = g.mesh ? &*g.mesh : nullptr;
  for (int k = 0; k < 3; ++k) a.offset[k] = -L.frame[part][k];
  out->push_back(a);
}

}  // namespace

Vec3 park_position(int serial, double radius) {
  const double spacing = std::max(0.2, 5 * radius);
  return {(serial % 20) * spacing, (serial / 20) * spacing, 50.0};
}

Plan make_plan(const Object& obj, const MjcfOptions& options) {
  Plan plan;
  plan.layout = lowering::make_layout(obj);
  const lowering::Layout& L = plan.layout;
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
  const std::vector<int> pool_sizes = lowering::droplet_pool_sizes(obj);
  for (size_t fi = 0; fi < obj.functions.size(); ++fi) {
    const Function& f = obj.functions[fi];
    const Effect& e = f.effect;
    const int eff = lowering::effector_part(obj, f);
    if (e.type == EffectType::Fluid) {
      Pool pool{f.name, e.droplet_radius.value_or(lowering::kDefaultDropletRadius), pool_sizes[fi]};
      plan.droplet_total += pool.count;
      plan.pools.push_back(pool);
    } else if (e.type == EffectType::Illumination) {
      ++lights;
    } else if (e.type == EffectType::Geometry) {
      driven[eff] = true;
      const double lo = std::min(e.lo, e.hi), hi = std::max(e.lo, e.hi);
      const lowering::DriveGains g = lowering::geometry_drive(obj, L, f, options.timestep);
      plan.armature[eff] = std::max(plan.armature[eff], g.armature);
      const std::string weak = lowering::weak_stiffness_warning(obj, L, f, options.timestep);
      if (!weak.empty())
        plan.warnings.push_back({spec_location(obj, e.loc.pointer + "/stiffness"), weak});
      plan.drives.push_back({naming::mjcf_drive(f.name), naming::mjcf_damp(f.name),
                             obj.parts[eff].name, g.kp, g.kv, true, lo, hi});
    }
  }
  if (lights > 7)
    plan.warnings.push_back(
        {spec_location(obj, "/functions"),
         "illumination: MuJoCo renders at most 8 lights (one is the scene light); " +
             std::to_string(lights) +
             " effect lights were emitted and the runtime drives them all, but only the first 7 "
             "appear in renders"});
  if (options.drive_receptors) {
    std::vector<bool> done(obj.parts.size(), false);
    for (const Function& f : obj.functions) {
      const int rec = lowering::receptor_part(obj, f);
      if (rec < 0 || driven[rec] || done[rec]) continue;
      done[rec] = true;
      const Joint& j = *obj.parts[rec].joint;
      const bool continuous = j.type == JointType::Continuous;
      const lowering::DriveGains g = lowering::receptor_drive(obj, L, rec, options.timestep);
      plan.armature[rec] = std::max(plan.armature[rec], g.armature);
      const std::string& n = obj.parts[rec].name;
      plan.drives.push_back({naming::mjcf_receptor_drive(n), naming::mjcf_receptor_damp(n), n, g.kp,
                             g.kv, !continuous, continuous ? 0 : j.lo,
                             continuous ? 2 * 3.14159265358979323846 : j.hi});
    }
  }
  return plan;
}

}  // namespace mjcf
}  // namespace efc
